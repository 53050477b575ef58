// What a finished mesomodel holds (mesh/mesomodel.h): each phase's meshed volume, nodes and
// element quality, the cohesive interface's area, and the node sets of the specimen's faces.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/pack/container.h"

namespace aggpack {

MesoReport measure_mesomodel(const MesoMesh& mesh) {
  MesoReport report;
  std::array<std::vector<Tetrahedron>, 3> by_phase;
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    by_phase[static_cast<int>(mesh.phase[e])].push_back(mesh.tetrahedra[e]);
  }
  for (int p = 0; p < 3; ++p) {
    MesoPhaseReport& phase = report.phases[p];
    std::vector<std::uint8_t> is_used(mesh.nodes.size(), 0);
    for (const Tetrahedron& tet : by_phase[p]) {
      phase.meshed_volume += tetra_volume(mesh.nodes[tet[0]], mesh.nodes[tet[1]],
                                          mesh.nodes[tet[2]], mesh.nodes[tet[3]]);
      for (const std::uint32_t node : tet) is_used[node] = 1;
    }
    phase.nodes = static_cast<std::uint64_t>(std::count(is_used.begin(), is_used.end(), 1));
    phase.quality = measure_quality(mesh.nodes, by_phase[p]);
  }
  MesoPhaseReport& itz = report.phases[static_cast<int>(MesoPhase::kItz)];
  std::vector<std::uint8_t> is_used(mesh.cohesive.empty() ? 0 : mesh.nodes.size(), 0);
  for (const CohesiveWedge& wedge : mesh.cohesive) {
    const Vec3& a = mesh.nodes[wedge[0]];
    report.interface_area +=
        0.5 * (mesh.nodes[wedge[1]] - a).cross(mesh.nodes[wedge[2]] - a).norm();
    for (const std::uint32_t node : wedge) is_used[node] = 1;
  }
  report.cohesive_elements = mesh.cohesive.size();
  itz.nodes += static_cast<std::uint64_t>(std::count(is_used.begin(), is_used.end(), 1));
  return report;
}

std::vector<std::uint32_t> face_nodes(const MesoMesh& mesh, SpecimenFace face) {
  const double tolerance = 1e-9 * mesh.bounds.extent().maxCoeff();
  std::vector<std::uint32_t> nodes;
  for (std::uint32_t i = 0; i < mesh.nodes.size(); ++i) {
    const Vec3& p = mesh.nodes[i];
    const bool is_bottom = p.z() <= mesh.bounds.lower.z() + tolerance;
    const bool is_top = p.z() >= mesh.bounds.upper.z() - tolerance;
    const bool is_side = is_on_prism_side(mesh.container, p, mesh.prism_sides, tolerance);
    const bool is_wanted = face == SpecimenFace::kBottom ? is_bottom
                           : face == SpecimenFace::kTop  ? is_top
                                                         : is_side;
    if (is_wanted) nodes.push_back(i);
  }
  return nodes;
}

std::vector<PeriodicPair> periodic_pairs(const MesoMesh& mesh) {
  std::vector<PeriodicPair> pairs;
  if (!(mesh.periodic[0] || mesh.periodic[1] || mesh.periodic[2])) return pairs;
  // The mesher made every upper-face point the exact translation of its partner: exact keys.
  std::map<std::array<double, 3>, std::uint32_t> lower;
  for (std::uint32_t i = 0; i < mesh.nodes.size(); ++i) {
    const Vec3& p = mesh.nodes[i];
    lower.try_emplace({p.x(), p.y(), p.z()}, i);
  }
  for (std::uint32_t i = 0; i < mesh.nodes.size(); ++i) {
    PeriodicPair pair{.node = i};
    Vec3 image = mesh.nodes[i];
    bool is_upper = false;
    for (int axis = 0; axis < 3; ++axis) {
      if (mesh.periodic[static_cast<std::size_t>(axis)] && image[axis] == mesh.bounds.upper[axis]) {
        image[axis] = mesh.bounds.lower[axis];
        pair.shifted[static_cast<std::size_t>(axis)] = true;
        is_upper = true;
      }
    }
    if (!is_upper) continue;
    const auto found = lower.find({image.x(), image.y(), image.z()});
    if (found == lower.end()) {
      throw LimitExceeded(Wording{Sentence::kMesomodelMesh, {}},
                          Wording{Sentence::kPeriodicNodeNoPartner, {std::to_string(i + 1)}},
                          Wording{Sentence::kAPeriodicMesh, {}});
    }
    pair.image = found->second;
    pairs.push_back(pair);
  }
  return pairs;
}

}  // namespace aggpack
