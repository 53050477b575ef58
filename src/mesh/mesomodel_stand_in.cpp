// STAND-IN for src/mesh/mesomodel.cpp (branch meso-io, issue 16): weak definitions of the two
// mesomodel.h functions the file writers use, so that the writers and their tests link before the
// mesher lands. The mesher's strong definitions replace these at link time; delete this file once
// src/mesh/mesomodel.cpp defines phase_set_name and face_nodes.

#include <cmath>

#include "aggpack/mesh/mesomodel.h"

namespace aggpack {

__attribute__((weak)) const char* phase_set_name(MesoPhase phase) {
  switch (phase) {
    case MesoPhase::kAggregate:
      return "AGGREGATE";
    case MesoPhase::kItz:
      return "ITZ";
    case MesoPhase::kMortar:
      break;
  }
  return "MORTAR";
}

__attribute__((weak)) std::vector<std::uint32_t> face_nodes(const MesoMesh& mesh,
                                                            SpecimenFace face) {
  const Vec3 extent = mesh.bounds.upper - mesh.bounds.lower;
  const double tolerance = 1e-9 * extent.maxCoeff();
  std::vector<std::uint32_t> nodes;
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const Vec3& p = mesh.nodes[i];
    bool is_on = false;
    switch (face) {
      case SpecimenFace::kBottom:
        is_on = std::abs(p.z() - mesh.bounds.lower.z()) <= tolerance;
        break;
      case SpecimenFace::kTop:
        is_on = std::abs(p.z() - mesh.bounds.upper.z()) <= tolerance;
        break;
      case SpecimenFace::kSide:
        if (mesh.is_cylinder) {
          const double r = std::hypot(p.x() - mesh.axis_point.x(), p.y() - mesh.axis_point.y());
          is_on = r >= mesh.cylinder_radius - tolerance;
        } else {
          for (int axis = 0; axis < 2; ++axis) {
            is_on = is_on || std::abs(p[axis] - mesh.bounds.lower[axis]) <= tolerance ||
                    std::abs(p[axis] - mesh.bounds.upper[axis]) <= tolerance;
          }
        }
        break;
    }
    if (is_on) nodes.push_back(static_cast<std::uint32_t>(i));
  }
  return nodes;
}

}  // namespace aggpack
