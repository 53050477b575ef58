// rock.dat, the paper's layout (Section 4): every node as "id, x, y, z", then every tetrahedron
// as "id, n1, n2, n3, n4"; comma separated, no header, ids from 1, particle by particle. Node
// lines have 4 fields and tetrahedron lines 5, so a reader can tell them apart without a header.

#include "export_detail.h"

namespace aggpack::detail {

void write_rock_dat(const ExportModel& model, std::ostream& out) {
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    append_node_lines(buffer, "", ", ", model.node_offset(k) + 1, nodes, kFeNumberWidth);
  });
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Tetrahedron> scratch;
    append_element_lines(buffer, "", ", ", model.element_offset(k) + 1, model.node_offset(k) + 1,
                         model.tetrahedra(k, scratch));
  });
}

}  // namespace aggpack::detail
