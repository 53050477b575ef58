// The densifier in a periodic box: neighbours found across periodic faces, centres wrapped back
// into the box, compression that scales the period, each checked by an independent brute force
// over all 27 image shifts; the same bytes at one and two threads.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/statistics.h"
#include "aggpack/pack/verify.h"
#include "pack/pack_test_util.h"
#include "support/packings.h"
#include "support/periodic.h"

namespace aggpack {
namespace {

// Single-size particles of alpha 0.5, L = r, placed by random sequential addition at 25 % in a
// periodic cube of side `side` (m): a densify start.
Packing periodic_rsa_start(double side, double radius, std::array<bool, 3> axes,
                           std::uint64_t seed) {
  RandomPackOptions options;
  options.container = test::periodic_box(side, side, side, axes);
  options.grading.kind = GradingKind::kUniform;
  options.grading.radius_min = radius;
  options.grading.radius_max = radius;
  options.shape = {.alpha = 0.5, .edge_length_ratio = 1.0};
  options.target = PackTarget::kVolumeFraction;
  options.volume_fraction = 0.25;
  options.gap = 0.0005;
  options.seed = seed;
  return pack_random(options).packing;
}

// Everything a periodic dense packing must be: no overlap among all images (brute force, the
// gap kept), whole particles inside the walls of the walled axes, centres in [0, L) along the
// periodic axes, the container's periodic axes kept; some particles cross a face.
void expect_valid_periodic(const Packing& packing, std::array<bool, 3> axes, double gap) {
  EXPECT_EQ(periodic_axes(packing.container), axes);
  double closest = 0.0;
  EXPECT_EQ(test::periodic_brute_force_overlaps(packing, gap, closest), 0u)
      << "closest " << closest;
  EXPECT_TRUE(verify(packing, {.gap = gap, .is_brute_force = true}).is_ok);
  const Vec3 extent = packing.container.bounds().extent();
  std::size_t crossing = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Vec3& centre = packing.particles[i].pose.position;
    EXPECT_TRUE(contains(packing.container, packing.local_body(i), packing.particles[i].pose));
    const Aabb box = packing.placed(i).bounds();
    for (int axis = 0; axis < 3; ++axis) {
      if (!axes[static_cast<std::size_t>(axis)]) {
        EXPECT_GE(box.lower[axis], 0.0);
        EXPECT_LE(box.upper[axis], extent[axis]);
        continue;
      }
      EXPECT_GE(centre[axis], 0.0) << "particle " << i << " axis " << axis;
      EXPECT_LT(centre[axis], extent[axis]) << "particle " << i << " axis " << axis;
      if (box.lower[axis] < 0.0 || box.upper[axis] > extent[axis]) ++crossing;
    }
  }
  EXPECT_GT(crossing, 2u);
}

DensifyResult densify_at_one_and_two_threads(const Packing& start, const DensifyOptions& options) {
  DensifyResult one = test::with_threads(1, [&] { return densify(start, options); });
  const DensifyResult two = test::with_threads(2, [&] { return densify(start, options); });
  testing::expect_identical(one.packing, two.packing);
  EXPECT_EQ(one.packing.container.get_if<BoxContainer>()->length,
            two.packing.container.get_if<BoxContainer>()->length);
  EXPECT_EQ(one.report.moves_accepted, two.report.moves_accepted);
  EXPECT_EQ(one.report.compressions, two.report.compressions);
  return one;
}

TEST(PeriodicDense, CompressesWithoutOverlapAmongAllImagesAtAnyThreadCount) {
  for (const std::array<bool, 3>& axes :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, true, false}}) {
    // r = 15 mm in a 0.24 m cube: four or more cells per periodic axis, and many particles
    // across the faces.
    const Packing start = periodic_rsa_start(0.24, 0.015, axes, 5);
    ASSERT_GT(start.particles.size(), 100u);
    const DensifyOptions options{
        .target_fraction = 0.5, .gap = 0.0005, .seed = 3, .max_sweeps = 250};
    const DensifyResult result = densify_at_one_and_two_threads(start, options);
    const DensifyReport& report = result.report;
    EXPECT_GT(report.solid_fraction, report.start_fraction + 0.1) << report.summary();
    EXPECT_GT(report.compressions, 5u);
    expect_valid_periodic(result.packing, axes, options.gap);
    // Each particle counts once: the fraction is the sum of the volumes over the box's.
    double solid = 0.0;
    for (std::size_t i = 0; i < result.packing.particles.size(); ++i) {
      solid += mass_properties(result.packing.placed(i)).volume;
    }
    EXPECT_NEAR(report.solid_fraction, solid / result.packing.container.volume(), 1e-9);
    const PackingStatistics stats = compute_statistics(result.packing, {.has_descriptors = false});
    EXPECT_NEAR(stats.solid_fraction, report.solid_fraction, 1e-9);
  }
}

TEST(PeriodicDense, FewCellsPerPeriodStillFindEveryImage) {
  // r = 20 mm in a 0.11 m cube compressed toward 0.45: one or two cells per periodic axis, so
  // every cell is a neighbour and a neighbour may meet a particle through two of its images.
  const std::array<bool, 3> axes{true, true, true};
  const Packing start = periodic_rsa_start(0.11, 0.02, axes, 8);
  ASSERT_GT(start.particles.size(), 8u);
  const DensifyOptions options{
      .target_fraction = 0.45, .gap = 0.0005, .seed = 4, .max_sweeps = 300};
  const DensifyResult result = densify_at_one_and_two_threads(start, options);
  EXPECT_GT(result.report.solid_fraction, result.report.start_fraction + 0.05)
      << result.report.summary();
  expect_valid_periodic(result.packing, axes, options.gap);
}

TEST(PeriodicDense, BedKeepsItsFloorAndATargetMustLeaveRoomForTheImages) {
  const Packing start = periodic_rsa_start(0.24, 0.015, {true, true, false}, 6);
  // A bed in a box periodic in x and y settles onto its floor.
  const DensifyResult bed =
      densify(start, {.mode = DensifyMode::kBed, .gap = 0.0005, .seed = 2, .max_sweeps = 40});
  expect_valid_periodic(bed.packing, {true, true, false}, 0.0005);
  EXPECT_LT(bed.report.solid_fraction, 1.0);
  // Periodic in z: no floor to settle on.
  const Packing lid = periodic_rsa_start(0.24, 0.015, {false, false, true}, 6);
  EXPECT_EQ(testing::invalid_field([&] { densify(lid, {.mode = DensifyMode::kBed}); }),
            "container.periodic");
  // A target period below 2 x the largest bounding radius + gap: refused before any sweep.
  DensifyOptions tight{.gap = 0.0005};
  tight.target_container = test::periodic_box(0.02, 0.24, 0.24, {});
  EXPECT_EQ(testing::invalid_field([&] { densify(start, tight); }), "container.periodic");
}

}  // namespace
}  // namespace aggpack
