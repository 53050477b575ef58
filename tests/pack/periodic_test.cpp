// The periodic box: image shifts, containment and the centre region, verify() through images
// (exact answers), and random packings checked by an independent brute force over all images.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/packer_kinds.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/statistics.h"
#include "aggpack/pack/verify.h"
#include "pack/pack_test_util.h"
#include "support/packings.h"
#include "support/periodic.h"

namespace aggpack {
namespace {

using test::periodic_box;
using test::periodic_brute_force_overlaps;

// Two cubes of half size 0.1 at x = first and x = second (y = z = 0.5) in a 1 m box.
Packing periodic_cube_pair(double first, double second, std::array<bool, 3> axes) {
  Packing packing;
  packing.container = periodic_box(1.0, 1.0, 1.0, axes);
  packing.shapes.push_back(make_box(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(first, 0.5, 0.5)}});
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(second, 0.5, 0.5)}});
  return packing;
}

RandomPackOptions periodic_random_options(std::array<bool, 3> axes, std::uint64_t seed) {
  return {.container = periodic_box(0.2, 0.2, 0.2, axes),
          .grading = {.kind = GradingKind::kUniform, .radius_min = 0.012, .radius_max = 0.025},
          .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
          .target = PackTarget::kVolumeFraction,
          .volume_fraction = 0.3,
          .gap = 0.001,
          .seed = seed};
}

TEST(PeriodicContainer, WordsRoundTrip) {
  for (const std::string& word : periodic_words()) {
    std::array<bool, 3> axes{true, false, true};
    ASSERT_TRUE(parse_periodic_word(word, axes)) << word;
    EXPECT_EQ(periodic_word(axes), word);
  }
  std::array<bool, 3> axes{};
  EXPECT_FALSE(parse_periodic_word("zx", axes));
  EXPECT_FALSE(parse_periodic_word("true", axes));
  EXPECT_EQ(periodic_word({false, true, true}), "yz");
  EXPECT_FALSE(is_periodic(periodic_box(1, 1, 1, {})));
  EXPECT_TRUE(is_periodic(periodic_box(1, 1, 1, {false, false, true})));
  EXPECT_FALSE(is_periodic({.shape = CylinderContainer{}}));
}

TEST(PeriodicContainer, ImageShiftsKnownAnswers) {
  const Container box = periodic_box(1.0, 2.0, 3.0, {true, false, true});
  // 0.1 from x = 0 (image at x + 1), 0.05 from z = 3 (image at z - 3), y has no images.
  const ImageShifts near = image_shifts(box, Vec3(0.1, 0.01, 2.95), 0.2);
  ASSERT_EQ(near.count, 4);
  EXPECT_EQ(near.shifts[0], Vec3::Zero());
  EXPECT_EQ(near.shifts[1], Vec3(0.0, 0.0, -3.0));
  EXPECT_EQ(near.shifts[2], Vec3(1.0, 0.0, 0.0));
  EXPECT_EQ(near.shifts[3], Vec3(1.0, 0.0, -3.0));
  EXPECT_EQ(image_shifts(box, Vec3(0.5, 0.01, 1.5), 0.2).count, 1);
  EXPECT_EQ(image_shifts(box, Vec3(0.5, 1.0, 1.5), 1e9).count, 9);
  EXPECT_EQ(image_shifts(periodic_box(1, 1, 1, {}), Vec3(0.0, 0.0, 0.0), 1e9).count, 1);
}

TEST(PeriodicContainer, NoWallsAlongPeriodicAxes) {
  const Container box = periodic_box(1.0, 1.0, 1.0, {true, false, false});
  const Aabb region = centre_region(box, 0.1);
  EXPECT_EQ(region.lower, Vec3(0.0, 0.1, 0.1));
  EXPECT_EQ(region.upper, Vec3(1.0, 0.9, 0.9));
  EXPECT_TRUE(is_in_centre_region(box, 0.1, Vec3(0.0, 0.5, 0.5)));
  EXPECT_FALSE(is_in_centre_region(box, 0.1, Vec3(0.5, 0.05, 0.5)));
  const ConvexPolyhedron cube = make_box(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1));
  EXPECT_TRUE(contains(box, cube, {.position = Vec3(0.98, 0.5, 0.5)}));   // crosses x = 1
  EXPECT_FALSE(contains(box, cube, {.position = Vec3(0.5, 0.98, 0.5)}));  // crosses y = 1
  EXPECT_NEAR(wall_clearance(box, cube, {.position = Vec3(0.98, 0.5, 0.3)}), 0.2, 1e-15);
  EXPECT_EQ(wall_clearance(periodic_box(1, 1, 1, {true, true, true}), Vec3(0.5, 0.5, 0.5)),
            std::numeric_limits<double>::infinity());
  const Container scaled = container_scaled(box, Vec3(2.0, 2.0, 2.0));
  EXPECT_EQ(periodic_axes(scaled), (std::array<bool, 3>{true, false, false}));
}

TEST(PeriodicVerify, OverlapOnlyThroughAnImageIsFound) {
  for (bool brute : {false, true}) {
    // Cubes spanning x in [0, 0.2] and [0.75, 0.95]: 0.55 apart inside, 0.05 through x = 1.
    const Packing walled = periodic_cube_pair(0.1, 0.85, {});
    const VerifyResult inside = verify(walled, {.gap = 0.06, .is_brute_force = brute});
    EXPECT_TRUE(inside.is_ok) << inside.message;
    // The grid tests only pairs whose bounding spheres meet; brute force tests every pair.
    if (brute) {
      EXPECT_NEAR(inside.min_distance, 0.55, 1e-12);
    }
    const Packing wrapped = periodic_cube_pair(0.1, 0.85, {true, false, false});
    EXPECT_TRUE(verify(wrapped, {.gap = 0.04, .is_brute_force = brute}).is_ok);
    const VerifyResult image = verify(wrapped, {.gap = 0.06, .is_brute_force = brute});
    EXPECT_FALSE(image.is_ok);
    EXPECT_EQ(image.overlapping_pairs, 1u);
    EXPECT_NEAR(image.min_distance, 0.05, 1e-12);
    // The second cube crosses x = 1 and its image overlaps the first; a wall would refuse it.
    const VerifyResult crossing =
        verify(periodic_cube_pair(0.1, 0.95, {true, false, false}), {.is_brute_force = brute});
    EXPECT_FALSE(crossing.is_ok);
    EXPECT_EQ(crossing.outside_particles, 0u);
    EXPECT_EQ(crossing.overlapping_pairs, 1u);
    EXPECT_EQ(
        verify(periodic_cube_pair(0.1, 0.95, {}), {.is_brute_force = brute}).outside_particles, 1u);
    // A centre given outside the box is wrapped: x = -0.05 is x = 0.95.
    EXPECT_FALSE(
        verify(periodic_cube_pair(0.1, -0.05, {true, false, false}), {.is_brute_force = brute})
            .is_ok);
    // A cube wider than the period meets its own image.
    Packing alone = periodic_cube_pair(0.5, 0.5, {true, false, false});
    alone.particles.pop_back();
    std::get<BoxContainer>(alone.container.shape).length = 0.15;
    const VerifyResult self = verify(alone, {.is_brute_force = brute});
    EXPECT_FALSE(self.is_ok);
    EXPECT_GE(self.overlapping_pairs, 1u);
  }
}

TEST(PeriodicRandom, PackingHasNoOverlapAmongAllImages) {
  for (const std::array<bool, 3>& axes :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, true, false}}) {
    const RandomPackOptions options = periodic_random_options(axes, 7);
    const PackResult result = pack_random(options);
    const Packing& packing = result.packing;
    ASSERT_GT(packing.particles.size(), 50u);
    EXPECT_TRUE(result.report.is_target_reached);
    EXPECT_EQ(periodic_axes(packing.container), axes);
    double closest = 0.0;
    EXPECT_EQ(periodic_brute_force_overlaps(packing, options.gap, closest), 0u)
        << "closest " << closest;
    // Walls only where the axis is not periodic; some particles really cross a periodic face.
    std::size_t crossing = 0;
    double solid = 0.0;
    for (std::size_t i = 0; i < packing.particles.size(); ++i) {
      const ConvexPolyhedron body = packing.placed(i);
      const Aabb box = body.bounds();
      EXPECT_TRUE(contains(packing.container, packing.local_body(i), packing.particles[i].pose));
      for (int axis = 0; axis < 3; ++axis) {
        const Vec3& centre = packing.particles[i].pose.position;
        EXPECT_GE(centre[axis], 0.0);
        EXPECT_LE(centre[axis], 0.2);
        if (!axes[static_cast<std::size_t>(axis)]) {
          EXPECT_GE(box.lower[axis], 0.0);
          EXPECT_LE(box.upper[axis], 0.2);
        }
      }
      if ((box.lower.array() < 0.0).any() || (box.upper.array() > 0.2).any()) ++crossing;
      solid += mass_properties(body).volume;
    }
    EXPECT_GT(crossing, 5u);
    // Each particle counts once, whole: the fraction is the sum of the volumes over the box's.
    EXPECT_NEAR(result.report.solid_fraction, solid / 0.008, 1e-9);
    EXPECT_GE(result.report.solid_fraction, 0.3);
    const PackingStatistics stats = compute_statistics(packing, {.has_descriptors = false});
    EXPECT_NEAR(stats.solid_fraction, solid / 0.008, 1e-9);
    // Along a periodic axis the parts beyond a face are binned on the opposite side: the bins
    // hold the whole solid volume, so their mean is the fraction.
    for (int axis = 0; axis < 3; ++axis) {
      if (!axes[static_cast<std::size_t>(axis)]) continue;
      double sum = 0.0;
      for (double value : stats.profiles[static_cast<std::size_t>(axis)].solid_fraction) {
        sum += value;
      }
      EXPECT_NEAR(sum / 10.0, stats.solid_fraction, 1e-9) << "axis " << axis;
    }
    for (bool brute : {false, true}) {
      const VerifyResult check = verify(packing, {.gap = options.gap, .is_brute_force = brute});
      EXPECT_TRUE(check.is_ok) << check.message;
    }
  }
}

TEST(PeriodicRandom, SameSeedSameResultAtOneAndTwoThreads) {
  const RandomPackOptions options = periodic_random_options({true, true, true}, 11);
  const PackResult one = test::with_threads(1, [&] { return pack_random(options); });
  const PackResult two = test::with_threads(2, [&] { return pack_random(options); });
  ASSERT_GT(one.packing.particles.size(), 50u);
  testing::expect_identical(one.packing, two.packing);
  EXPECT_EQ(one.report.attempts, two.report.attempts);
}

TEST(PeriodicRandom, BoxMustExceedTwiceTheLargestParticle) {
  RandomPackOptions options = periodic_random_options({false, true, false}, 3);
  std::get<BoxContainer>(options.container.shape).width = 0.045;  // < 2 x 0.025 + gap
  try {
    (void)pack_random(options);
    ADD_FAILURE() << "accepted";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "container.periodic");
    EXPECT_EQ(error.value(), "\"y\"");
    const std::string text = error.what();
    EXPECT_NE(text.find("container.width = 0.045 m"), std::string::npos) << text;
    EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  }
  // The same box without the periodic axis is not refused for that reason.
  options.container = periodic_box(0.2, 0.2, 0.2, {});
  EXPECT_NO_THROW((void)pack_random(options));
}

TEST(PeriodicRandom, LatticeAndBedRefusePeriodicBoxes) {
  const Container box = periodic_box(1.0, 1.0, 1.0, {false, false, true});
  EXPECT_EQ(testing::invalid_field([&] { pack_lattice({.container = box}); }),
            "container.periodic");
  // The dense kind takes periodic boxes (periodic_dense_test.cpp), but a bed needs its floor.
  DensePackOptions dense;
  std::get<RandomPackOptions>(dense.fill).container = box;
  EXPECT_NO_THROW(validate(dense));
  dense.densify.mode = DensifyMode::kBed;
  EXPECT_EQ(testing::invalid_field([&] { validate(dense); }), "container.periodic");
  std::get<RandomPackOptions>(dense.fill).container =
      periodic_box(1.0, 1.0, 1.0, {true, true, false});
  EXPECT_NO_THROW(validate(dense));
}

}  // namespace
}  // namespace aggpack
