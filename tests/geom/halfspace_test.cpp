// Clipping by half-spaces and the mitred offset (geom/halfspace.h), against exact solids.

#include "aggpack/geom/halfspace.h"

#include <gtest/gtest.h>

#include <cmath>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"

namespace aggpack {
namespace {

void expect_valid(const ConvexPolyhedron& body, double tolerance = 1e-12) {
  const CheckResult manifold = check_closed_manifold(body);
  EXPECT_TRUE(manifold.is_ok) << manifold.message;
  const CheckResult convex = check_convex(body, tolerance);
  EXPECT_TRUE(convex.is_ok) << convex.message;
}

TEST(HalfSpaceClip, CubeCutByAPlaneAndACorner) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const HalfSpace half{Vec3::UnitX(), 0.3};
  const ConvexPolyhedron slab = clip(cube, {&half, 1}, 1e-12);
  expect_valid(slab);
  EXPECT_NEAR(mass_properties(slab).volume, 0.3, 1e-15);
  // Cutting off the corner (1,1,1) by x + y + z <= 2.5 removes a tetrahedron of legs 0.5.
  const HalfSpace corner{Vec3::Ones().normalized(), 2.5 / std::sqrt(3.0)};
  const ConvexPolyhedron cut = clip(cube, {&corner, 1}, 1e-12);
  expect_valid(cut);
  EXPECT_NEAR(mass_properties(cut).volume, 1.0 - 0.125 / 6.0, 1e-14);
  EXPECT_EQ(cut.vertex_count(), 10U);
}

TEST(HalfSpaceClip, PlaneMissingOrSwallowingTheBody) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const HalfSpace far{Vec3::UnitZ(), 2.0};
  EXPECT_EQ(clip(cube, {&far, 1}, 1e-12).vertices(), cube.vertices());
  const HalfSpace below{Vec3::UnitZ(), -0.5};
  EXPECT_TRUE(clip(cube, {&below, 1}, 1e-12).is_empty());
  // A plane through a face (within tolerance) leaves the cube as it is.
  const HalfSpace flush{Vec3::UnitZ(), 1.0 + 1e-14};
  EXPECT_NEAR(mass_properties(clip(cube, {&flush, 1}, 1e-12)).volume, 1.0, 1e-15);
  const HalfSpace bad{Vec3(1, 1, 0), 0.0};
  EXPECT_THROW((void)clip(cube, {&bad, 1}, 1e-12), InvalidInput);
}

TEST(MitredOffset, CubeGrowsByTwiceTheThickness) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const ConvexPolyhedron offset = mitred_offset(cube, 0.1, {}, 1e-9);
  expect_valid(offset);
  EXPECT_NEAR(mass_properties(offset).volume, 1.2 * 1.2 * 1.2, 1e-13);
  // The cube's mitre reaches its corners: sqrt(3) t.
  EXPECT_NEAR(mitre_factor(cube, offset, 0.1), std::sqrt(3.0), 1e-12);
  // Clipped by a wall at z <= 1.05: the top grows by 0.05 only.
  const HalfSpace wall{Vec3::UnitZ(), 1.05};
  const ConvexPolyhedron clipped = mitred_offset(cube, 0.1, {&wall, 1}, 1e-9);
  expect_valid(clipped);
  EXPECT_NEAR(mass_properties(clipped).volume, 1.2 * 1.2 * 1.15, 1e-13);
}

TEST(MitredOffset, RegularTetrahedronScalesAboutItsCentre) {
  // Moving every face of a regular tetrahedron out by t scales it about its centre by
  // (r_in + t) / r_in, r_in = R / 3 for circumradius R.
  const double radius = 1.0;
  const ConvexPolyhedron tetra = make_regular_tetrahedron(radius);
  const double t = 0.05;
  const ConvexPolyhedron offset = mitred_offset(tetra, t, {}, 1e-12);
  expect_valid(offset);
  const double factor = (radius / 3.0 + t) / (radius / 3.0);
  EXPECT_NEAR(mass_properties(offset).volume,
              mass_properties(tetra).volume * factor * factor * factor, 1e-12);
  EXPECT_NEAR(mitre_factor(tetra, offset, t), 3.0, 1e-9);  // corner reach 3 t
}

TEST(MitredOffset, GeneratedParticlesKeepEveryFaceAtTheThickness) {
  GeneratorOptions options;
  options.alpha = 0.5;
  options.radius_min = options.radius_max = 0.005;
  options.edge_length = 0.005;
  const double t = 2e-4;
  for (std::uint64_t i = 0; i < 20; ++i) {
    const ConvexPolyhedron body = generate_particle(options, i).body;
    const ConvexPolyhedron offset = mitred_offset(body, t, {}, 1e-6 * t);
    expect_valid(offset, 1e-6 * t);
    // Every body vertex is at least t inside every offset face plane, and at exactly t from
    // the plane of a face moved from the body's (some offset face lies on each moved plane).
    for (const HalfSpace& plane : face_half_spaces(offset)) {
      for (const Vec3& v : body.vertices())
        EXPECT_LE(plane.normal.dot(v), plane.offset - t * (1 - 1e-6));
    }
    double nearest_gap = 1e300;
    for (const Vec3& v : offset.vertices())
      nearest_gap = std::min(nearest_gap, distance_to_body(body, v));
    EXPECT_GE(nearest_gap, t * (1 - 1e-6));
    // The polyhedral shell exceeds Steiner's rounded one, which exceeds the flat S t.
    const MassProperties b = mass_properties(body);
    EXPECT_GT(mass_properties(offset).volume - b.volume, b.surface_area * t);
    EXPECT_GE(mitre_factor(body, offset, t), 1.0);
  }
}

TEST(DistanceToBody, FaceEdgeCornerAndInside) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  EXPECT_NEAR(distance_to_body(cube, Vec3(0.5, 0.5, 1.3)), 0.3, 1e-15);
  EXPECT_NEAR(distance_to_body(cube, Vec3(-1, -2, 3)), std::sqrt(1 + 4 + 4.0), 1e-14);
  EXPECT_EQ(distance_to_body(cube, Vec3(0.2, 0.9, 0.5)), 0.0);
}

}  // namespace
}  // namespace aggpack
