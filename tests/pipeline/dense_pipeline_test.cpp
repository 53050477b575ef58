// The "dense" packer kind in fixed mode with a fraction target ends in exactly the user's
// container (issue 14, item 1a): the random fill runs in it enlarged by
// (densify.target_fraction / packer.target_fraction)^(1/3) and the densifier compresses it into
// the given container. A fill that jams is reported, bad combinations name both keys.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/verify.h"
#include "aggpack/pipeline/pipeline.h"
#include "pack/pack_test_util.h"
#include "support/paths.h"

namespace aggpack {
namespace {

using testing::expect_valid_packing;

// A few hundred single-size particles: fill 20 %, densify to 35 % (fractions of the given box).
std::vector<std::string> small_fixed(std::vector<std::string> more = {}) {
  std::vector<std::string> keys = {"packer.kind=dense",
                                   "packer.seed=3",
                                   "container.length=0.3",
                                   "container.width=0.3",
                                   "container.depth=0.3",
                                   "particle.radius=0.03",
                                   "particle.edge_length=0",
                                   "packer.target_fraction=0.2",
                                   "densify.target_fraction=0.35",
                                   "densify.max_sweeps=3000"};
  keys.insert(keys.end(), more.begin(), more.end());
  return keys;
}

std::string config_error(const std::vector<std::string>& overrides) {
  try {
    (void)parse_pack_config("", "test", overrides);
  } catch (const ConfigError& error) {
    return error.key() + ": " + error.what();
  }
  return "(accepted)";
}

// Every extent of the final container equals the given one; the packing is exact.
void expect_in_given_container(const PipelineResult& result, const Container& given, double gap) {
  const ContainerKindInfo& kind = container_kind_info(given);
  ASSERT_EQ(&container_kind_info(result.packing.container), &kind);
  for (const ContainerParam& param : kind.params) {
    EXPECT_EQ(param.get(result.packing.container), param.get(given)) << param.name;
  }
  EXPECT_EQ(result.packing.container.wall_gap, given.wall_gap);
  EXPECT_EQ(result.report.container_volume, given.volume());
  expect_valid_packing(result.packing, gap);  // brute force: every pair, every particle
  const VerifyResult verified = verify(result.packing, {.gap = gap});
  EXPECT_TRUE(verified.is_ok) << verified.message;
}

TEST(DensePipeline, FixedModeEndsInTheGivenBoxAtTheAskedFraction) {
  const PackConfig config = parse_pack_config("", "test", small_fixed());
  const PipelineResult result = pack(config);
  ASSERT_TRUE(result.densify);
  ASSERT_TRUE(result.fill);
  // The fill ran in the box enlarged by (0.35 / 0.2)^(1/3) in every extent.
  const double k = std::cbrt(0.35 / 0.2);
  EXPECT_NEAR(result.fill->scale, k, 1e-12);
  const auto* fill_box = result.fill->container.get_if<BoxContainer>();
  ASSERT_NE(fill_box, nullptr);
  EXPECT_NEAR(fill_box->length, 0.3 * k, 1e-12);
  EXPECT_NEAR(fill_box->depth, 0.3 * k, 1e-12);
  EXPECT_EQ(result.fill->report.stop_reason, StopReason::kTargetReached);
  EXPECT_EQ(result.fill->asked_fraction, 0.35);
  EXPECT_EQ(result.densify->stop, DensifyStop::kTargetReached) << result.densify->summary();
  EXPECT_GE(result.report.solid_fraction, 0.35 * (1 - 1e-9));
  EXPECT_TRUE(result.report.is_target_reached);
  expect_in_given_container(result, config.container(), 0.0);
  // Provenance records what was asked: the given box and both fractions.
  const PackConfig again = parse_pack_config(result.packing.provenance.config_toml, "stored");
  EXPECT_TRUE(again.container().shape == config.container().shape);
  EXPECT_NE(result.packing.provenance.config_toml.find("target_fraction = 0.35"),
            std::string::npos);
}

TEST(DensePipeline, FixedModeEndsInTheGivenCylinderWithItsWallGap) {
  const PackConfig config = parse_pack_config(
      "", "test",
      small_fixed({"container.kind=cylinder", "container.radius=0.15", "container.height=0.3",
                   "container.wall_gap=0.004", "packer.gap=0.001"}));
  const PipelineResult result = pack(config);
  ASSERT_TRUE(result.fill);
  const auto* fill_cylinder = result.fill->container.get_if<CylinderContainer>();
  ASSERT_NE(fill_cylinder, nullptr);
  const double k = std::cbrt(0.35 / 0.2);
  EXPECT_NEAR(fill_cylinder->radius, 0.15 * k, 1e-12);
  EXPECT_NEAR(fill_cylinder->height, 0.3 * k, 1e-12);
  EXPECT_EQ(result.fill->container.wall_gap, 0.004);  // same wall gap
  EXPECT_GE(result.report.solid_fraction, 0.35 * (1 - 1e-9)) << result.densify->summary();
  expect_in_given_container(result, config.container(), 0.001);
}

TEST(DensePipeline, AJammedFillIsReportedBelowTheAskedFraction) {
  // One attempt per particle and one failure in a row: the fill stops far below its target.
  const PackConfig config =
      parse_pack_config("", "test",
                        small_fixed({"packer.attempts=1", "packer.max_consecutive_failures=1",
                                     "packer.target_fraction=0.3", "densify.target_fraction=0.4"}));
  const PipelineResult result = pack(config);
  ASSERT_TRUE(result.fill);
  ASSERT_TRUE(result.densify);
  EXPECT_NE(result.fill->report.stop_reason, StopReason::kTargetReached);
  EXPECT_LT(result.fill->report.solid_fraction, 0.3);
  // Still compressed into the given box, at the fraction the fill's particles give there.
  EXPECT_EQ(result.densify->stop, DensifyStop::kTargetReached) << result.densify->summary();
  EXPECT_LT(result.report.solid_fraction, 0.4);
  EXPECT_NEAR(result.report.solid_fraction,
              result.report.solid_volume / config.container().volume(), 1e-12);
  EXPECT_FALSE(result.report.is_target_reached);
  EXPECT_EQ(result.report.target_solid_fraction, 0.4);
  expect_in_given_container(result, config.container(), 0.0);
}

TEST(DensePipeline, WithoutAFractionTargetOrInBedModeTheFillIsNotEnlarged) {
  for (const auto& more :
       std::vector<std::vector<std::string>>{{"densify.target_fraction=0", "densify.max_sweeps=20"},
                                             {"densify.mode=bed", "densify.max_sweeps=20"}}) {
    const PackConfig config = parse_pack_config("", "test", small_fixed(more));
    const PipelineResult result = pack(config);
    ASSERT_TRUE(result.fill);
    EXPECT_EQ(result.fill->scale, 1.0);
    EXPECT_TRUE(result.fill->container.shape == config.container().shape);
    EXPECT_TRUE(result.packing.container.shape == config.container().shape);
  }
}

TEST(DensePipeline, BadCombinationsNameBothKeys) {
  const std::string too_high = config_error(small_fixed({"packer.target_fraction=0.35"}));
  EXPECT_EQ(too_high.rfind("packer.target_fraction: ", 0), 0u) << too_high;
  EXPECT_NE(too_high.find("densify.target_fraction"), std::string::npos) << too_high;
  EXPECT_EQ(too_high.find('\n'), std::string::npos) << too_high;
  const std::string lattice =
      config_error(small_fixed({"packer.fill=lattice", "particle.edge_length=0.03"}));
  EXPECT_EQ(lattice.rfind("packer.fill: ", 0), 0u) << lattice;
  EXPECT_NE(lattice.find("densify.target_fraction"), std::string::npos) << lattice;
  std::vector<std::string> by_count = small_fixed({"packer.target_count=50"});
  std::erase(by_count, "packer.target_fraction=0.2");
  const std::string count = config_error(by_count);
  EXPECT_EQ(count.rfind("packer.target_count: ", 0), 0u) << count;
  EXPECT_NE(count.find("densify.target_fraction"), std::string::npos) << count;
  // Fine without a fraction target, or as a gravity bed.
  EXPECT_EQ(config_error(small_fixed(
                {"packer.fill=lattice", "particle.edge_length=0.03", "densify.target_fraction=0"})),
            "(accepted)");
  EXPECT_EQ(config_error(small_fixed({"packer.target_fraction=0.5", "densify.mode=bed"})),
            "(accepted)");
  // The library names the options' fields.
  DensePackOptions options =
      std::get<DensePackOptions>(parse_pack_config("", "test", small_fixed()).packer);
  std::get<RandomPackOptions>(options.fill).volume_fraction = 0.4;
  EXPECT_EQ(testing::invalid_field([&] { (void)pack(PackerOptions{options}); }),
            "random.volume_fraction");
}

TEST(DensePipeline, DenseExamplesHaveTheDocumentedSettings) {
  const std::string root = test::source_dir() + "/examples/";
  const auto dense_of = [](const PackConfig& config) {
    return std::get<DensePackOptions>(config.packer);
  };
  const PackConfig fuller = load_pack_config(root + "dense-fuller.toml");
  const DensePackOptions f = dense_of(fuller);
  const auto& f_fill = std::get<RandomPackOptions>(f.fill);
  EXPECT_EQ(f_fill.grading.kind, GradingKind::kFuller);
  EXPECT_EQ(f_fill.grading.size_min, 0.005);
  EXPECT_EQ(f_fill.grading.size_max, 0.02);
  EXPECT_EQ(f_fill.grading.exponent, 0.5);
  EXPECT_EQ(fuller.container().get_if<BoxContainer>()->length, 0.1);
  EXPECT_EQ(f.densify.mode, DensifyMode::kFixed);
  EXPECT_EQ(f.densify.target_fraction, 0.5);
  EXPECT_EQ(f_fill.volume_fraction, 0.35);
  const DensePackOptions box = dense_of(load_pack_config(root + "dense-box.toml"));
  EXPECT_EQ(box.densify.target_fraction, 0.56);
  EXPECT_EQ(std::get<RandomPackOptions>(box.fill).volume_fraction, 0.2);
  EXPECT_TRUE(is_into_given_container(box));
  const PackConfig bed_config = load_pack_config(root + "dense-bed.toml");
  const DensePackOptions bed = dense_of(bed_config);
  const auto& b_fill = std::get<RandomPackOptions>(bed.fill);
  EXPECT_EQ(bed.densify.mode, DensifyMode::kBed);
  EXPECT_EQ(b_fill.shape.alpha, 0.5);
  EXPECT_EQ(b_fill.grading.radius_min, 0.1);
  EXPECT_EQ(b_fill.grading.radius_max, 0.1);
  EXPECT_EQ(b_fill.shape.edge_length, 0.1);
  EXPECT_EQ(b_fill.target, PackTarget::kCount);
  EXPECT_EQ(b_fill.count, 1050u);
  EXPECT_EQ(bed_config.container().get_if<BoxContainer>()->depth, 3.5);
  EXPECT_FALSE(is_into_given_container(bed));
}

}  // namespace
}  // namespace aggpack
