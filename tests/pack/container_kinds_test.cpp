// Every container kind, through the generic operations of container.h: exact volumes, floor areas
// and slab volumes, containment on known points and bodies, walls that close the interior without
// entering it, the outline on the surface, per-axis scaling, and the params list.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/pack/container.h"

namespace aggpack {
namespace {

// A container of `kind` with parameters 1, 1.5, 2, ... (m) and no wall gap.
Container sized(const ContainerKindInfo& kind) {
  Container container = kind.defaults;
  double value = 1.0;
  for (const ContainerParam& param : kind.params) {
    param.set(container, value);
    value += 0.5;
  }
  return container;
}

bool is_in_wall(const ContainerWall& wall, const Vec3& point) {
  const Vec3 local = Eigen::AngleAxisd(-wall.angle, Vec3::UnitZ()) * (point - wall.centre);
  return (local.cwiseAbs().array() <= wall.half_extent.array()).all();
}

TEST(ContainerKinds, ListMatchesTheVariantAndNamesAreUnique) {
  const auto& kinds = container_kinds();
  ASSERT_EQ(kinds.size(), std::variant_size_v<ContainerShape>);
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    EXPECT_EQ(kinds[k].defaults.shape.index(), k);
    EXPECT_TRUE(kinds[k].holds(kinds[k].defaults));
    EXPECT_EQ(&container_kind_info(kinds[k].defaults), &kinds[k]);
    EXPECT_EQ(find_container_kind(kinds[k].name), &kinds[k]);
    EXPECT_FALSE(kinds[k].params.empty());
    EXPECT_NO_THROW(validate(kinds[k].defaults)) << kinds[k].name;
  }
  EXPECT_EQ(find_container_kind("sphere"), nullptr);
  EXPECT_EQ(container_kind_names(), "box or cylinder");
}

TEST(ContainerKinds, ParamsSetOnlyTheirOwnKind) {
  const ContainerKindInfo& box = *find_container_kind("box");
  const ContainerKindInfo& cylinder = *find_container_kind("cylinder");
  Container c = box.defaults;
  box.params[0].set(c, 7.0);
  EXPECT_EQ(c.get_if<BoxContainer>()->length, 7.0);
  cylinder.params[0].set(c, 9.0);  // another kind's parameter: no place for it, ignored
  EXPECT_NE(c.get_if<BoxContainer>(), nullptr);
  EXPECT_EQ(cylinder.params[0].get(c), 0.05);  // the cylinder default
  EXPECT_STREQ(box.params[2].name, "depth");
  EXPECT_STREQ(cylinder.params[1].name, "height");
}

TEST(ContainerKinds, ExactVolumesFloorAreasAndSlabs) {
  const Container box{.shape = BoxContainer{.length = 2.0, .width = 3.0, .depth = 4.0}};
  EXPECT_EQ(box.volume(), 24.0);
  EXPECT_EQ(container_floor_area(box), 6.0);
  EXPECT_EQ(container_slab_volume(box, 1, 0.5, 1.0), 4.0);
  EXPECT_EQ(container_slab_volume(box, 2, 3.0, 9.0), 6.0);  // clipped to the box
  const Container cylinder{.shape = CylinderContainer{.radius = 2.0, .height = 3.0}};
  EXPECT_DOUBLE_EQ(cylinder.volume(), std::numbers::pi * 12.0);
  EXPECT_DOUBLE_EQ(container_floor_area(cylinder), std::numbers::pi * 4.0);
  EXPECT_DOUBLE_EQ(container_slab_volume(cylinder, 2, 1.0, 2.0), std::numbers::pi * 4.0);
  EXPECT_DOUBLE_EQ(container_slab_volume(cylinder, 0, 0.0, 5.0), std::numbers::pi * 6.0);
  // For every kind the slabs along each axis add up to the volume.
  for (const ContainerKindInfo& kind : container_kinds()) {
    const Container c = sized(kind);
    const Aabb bounds = c.bounds();
    for (int axis = 0; axis < 3; ++axis) {
      double sum = 0.0;
      for (int k = 0; k < 5; ++k) {
        const double lo = bounds.lower[axis] + bounds.extent()[axis] * k / 5.0;
        const double hi = bounds.lower[axis] + bounds.extent()[axis] * (k + 1) / 5.0;
        sum += container_slab_volume(c, axis, lo, hi);
      }
      EXPECT_NEAR(sum, c.volume(), 1e-12 * c.volume()) << kind.name << " axis " << axis;
    }
  }
}

TEST(ContainerKinds, ContainsKnownPointsAndBodies) {
  const ConvexPolyhedron cube = make_box(Vec3(-0.25, -0.25, -0.25), Vec3(0.25, 0.25, 0.25));
  const Container box{.shape = BoxContainer{.length = 2.0, .width = 1.0, .depth = 1.0},
                      .wall_gap = 0.125};
  EXPECT_TRUE(contains(box, cube, Pose{.position = Vec3(1.0, 0.5, 0.5)}));
  EXPECT_TRUE(contains(box, cube, Pose{.position = Vec3(1.625, 0.5, 0.5)}));  // at the gap
  EXPECT_FALSE(contains(box, cube, Pose{.position = Vec3(1.75, 0.5, 0.5)}));
  EXPECT_EQ(wall_clearance(box, Vec3(1.0, 0.25, 0.5)), 0.25);
  const Container cylinder{.shape = CylinderContainer{.radius = 1.0, .height = 1.0}};
  EXPECT_TRUE(contains(cylinder, cube, Pose{.position = Vec3(0.0, 0.0, 0.5)}));
  EXPECT_TRUE(contains(cylinder, cube, Pose{.position = Vec3(0.5, 0.0, 0.5)}));
  EXPECT_FALSE(contains(cylinder, cube, Pose{.position = Vec3(0.0, 0.0, 0.2)}));  // floor
  EXPECT_FALSE(contains(cylinder, cube, Pose{.position = Vec3(0.55, 0.55, 0.5)}));
  EXPECT_EQ(wall_clearance(cylinder, Vec3(0.0, 0.75, 0.5)), 0.25);
  EXPECT_TRUE(centre_region_is_bounds(box));
  EXPECT_FALSE(centre_region_is_bounds(cylinder));
}

// The physics walls never enter the interior, and every point just outside the side walls or
// the floor (below the top; the container is open above) lies in some wall.
TEST(ContainerKinds, WallBoxesCloseTheInteriorWithoutEnteringIt) {
  for (const ContainerKindInfo& kind : container_kinds()) {
    const Container c = sized(kind);
    const Aabb bounds = c.bounds();
    const double size = bounds.extent().minCoeff();
    const double thickness = 0.1 * size;
    const double top = bounds.upper.z() + 0.5;  // walls rise above the container
    const std::vector<ContainerWall> walls = container_walls(c, thickness, top);
    ASSERT_FALSE(walls.empty()) << kind.name;
    Rng rng(7, 0);
    const Vec3 centre = 0.5 * (bounds.lower + bounds.upper);
    int outside_points = 0;
    for (int n = 0; n < 2000; ++n) {
      // A random point of the interior is in no wall.
      const Vec3 inside(bounds.lower.x() + bounds.extent().x() * rng.uniform(),
                        bounds.lower.y() + bounds.extent().y() * rng.uniform(),
                        bounds.lower.z() + bounds.extent().z() * rng.uniform());
      if (wall_clearance(c, inside) > 1e-9) {
        for (const auto& wall : walls) {
          ASSERT_FALSE(is_in_wall(wall, inside)) << kind.name << " " << inside.transpose();
        }
      }
      // Leave the container from its centre along a random direction; 1 % of its size beyond
      // the wall the point must be in a wall unless it left through the open top.
      Vec3 direction(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
      if (direction.norm() < 1e-3) continue;
      direction.normalize();
      double lo = 0.0;
      double hi = bounds.extent().norm();
      for (int step = 0; step < 60; ++step) {
        const double mid = 0.5 * (lo + hi);
        (wall_clearance(c, centre + mid * direction) >= 0.0 ? lo : hi) = mid;
      }
      const Vec3 beyond = centre + (hi + 0.01 * size) * direction;
      if (beyond.z() >= bounds.upper.z()) continue;
      ++outside_points;
      bool is_covered = false;
      for (const auto& wall : walls) is_covered = is_covered || is_in_wall(wall, beyond);
      EXPECT_TRUE(is_covered) << kind.name << " " << beyond.transpose();
    }
    EXPECT_GT(outside_points, 500) << kind.name;
    // Walls reach at least the requested height.
    double highest = 0.0;
    for (const auto& wall : walls)
      highest = std::max(highest, wall.centre.z() + wall.half_extent.z());
    EXPECT_GE(highest, top) << kind.name;
  }
}

TEST(ContainerKinds, OutlineLiesOnTheSurface) {
  for (const ContainerKindInfo& kind : container_kinds()) {
    const Container c = sized(kind);
    const std::vector<OutlineSegment> outline = container_outline(c);
    ASSERT_GE(outline.size(), 8u) << kind.name;
    for (const OutlineSegment& segment : outline) {
      for (const Vec3& end : segment) {
        EXPECT_NEAR(wall_clearance(c, end), 0.0, 1e-12) << kind.name << " " << end.transpose();
      }
    }
  }
}

TEST(ContainerKinds, PerAxisScalingAndRatios) {
  const Container box{.shape = BoxContainer{.length = 2.0, .width = 4.0, .depth = 8.0}};
  const Container half = container_scaled(box, Vec3(0.5, 0.25, 0.125));
  EXPECT_EQ(*half.get_if<BoxContainer>(),
            (BoxContainer{.length = 1.0, .width = 1.0, .depth = 1.0}));
  EXPECT_EQ(container_ratio(box, half), Vec3(0.5, 0.25, 0.125));
  const Container cylinder{.shape = CylinderContainer{.radius = 2.0, .height = 4.0},
                           .wall_gap = 0.1};
  const Container smaller = container_scaled(cylinder, Vec3(0.5, 0.5, 0.25));
  EXPECT_EQ(*smaller.get_if<CylinderContainer>(),
            (CylinderContainer{.radius = 1.0, .height = 1.0}));
  EXPECT_EQ(smaller.wall_gap, 0.1);
  EXPECT_EQ(container_ratio(cylinder, smaller), Vec3(0.5, 0.5, 0.25));
  EXPECT_THROW((void)container_ratio(box, cylinder), InvalidInput);
  // Uniform scaling scales the volume by the cube, for every kind.
  for (const ContainerKindInfo& kind : container_kinds()) {
    const Container c = sized(kind);
    EXPECT_NEAR(container_scaled(c, Vec3::Constant(0.5)).volume(), c.volume() / 8.0,
                1e-15 * c.volume())
        << kind.name;
  }
}

}  // namespace
}  // namespace aggpack
