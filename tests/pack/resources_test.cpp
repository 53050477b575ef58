// Up-front refusal of runaway runs (issue 12): a size list the container cannot hold or whose
// shapes would not fit in memory is refused by validate(), before any shape is grown for the run.

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <numbers>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/resources.h"

namespace aggpack {
namespace {

// Sets AGGPACK_MEMORY_LIMIT for one scope.
class ScopedMemoryLimit {
 public:
  explicit ScopedMemoryLimit(const char* value) { setenv("AGGPACK_MEMORY_LIMIT", value, 1); }
  ~ScopedMemoryLimit() { unsetenv("AGGPACK_MEMORY_LIMIT"); }
  ScopedMemoryLimit(const ScopedMemoryLimit&) = delete;
  ScopedMemoryLimit& operator=(const ScopedMemoryLimit&) = delete;
};

std::string limit_message(const auto& options) {
  try {
    validate(options);
  } catch (const Error& error) {
    EXPECT_EQ(error.kind(), ErrorKind::kLimitExceeded) << error.what();
    return error.what();
  }
  return "";
}

RandomPackOptions count_target(std::uint64_t count) {
  return {.target = PackTarget::kCount, .count = count};  // default box 3 x 1 x 2.8 m, r = 0.1 m
}

TEST(Resources, CountTheContainerCannotHoldIsRefusedWithTheEstimate) {
  // count_1e8_default_box.toml: 10^8 particles of r = 0.1 m in 8.4 m^3.
  const std::string message = limit_message(count_target(100000000));
  EXPECT_NE(message.find("random.count = 100000000"), std::string::npos) << message;
  EXPECT_NE(message.find("at most ~"), std::string::npos) << message;
  EXPECT_NE(message.find("8.4 m^3"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // The estimate itself: an aggregate of alpha 0.5, L = r fills about 0.2 of its control sphere,
  // so the box holds some thousands at 0.74.
  const RunEstimate estimate = estimate_run(count_target(100000000));
  const double sphere = 4.0 / 3.0 * std::numbers::pi * 0.001;
  EXPECT_GT(estimate.mean_volume, 0.1 * sphere);
  EXPECT_LT(estimate.mean_volume, 0.4 * sphere);
  EXPECT_GT(estimate.capacity, 3000.0);
  EXPECT_LT(estimate.capacity, 15000.0);
  EXPECT_GT(estimate.solid_fraction, 1000.0);
}

TEST(Resources, CountsTheContainerCanHoldPass) {
  EXPECT_NO_THROW(validate(count_target(1000)));
  // Just below the capacity is still accepted: the packer then reports what it placed.
  const double capacity = estimate_run(count_target(1)).capacity;
  EXPECT_NO_THROW(validate(count_target(static_cast<std::uint64_t>(0.9 * capacity))));
  EXPECT_THROW(validate(count_target(static_cast<std::uint64_t>(1.2 * capacity))), LimitExceeded);
}

TEST(Resources, MeanVolumeEstimateMatchesAPackedRun) {
  RandomPackOptions options{
      .container = {.shape = BoxContainer{.length = 0.4, .width = 0.4, .depth = 0.4}},
      .grading = {.kind = GradingKind::kFuller,
                  .size_min = 0.02,
                  .size_max = 0.06,
                  .exponent = 0.5},
      .target = PackTarget::kCount,
      .count = 300,
      .seed = 3};
  const RunEstimate estimate = estimate_run(options);
  const PackResult result = pack_random(options);
  ASSERT_EQ(result.report.placed, 300u);
  const double measured = result.report.solid_volume / 300.0;
  EXPECT_NEAR(estimate.mean_volume / measured, 1.0, 0.2);
}

TEST(Resources, SizeListBeyondTheMemoryLimitIsRefused) {
  // fuller_in_default_box.toml: ~5 x 10^7 particles of 5-20 mm at 35 % of 8.4 m^3.
  RandomPackOptions fuller{.grading = {.kind = GradingKind::kFuller},
                           .target = PackTarget::kVolumeFraction,
                           .volume_fraction = 0.35};
  const RunEstimate estimate = estimate_run(fuller);
  EXPECT_GT(estimate.particles, 1e7);
  EXPECT_LT(estimate.particles, 2e8);
  {
    const ScopedMemoryLimit limit("8G");
    const std::string message = limit_message(fuller);
    EXPECT_NE(message.find("random.volume_fraction = 0.35"), std::string::npos) << message;
    EXPECT_NE(message.find("memory limit of 8.59 GB (AGGPACK_MEMORY_LIMIT=8G)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("shape.library_size"), std::string::npos) << message;
  }
  // The same small run passes or fails only by the limit.
  const RandomPackOptions small = count_target(2000);
  const double bytes = estimate_run(small).bytes;
  EXPECT_GT(bytes, 2000 * 500.0);
  EXPECT_LT(bytes, 2000 * 5000.0);
  {
    const ScopedMemoryLimit limit("1M");
    EXPECT_THROW(validate(small), LimitExceeded);
  }
  {
    const ScopedMemoryLimit limit("1G");
    EXPECT_NO_THROW(validate(small));
  }
}

// A shape library grows every shape before placement: far more shapes than the target needs (10 x
// the particles, at least 1000 shapes) is refused with the estimate when growing it is heavy
// (above 1 GB or 10 s); a few thousand spare shapes are not.
TEST(Resources, LibraryFarAboveTheTargetIsRefusedWhenGrowingItIsHeavy) {
  const ScopedMemoryLimit limit("1T");  // the library check, not the memory limit's
  RandomPackOptions options = count_target(100);
  options.shape.edge_length = 0.0;
  options.shape.library_size = 1000;  // the floor: accepted for any target
  EXPECT_NO_THROW(validate(options));
  options.shape.library_size = 1001;  // above 10 x 100, but a few MB: accepted
  EXPECT_NO_THROW(validate(options));
  options.shape.library_size = 1000000;  // gigabytes of shapes never used
  const std::string message = limit_message(options);
  EXPECT_EQ(message.rfind("limit exceeded for shape.library_size = 1000000 (allowed: at most 1000 "
                          "(10 x the ~100 particles this target needs, at least 1000): every "
                          "library shape is grown before placement, so the run would need ~",
                          0),
            0U)
      << message;
  EXPECT_NE(message.find(" GB and ~"), std::string::npos) << message;
}

// The heads-up of a heavy run: one line above 10 s or 1 GB, nothing below both.
TEST(Resources, HeavyRunNoteAboveTenSecondsOrOneGigabyte) {
  RunEstimate estimate{.particles = 5000, .bytes = 5e8, .seconds = 3.0};
  EXPECT_EQ(heavy_run_note(estimate), "");
  estimate.bytes = 2.5e9;
  EXPECT_EQ(heavy_run_note(estimate),
            "a large run: ~5000 particles, ~2.5 GB of memory, ~3 s (rough estimate; Ctrl-C stops "
            "it)");
  estimate.bytes = 5e8;
  estimate.seconds = 600.0;
  EXPECT_EQ(heavy_run_note(estimate),
            "a large run: ~5000 particles, ~500 MB of memory, ~10 min (rough estimate; Ctrl-C "
            "stops it)");
}

// The other commands' estimates: the per-unit costs times the work, exactly.
TEST(Resources, DensifySimulationAndMesomodelEstimates) {
  // densify: 5e-6 s per particle and sweep over the threads, capped by --max-time; 5.2 kB each.
  RunEstimate densify = estimate_densify(1000, 4000, 0.0, 2);
  EXPECT_DOUBLE_EQ(densify.seconds, 1000 * 4000 * 5e-6 / 2);
  EXPECT_DOUBLE_EQ(densify.bytes, 1000 * 5.2e3);
  EXPECT_TRUE(densify.is_upper_bound);
  EXPECT_DOUBLE_EQ(estimate_densify(1000, 4000, 3.0, 2).seconds, 3.0);
  EXPECT_EQ(heavy_run_note(estimate_densify(1e5, 2000, 0.0, 1)),
            "a large run: ~100000 particles, ~520 MB of memory, up to ~17 min (rough estimate; "
            "Ctrl-C stops it)");
  // Bullet: 5.7e-5 s per body and step up to 1,000 bodies, x (n / 1000)^0.42 above; runs in
  // rounds of `parallel`; 4 kB per body plus twice the shapes, for each run at a time.
  const RunEstimate small = estimate_simulation(500, 1e6, 1000, 1, 1);
  EXPECT_DOUBLE_EQ(small.seconds, 500 * 1000 * 5.7e-5);
  EXPECT_DOUBLE_EQ(small.bytes, 500 * 4e3 + 2e6);
  const RunEstimate large = estimate_simulation(10000, 0.0, 100, 5, 2);
  EXPECT_NEAR(large.seconds, 3 * 10000 * 100 * 5.7e-5 * std::pow(10.0, 0.42), 1e-9);
  EXPECT_DOUBLE_EQ(large.bytes, 2 * 10000 * 4e3);
  // Steps to rest: twice the fall from h, min_time, quiet_time and 1 s, capped by max_time.
  EXPECT_DOUBLE_EQ(expected_steps(4.905, 0.5, 0.25, 30.0, 0.01), (0.5 + 2.0 + 0.25 + 1.0) / 0.01);
  EXPECT_DOUBLE_EQ(expected_steps(4.905, 0.5, 0.25, 2.0, 0.01), 2.0 / 0.01);
  EXPECT_NEAR(automatic_time_step(0.0981, 0.04), 0.004, 1e-15);
  // mesomodel: 2.8 ms and 190 kB per aggregate; a phase image 0.8 us and 5 bytes per voxel.
  EXPECT_DOUBLE_EQ(estimate_mesomodel(6000, 0.0).bytes, 6000 * 1.9e5);
  EXPECT_DOUBLE_EQ(estimate_mesomodel(6000, 0.0).seconds, 6000 * 2.8e-3);
  EXPECT_DOUBLE_EQ(estimate_mesomodel(6000, 1e9).bytes, 5e9);
  EXPECT_DOUBLE_EQ(estimate_mesomodel(6000, 1e9).seconds, 800.0);
}

TEST(Resources, LatticeBeyondTheMemoryLimitIsRefused) {
  LatticeOptions options;  // the paper's box
  options.radius = 0.003;  // ~3.9 x 10^7 sites
  options.edge_length = 0.003;
  const ScopedMemoryLimit limit("4G");
  const std::string message = limit_message(options);
  EXPECT_NE(message.find("lattice.radius = 0.003"), std::string::npos) << message;
  EXPECT_NE(message.find("~3.9e+07 particles"), std::string::npos) << message;
  options.radius = 1e-12;  // 10^12 sites per axis: refused, never overflows
  options.edge_length = 1e-12;
  EXPECT_THROW(validate(options), LimitExceeded);
}

TEST(Resources, MemoryLimitComesFromTheMachineOrTheEnvironment) {
  const MemoryLimit machine = memory_limit();
  EXPECT_GT(machine.bytes, 1e8);
  EXPECT_NE(machine.source.find("80% of"), std::string::npos);
  {
    const ScopedMemoryLimit limit("2G");
    EXPECT_EQ(memory_limit().bytes, 2.0 * 1024 * 1024 * 1024);
  }
  for (const char* bad : {"abc", "-1", "0", "5X", "1e999"}) {
    const ScopedMemoryLimit limit(bad);
    EXPECT_THROW((void)memory_limit(), InvalidInput) << bad;
  }
  EXPECT_EQ(format_bytes(950), "950 B");
  EXPECT_EQ(format_bytes(48.6e9), "48.6 GB");
}

TEST(RandomPacker, NonFiniteShapeVolumeStopsTheSizeList) {
  // A grading whose sizes underflow the shape volume to 0 cannot reach a volume target: refused
  // before work (no particle volume) instead of drawing until the 10^8 cap.
  RandomPackOptions options{
      .container = {.shape = BoxContainer{.length = 1e-100, .width = 1e-100, .depth = 1e-100}},
      .grading = {.kind = GradingKind::kUniform, .radius_min = 1e-103, .radius_max = 1e-103}};
  EXPECT_THROW(pack_random(options), Error);
}

}  // namespace
}  // namespace aggpack
