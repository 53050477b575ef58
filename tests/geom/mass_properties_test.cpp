// Exact mass properties (divergence theorem) against closed forms, their behaviour under rigid
// motion and scaling, and the paper's signed-tetrahedron point test (Section 2.3).

#include "aggpack/geom/mass_properties.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "aggpack/core/rng.h"
#include "support/random_rotation.h"

namespace aggpack {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_matrix_near(const Mat3& actual, const Mat3& expected, double tolerance) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(actual(i, j), expected(i, j), tolerance) << "(" << i << "," << j << ")";
    }
  }
}

TEST(MassProperties, UnitCube) {
  const auto m = mass_properties(make_box(Vec3::Zero(), Vec3::Ones()));
  EXPECT_NEAR(m.volume, 1.0, 1e-15);
  EXPECT_NEAR(m.surface_area, 6.0, 1e-14);
  EXPECT_NEAR((m.centroid - Vec3(0.5, 0.5, 0.5)).norm(), 0.0, 1e-15);
  // Unit density: I = M (a^2 + a^2) / 12 = 1/6 on the diagonal, products of inertia 0.
  expect_matrix_near(m.inertia, Mat3::Identity() / 6.0, 1e-15);
}

TEST(MassProperties, Box) {
  const double a = 4, b = 2, c = 0.5;
  const auto m = mass_properties(make_box(Vec3(-1, 3, 7), Vec3(-1 + a, 3 + b, 7 + c)));
  const double volume = a * b * c;
  EXPECT_NEAR(m.volume, volume, 1e-13);
  EXPECT_NEAR(m.surface_area, 2 * (a * b + b * c + a * c), 1e-13);
  EXPECT_NEAR((m.centroid - Vec3(-1 + a / 2, 3 + b / 2, 7 + c / 2)).norm(), 0.0, 1e-14);
  const Mat3 expected = Vec3(volume * (b * b + c * c) / 12, volume * (a * a + c * c) / 12,
                             volume * (a * a + b * b) / 12)
                            .asDiagonal();
  expect_matrix_near(m.inertia, expected, 1e-13);
}

TEST(MassProperties, RegularOctahedron) {
  for (const double r : {1e-3, 1.0, 42.0}) {
    const auto m = mass_properties(make_octahedron({r, r, r, r, r, r}));
    const double volume = 4.0 / 3.0 * r * r * r;
    const double surface = 4 * std::sqrt(3.0) * r * r;
    EXPECT_NEAR(m.volume, volume, 1e-14 * volume);
    EXPECT_NEAR(m.surface_area, surface, 1e-14 * surface);
    EXPECT_NEAR(m.centroid.norm(), 0.0, 1e-15 * r);
    // |x|+|y|+|z| <= r: integral of x^2 = 8 r^5 * (2! / 5!) = 2 r^5 / 15 (Dirichlet), so the
    // moment about each axis is 4 r^5 / 15 = M r^2 / 5 for unit density.
    const double moment = 4.0 / 15.0 * std::pow(r, 5);
    expect_matrix_near(m.inertia, moment * Mat3::Identity(), 1e-14 * moment);
    EXPECT_NEAR(moment, m.volume * r * r / 5, 1e-14 * moment);
  }
}

TEST(MassProperties, IrregularOctahedronVolume) {
  // Each octant is a tetrahedron with three perpendicular legs: V = sum of x y z / 6.
  const std::array<double, 6> d = {0.2, 1.0, 0.5, 0.9, 0.3, 0.75};
  double volume = 0;
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) volume += d[sx] * d[2 + sy] * d[4 + sz] / 6;
    }
  }
  const auto m = mass_properties(make_octahedron(d));
  EXPECT_NEAR(m.volume, volume, 1e-15);
  // Centroid of the octant tetrahedron (0, x, y, z) is (x, y, z) / 4 along the signed axes.
  Vec3 moment = Vec3::Zero();
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) {
        const double v = d[sx] * d[2 + sy] * d[4 + sz] / 6;
        moment +=
            v * Vec3(sx == 0 ? d[0] : -d[1], sy == 0 ? d[2] : -d[3], sz == 0 ? d[4] : -d[5]) / 4;
      }
    }
  }
  EXPECT_NEAR((m.centroid - moment / volume).norm(), 0.0, 1e-15);
}

TEST(MassProperties, RegularTetrahedron) {
  const double radius = 0.8;
  const double a = radius * std::sqrt(8.0 / 3.0);  // edge length
  const auto m = mass_properties(make_regular_tetrahedron(radius));
  const double volume = a * a * a / (6 * std::sqrt(2.0));
  EXPECT_NEAR(m.volume, volume, 1e-15);
  EXPECT_NEAR(m.surface_area, std::sqrt(3.0) * a * a, 1e-14);
  EXPECT_NEAR(m.centroid.norm(), 0.0, 1e-15);
  // Isotropic: I = M a^2 / 20 about every axis through the centroid.
  expect_matrix_near(m.inertia, volume * a * a / 20 * Mat3::Identity(), 1e-15);
}

// Rigid motion moves the centroid with the body, rotates the inertia (R I R^T) and leaves the
// volume and surface unchanged -- also far from the origin, where naive integration cancels.
TEST(MassProperties, InvariantUnderRigidMotion) {
  const ConvexPolyhedron bodies[] = {make_box(Vec3(-0.1, -0.2, -0.3), Vec3(0.4, 0.1, 0.05)),
                                     make_octahedron({0.2, 1.0, 0.5, 0.9, 0.3, 0.75}),
                                     make_regular_tetrahedron(0.5)};
  Rng rng(7, 0);
  for (const auto& body : bodies) {
    const auto reference = mass_properties(body);
    for (const double distance : {1.0, 1e3, 1e6}) {
      const Pose pose{.position = distance * Vec3(rng.normal(), rng.normal(), rng.normal()),
                      .rotation = test::random_rotation(rng)};
      const auto m = mass_properties(body.transformed(pose));
      const double tolerance = 1e-15 * distance * 10;
      EXPECT_NEAR(m.volume, reference.volume, 1e-12 * reference.volume + 1e-14 * distance);
      EXPECT_NEAR(m.surface_area, reference.surface_area, 1e-9 * reference.surface_area);
      EXPECT_NEAR((m.centroid - pose.apply(reference.centroid)).norm(), 0.0, tolerance + 1e-15);
      const Mat3 rotation = pose.rotation.toRotationMatrix();
      expect_matrix_near(m.inertia, rotation * reference.inertia * rotation.transpose(),
                         1e-8 * reference.inertia.norm());
    }
  }
}

TEST(MassProperties, Scaling) {
  const auto body = make_octahedron({0.2, 1.0, 0.5, 0.9, 0.3, 0.75});
  const auto a = mass_properties(body);
  const double k = 3.0;
  const auto b = mass_properties(body.scaled(k));
  EXPECT_NEAR(b.volume, k * k * k * a.volume, 1e-14);
  EXPECT_NEAR(b.surface_area, k * k * a.surface_area, 1e-14);
  EXPECT_NEAR((b.centroid - k * a.centroid).norm(), 0.0, 1e-15);
  expect_matrix_near(b.inertia, std::pow(k, 5) * a.inertia, 1e-13);
}

TEST(MassProperties, InsideOutHasNegativeVolume) {
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  auto flipped = cube.triangles();
  for (auto& t : flipped) std::swap(t[1], t[2]);
  const auto m = mass_properties(ConvexPolyhedron(cube.vertices(), flipped));
  EXPECT_NEAR(m.volume, -1.0, 1e-15);
  EXPECT_NEAR(m.surface_area, 6.0, 1e-14);
  EXPECT_EQ(mass_properties(ConvexPolyhedron()).volume, 0.0);
}

TEST(SignedTetraVolume, PaperSignConvention) {
  // Triangle in the z = 0 plane, counter-clockwise seen from +z: +z is its outer side.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_DOUBLE_EQ(signed_tetra_volume(Vec3(0, 0, 1), a, b, c), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(signed_tetra_volume(Vec3(0, 0, -2), a, b, c), -2.0 / 6.0);
  EXPECT_EQ(signed_tetra_volume(Vec3(0.3, 0.3, 0), a, b, c), 0.0);
  EXPECT_EQ(signed_tetra_volume(Vec3(5, -7, 0), a, b, c), 0.0);  // in the plane, off the triangle
}

TEST(LocatePoint, InsideBoundaryOutside) {
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  const double tolerance = 1e-12;
  EXPECT_EQ(locate_point(cube, Vec3(0.5, 0.5, 0.5), tolerance), PointLocation::kInside);
  EXPECT_EQ(locate_point(cube, Vec3(1e-6, 0.999999, 0.5), tolerance), PointLocation::kInside);
  // On a face, an edge, a vertex.
  EXPECT_EQ(locate_point(cube, Vec3(0.5, 0.25, 1.0), tolerance), PointLocation::kOnBoundary);
  EXPECT_EQ(locate_point(cube, Vec3(0.0, 0.3, 1.0), tolerance), PointLocation::kOnBoundary);
  EXPECT_EQ(locate_point(cube, Vec3(1.0, 1.0, 1.0), tolerance), PointLocation::kOnBoundary);
  // On a face diagonal (the shared edge of a face's two triangles).
  EXPECT_EQ(locate_point(cube, Vec3(0.5, 0.5, 0.0), tolerance), PointLocation::kOnBoundary);
  EXPECT_EQ(locate_point(cube, Vec3(0.5, 0.5, 1.0 + 1e-6), tolerance), PointLocation::kOutside);
  EXPECT_EQ(locate_point(cube, Vec3(-1e-6, 0.5, 0.5), tolerance), PointLocation::kOutside);
  EXPECT_EQ(locate_point(cube, Vec3(3, 3, 3), tolerance), PointLocation::kOutside);
  // Points in a face's plane but beyond the cube are outside (another face sees them).
  EXPECT_EQ(locate_point(cube, Vec3(2.0, 0.5, 1.0), tolerance), PointLocation::kOutside);
}

TEST(LocatePoint, AgreesWithAnalyticTestOnRotatedOctahedron) {
  // |x|+|y|+|z| <= r in the body frame; test points through the pose.
  const double r = 0.5;
  const Pose pose{.position = Vec3(3, -1, 2),
                  .rotation = Quat(Eigen::AngleAxisd(0.9, Vec3(1, 1, 0).normalized()))};
  const auto body = make_octahedron({r, r, r, r, r, r}).transformed(pose);
  Rng rng(3, 3);
  int inside = 0;
  int outside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 local(rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r));
    const double l1 = local.cwiseAbs().sum();
    if (std::abs(l1 - r) < 1e-9) continue;  // too close to call
    const auto where = locate_point(body, pose.apply(local), 1e-15);
    ASSERT_EQ(where, l1 < r ? PointLocation::kInside : PointLocation::kOutside)
        << local.transpose();
    (l1 < r ? inside : outside)++;
  }
  EXPECT_GT(inside, 3000);  // the octahedron fills 1/6 of its bounding cube
  EXPECT_GT(outside, 15000);
  // Vertices and face centres are on the boundary.
  for (const auto& v : body.vertices()) {
    EXPECT_EQ(locate_point(body, v, 1e-15), PointLocation::kOnBoundary);
  }
  for (const auto& t : body.triangles()) {
    const Vec3 centre = (body.vertices()[t[0]] + body.vertices()[t[1]] + body.vertices()[t[2]]) / 3;
    EXPECT_EQ(locate_point(body, centre, 1e-14), PointLocation::kOnBoundary);
  }
}

}  // namespace
}  // namespace aggpack
