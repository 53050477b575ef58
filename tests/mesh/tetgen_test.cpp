// TetGen through worker processes: shapes on which Debian's TetGen 1.5 aborts (fixtures from the
// paper's default packing) fail alone, are reported and fall back to a valid centroid fan; the
// quality switches keep slivers rare while the surface and volume stay exact.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/mesh/tetrahedra.h"
#include "aggpack/shape/generator.h"
#include "support/paths.h"
#include "support/poly_file.h"

namespace aggpack {
namespace {

#ifdef AGGPACK_HAS_TETGEN

// Shapes 324, 336, 599 and 988 of `aggpack pack -o paper.h5` (seed 1): TetGen 1.5 fails
// `Assertion 'nonconvex'` in finddirection on each (README.md in the folder).
const std::vector<std::string> kAbortFixtures = {"s00324", "s00336", "s00599", "s00988"};

ConvexPolyhedron abort_fixture(const std::string& name) {
  return test::read_poly(test::source_dir() + "/tests/mesh/fixtures/tetgen-abort/" + name +
                         ".poly");
}

// The surface triangles of the body, each as a sorted node triple, are exactly the mesh's faces
// used once, and the body's vertices are the first nodes, unmoved.
void expect_surface_kept(const TetMesh& mesh, const ConvexPolyhedron& body) {
  for (std::size_t i = 0; i < body.vertex_count(); ++i) {
    ASSERT_EQ(mesh.nodes[i], body.vertices()[i]);
  }
  std::multiset<std::array<std::uint32_t, 3>> faces;
  for (const Tetrahedron& tet : mesh.tetrahedra) {
    for (const auto& face : kTetraFaces) {
      std::array<std::uint32_t, 3> key{tet[face[0]], tet[face[1]], tet[face[2]]};
      std::sort(key.begin(), key.end());
      faces.insert(key);
    }
  }
  std::set<std::array<std::uint32_t, 3>> once;
  for (const auto& key : faces) {
    if (faces.count(key) == 1) once.insert(key);
  }
  std::set<std::array<std::uint32_t, 3>> surface;
  for (const Triangle& t : body.triangles()) {
    std::array<std::uint32_t, 3> key = t;
    std::sort(key.begin(), key.end());
    surface.insert(key);
  }
  EXPECT_EQ(once, surface);
}

// A valid mesh of the body: every tetrahedron positive, volumes summing to the body's.
void expect_valid(const TetMesh& mesh, const ConvexPolyhedron& body) {
  const double volume = mass_properties(body).volume;
  EXPECT_GT(min_tetra_volume(mesh), 0.0);
  EXPECT_NEAR(mesh_volume(mesh), volume, 1e-12 * volume);
}

TEST(TetGenIsolated, AbortingShapesFailAloneAndFallBackToAValidFan) {
  // The failing shapes between shapes TetGen meshes, so the workers must carry on after each.
  std::vector<ConvexPolyhedron> bodies;
  std::vector<bool> is_abort_fixture;
  for (std::size_t i = 0; i < kAbortFixtures.size(); ++i) {
    bodies.push_back(generate_particle({.alpha = 0.5, .seed = 3}, i).body);
    is_abort_fixture.push_back(false);
    bodies.push_back(abort_fixture(kAbortFixtures[i]));
    is_abort_fixture.push_back(true);
  }
  std::vector<const ConvexPolyhedron*> pointers;
  for (const auto& body : bodies) pointers.push_back(&body);
  const TetOptions options{.method = TetMethod::kTetGen};
  const std::vector<TetGenOutcome> outcomes = tetgen_meshes(pointers, options);
  ASSERT_EQ(outcomes.size(), bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const TetGenOutcome& outcome = outcomes[i];
    if (is_abort_fixture[i]) {
      // If a newer TetGen meshes these, the fallback needs other fixtures to stay tested.
      EXPECT_FALSE(outcome.is_meshed) << "TetGen no longer fails on fixture " << i / 2;
      EXPECT_EQ(outcome.failure, "TetGen died of signal 6 (Aborted)");
      EXPECT_TRUE(outcome.mesh.tetrahedra.empty());
      // What the exporters put in its place.
      const TetMesh fan = centroid_fan(bodies[i]);
      EXPECT_EQ(fan.tetrahedra.size(), bodies[i].triangle_count());
      expect_valid(fan, bodies[i]);
      expect_surface_kept(fan, bodies[i]);
    } else {
      ASSERT_TRUE(outcome.is_meshed) << outcome.failure;
      EXPECT_TRUE(outcome.failure.empty());
      expect_valid(outcome.mesh, bodies[i]);
      expect_surface_kept(outcome.mesh, bodies[i]);
      // The same mesh as TetGen makes for the shape alone.
      const TetMesh alone = tetgen_mesh(bodies[i], options);
      EXPECT_EQ(outcome.mesh.nodes, alone.nodes);
      EXPECT_EQ(outcome.mesh.tetrahedra, alone.tetrahedra);
      EXPECT_EQ(outcome.mesh.boundary_faces, alone.boundary_faces);
    }
  }
}

TEST(TetGenIsolated, SingleShapeFailureIsALimitExceededError) {
  try {
    (void)tetgen_mesh(abort_fixture(kAbortFixtures[0]), {.method = TetMethod::kTetGen});
    FAIL() << "TetGen meshed fixture " << kAbortFixtures[0];
  } catch (const LimitExceeded& error) {
    EXPECT_NE(std::string(error.what()).find("TetGen died of signal 6 (Aborted)"),
              std::string::npos)
        << error.what();
  }
  EXPECT_THROW((void)tetgen_mesh(abort_fixture(kAbortFixtures[0]),
                                 {.method = TetMethod::kTetGen, .time_limit = 0.0}),
               InvalidInput);
}

TEST(TetGenIsolated, ShapeTetGenNeverFinishesIsStoppedAtTheTimeLimit) {
  const ConvexPolyhedron hang =
      test::read_poly(test::source_dir() + "/tests/mesh/fixtures/tetgen-hang/s06534.poly");
  const ConvexPolyhedron good = generate_particle({.alpha = 0.5, .seed = 3}, 0).body;
  const std::vector<const ConvexPolyhedron*> bodies = {&hang, &good};
  // One second instead of the default 20 s keeps the test short; TetGen takes milliseconds on
  // `good` and never finishes `hang` (fixture README).
  const std::vector<TetGenOutcome> outcomes =
      tetgen_meshes(bodies, {.method = TetMethod::kTetGen, .time_limit = 1.0});
  EXPECT_FALSE(outcomes[0].is_meshed);
  EXPECT_EQ(outcomes[0].failure, "TetGen timed out after 1 s");
  ASSERT_TRUE(outcomes[1].is_meshed) << outcomes[1].failure;
  expect_valid(outcomes[1].mesh, good);
  expect_valid(centroid_fan(hang), hang);
}

// Smallest dihedral angle of a tetrahedron (degrees): 180 minus the angle between the outward
// normals of the two faces at each edge.
double min_dihedral_degrees(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const std::array<Vec3, 4> p = {a, b, c, d};
  std::array<Vec3, 4> normals;
  for (int i = 0; i < 4; ++i) {
    const Vec3& q0 = p[(i + 1) % 4];
    Vec3 normal = (p[(i + 2) % 4] - q0).cross(p[(i + 3) % 4] - q0);
    if (normal.dot(p[i] - q0) > 0) normal = -normal;  // away from the opposite corner
    normals[i] = normal.normalized();
  }
  double smallest = 180.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const double cosine = std::clamp(-normals[i].dot(normals[j]), -1.0, 1.0);
      smallest = std::min(smallest, std::acos(cosine) * 180.0 / std::numbers::pi);
    }
  }
  return smallest;
}

// TetGen keeps each particle's surface, so a surface triangle's small angles bound the
// tetrahedra beside it. Measured (300 particles, L = r = 0.1 m): midpoint growth 11,145
// tetrahedra, 4 below 10 degrees (0.036 %; without the angle switches, q ratio only, 163 of
// 11,702, 1.4 %); hull growth, whose random points leave thin surface triangles (0.5 % of the
// surface angles below 10 degrees at L = r, none under the midpoint rule), more: the bound below.
// Shapes TetGen fails on (5 of 300 here) are the fallback's business, tested above.
void expect_few_slivers(Growth growth, double max_fraction) {
  std::vector<ConvexPolyhedron> bodies;
  for (const double alpha : {0.3, 0.5, 0.8}) {
    for (std::uint64_t index = 0; index < 100; ++index) {
      bodies.push_back(
          generate_particle({.alpha = alpha, .seed = 17, .form = {.growth = growth}}, index).body);
    }
  }
  std::vector<const ConvexPolyhedron*> pointers;
  for (const auto& body : bodies) pointers.push_back(&body);
  const std::vector<TetGenOutcome> outcomes =
      tetgen_meshes(pointers, {.method = TetMethod::kTetGen});
  std::size_t tetrahedra = 0;
  std::size_t slivers = 0;
  std::size_t failed = 0;
  double smallest = 180.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!outcomes[i].is_meshed) {
      ++failed;
      continue;
    }
    const TetMesh& mesh = outcomes[i].mesh;
    expect_valid(mesh, bodies[i]);
    expect_surface_kept(mesh, bodies[i]);
    for (const Tetrahedron& t : mesh.tetrahedra) {
      const double angle = min_dihedral_degrees(mesh.nodes[t[0]], mesh.nodes[t[1]],
                                                mesh.nodes[t[2]], mesh.nodes[t[3]]);
      smallest = std::min(smallest, angle);
      if (angle < 10.0) ++slivers;
    }
    tetrahedra += mesh.tetrahedra.size();
  }
  const double fraction = static_cast<double>(slivers) / static_cast<double>(tetrahedra);
  std::printf(
      "%s growth: %zu tetrahedra, %zu below 10 degrees (%.3f %%), smallest %.2f deg, "
      "%zu of %zu shapes fell back\n",
      growth_name(growth), tetrahedra, slivers, 100.0 * fraction, smallest, failed, bodies.size());
  EXPECT_LE(failed, bodies.size() / 50);
  EXPECT_GT(tetrahedra, 10000U);
  EXPECT_LT(fraction, max_fraction) << slivers << " of " << tetrahedra << " below 10 degrees";
}

TEST(TetGenQuality, FewSliversAndExactSurfaceOverGeneratedShapes) {
  expect_few_slivers(Growth::kMidpoint, 0.001);
  expect_few_slivers(Growth::kHull, 0.025);
}

#endif

}  // namespace
}  // namespace aggpack
