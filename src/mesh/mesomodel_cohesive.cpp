// The cohesive ITZ (mesh/mesomodel.h, ItzKind::kCohesive): the bonded aggregate + mortar mesh cut
// open along every aggregate's surface and closed again by zero-thickness 6-node wedges.

#include <algorithm>
#include <cmath>
#include <limits>

#include "aggpack/core/error.h"
#include "aggpack/mesh/mesomodel.h"
#include "mesomodel_plc.h"

namespace aggpack {

namespace {

// One face of a tetrahedron, keyed by its sorted nodes.
struct FaceRecord {
  std::array<std::uint32_t, 3> key;
  std::uint32_t tetrahedron;
  std::uint8_t face;  // kTetraFaces index
};

}  // namespace

namespace detail {

void check_cohesive_thickness(double thickness) {
  if (!(thickness > 0.0) || !std::isfinite(thickness)) {
    throw InvalidInput(
        "itz_thickness", format_value(thickness),
        "> 0 (m) for a cohesive ITZ (the cohesive elements' constitutive thickness)");
  }
}

}  // namespace detail

void split_cohesive_interfaces(MesoMesh& mesh, double thickness) {
  detail::check_cohesive_thickness(thickness);
  if (!mesh.cohesive.empty() ||
      std::find(mesh.phase.begin(), mesh.phase.end(), MesoPhase::kItz) != mesh.phase.end()) {
    throw InvalidInput("mesh", "an ITZ already (tetrahedra or cohesive elements)",
                       "a bonded mesh of aggregate and mortar tetrahedra");
  }
  mesh.itz_thickness = thickness;
  const std::size_t count = mesh.tetrahedra.size();
  // Faces of aggregate and mortar tetrahedra; a face of both kinds is an interface triangle.
  std::vector<FaceRecord> faces;
  faces.reserve(4 * count);
  for (std::uint32_t e = 0; e < count; ++e) {
    for (std::uint8_t f = 0; f < 4; ++f) {
      const Tetrahedron& t = mesh.tetrahedra[e];
      std::array<std::uint32_t, 3> key = {t[kTetraFaces[f][0]], t[kTetraFaces[f][1]],
                                          t[kTetraFaces[f][2]]};
      std::sort(key.begin(), key.end());
      faces.push_back({key, e, f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const FaceRecord& a, const FaceRecord& b) {
    return std::tie(a.key, a.tetrahedron, a.face) < std::tie(b.key, b.tetrahedron, b.face);
  });
  // (aggregate tetrahedron, its face) of every interface triangle.
  std::vector<std::pair<std::uint32_t, std::uint8_t>> interface;
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i].key != faces[i + 1].key) continue;
    const FaceRecord& a = faces[i];
    const FaceRecord& b = faces[i + 1];
    const MesoPhase pa = mesh.phase[a.tetrahedron];
    const MesoPhase pb = mesh.phase[b.tetrahedron];
    if (pa == MesoPhase::kAggregate && pb == MesoPhase::kMortar) {
      interface.emplace_back(a.tetrahedron, a.face);
    } else if (pb == MesoPhase::kAggregate && pa == MesoPhase::kMortar) {
      interface.emplace_back(b.tetrahedron, b.face);
    }
  }
  faces = {};
  std::sort(interface.begin(), interface.end(), [&](const auto& a, const auto& b) {
    return std::tie(mesh.particle[a.first], a) < std::tie(mesh.particle[b.first], b);
  });

  // Nodes used on both sides get a mortar-side copy.
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint8_t> sides(mesh.nodes.size(), 0);   // bit 0 aggregate, bit 1 mortar
  std::vector<std::uint32_t> owner(mesh.nodes.size(), 0);  // the aggregate's particle
  for (std::size_t e = 0; e < count; ++e) {
    const bool is_aggregate = mesh.phase[e] == MesoPhase::kAggregate;
    for (const std::uint32_t node : mesh.tetrahedra[e]) {
      sides[node] |= is_aggregate ? 1 : 2;
      if (!is_aggregate) continue;
      const std::uint32_t particle = mesh.particle[e];
      if (owner[node] != 0 && owner[node] != particle) {
        throw InvalidInput("mesh",
                           "aggregates " + std::to_string(std::min(owner[node], particle)) +
                               " and " + std::to_string(std::max(owner[node], particle)) +
                               " share node " + std::to_string(node + 1),
                           "aggregates apart (a cohesive interface joins one aggregate to mortar)");
      }
      owner[node] = particle;
    }
  }
  const std::size_t shared = static_cast<std::size_t>(std::count(sides.begin(), sides.end(), 3));
  if (mesh.nodes.size() + shared > std::numeric_limits<std::uint32_t>::max()) {
    throw LimitExceeded("cohesive ITZ nodes", std::to_string(mesh.nodes.size() + shared), "< 2^32");
  }
  std::vector<std::uint32_t> copy(mesh.nodes.size(), kNone);
  mesh.nodes.reserve(mesh.nodes.size() + shared);
  for (std::size_t n = 0; n < sides.size(); ++n) {
    if (sides[n] != 3) continue;
    copy[n] = static_cast<std::uint32_t>(mesh.nodes.size());
    mesh.nodes.push_back(mesh.nodes[n]);
  }
  for (std::size_t e = 0; e < count; ++e) {
    if (mesh.phase[e] != MesoPhase::kMortar) continue;
    for (std::uint32_t& node : mesh.tetrahedra[e]) {
      if (node < copy.size() && copy[node] != kNone) node = copy[node];
    }
  }

  mesh.cohesive.clear();
  mesh.cohesive_particle.clear();
  mesh.cohesive.reserve(interface.size());
  mesh.cohesive_particle.reserve(interface.size());
  for (const auto& [e, f] : interface) {
    const Tetrahedron& t = mesh.tetrahedra[e];
    // The aggregate tetrahedron's face has its right-hand normal pointing into the aggregate
    // (tetrahedra.h); reversed, it points out, into the mortar: bottom to top of the wedge.
    const std::uint32_t a = t[kTetraFaces[f][0]];
    const std::uint32_t b = t[kTetraFaces[f][2]];
    const std::uint32_t c = t[kTetraFaces[f][1]];
    mesh.cohesive.push_back({a, b, c, copy[a], copy[b], copy[c]});
    mesh.cohesive_particle.push_back(mesh.particle[e]);
  }
}

}  // namespace aggpack
