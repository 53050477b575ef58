#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <nlohmann/json.hpp>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/packing_stats_json.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/statistics.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

using testing::invalid_field;

// Two axis-aligned cubes of side 0.2 in a 1 x 1 x 1 box, at known places.
Packing two_cubes() {
  Packing packing;
  packing.container = {.shape = BoxContainer{.length = 1.0, .width = 1.0, .depth = 1.0}};
  packing.shapes.push_back(make_box(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1)));
  packing.particles.push_back(
      {.shape = 0, .pose = {.position = Vec3(0.15, 0.5, 0.5)}, .control_radius = 0.18});
  // Same shape at scale 2: a cube of side 0.4 spanning x in [0.5, 0.9].
  packing.particles.push_back({.shape = 0,
                               .pose = {.position = Vec3(0.7, 0.5, 0.3)},
                               .control_radius = 0.36,
                               .scale = 2.0});
  return packing;
}

TEST(Statistics, VolumeBelowAPlaneIsExact) {
  const ConvexPolyhedron cube = make_box(Vec3(0, 0, 0), Vec3(1, 2, 3));
  EXPECT_NEAR(volume_below(cube, 0, 0.3), 0.3 * 6.0, 1e-14);
  EXPECT_NEAR(volume_below(cube, 2, 1.5), 3.0, 1e-14);
  EXPECT_DOUBLE_EQ(volume_below(cube, 1, -1.0), 0.0);
  EXPECT_NEAR(volume_below(cube, 1, 5.0), 6.0, 1e-14);
  // Regular octahedron of radius 1 (volume 4/3): below z = 0 is half; above z = 0.5 is the top
  // pyramid scaled by 1/2, 2/3 * 1/8.
  const ConvexPolyhedron octahedron = make_octahedron({1, 1, 1, 1, 1, 1});
  EXPECT_NEAR(volume_below(octahedron, 2, 0.0), 2.0 / 3.0, 1e-14);
  EXPECT_NEAR(volume_below(octahedron, 2, 0.5), 4.0 / 3.0 - 1.0 / 12.0, 1e-14);
  EXPECT_NEAR(volume_below(octahedron, 0, -0.5), 1.0 / 12.0, 1e-14);
}

TEST(Statistics, KnownPackingHasExactFractionsAndProfiles) {
  const Packing packing = two_cubes();
  const PackingStatistics stats = compute_statistics(packing, {.bins = 10});
  EXPECT_EQ(stats.particle_count, 2u);
  EXPECT_EQ(stats.shape_count, 1u);
  const double solid = 0.008 + 0.064;
  EXPECT_NEAR(stats.solid_volume, solid, 1e-15);
  EXPECT_NEAR(stats.container_volume, 1.0, 1e-15);
  EXPECT_NEAR(stats.solid_fraction, solid, 1e-15);
  // Along x, bins of 0.1: cube 1 fills x in [0.05, 0.25], cube 2 x in [0.5, 0.9].
  const auto& x = stats.profiles[0].solid_fraction;
  ASSERT_EQ(x.size(), 10u);
  const double small_slab = 0.04 * 0.1 / 0.1;  // 0.2 x 0.2 cross-section per unit length
  EXPECT_NEAR(x[0], 0.5 * small_slab, 1e-12);
  EXPECT_NEAR(x[1], small_slab, 1e-12);
  EXPECT_NEAR(x[2], 0.5 * small_slab, 1e-12);
  EXPECT_NEAR(x[3], 0.0, 1e-12);
  EXPECT_NEAR(x[4], 0.0, 1e-12);
  for (int k = 5; k < 9; ++k) EXPECT_NEAR(x[static_cast<std::size_t>(k)], 0.16, 1e-12);
  EXPECT_NEAR(x[9], 0.0, 1e-12);
  // Along z: cube 2 spans z in [0.1, 0.5], cube 1 z in [0.4, 0.6].
  const auto& z = stats.profiles[2].solid_fraction;
  EXPECT_NEAR(z[0], 0.0, 1e-12);
  EXPECT_NEAR(z[1], 0.16, 1e-12);
  EXPECT_NEAR(z[4], 0.16 + 0.04, 1e-12);
  EXPECT_NEAR(z[5], 0.04, 1e-12);
  // Descriptors at true size: volumes 0.008 and 0.064.
  bool found = false;
  for (const auto& d : stats.descriptors) {
    if (d.name == "volume") {
      found = true;
      EXPECT_NEAR(d.stats.minimum, 0.008, 1e-15);
      EXPECT_NEAR(d.stats.maximum, 0.064, 1e-15);
      EXPECT_EQ(d.stats.count, 2u);
    }
    if (d.name == "sphericity") {
      EXPECT_NEAR(d.stats.mean, std::cbrt(std::numbers::pi / 6.0), 1e-12);
    }
  }
  EXPECT_TRUE(found);
}

// Over a real random packing (box and cylinder), each profile integrates back to the solid volume.
TEST(Statistics, ProfilesIntegrateToTheSolidVolume) {
  for (const ContainerShape& shape :
       {ContainerShape{BoxContainer{.length = 0.2, .width = 0.1, .depth = 0.15}},
        ContainerShape{CylinderContainer{.radius = 0.07, .height = 0.12}}}) {
    RandomPackOptions options{
        .container = {.shape = shape},
        .grading = {.kind = GradingKind::kFuller, .size_min = 0.01, .size_max = 0.04},
        .volume_fraction = 0.2,
        .seed = 3};
    const PackResult result = pack_random(options);
    const PackingStatistics stats =
        compute_statistics(result.packing, {.bins = 7, .target = options.grading});
    EXPECT_NEAR(stats.solid_volume, result.report.solid_volume, 1e-12 * stats.solid_volume);
    for (const auto& profile : stats.profiles) {
      double solid = 0.0;
      for (std::size_t k = 0; k < profile.solid_fraction.size(); ++k) {
        const double lo = profile.lower + profile.bin_width * static_cast<double>(k);
        solid += profile.solid_fraction[k] * container_slab_volume(result.packing.container,
                                                                   profile.axis, lo,
                                                                   lo + profile.bin_width);
        EXPECT_GE(profile.solid_fraction[k], 0.0);
        EXPECT_LE(profile.solid_fraction[k], 1.0);
      }
      EXPECT_NEAR(solid, stats.solid_volume, 1e-10 * stats.solid_volume) << "axis " << profile.axis;
    }
    ASSERT_EQ(stats.grading.size(), 9u);
    EXPECT_DOUBLE_EQ(stats.grading.back().achieved_percent, 100.0);
    EXPECT_DOUBLE_EQ(stats.grading.back().target_percent, 100.0);
    const std::string text = format_statistics(stats);
    EXPECT_NE(text.find("solid fraction"), std::string::npos);
    EXPECT_NE(text.find("sphericity"), std::string::npos);
    EXPECT_NE(text.find("grading"), std::string::npos);
  }
}

TEST(Statistics, JsonHasEveryFieldAndParses) {
  const Packing packing = two_cubes();
  const PackingStatistics stats = compute_statistics(
      packing,
      {.bins = 4,
       .target = Grading{.kind = GradingKind::kUniform, .radius_min = 0.18, .radius_max = 0.36}});
  const auto json = nlohmann::json::parse(to_json(stats));
  EXPECT_EQ(json["particle_count"], 2);
  EXPECT_NEAR(json["solid_volume_m3"].get<double>(), 0.072, 1e-15);
  EXPECT_EQ(json["profiles"]["z"]["solid_fraction"].size(), 4u);
  EXPECT_EQ(json["grading"].size(), stats.grading.size());
  EXPECT_EQ(json["descriptors"]["volume"]["unit"], "m^3");
  EXPECT_EQ(json["descriptors"]["volume"]["count"], 2);
  PackReport report{.placed = 5, .requested = 7, .rejected = 2};
  const auto report_json = nlohmann::json::parse(to_json(report, -1));
  EXPECT_EQ(report_json["placed"], 5);
  EXPECT_EQ(report_json["stop_reason"], "target reached");
}

TEST(Statistics, BadOptionsAreNamed) {
  const Packing packing = two_cubes();
  EXPECT_EQ(invalid_field([&] { compute_statistics(packing, {.bins = 0}); }), "statistics.bins");
  EXPECT_EQ(invalid_field([&] {
              compute_statistics(
                  packing, {.target = Grading{.kind = GradingKind::kFuller, .size_min = -1.0}});
            }),
            "grading.size_min");
  Packing broken = two_cubes();
  broken.particles[1].shape = 3;
  EXPECT_EQ(invalid_field([&] { compute_statistics(broken); }), "particles[1].shape");
}

}  // namespace
}  // namespace aggpack
