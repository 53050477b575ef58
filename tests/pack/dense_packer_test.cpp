#include "aggpack/pack/dense_packer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/statistics.h"
#include "pack/pack_test_util.h"
#include "support/packings.h"

namespace aggpack {
namespace {

using testing::expect_identical;
using testing::expect_valid_packing;
using testing::invalid_field;

// Particles placed by random sequential addition at `fraction` of the container: a densify start.
Packing rsa_start(const Container& container, double radius_min, double radius_max, double fraction,
                  std::uint64_t seed, double gap = 0.0, const ShapeOptions& shape = {}) {
  // Member by member: GCC 12 warns (maybe-uninitialized, a false positive) about the grading's
  // sieve when these options are built with designated initialisers from parameters.
  RandomPackOptions options;
  options.container = container;
  options.grading.kind = GradingKind::kUniform;
  options.grading.radius_min = radius_min;
  options.grading.radius_max = radius_max;
  options.shape = shape;
  options.target = PackTarget::kVolumeFraction;
  options.volume_fraction = fraction;
  options.gap = gap;
  options.seed = seed;
  return pack_random(options).packing;
}

// Single-size particles of alpha 0.5 and L = r (the packers' test shape).
const ShapeOptions kTestShape{.alpha = 0.5, .edge_length_ratio = 1.0};

// ~60 single-size particles (alpha 0.5, L = r) placed by RSA at 25 % in a 0.4 m cube.
Packing loose_start(double gap = 0.0, double wall_gap = 0.0, std::uint64_t seed = 3) {
  const Container cube{.shape = BoxContainer{.length = 0.4, .width = 0.4, .depth = 0.4},
                       .wall_gap = wall_gap};
  return rsa_start(cube, 0.05, 0.05, 0.25, seed, gap, kTestShape);
}

// The same densify run at one and at two threads: the packings, the container and the accepted
// moves must be identical. Returns the one-thread run.
DensifyResult expect_thread_independent(const Packing& start, const DensifyOptions& options) {
  DensifyResult one = test::with_threads(1, [&] { return densify(start, options); });
  const DensifyResult two = test::with_threads(2, [&] { return densify(start, options); });
  expect_identical(one.packing, two.packing);
  EXPECT_EQ(one.packing.container.get_if<BoxContainer>()->length,
            two.packing.container.get_if<BoxContainer>()->length);
  EXPECT_EQ(one.report.moves_accepted, two.report.moves_accepted);
  EXPECT_EQ(one.report.compressions, two.report.compressions);
  return one;
}

TEST(DensePacker, FixedModeReachesTheTargetFractionExactly) {
  const Packing start = loose_start();
  DensifyOptions options{.target_fraction = 0.42, .seed = 5, .max_sweeps = 3000};
  const DensifyResult result = densify(start, options);
  EXPECT_EQ(result.report.stop, DensifyStop::kTargetReached) << result.report.summary();
  EXPECT_GE(result.report.solid_fraction, 0.42 * (1 - 1e-9));
  EXPECT_LT(result.report.start_fraction, 0.30);
  EXPECT_EQ(result.packing.provenance.packer, "dense");
  EXPECT_LT(result.packing.container.get_if<BoxContainer>()->length,
            start.container.get_if<BoxContainer>()->length);
  ASSERT_EQ(result.packing.particles.size(), start.particles.size());
  // Shapes are never deformed: same shapes, scales and classes.
  for (std::size_t i = 0; i < start.particles.size(); ++i) {
    EXPECT_EQ(result.packing.particles[i].shape, start.particles[i].shape);
    EXPECT_EQ(result.packing.particles[i].scale, start.particles[i].scale);
  }
  expect_valid_packing(result.packing, 0.0);
}

TEST(DensePacker, EachParticleAdaptsItsStepsToTheTargetAcceptance) {
  // Fixed mode: every particle tunes its own translation and rotation steps by its own moves
  // (up on acceptance, down on rejection, balanced at target_acceptance). Over a run the
  // acceptance rate settles near the target, and a lower target means larger steps.
  const Packing start = loose_start();
  auto run = [&](double acceptance) {
    const DensifyOptions options{
        .target_fraction = 0.6, .seed = 5, .max_sweeps = 1500, .target_acceptance = acceptance};
    return densify(start, options).report;
  };
  const DensifyReport at_30 = run(0.3);
  const DensifyReport at_15 = run(0.15);
  for (const auto& [report, target] : {std::pair{at_30, 0.3}, std::pair{at_15, 0.15}}) {
    ASSERT_GT(report.moves_tried, 0U);
    const double rate =
        static_cast<double>(report.moves_accepted) / static_cast<double>(report.moves_tried);
    EXPECT_NEAR(rate, target, 0.05) << report.summary();
  }
  EXPECT_GT(at_15.translation_step, at_30.translation_step);
  EXPECT_GT(at_15.rotation_step, at_30.rotation_step);
}

TEST(DensePacker, GapsAndWallGapsAreKeptToAnExplicitTargetContainer) {
  const double gap = 0.002;
  const double wall_gap = 0.003;
  const Packing start = loose_start(gap, wall_gap);
  Container target = start.container;
  target.get_if<BoxContainer>()->length = 0.36;
  target.get_if<BoxContainer>()->depth = 0.37;
  const DensifyOptions options{.target_container = target, .gap = gap, .max_sweeps = 2000};
  const DensifyResult result = densify(start, options);
  EXPECT_EQ(result.report.stop, DensifyStop::kTargetReached) << result.report.summary();
  EXPECT_EQ(result.packing.container.get_if<BoxContainer>()->length, 0.36);
  EXPECT_EQ(result.packing.container.get_if<BoxContainer>()->width, 0.4);
  EXPECT_EQ(result.packing.container.get_if<BoxContainer>()->depth, 0.37);
  EXPECT_EQ(result.packing.container.wall_gap, wall_gap);
  expect_valid_packing(result.packing, gap);
  EXPECT_GE(result.report.min_distance, gap * (1.0 - 1e-9));
}

TEST(DensePacker, CylinderIsCompressedTowardItsTarget) {
  const Packing start =
      rsa_start({.shape = CylinderContainer{.radius = 0.25, .height = 0.4}, .wall_gap = 0.002},
                0.04, 0.05, 0.22, 8, 0.001);
  Container target = start.container;
  target.get_if<CylinderContainer>()->radius = 0.22;
  target.get_if<CylinderContainer>()->height = 0.36;
  const DensifyOptions options{.target_container = target, .gap = 0.001, .max_sweeps = 3000};
  const DensifyResult result = densify(start, options);
  EXPECT_EQ(result.report.stop, DensifyStop::kTargetReached) << result.report.summary();
  ASSERT_NE(result.packing.container.get_if<CylinderContainer>(), nullptr);
  EXPECT_EQ(result.packing.container.get_if<CylinderContainer>()->radius, 0.22);
  EXPECT_EQ(result.packing.container.get_if<CylinderContainer>()->height, 0.36);
  expect_valid_packing(result.packing, 0.001);
}

TEST(DensePacker, SameSeedIsByteIdenticalAtOneAndTwoThreads) {
  const Packing start = loose_start();
  const DensifyOptions options{.target_fraction = 0.38, .seed = 9, .max_sweeps = 60};
  const DensifyResult one = expect_thread_independent(start, options);
  EXPECT_GT(one.report.moves_accepted, 0u);
  DensifyOptions other = options;
  other.seed = 10;
  const DensifyResult three = densify(start, other);
  EXPECT_NE(three.packing.particles[0].pose.position, one.packing.particles[0].pose.position);
}

// A few hundred particles (r = 20 mm in the 0.4 m cube): enough cells for both threads to move
// particles at once, and squeezes that make overlaps which the repair passes on (overlap
// transfer) to particles in other cells.
Packing crowded_start() {
  const Container cube{.shape = BoxContainer{.length = 0.4, .width = 0.4, .depth = 0.4}};
  return rsa_start(cube, 0.02, 0.02, 0.3, 4, 0.0, kTestShape);
}

TEST(DensePacker, OverlapTolerantCompressionEndsOverlapFreeAndThreadIndependent) {
  const Packing start = crowded_start();
  ASSERT_GT(start.particles.size(), 300u);
  const DensifyOptions options{.target_fraction = 0.6, .seed = 7, .max_sweeps = 300};
  const DensifyResult one = expect_thread_independent(start, options);
  // It compressed a long way (squeezes repaired many times over)...
  EXPECT_GT(one.report.compressions, 20u);
  EXPECT_GT(one.report.solid_fraction, one.report.start_fraction + 0.12) << one.report.summary();
  const PackingStatistics measured = compute_statistics(one.packing, {.has_descriptors = false});
  EXPECT_NEAR(one.report.solid_fraction, measured.solid_fraction, 1e-9);
  // ... and only an overlap-free state came back: every pair by an independent distance check.
  expect_valid_packing(one.packing, 0.0);
}

TEST(DensePacker, ProgressNeverGoesBackward) {
  const Packing start = crowded_start();
  PackControl control;
  control.progress_interval = 0.0;
  std::vector<PackProgress> seen;
  control.on_progress = [&](const PackProgress& progress) { seen.push_back(progress); };
  const DensifyResult result =
      densify(start, {.target_fraction = 0.6, .seed = 3, .max_sweeps = 200}, control);
  ASSERT_GE(seen.size(), 200u);
  for (std::size_t k = 1; k < seen.size(); ++k) {
    EXPECT_GE(seen[k].fraction, seen[k - 1].fraction) << "update " << k;
    EXPECT_GE(seen[k].solid_fraction, seen[k - 1].solid_fraction) << "update " << k;
    EXPECT_GE(seen[k].placed, seen[k - 1].placed) << "update " << k;
  }
  EXPECT_EQ(seen.back().fraction, 1.0);
  EXPECT_EQ(seen.back().solid_fraction, result.report.solid_fraction);
  EXPECT_GT(seen.back().solid_fraction, seen.front().solid_fraction + 0.05);
}

TEST(DensePacker, FractionRisesMonotonicallyWithTheSweepBudget) {
  const Packing start = loose_start();
  double previous = 0.0;
  double first = 0.0;
  for (const std::uint64_t sweeps : {5u, 20u, 60u, 150u}) {
    const DensifyOptions options{.target_fraction = 0.55, .seed = 2, .max_sweeps = sweeps};
    const DensifyResult result = densify(start, options);
    EXPECT_EQ(result.report.sweeps, sweeps);
    EXPECT_GE(result.report.solid_fraction, previous) << sweeps << " sweeps";
    if (first == 0.0) first = result.report.solid_fraction;
    previous = result.report.solid_fraction;
    expect_valid_packing(result.packing, 0.0);
  }
  EXPECT_GT(previous, first + 0.01);
}

// A run continued from a dense packing starts with a squeeze sized for a loose one (here the
// largest allowed, max_compression 0.1, a quarter of it first); it must still compress (an early
// version waited forever: more than 5 % flagged, so no squeeze, so no consolidation, so no stall
// handling, and it stopped as jammed with nothing gained).
TEST(DensePacker, ContinuingFromADensePackingKeepsCompressing) {
  const DensifyOptions first{.target_fraction = 0.62, .seed = 2, .max_sweeps = 1500};
  const DensifyResult dense = densify(loose_start(), first);
  ASSERT_GT(dense.report.solid_fraction, 0.45) << dense.report.summary();
  const DensifyOptions more{
      .target_fraction = 0.62, .seed = 3, .max_sweeps = 800, .max_compression = 0.1};
  const DensifyResult continued = densify(dense.packing, more);
  EXPECT_GT(continued.report.solid_fraction, dense.report.solid_fraction + 0.003)
      << continued.report.summary();
  expect_valid_packing(continued.packing, 0.0);
}

TEST(DensePacker, GravityBedSinksAndStaysValid) {
  const Packing start = rsa_start(
      {.shape = BoxContainer{.length = 0.3, .width = 0.3, .depth = 0.6}}, 0.04, 0.05, 0.2, 4);
  auto centre_height = [](const Packing& packing) {
    double sum = 0.0;
    for (const Particle& p : packing.particles) sum += p.pose.position.z();
    return sum / static_cast<double>(packing.particles.size());
  };
  DensifyOptions options{.mode = DensifyMode::kBed, .seed = 6, .max_sweeps = 300};
  options.bed_temperature = 0.05;  // a quick quench: this test is about sinking
  options.bed_cooling = 0.99;
  const DensifyResult result = densify(start, options);
  EXPECT_LT(centre_height(result.packing), 0.8 * centre_height(start));
  EXPECT_GT(result.report.bulk_fraction, 0.2);
  EXPECT_GT(result.report.surface_height, 0.0);
  EXPECT_LT(result.report.surface_height, 0.6);
  EXPECT_EQ(result.packing.container.get_if<BoxContainer>()->depth,
            0.6);  // the bed's container is not shrunk
  expect_valid_packing(result.packing, 0.0);
}

TEST(DensePacker, EachBadOptionNamesItself) {
  const Packing start = loose_start();
  auto field = [&](auto change) {
    DensifyOptions options;
    change(options);
    return invalid_field([&] { (void)densify(start, options); });
  };
  EXPECT_EQ(field([](auto& o) { o.target_fraction = 0.97; }), "densify.target_fraction");
  EXPECT_EQ(field([](auto& o) { o.gap = -1.0; }), "densify.gap");
  EXPECT_EQ(field([](auto& o) { o.max_sweeps = 0; }), "densify.max_sweeps");
  EXPECT_EQ(field([](auto& o) { o.max_seconds = -1.0; }), "densify.max_seconds");
  EXPECT_EQ(field([](auto& o) { o.target_acceptance = 1.0; }), "densify.target_acceptance");
  EXPECT_EQ(field([](auto& o) { o.translation_step = 0.0; }), "densify.translation_step");
  EXPECT_EQ(field([](auto& o) { o.rotation_step = 4.0; }), "densify.rotation_step");
  EXPECT_EQ(field([](auto& o) { o.rotation_probability = 1.5; }), "densify.rotation_probability");
  EXPECT_EQ(field([](auto& o) { o.compress_interval = 0; }), "densify.compress_interval");
  EXPECT_EQ(field([](auto& o) { o.max_compression = 0.5; }), "densify.max_compression");
  EXPECT_EQ(field([](auto& o) { o.bed_temperature = -0.1; }), "densify.bed_temperature");
  EXPECT_EQ(field([](auto& o) { o.bed_cooling = 0.0; }), "densify.bed_cooling");
  EXPECT_EQ(field([](auto& o) { o.stall_sweeps = 0; }), "densify.stall_sweeps");
  EXPECT_EQ(field([](auto& o) { o.stall_tolerance = -1.0; }), "densify.stall_tolerance");
  EXPECT_EQ(field([&](auto& o) {
              o.target_container = start.container;
              std::get<BoxContainer>(o.target_container->shape).length = 0.5;
            }),
            "densify.target_container.length");
  EXPECT_EQ(field([&](auto& o) {
              o.target_container = start.container;
              o.target_container->shape = CylinderContainer{};
            }),
            "densify.target_container");
  EXPECT_EQ(field([&](auto& o) {
              o.target_container = start.container;
              o.target_container->wall_gap = 0.01;
            }),
            "densify.target_container.wall_gap");
  // A start packing that overlaps (or sits closer than the gap) is refused.
  Packing overlapping = start;
  overlapping.particles[1].pose.position = overlapping.particles[0].pose.position;
  EXPECT_EQ(invalid_field([&] { (void)densify(overlapping, {}); }), "start packing");
  EXPECT_EQ(invalid_field([&] { (void)densify(start, {.gap = 0.5}); }), "start packing");
}

TEST(DensePacker, CancelStopsWithAValidPacking) {
  const Packing start = loose_start();
  std::atomic<bool> cancel{false};
  int calls = 0;
  PackControl control;
  control.progress_interval = 0.0;
  control.cancel = &cancel;
  control.on_progress = [&](const PackProgress& progress) {
    ++calls;
    EXPECT_GE(progress.solid_fraction, 0.2);
    if (progress.placed >= 3) cancel = true;
  };
  const DensifyResult result =
      densify(start, {.target_fraction = 0.6, .max_sweeps = 100000}, control);
  EXPECT_EQ(result.report.stop, DensifyStop::kCancelled);
  EXPECT_EQ(result.report.sweeps, 3u);
  EXPECT_GE(calls, 3);
  expect_valid_packing(result.packing, 0.0);
}

}  // namespace
}  // namespace aggpack
