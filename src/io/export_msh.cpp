// Gmsh MSH 4.1, ASCII. One geometric entity per particle (a volume for tetrahedra, a surface for
// triangles) with a physical group of the same tag named "P<id>", so Gmsh and solvers that read
// physical groups (Elmer, FEniCS via meshio, ...) see one region per particle.

#include "export_detail.h"

namespace aggpack::detail {

namespace {

constexpr int kGmshTriangle = 2;
constexpr int kGmshTetrahedron = 4;

}  // namespace

void write_gmsh(const ExportModel& model, std::ostream& out) {
  require_ids_fit(model, 0x7FFFFFFF, "Gmsh");
  const bool is_surface = model.mode() == ElementMode::kSurface;
  const int dimension = is_surface ? 2 : 3;
  const std::string dim = std::to_string(dimension);

  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n" << model.size() << '\n';
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::string tag = std::to_string(model.particle_number(k));
    buffer += dim + ' ' + tag + " \"P" + tag + "\"\n";
  });
  out << "$EndPhysicalNames\n$Entities\n"
      << (is_surface ? "0 0 " + std::to_string(model.size()) + " 0\n"
                     : "0 0 0 " + std::to_string(model.size()) + "\n");
  // Entity line: tag, bounding box, 1 physical tag (= entity tag), 0 bounding entities.
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    Aabb box;
    for (const Vec3& node : nodes) box.expand(node);
    const std::uint64_t tag = model.particle_number(k);
    append_number(buffer, tag);
    for (const Vec3* corner : {&box.lower, &box.upper}) {
      for (int axis = 0; axis < 3; ++axis) {
        buffer += ' ';
        append_number(buffer, (*corner)[axis]);
      }
    }
    buffer += " 1 ";
    append_number(buffer, tag);
    buffer += " 0\n";
  });
  out << "$EndEntities\n$Nodes\n"
      << model.size() << ' ' << model.node_count() << " 1 " << model.node_count() << '\n';
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    buffer += dim + ' ' + std::to_string(model.particle_number(k)) + " 0 " +
              std::to_string(nodes.size()) + '\n';
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      append_number(buffer, model.node_offset(k) + i + 1);
      buffer += '\n';
    }
    for (const Vec3& node : nodes) {
      append_number(buffer, node.x());
      buffer += ' ';
      append_number(buffer, node.y());
      buffer += ' ';
      append_number(buffer, node.z());
      buffer += '\n';
    }
  });
  out << "$EndNodes\n$Elements\n"
      << model.size() << ' ' << model.element_count() << " 1 " << model.element_count() << '\n';
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::uint64_t first_node = model.node_offset(k) + 1;
    const std::uint64_t first_element = model.element_offset(k) + 1;
    buffer += dim + ' ' + std::to_string(model.particle_number(k)) + ' ' +
              std::to_string(is_surface ? kGmshTriangle : kGmshTetrahedron) + ' ' +
              std::to_string(model.elements_of(k)) + '\n';
    if (is_surface) {
      append_element_lines(buffer, "", " ", first_element, first_node, model.triangles(k));
    } else {
      std::vector<Tetrahedron> scratch;
      append_element_lines(buffer, "", " ", first_element, first_node,
                           model.tetrahedra(k, scratch));
    }
  });
  out << "$EndElements\n";
}

}  // namespace aggpack::detail
