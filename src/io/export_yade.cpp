// YADE script (.py): rebuilds the packing as Polyhedra bodies (yade.polyhedra_utils.polyhedra,
// which takes world-coordinate vertices, builds their convex hull and sets the body's position,
// orientation, mass and inertia from it). Run with `yade file.py`.

#include <cstdio>

#include "export_detail.h"

namespace aggpack::detail {

void write_yade(const ExportModel& model, std::ostream& out) {
  const MaterialOptions& material = model.options().material;
  std::string head = "# aggpack " AGGPACK_VERSION " packing, " + std::to_string(model.size()) +
                     " particles, rebuilt as YADE polyhedra.\n# Run with: yade this_file.py\n";
  char line[160];
  std::snprintf(line, sizeof line, "# Coordinates in metres times %.17g.\n", model.options().scale);
  head += line;
  head += "from yade import polyhedra_utils\n\nmaterial = PolyhedraMat(label='" + material.name +
          "', density=";
  append_number(head, material.density);
  head += ", young=";
  append_number(head, material.youngs_modulus);
  head += ", poisson=";
  append_number(head, material.poisson_ratio);
  head +=
      ")\nO.materials.append(material)\n\n"
      "# One entry per particle (particle i+1 of the packing): its vertices in world "
      "coordinates.\nparticles = [\n";
  out << head;
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.surface_nodes(k, nodes);
    buffer += "    [";
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      buffer += i == 0 ? "(" : ", (";
      for (int axis = 0; axis < 3; ++axis) {
        if (axis > 0) buffer += ", ";
        append_number(buffer, nodes[i][axis]);
      }
      buffer += ')';
    }
    buffer += "],\n";
  });
  out << "]\n\nfor vertices in particles:\n"
         "    O.bodies.append(polyhedra_utils.polyhedra(material, v=vertices))\n";
}

}  // namespace aggpack::detail
