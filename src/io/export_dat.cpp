// rock.dat, the paper's layout (Section 4): every node as "id, x, y, z", then every tetrahedron
// as "id, n1, n2, n3, n4"; comma separated, no header, ids from 1, particle by particle. Node
// lines have 4 fields and tetrahedron lines 5, so a reader can tell them apart without a header.

#include "export_detail.h"

namespace aggpack::detail {

void write_rock_dat(const ExportModel& model, std::ostream& out) {
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    std::uint64_t id = model.node_offset(k) + 1;
    for (const Vec3& node : nodes) {
      append_number(buffer, id++);
      for (int axis = 0; axis < 3; ++axis) {
        buffer += ", ";
        append_number(buffer, node[axis]);
      }
      buffer += '\n';
    }
  });
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Tetrahedron> scratch;
    const std::uint64_t first_node = model.node_offset(k) + 1;
    std::uint64_t id = model.element_offset(k) + 1;
    for (const auto& tet : model.tetrahedra(k, scratch)) {
      append_number(buffer, id++);
      for (auto index : tet) {
        buffer += ", ";
        append_number(buffer, first_node + index);
      }
      buffer += '\n';
    }
  });
}

}  // namespace aggpack::detail
