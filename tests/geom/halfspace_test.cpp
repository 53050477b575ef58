// Convex bodies as half-spaces (geom/halfspace.h), against exact solids.

#include "aggpack/geom/halfspace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace aggpack {
namespace {

TEST(FaceHalfSpaces, CubePlanesAreUnitOutwardAndTouchTheCube) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const std::vector<HalfSpace> planes = face_half_spaces(cube);
  ASSERT_EQ(planes.size(), cube.triangle_count());  // two coplanar triangles per face
  for (const HalfSpace& plane : planes) {
    EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-15);
    // Every vertex on or behind the plane, some on it.
    double highest = -1.0;
    for (const Vec3& v : cube.vertices()) highest = std::max(highest, plane.normal.dot(v));
    EXPECT_NEAR(highest, plane.offset, 1e-15);
    // Outward: the centre lies half a side behind every plane.
    EXPECT_NEAR(plane.normal.dot(Vec3::Constant(0.5)) - plane.offset, -0.5, 1e-15);
  }
}

TEST(PlaneExcess, InsideNegativeOutsideALowerBoundOfTheDistance) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  const std::vector<HalfSpace> planes = face_half_spaces(cube);
  EXPECT_NEAR(plane_excess(planes, Vec3(0.5, 0.5, 0.9)), -0.1, 1e-15);  // 0.1 below the top
  EXPECT_NEAR(plane_excess(planes, Vec3(0.5, 0.5, 1.3)), 0.3, 1e-15);   // above a face: exact
  // Off a corner the excess (0.4) is below the distance (sqrt 3 x 0.4).
  const Vec3 corner(1.4, 1.4, 1.4);
  EXPECT_NEAR(plane_excess(planes, corner), 0.4, 1e-15);
  EXPECT_LT(plane_excess(planes, corner), distance_to_body(cube, corner));
  EXPECT_EQ(plane_excess({}, corner), -std::numeric_limits<double>::infinity());
}

TEST(DistanceToBody, FaceEdgeCornerAndInside) {
  const ConvexPolyhedron cube = make_box(Vec3::Zero(), Vec3::Ones());
  EXPECT_NEAR(distance_to_body(cube, Vec3(0.5, 0.5, 1.3)), 0.3, 1e-15);
  EXPECT_NEAR(distance_to_body(cube, Vec3(-1, -2, 3)), std::sqrt(1 + 4 + 4.0), 1e-14);
  EXPECT_EQ(distance_to_body(cube, Vec3(0.2, 0.9, 0.5)), 0.0);
}

}  // namespace
}  // namespace aggpack
