#include <gtest/gtest.h>

#include "aggpack/pack/verify.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

Packing pair_of_cubes(double separation) {
  Packing packing;
  packing.container = {.shape = BoxContainer{.length = 2.0, .width = 1.0, .depth = 1.0},
                       .wall_gap = 0.05};
  packing.shapes.push_back(make_box(Vec3(-0.2, -0.2, -0.2), Vec3(0.2, 0.2, 0.2)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.5, 0.5, 0.5)}});
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.9 + separation, 0.5, 0.5)}});
  return packing;
}

TEST(Verify, FindsOverlapsGapsAndEscapes) {
  for (bool brute : {false, true}) {
    const VerifyOptions gap{.gap = 0.01, .is_brute_force = brute};
    EXPECT_TRUE(verify(pair_of_cubes(0.02), gap).is_ok);
    const VerifyResult close = verify(pair_of_cubes(0.005), gap);
    EXPECT_FALSE(close.is_ok);
    EXPECT_EQ(close.overlapping_pairs, 1u);
    EXPECT_NEAR(close.min_distance, 0.005, 1e-12);
    EXPECT_FALSE(verify(pair_of_cubes(-0.1), {.is_brute_force = brute}).is_ok);
    EXPECT_FALSE(verify(pair_of_cubes(0.0), {.is_brute_force = brute}).is_ok);  // touching
    Packing escaped = pair_of_cubes(0.5);
    escaped.particles[0].pose.position.z() = 0.26;  // 0.06 from the floor... still inside
    EXPECT_TRUE(verify(escaped, gap).is_ok);
    escaped.particles[0].pose.position.z() = 0.24;  // 0.04 < wall_gap 0.05
    const VerifyResult result = verify(escaped, gap);
    EXPECT_FALSE(result.is_ok);
    EXPECT_EQ(result.outside_particles, 1u);
    EXPECT_NEAR(result.min_wall_clearance, 0.04, 1e-12);
  }
}

}  // namespace
}  // namespace aggpack
