#include <gtest/gtest.h>

#include <atomic>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/verify.h"
#include "pack/pack_test_util.h"
#include "support/packings.h"

namespace aggpack {
namespace {

using testing::expect_identical;
using testing::expect_valid_packing;
using testing::invalid_field;

TEST(LatticePacker, PaperCaseHas1050Sites) {
  const auto counts = lattice_counts(LatticeOptions{});
  EXPECT_EQ(counts, (std::array<std::uint32_t, 3>{15, 5, 14}));
}

// The paper's stacking case end to end: 1,050 particles, all inside, none touching (brute force).
TEST(LatticePacker, PaperCaseIsValidAndReportsItsVolume) {
  const PackResult result = pack_lattice(LatticeOptions{});
  EXPECT_EQ(result.report.placed, 1050u);
  EXPECT_EQ(result.report.requested, 1050u);
  EXPECT_TRUE(result.report.is_target_reached);
  EXPECT_EQ(result.report.shrunk, 0u);
  EXPECT_EQ(result.packing.particles.size(), 1050u);
  EXPECT_EQ(result.packing.provenance.packer, "lattice");
  // Solid volume: each particle lies inside its control sphere, so at most 1050 * 4/3 pi R^3.
  EXPECT_GT(result.report.solid_volume, 0.3);
  EXPECT_LT(result.report.solid_volume, 1050 * 4.18879e-3);
  RecordProperty("solid_volume_m3", std::to_string(result.report.solid_volume));
  expect_valid_packing(result.packing, 0.0);
  // Every centroid lies within R of its lattice site (x fastest: site 0 at (0.1, 0.1, 0.1)).
  EXPECT_LT((result.packing.particles[0].pose.position - Vec3(0.1, 0.1, 0.1)).norm(), 0.1);
  EXPECT_LT((result.packing.particles[1].pose.position - Vec3(0.3, 0.1, 0.1)).norm(), 0.1);
}

TEST(LatticePacker, GapsAndCylinderAreRespected) {
  LatticeOptions options{
      .container = {.shape = CylinderContainer{.radius = 0.05, .height = 0.1}, .wall_gap = 0.002},
      .alpha = 0.7,
      .radius = 0.008,
      .edge_length = 0.006,
      .gap = 0.001,
      .seed = 7};
  const PackResult result = pack_lattice(options);
  EXPECT_GT(result.report.placed, 50u);
  expect_valid_packing(result.packing, 0.001);
}

// Sites closer than 2R: the paper's contact check limits growth, then the exact test (and a
// shrink where an edge crossing remains) makes the packing valid.
TEST(LatticePacker, ContactModeIsValidWithGap) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    LatticeOptions options{
        .container = {.shape = BoxContainer{.length = 0.6, .width = 0.6, .depth = 0.6}},
        .alpha = 0.3,
        .radius = 0.1,
        .edge_length = 0.05,
        .gap = 0.002,
        .spacing = 0.15,
        .seed = seed};
    const PackResult result = pack_lattice(options);
    EXPECT_EQ(result.report.placed, 27u);
    expect_valid_packing(result.packing, 0.002);
    EXPECT_TRUE(verify(result.packing, {.gap = 0.002}).is_ok);
  }
}

TEST(LatticePacker, SameSeedSamePackingWithOneAndTwoThreads) {
  LatticeOptions options{
      .container = {.shape = BoxContainer{.length = 1.0, .width = 0.6, .depth = 0.6}},
      .radius = 0.05,
      .edge_length = 0.03,
      .seed = 11};
  const PackResult one = test::with_threads(1, [&] { return pack_lattice(options); });
  const PackResult two = test::with_threads(2, [&] { return pack_lattice(options); });
  expect_identical(one.packing, two.packing);
  EXPECT_EQ(one.report.solid_volume, two.report.solid_volume);
  options.seed = 12;
  const PackResult other = pack_lattice(options);
  EXPECT_NE(other.report.solid_volume, one.report.solid_volume);
}

TEST(LatticePacker, CancelStopsEarlyAndProgressIsReported) {
  std::atomic<bool> cancel{false};
  int calls = 0;
  double last_fraction = 0.0;
  double last_solid = 0.0;
  PackControl control{.on_progress =
                          [&](const PackProgress& progress) {
                            ++calls;
                            EXPECT_GE(progress.fraction, last_fraction);
                            // The live solid fraction grows with the particles grown.
                            EXPECT_GE(progress.solid_fraction, last_solid);
                            last_fraction = progress.fraction;
                            last_solid = progress.solid_fraction;
                          },
                      .progress_interval = 0.0};
  const PackResult full = pack_lattice(LatticeOptions{.radius = 0.2, .edge_length = 0.2}, control);
  EXPECT_GE(calls, 2);
  EXPECT_DOUBLE_EQ(last_fraction, 1.0);
  EXPECT_NEAR(last_solid, full.report.solid_fraction, 1e-3);
  cancel = true;
  const PackResult cancelled = pack_lattice(LatticeOptions{.radius = 0.2, .edge_length = 0.2},
                                            PackControl{.cancel = &cancel});
  EXPECT_EQ(cancelled.report.stop_reason, StopReason::kCancelled);
  EXPECT_FALSE(cancelled.report.is_target_reached);
  EXPECT_LT(cancelled.report.placed, full.report.placed);
}

TEST(LatticePacker, EachBadOptionIsNamed) {
  EXPECT_EQ(invalid_field([] { pack_lattice({.alpha = 1.5}); }), "lattice.alpha");
  EXPECT_EQ(invalid_field([] { pack_lattice({.radius = 0.0}); }), "lattice.radius");
  EXPECT_EQ(invalid_field([] { pack_lattice({.radius = 2.0, .edge_length = 2.0}); }),
            "lattice.radius");
  EXPECT_EQ(invalid_field([] { pack_lattice({.edge_length = -1.0}); }), "lattice.edge_length");
  EXPECT_EQ(invalid_field([] { pack_lattice({.gap = -0.1}); }), "lattice.gap");
  EXPECT_EQ(invalid_field([] { pack_lattice({.spacing = 0.1}); }), "lattice.spacing");
  EXPECT_EQ(invalid_field([] { pack_lattice({.max_vertices = 3}); }), "lattice.max_vertices");
  EXPECT_EQ(
      invalid_field([] { pack_lattice({.container = {.shape = BoxContainer{.length = -3.0}}}); }),
      "container.length");
  EXPECT_THROW(pack_lattice({.edge_length = 0.001, .max_vertices = 100}), LimitExceeded);
}

}  // namespace
}  // namespace aggpack
