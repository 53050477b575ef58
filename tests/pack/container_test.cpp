#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

using testing::invalid_field;

Container box(double l, double w, double d, double gap = 0.0) {
  return {.shape = BoxContainer{.length = l, .width = w, .depth = d}, .wall_gap = gap};
}
Container cylinder(double r, double h, double gap = 0.0) {
  return {.shape = CylinderContainer{.radius = r, .height = h}, .wall_gap = gap};
}

TEST(Container, BoundsAndVolumeOfBoxAndCylinder) {
  const Container b = box(3.0, 1.0, 2.8);
  EXPECT_DOUBLE_EQ(b.volume(), 8.4);
  EXPECT_EQ(b.bounds().lower, Vec3(0, 0, 0));
  EXPECT_EQ(b.bounds().upper, Vec3(3.0, 1.0, 2.8));
  const Container c = cylinder(0.05, 0.1);
  EXPECT_DOUBLE_EQ(c.volume(), std::numbers::pi * 0.05 * 0.05 * 0.1);
  EXPECT_EQ(c.bounds().lower, Vec3(-0.05, -0.05, 0));
  EXPECT_EQ(c.bounds().upper, Vec3(0.05, 0.05, 0.1));
}

TEST(Container, EachBadFieldIsNamed) {
  EXPECT_EQ(invalid_field([] { validate(box(0.0, 1, 1)); }), "container.length");
  EXPECT_EQ(invalid_field([] { validate(box(1, -1, 1)); }), "container.width");
  EXPECT_EQ(invalid_field([] { validate(box(1, 1, NAN)); }), "container.depth");
  EXPECT_EQ(invalid_field([] { validate(box(1, 1, 1, -0.1)); }), "container.wall_gap");
  EXPECT_EQ(invalid_field([] { validate(box(1, 1, 1, 0.5)); }), "container.wall_gap");
  EXPECT_EQ(invalid_field([] { validate(cylinder(0, 1)); }), "container.radius");
  EXPECT_EQ(invalid_field([] { validate(cylinder(1, 0)); }), "container.height");
  EXPECT_NO_THROW(validate(box(1, 1, 1, 0.49)));
  EXPECT_NO_THROW(validate(cylinder(0.05, 0.1, 0.01)));
}

TEST(Container, WallClearanceOfPoints) {
  const Container b = box(2.0, 1.0, 1.0);
  EXPECT_DOUBLE_EQ(wall_clearance(b, Vec3(1.0, 0.5, 0.5)), 0.5);
  EXPECT_DOUBLE_EQ(wall_clearance(b, Vec3(0.1, 0.5, 0.5)), 0.1);
  EXPECT_DOUBLE_EQ(wall_clearance(b, Vec3(2.3, 0.5, 0.5)), -0.3);
  EXPECT_DOUBLE_EQ(wall_clearance(b, Vec3(-0.3, -0.4, 0.5)), -0.5);
  const Container c = cylinder(1.0, 2.0);
  EXPECT_DOUBLE_EQ(wall_clearance(c, Vec3(0.0, 0.0, 1.0)), 1.0);
  EXPECT_DOUBLE_EQ(wall_clearance(c, Vec3(0.6, 0.0, 1.0)), 0.4);
  EXPECT_NEAR(wall_clearance(c, Vec3(0.0, 0.0, 1.9)), 0.1, 1e-12);
  EXPECT_NEAR(wall_clearance(c, Vec3(1.3, 0.0, 2.4)), -0.5, 1e-12);
}

// Binary-exact numbers (multiples of 1/8) so "exactly at the gap" is exact in floating point.
TEST(Container, ContainmentIsExactAtTheWallGap) {
  const Container b = box(1.0, 1.0, 1.0, 0.125);
  const ConvexPolyhedron cube = make_box(Vec3(-0.25, -0.25, -0.25), Vec3(0.25, 0.25, 0.25));
  EXPECT_TRUE(contains(b, cube, Pose{.position = Vec3(0.5, 0.5, 0.5)}));
  EXPECT_TRUE(contains(b, cube, Pose{.position = Vec3(0.375, 0.5, 0.625)}));  // at the gap
  EXPECT_FALSE(contains(b, cube, Pose{.position = Vec3(0.375 - 1e-12, 0.5, 0.5)}));
  EXPECT_FALSE(contains(b, cube, Pose{.position = Vec3(0.5, 0.5, 0.625 + 1e-12)}));
  // Rotated 45 degrees about z the cube reaches 0.25 sqrt(2) along x.
  const Pose turned{.position = Vec3(0.125 + 0.25 * std::sqrt(2.0) + 1e-9, 0.5, 0.5),
                    .rotation = Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()))};
  EXPECT_TRUE(contains(b, cube, turned));
  Pose shifted = turned;
  shifted.position.x() -= 2e-9;
  EXPECT_FALSE(contains(b, cube, shifted));
  EXPECT_NEAR(wall_clearance(b, cube, shifted), 0.125 - 1e-9, 1e-12);

  const Container c = cylinder(1.0, 1.0, 0.0625);
  EXPECT_TRUE(contains(c, cube, Pose{.position = Vec3(0.0, 0.0, 0.5)}));
  // Corner (0.25, 0.25) of the cube at x offset: |(ox + 0.25, 0.25)| <= 0.9375.
  const double ox = std::sqrt(0.9375 * 0.9375 - 0.0625) - 0.25;
  EXPECT_TRUE(contains(c, cube, Pose{.position = Vec3(ox - 1e-9, 0.0, 0.5)}));
  EXPECT_FALSE(contains(c, cube, Pose{.position = Vec3(ox + 1e-9, 0.0, 0.5)}));
  EXPECT_TRUE(contains(c, cube, Pose{.position = Vec3(0.0, 0.0, 0.3125)}));
  EXPECT_FALSE(contains(c, cube, Pose{.position = Vec3(0.0, 0.0, 0.3125 - 1e-12)}));
}

TEST(Container, CentreRegions) {
  const Container b = box(2.0, 1.0, 1.0, 0.125);
  const Aabb region = centre_region(b, 0.25);
  EXPECT_EQ(region.lower.x(), 0.375);
  EXPECT_EQ(region.upper.x(), 1.625);
  EXPECT_TRUE(is_in_centre_region(b, 0.25, Vec3(0.375, 0.375, 0.625)));
  EXPECT_FALSE(is_in_centre_region(b, 0.25, Vec3(0.375 - 1e-12, 0.5, 0.5)));
  EXPECT_TRUE(centre_region(b, 0.45).is_empty());
  const Container c = cylinder(1.0, 1.0);
  EXPECT_TRUE(is_in_centre_region(c, 0.5, Vec3(0.3, 0.4, 0.5)));
  EXPECT_FALSE(is_in_centre_region(c, 0.5, Vec3(0.31, 0.4, 0.5)));
}

TEST(Container, SlabVolumesAreExactAndAddUp) {
  const Container b = box(3.0, 1.0, 2.8);
  EXPECT_DOUBLE_EQ(container_slab_volume(b, 0, 1.0, 1.5), 0.5 * 2.8);
  EXPECT_DOUBLE_EQ(container_slab_volume(b, 2, -1.0, 10.0), 8.4);
  const Container c = cylinder(0.5, 2.0);
  EXPECT_NEAR(container_slab_volume(c, 0, -0.5, 0.0), c.volume() / 2.0, 1e-15);
  EXPECT_NEAR(container_slab_volume(c, 2, 0.5, 1.0), c.volume() / 4.0, 1e-15);
  // Circular segment of half-width h = r/2 beyond x = r/2: r^2 (pi/3 - sqrt(3)/4).
  EXPECT_NEAR(container_slab_volume(c, 1, 0.25, 0.5),
              2.0 * 0.25 * (std::numbers::pi / 3.0 - std::sqrt(3.0) / 4.0), 1e-14);
  double sum = 0.0;
  for (int k = 0; k < 7; ++k)
    sum += container_slab_volume(c, 0, -0.5 + k / 7.0, -0.5 + (k + 1) / 7.0);
  EXPECT_NEAR(sum, c.volume(), 1e-14);
}

TEST(Container, MeshPrismOfEachKind) {
  const Container b = box(3.0, 1.0, 2.8);
  EXPECT_EQ(container_prism_floor(b, 96),
            (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(0, 1, 0)}));
  EXPECT_TRUE(is_on_prism_side(b, Vec3(3.0, 0.5, 1.0), 96, 1e-9));
  EXPECT_TRUE(is_on_prism_side(b, Vec3(1.0, 0.0, 1.0), 96, 1e-9));
  EXPECT_FALSE(is_on_prism_side(b, Vec3(1.0, 0.5, 0.0), 96, 1e-9));  // the floor only
  EXPECT_EQ(prism_summary(b, 96), "box");
  // A cylinder's prism circumscribes it: n corners at R / cos(pi / n), counter-clockwise, area
  // n R^2 tan(pi / n); side k touches the circle at angle 2 pi k / n.
  const Container c = cylinder(0.5, 2.0);
  const std::vector<Vec3> ring = container_prism_floor(c, 8);
  ASSERT_EQ(ring.size(), 8U);
  double area = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    EXPECT_NEAR(ring[k].norm(), 0.5 / std::cos(std::numbers::pi / 8), 1e-15);
    area += 0.5 * ring[k].cross(ring[(k + 1) % ring.size()]).z();
  }
  EXPECT_NEAR(area, 8 * 0.25 * std::tan(std::numbers::pi / 8), 1e-15);
  EXPECT_TRUE(is_on_prism_side(c, Vec3(0.5, 0.1, 1.0), 8, 1e-9));        // on side 0 (x = R)
  EXPECT_FALSE(is_on_prism_side(c, Vec3(0.49, 0.0, 1.0), 8, 1e-9));      // inside it
  EXPECT_TRUE(is_on_prism_side(c, ring[3] + Vec3(0, 0, 0.5), 8, 1e-9));  // a corner's edge
  EXPECT_EQ(prism_summary(c, 8), "prism of 8 sides about the cylinder");
}

}  // namespace
}  // namespace aggpack
