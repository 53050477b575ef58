// The periodic mesomodel (mesh/mesomodel.h with a periodic box): nodes on opposite faces pair up
// exactly (edges and corners included), the mesh fills the box, the aggregate phase is exactly
// the particles' volume (their clipped images add up to it), the refusals, and determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/pack/random_packer.h"
#include "support/packings.h"

namespace aggpack {
namespace {

Packing periodic_rve_packing(std::array<bool, 3> axes, std::uint64_t seed) {
  const RandomPackOptions options{
      .container = {.shape =
                        BoxContainer{
                            .length = 0.1, .width = 0.08, .depth = 0.09, .periodic = axes}},
      .grading = {.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.02},
      .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
      .target = PackTarget::kVolumeFraction,
      .volume_fraction = 0.3,
      .gap = 0.001,
      .seed = seed};
  return pack_random(options).packing;
}

// For every periodic axis: the nodes on the lower face and on the upper face, each matched to
// exactly one node of the other face at the same in-plane coordinates (within 1e-9 of the box).
void expect_faces_pair_up(const MesoMesh& mesh) {
  const Vec3 extent = mesh.bounds.extent();
  const double tolerance = 1e-9 * extent.maxCoeff();
  for (int axis = 0; axis < 3; ++axis) {
    if (!mesh.periodic[static_cast<std::size_t>(axis)]) continue;
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    std::array<std::vector<Vec3>, 2> sides;
    for (const Vec3& p : mesh.nodes) {
      if (std::abs(p[axis] - mesh.bounds.lower[axis]) <= tolerance) sides[0].push_back(p);
      if (std::abs(p[axis] - mesh.bounds.upper[axis]) <= tolerance) sides[1].push_back(p);
    }
    ASSERT_GT(sides[0].size(), 10U);
    EXPECT_EQ(sides[0].size(), sides[1].size()) << "axis " << axis;
    std::size_t edge_nodes = 0;
    for (int side = 0; side < 2; ++side) {
      for (const Vec3& p : sides[static_cast<std::size_t>(side)]) {
        int partners = 0;
        for (const Vec3& q : sides[static_cast<std::size_t>(1 - side)]) {
          partners += std::abs(p[u] - q[u]) <= tolerance && std::abs(p[v] - q[v]) <= tolerance;
        }
        EXPECT_EQ(partners, 1) << "axis " << axis << " node (" << p.transpose() << ")";
        const bool is_on_edge = std::min(std::abs(p[u]), std::abs(p[u] - extent[u])) <= tolerance ||
                                std::min(std::abs(p[v]), std::abs(p[v] - extent[v])) <= tolerance;
        edge_nodes += is_on_edge;
      }
    }
    EXPECT_GE(edge_nodes, 8U) << "the corners at least";
  }
}

// The boundary triangles on each lower periodic face, moved onto the upper face, are exactly the
// upper face's triangles (so a homogeneous box takes an affine field under periodic ties).
void expect_faces_triangulated_alike(const MesoMesh& mesh) {
  std::map<std::array<std::uint32_t, 3>, int> faces;
  for (const Tetrahedron& tet : mesh.tetrahedra) {
    for (const auto& local : kTetraFaces) {
      std::array<std::uint32_t, 3> key{tet[local[0]], tet[local[1]], tet[local[2]]};
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (!mesh.periodic[static_cast<std::size_t>(axis)]) continue;
    std::array<std::vector<std::array<std::array<double, 3>, 3>>, 2> sides;
    for (const auto& [key, count] : faces) {
      if (count != 1) continue;
      for (int side = 0; side < 2; ++side) {
        const double at = side == 0 ? mesh.bounds.lower[axis] : mesh.bounds.upper[axis];
        if (!std::all_of(key.begin(), key.end(),
                         [&](std::uint32_t k) { return mesh.nodes[k][axis] == at; })) {
          continue;
        }
        std::array<std::array<double, 3>, 3> corners{};
        for (int c = 0; c < 3; ++c) {
          const Vec3& p = mesh.nodes[key[static_cast<std::size_t>(c)]];
          corners[static_cast<std::size_t>(c)] = {p.x(), p.y(), p.z()};
          corners[static_cast<std::size_t>(c)][static_cast<std::size_t>(axis)] = 0.0;
        }
        std::sort(corners.begin(), corners.end());
        sides[static_cast<std::size_t>(side)].push_back(corners);
      }
    }
    std::sort(sides[0].begin(), sides[0].end());
    std::sort(sides[1].begin(), sides[1].end());
    EXPECT_GT(sides[0].size(), 10U);
    EXPECT_TRUE(sides[0] == sides[1])
        << "axis " << axis << ": " << sides[0].size() << " vs " << sides[1].size() << " triangles";
  }
}

double particle_volume(const Packing& packing) {
  double volume = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    volume += mass_properties(packing.placed(i)).volume;
  }
  return volume;
}

TEST(PeriodicMesomodel, OppositeFacesPairUpAndTheVolumesAreExact) {
  for (const std::array<bool, 3>& axes :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true}}) {
    for (const std::uint64_t seed : {3U, 8U}) {
      const Packing packing = periodic_rve_packing(axes, seed);
      ASSERT_GT(packing.particles.size(), 5U);
      MesoReport report;
      const MesoMesh mesh = build_mesomodel(packing, {}, &report);
      EXPECT_EQ(mesh.periodic, axes);
      expect_faces_pair_up(mesh);
      expect_faces_triangulated_alike(mesh);
      const Vec3 extent = mesh.bounds.extent();
      const double box = extent.prod();
      double total = 0.0;
      double aggregate = 0.0;
      std::size_t crossing = 0;
      std::map<std::uint32_t, int> pieces;
      for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
        const Tetrahedron& t = mesh.tetrahedra[e];
        const double v =
            tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
        ASSERT_GT(v, 0.0);
        total += v;
        if (mesh.phase[e] == MesoPhase::kAggregate) aggregate += v;
      }
      for (std::size_t i = 0; i < packing.particles.size(); ++i) {
        const Aabb b = packing.placed(i).bounds();
        crossing += (b.lower.array() < 0.0).any() || (b.upper.array() > extent.array()).any();
      }
      EXPECT_GT(crossing, 2U) << "the test needs particles that cross faces";
      EXPECT_NEAR(total / box, 1.0, 1e-9);
      // Each particle's clipped images add up to the particle: the aggregate phase is exactly the
      // particles' volume, measured independently of the mesher.
      EXPECT_NEAR(aggregate / particle_volume(packing), 1.0, 1e-9);
      const auto& phase = report.phases[static_cast<int>(MesoPhase::kAggregate)];
      EXPECT_NEAR(phase.expected_volume / particle_volume(packing), 1.0, 1e-9);
      EXPECT_EQ(report.relabelled_tetrahedra, 0U);
    }
  }
}

TEST(PeriodicMesomodel, TenSeedsOfATouchingPackingMesh) {
  // No packer gap, many particles crossing faces and edges: TetGen once aborted on 2 of 8 such
  // packings (a face triangulated into overlapping triangles).
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const RandomPackOptions options{
        .container = {.shape = BoxContainer{.length = 0.04,
                                            .width = 0.04,
                                            .depth = 0.04,
                                            .periodic = {true, true, true}}},
        .grading = {.kind = GradingKind::kUniform, .radius_min = 0.006, .radius_max = 0.012},
        .target = PackTarget::kVolumeFraction,
        .volume_fraction = 0.25,
        .seed = seed};
    const Packing packing = pack_random(options).packing;
    MesoMesh mesh;
    try {
      mesh = build_mesomodel(packing, {});
    } catch (const Error& error) {
      ADD_FAILURE() << "seed " << seed << ": " << error.what();
      continue;
    }
    expect_faces_pair_up(mesh);
    double aggregate = 0.0;
    for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
      const Tetrahedron& t = mesh.tetrahedra[e];
      if (mesh.phase[e] != MesoPhase::kAggregate) continue;
      aggregate +=
          tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
    }
    EXPECT_NEAR(aggregate / particle_volume(packing), 1.0, 1e-9) << "seed " << seed;
  }
}

TEST(PeriodicMesomodel, SameResultAtOneAndTwoThreads) {
  const Packing packing = periodic_rve_packing({true, true, true}, 5);
  const MesoMesh one = test::with_threads(1, [&] { return build_mesomodel(packing, {}); });
  const MesoMesh two = test::with_threads(2, [&] { return build_mesomodel(packing, {}); });
  ASSERT_EQ(one.nodes.size(), two.nodes.size());
  EXPECT_TRUE(one.nodes == two.nodes);
  EXPECT_TRUE(one.tetrahedra == two.tetrahedra);
  EXPECT_TRUE(one.particle == two.particle);
}

TEST(PeriodicMesomodel, RefusesAnItzNamingTheKey) {
  const Packing packing = periodic_rve_packing({true, true, true}, 5);
  for (const ItzKind kind : {ItzKind::kSolid, ItzKind::kCohesive}) {
    try {
      (void)build_mesomodel(packing, {.itz_thickness = 1e-4, .itz_kind = kind});
      ADD_FAILURE() << "an ITZ in a periodic box was accepted";
    } catch (const InvalidInput& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("itz_thickness = 0.0001"), std::string::npos) << message;
      EXPECT_NE(message.find("container.periodic"), std::string::npos) << message;
    }
  }
}

TEST(PeriodicMesomodel, RefusesAVertexOnAPeriodicFace) {
  Packing packing = test::box_with(1.0, {make_box(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1))},
                                   {Vec3(0.1, 0.5, 0.5)});
  std::get<BoxContainer>(packing.container.shape).periodic = {true, true, true};
  try {
    (void)build_mesomodel(packing, {});
    ADD_FAILURE() << "a vertex on a periodic face was accepted";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("particle 1 = 0 m from a periodic face"),
              std::string::npos)
        << error.what();
  }
  // A walled axis keeps the walled box's rule: a particle crossing the wall is refused.
  std::get<BoxContainer>(packing.container.shape).periodic = {false, true, true};
  EXPECT_THROW((void)build_mesomodel(packing, {}), InvalidInput);
  std::get<BoxContainer>(packing.container.shape).periodic = {true, true, true};
  // Moved off the face it meshes: one cube cut in two by x = 0.
  packing.particles[0].pose.position.x() = 0.05;
  const MesoMesh mesh = build_mesomodel(packing, {});
  expect_faces_pair_up(mesh);
  double aggregate = 0.0;
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = mesh.tetrahedra[e];
    if (mesh.phase[e] != MesoPhase::kAggregate) continue;
    aggregate +=
        tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
  }
  EXPECT_NEAR(aggregate, 0.008, 1e-15);
}

}  // namespace
}  // namespace aggpack
