// The HPMC engine's relief of a relief_squeezed, overlapping state (src/pack/hpmc.h,
// Hpmc::relieve): the smallest uniform expansion that leaves no overlap, checked against the
// brute-force test.

#include <gtest/gtest.h>

#include "aggpack/pack/random_packer.h"
#include "hpmc.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

using detail::Hpmc;

// ~60 single-size particles (alpha 0.5, L = r) placed by RSA at 25 % in a 0.4 m cube.
Packing relief_start() {
  RandomPackOptions options;
  options.container = {.shape = BoxContainer{.length = 0.4, .width = 0.4, .depth = 0.4}};
  options.grading.kind = GradingKind::kUniform;
  options.grading.radius_min = 0.05;
  options.grading.radius_max = 0.05;
  options.shape = {.alpha = 0.5, .edge_length_ratio = 1.0};
  options.target = PackTarget::kVolumeFraction;
  options.volume_fraction = 0.25;
  options.seed = 3;
  return pack_random(options).packing;
}

double relief_length(const Hpmc& engine) {
  return engine.container().get_if<BoxContainer>()->length;
}

Packing relief_packing(const Packing& start, const Hpmc& engine) {
  Packing packing = start;
  packing.container = engine.container();
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    packing.particles[i].pose = engine.poses()[i];
  }
  return packing;
}

// The start relief_squeezed by 15 % per axis without checking: many overlaps and particles outside.
Hpmc relief_squeezed(const Packing& start) {
  Hpmc engine(start, 0.0, 7, 0.1);
  const Container target = container_scaled(start.container, Vec3::Constant(0.85));
  EXPECT_GT(engine.squeeze(target, 1.0), 0u);
  return engine;
}

TEST(HpmcRelieve, ExpandsJustEnoughToClearEveryOverlap) {
  const Packing start = relief_start();
  ASSERT_GT(start.particles.size(), 40u);
  Hpmc engine = relief_squeezed(start);
  const double before = relief_length(engine);
  ASSERT_TRUE(engine.relieve(1.0 / 0.85));
  EXPECT_EQ(engine.flagged_count(), 0u);
  EXPECT_EQ(engine.refresh_flags(), 0u);
  const double scale = relief_length(engine) / before;
  EXPECT_GT(scale, 1.0);
  EXPECT_LE(scale, 1.0 / 0.85);
  testing::expect_valid_packing(relief_packing(start, engine), 0.0);
  // Smallest: the relief_squeezed state expanded a little less still overlaps (or leaves a particle
  // out).
  Hpmc less = relief_squeezed(start);
  const double smaller = 1.0 + (scale - 1.0) * 0.99;
  EXPECT_GT(less.rescale(Vec3::Constant(smaller),
                         container_scaled(less.container(), Vec3::Constant(smaller)), 0.0),
            0u);
}

TEST(HpmcRelieve, LeavesTheStateAloneWhenTheLimitIsTooSmall) {
  const Packing start = relief_start();
  Hpmc engine = relief_squeezed(start);
  const Hpmc::State before = engine.state(true);
  const std::size_t flagged = engine.flagged_count();
  EXPECT_FALSE(engine.relieve(1.0 + 1e-6));
  EXPECT_EQ(engine.flagged_count(), flagged);
  EXPECT_EQ(relief_length(engine), before.container.get_if<BoxContainer>()->length);
  for (std::size_t i = 0; i < before.poses.size(); ++i) {
    ASSERT_EQ(engine.poses()[i].position, before.poses[i].position) << i;
  }
  // A clean state has nothing to relieve.
  Hpmc clean(start, 0.0, 7, 0.1);
  EXPECT_FALSE(clean.relieve(2.0));
  EXPECT_EQ(clean.poses()[0].position, start.particles[0].pose.position);
}

}  // namespace
}  // namespace aggpack
