// Tetrahedron quality against exact answers: the regular tetrahedron, the trirectangular corner
// of a cube and a symmetric sliver whose angles and radii have closed forms.

#include "aggpack/mesh/quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace aggpack {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

// Regular tetrahedron with edge 2 sqrt 2 (alternate corners of a cube), positively oriented.
const std::vector<Vec3> kRegular = {Vec3(1, 1, 1), Vec3(-1, 1, -1), Vec3(1, -1, -1),
                                    Vec3(-1, -1, 1)};

// Sliver of height h: (+-1, 0, 0) and (0, +-1, h). All faces have area sqrt(1 + h^2), volume
// 2h/3, circumradius sqrt(1 + h^2/4), inradius h / (2 sqrt(1 + h^2)); dihedral angles
// acos(1 / (1 + h^2)) at the four side edges and 180 - 2 atan(h) degrees at the two others.
std::vector<Vec3> sliver(double h) {
  return {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, h), Vec3(0, 1, h)};
}

TEST(TetQuality, RegularTetrahedron) {
  const auto& p = kRegular;
  ASSERT_GT(tetra_volume(p[0], p[1], p[2], p[3]), 0);
  for (const double angle : dihedral_angles_degrees(p[0], p[1], p[2], p[3])) {
    EXPECT_NEAR(angle, std::acos(1.0 / 3.0) * kDegrees, 1e-12);
    EXPECT_NEAR(angle, 70.5288, 1e-4);
  }
  EXPECT_NEAR(aspect_ratio(p[0], p[1], p[2], p[3]), 1.0, 1e-14);
  // Scale- and position-free.
  EXPECT_NEAR(aspect_ratio(1e-3 * p[0] + Vec3(5, 6, 7), 1e-3 * p[1] + Vec3(5, 6, 7),
                           1e-3 * p[2] + Vec3(5, 6, 7), 1e-3 * p[3] + Vec3(5, 6, 7)),
              1.0, 1e-10);
}

TEST(TetQuality, CornerOfACube) {
  const Vec3 o(0, 0, 0);
  const Vec3 x(1, 0, 0);
  const Vec3 y(0, 1, 0);
  const Vec3 z(0, 0, 1);
  const auto angles = dihedral_angles_degrees(o, x, y, z);
  // Edges o-x, o-y, o-z meet at right angles; x-y, y-z, z-x at acos(1/sqrt 3).
  EXPECT_NEAR(angles[0], 90.0, 1e-12);                                        // o-x
  EXPECT_NEAR(angles[1], std::acos(1.0 / std::sqrt(3.0)) * kDegrees, 1e-12);  // x-y
  EXPECT_NEAR(angles[3], 90.0, 1e-12);                                        // o-z
  EXPECT_NEAR(aspect_ratio(o, x, y, z), (1.0 + std::sqrt(3.0)) / 2.0, 1e-14);
}

TEST(TetQuality, SliverHasClosedFormAngles) {
  for (const double h : {0.5, 0.1, 1e-3}) {
    const auto p = sliver(h);
    ASSERT_GT(tetra_volume(p[0], p[1], p[2], p[3]), 0) << h;
    const TetQuality quality = measure_quality(p, std::vector<Tetrahedron>{{0, 1, 2, 3}});
    EXPECT_EQ(quality.tetrahedra, 1U);
    EXPECT_NEAR(quality.min_dihedral_degrees, std::acos(1.0 / (1.0 + h * h)) * kDegrees, 1e-9) << h;
    EXPECT_NEAR(quality.max_dihedral_degrees, 180.0 - 2.0 * std::atan(h) * kDegrees, 1e-9) << h;
    const double ratio = 2.0 * std::sqrt(1.0 + h * h / 4.0) * std::sqrt(1.0 + h * h) / (3.0 * h);
    EXPECT_NEAR(quality.max_aspect_ratio, ratio, 1e-9 * ratio) << h;
    EXPECT_EQ(quality.below_10_degrees, h < 0.2 ? 1U : 0U) << h;
  }
}

TEST(TetQuality, FlatAndInvertedTetrahedraAreInfinitelyBad) {
  const auto p = sliver(0.0);
  EXPECT_EQ(aspect_ratio(p[0], p[1], p[2], p[3]), std::numeric_limits<double>::infinity());
  const auto q = sliver(0.1);
  EXPECT_EQ(aspect_ratio(q[1], q[0], q[2], q[3]), std::numeric_limits<double>::infinity());
  const TetQuality quality = measure_quality(p, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  EXPECT_EQ(quality.min_dihedral_degrees, 0.0);
  EXPECT_EQ(quality.below_10_degrees, 1U);
}

TEST(TetQuality, AddWeighsBySharedMeshes) {
  std::vector<Vec3> nodes = kRegular;
  for (const Vec3& v : sliver(0.1)) nodes.push_back(v + Vec3(10, 0, 0));
  const TetQuality regular = measure_quality(nodes, std::vector<Tetrahedron>{{0, 1, 2, 3}});
  const TetQuality mixed =
      measure_quality(nodes, std::vector<Tetrahedron>{{0, 1, 2, 3}, {4, 5, 6, 7}});
  EXPECT_EQ(mixed.tetrahedra, 2U);
  EXPECT_EQ(mixed.below_10_degrees, 1U);
  TetQuality total;
  EXPECT_EQ(total.tetrahedra, 0U);
  total.add(regular, 3);
  total.add(mixed, 2);
  total.add(mixed, 0);
  EXPECT_EQ(total.tetrahedra, 7U);
  EXPECT_EQ(total.below_10_degrees, 2U);
  EXPECT_EQ(total.min_dihedral_degrees, mixed.min_dihedral_degrees);
  EXPECT_EQ(total.max_aspect_ratio, mixed.max_aspect_ratio);
  EXPECT_NEAR(regular.max_aspect_ratio, 1.0, 1e-14);
}

TEST(TetQuality, CentroidFanOfACube) {
  // Each fan tetrahedron over half a unit-cube face with apex at the centre.
  const ConvexPolyhedron cube = make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  const TetMesh fan = centroid_fan(cube);
  const TetQuality quality = measure_quality(fan.nodes, fan.tetrahedra);
  EXPECT_EQ(quality.tetrahedra, 12U);
  EXPECT_EQ(quality.below_10_degrees, 0U);
  EXPECT_GT(quality.min_dihedral_degrees, 30.0);
  EXPECT_LT(quality.max_aspect_ratio, 3.0);
}

}  // namespace
}  // namespace aggpack
