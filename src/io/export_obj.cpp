// Wavefront OBJ: one object "o P<id>" per particle with its vertices ("v x y z") and outward
// counter-clockwise triangles ("f a b c", global 1-based vertex numbers).

#include "export_detail.h"

namespace aggpack::detail {

void write_obj(const ExportModel& model, std::ostream& out) {
  out << "# aggpack " AGGPACK_VERSION " packing, " << model.size() << " particles\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.surface_nodes(k, nodes);
    buffer += "o P" + std::to_string(model.particle_number(k)) + '\n';
    for (const Vec3& node : nodes) {
      buffer += 'v';
      for (int axis = 0; axis < 3; ++axis) {
        buffer += ' ';
        append_number(buffer, node[axis]);
      }
      buffer += '\n';
    }
    const std::uint64_t first = model.node_offset(k) + 1;
    for (const auto& t : model.triangles(k)) {
      buffer += 'f';
      for (auto index : t) {
        buffer += ' ';
        append_number(buffer, first + index);
      }
      buffer += '\n';
    }
  });
}

}  // namespace aggpack::detail
