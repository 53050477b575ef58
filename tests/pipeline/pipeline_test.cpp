// The pipeline entry: every packer kind dispatched by pack() gives the packing its packer gives
// when called directly, provenance is stamped, cancel works through the control, bad kinds and
// options name the key.

#include "aggpack/pipeline/pipeline.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "aggpack/core/error.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

using testing::expect_identical;
using testing::expect_valid_packing;
using testing::invalid_field;

// A few dozen lattice sites in a small box: fast.
LatticeOptions small_lattice() {
  return {.container = {.shape = BoxContainer{.length = 0.6, .width = 0.4, .depth = 0.4}},
          .radius = 0.1,
          .edge_length = 0.1,
          .seed = 7};
}

// ~40 single-size particles placed by RSA at 22 % in a 0.4 m cube.
RandomPackOptions small_random(std::uint64_t seed = 3) {
  return {.container = {.shape = BoxContainer{.length = 0.4, .width = 0.4, .depth = 0.4}},
          .grading = {.kind = GradingKind::kUniform, .radius_min = 0.05, .radius_max = 0.05},
          .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
          .target = PackTarget::kVolumeFraction,
          .volume_fraction = 0.22,
          .seed = seed};
}

DensePackOptions small_dense() {
  return {.fill = small_random(),
          .densify = {.target_fraction = 0.3, .seed = 5, .max_sweeps = 400}};
}

TEST(Pipeline, KindsAreOneListWithWordsAndDefaults) {
  EXPECT_EQ(packer_kind_names(), (std::vector<std::string>{"lattice", "random", "dense"}));
  for (const auto& word : packer_kind_names()) {
    EXPECT_EQ(packer_kind_name(default_packer_options(word)), word);
  }
  EXPECT_TRUE(std::holds_alternative<LatticeOptions>(PackerOptions{}));  // the paper's case
}

TEST(Pipeline, LatticeKindGivesTheLatticePackersPacking) {
  const PackResult direct = pack_lattice(small_lattice());
  const PipelineResult piped = pack(PackerOptions{small_lattice()});
  ASSERT_GT(direct.packing.particles.size(), 5u);
  expect_identical(piped.packing, direct.packing);
  EXPECT_EQ(piped.report.solid_volume, direct.report.solid_volume);
  EXPECT_FALSE(piped.densify);
  EXPECT_EQ(piped.packing.provenance.packer, "lattice");
  EXPECT_EQ(piped.packing.provenance.seed, 7u);
  EXPECT_TRUE(piped.packing.provenance.config_toml.empty());
}

TEST(Pipeline, RandomKindGivesTheRandomPackersPacking) {
  const PackResult direct = pack_random(small_random());
  const PipelineResult piped = pack(PackerOptions{small_random()});
  ASSERT_GT(direct.packing.particles.size(), 20u);
  expect_identical(piped.packing, direct.packing);
  EXPECT_EQ(piped.report.placed, direct.report.placed);
  EXPECT_EQ(piped.packing.provenance.packer, "random");
  EXPECT_EQ(piped.packing.provenance.seed, 3u);
}

TEST(Pipeline, DenseKindIsTheFillThenTheDensifier) {
  // Fixed mode with a fraction target: the fill runs in the given container enlarged by
  // (0.3 / 0.22)^(1/3), the densifier compresses it into the given container.
  const DensePackOptions options = small_dense();
  RandomPackOptions fill = small_random();
  volatile double fraction = 0.22;  // cbrt at run time, as the pipeline (no constant folding)
  fill.container = container_scaled(fill.container, Vec3::Constant(std::cbrt(0.3 / fraction)));
  DensifyOptions densify_options = options.densify;
  densify_options.target_container = small_random().container;
  const PackResult filled = pack_random(fill);
  if (filled.report.solid_volume < 0.3 * small_random().container.volume()) {
    densify_options.target_fraction = 0.0;  // the fill jammed: the given container only
  }
  const DensifyResult direct = densify(filled.packing, densify_options);
  const PipelineResult piped = pack(PackerOptions{options});
  expect_identical(piped.packing, direct.packing);
  ASSERT_TRUE(piped.densify);
  EXPECT_EQ(piped.densify->sweeps, direct.report.sweeps);
  EXPECT_EQ(piped.densify->stop, DensifyStop::kTargetReached) << piped.densify->summary();
  EXPECT_EQ(piped.report.solid_fraction, direct.report.solid_fraction);
  EXPECT_TRUE(piped.packing.container.shape == small_random().container.shape);
  ASSERT_TRUE(piped.fill);
  EXPECT_EQ(piped.fill->report.placed, filled.report.placed);
  EXPECT_TRUE(piped.fill->container.shape == fill.container.shape);
  EXPECT_EQ(piped.report.container_volume, piped.packing.container.volume());
  EXPECT_EQ(piped.packing.provenance.packer, "dense");
  EXPECT_EQ(piped.packing.provenance.seed, 3u);  // the fill's seed
  expect_valid_packing(piped.packing, 0.0);
}

TEST(Pipeline, DenseConfigRunEqualsTheOptionsRunAndItsResolvedConfig) {
  const PackConfig config = parse_pack_config(
      "", "test",
      {"packer.kind=dense", "packer.seed=3", "container.length=0.4", "container.width=0.4",
       "container.depth=0.4", "particle.radius=0.05", "particle.edge_length=0",
       "packer.target_fraction=0.22", "densify.target_fraction=0.3", "densify.max_sweeps=400"});
  DensePackOptions options = small_dense();
  options.densify.seed = derived_densify_seed(3);  // what packer.seed = 3 gives the densifier
  const PipelineResult piped = pack(config);
  const PipelineResult direct = pack(PackerOptions{options});
  expect_identical(piped.packing, direct.packing);
  EXPECT_EQ(piped.report.solid_fraction, direct.report.solid_fraction);
  EXPECT_EQ(piped.packing.provenance.config_toml, config.resolved_toml);
  EXPECT_EQ(piped.packing.provenance.packer, "dense");
  EXPECT_EQ(piped.packing.provenance.seed, 3u);
  expect_valid_packing(piped.packing, 0.0);
  // The stored configuration packs the same packing again.
  const PipelineResult again = pack(parse_pack_config(piped.packing.provenance.config_toml));
  expect_identical(again.packing, piped.packing);
}

TEST(Pipeline, ConfigRunStampsTheResolvedConfiguration) {
  const PackConfig config = parse_pack_config(
      "", "test",
      {"packer.kind=random", "packer.seed=11", "container.length=0.4", "container.width=0.4",
       "container.depth=0.4", "particle.radius=0.05", "packer.target_count=15"});
  ASSERT_TRUE(std::holds_alternative<RandomPackOptions>(packer_options(config)));
  const PipelineResult piped = pack(config);
  const PackResult direct = pack_random(std::get<RandomPackOptions>(config.packer));
  ASSERT_EQ(piped.packing.particles.size(), 15u);
  expect_identical(piped.packing, direct.packing);
  const Provenance& p = piped.packing.provenance;
  EXPECT_EQ(p.config_toml, config.resolved_toml);
  EXPECT_FALSE(p.config_toml.empty());
  EXPECT_EQ(p.seed, 11u);
  EXPECT_EQ(p.packer, "random");
  EXPECT_EQ(p.aggpack_version, AGGPACK_VERSION);
  // The default configuration is the paper's lattice case.
  EXPECT_TRUE(std::holds_alternative<LatticeOptions>(packer_options(parse_pack_config(""))));
}

TEST(Pipeline, CancelThroughTheControlStopsEveryKind) {
  std::atomic<bool> cancel{true};
  const PackControl control{.cancel = &cancel};
  for (const auto& word : {"lattice", "random"}) {
    PackerOptions options = default_packer_options(word);
    if (word == std::string("random")) options = small_random();
    const PipelineResult result = pack(options, control);
    EXPECT_EQ(result.report.stop_reason, StopReason::kCancelled) << word;
  }
  // Dense: the fill completes, the densifier is cancelled after its third sweep.
  std::atomic<bool> later{false};
  std::vector<PackStage> stages;
  PackControl densify_control{.progress_interval = 0.0, .cancel = &later};
  densify_control.on_progress = [&](const PackProgress& progress) {
    if (stages.empty() || stages.back() != progress.stage) stages.push_back(progress.stage);
    if (progress.stage == PackStage::kDensify && progress.placed >= 3) later = true;
  };
  DensePackOptions dense = small_dense();
  dense.densify.target_fraction = 0.6;
  dense.densify.max_sweeps = 100000;
  const PipelineResult result = pack(PackerOptions{dense}, densify_control);
  EXPECT_EQ(result.report.stop_reason, StopReason::kCancelled);
  ASSERT_TRUE(result.densify);
  EXPECT_EQ(result.densify->stop, DensifyStop::kCancelled);
  EXPECT_EQ(result.densify->sweeps, 3u);
  ASSERT_FALSE(stages.empty());
  EXPECT_EQ(stages.back(), PackStage::kDensify);
  expect_valid_packing(result.packing, 0.0);
}

TEST(Pipeline, ContinuingASavedPackingStampsItsProvenance) {
  Packing start = pack_random(small_random()).packing;
  start.provenance.config_toml = "[packer]\nkind = \"random\"\n";
  const DensifyOptions options{.target_fraction = 0.28, .seed = 9, .max_sweeps = 300};
  const DensifyResult direct = densify(start, options);
  const PipelineResult piped = densify_packing(start, options, "# densify.seed = 9\n");
  expect_identical(piped.packing, direct.packing);
  ASSERT_TRUE(piped.densify);
  EXPECT_EQ(piped.densify->sweeps, direct.report.sweeps);
  EXPECT_EQ(piped.report.solid_fraction, direct.report.solid_fraction);
  EXPECT_TRUE(piped.report.is_target_reached);
  const Provenance& p = piped.packing.provenance;
  EXPECT_EQ(p.config_toml, "[packer]\nkind = \"random\"\n# densify.seed = 9\n");
  EXPECT_EQ(p.seed, 9u);
  EXPECT_EQ(p.packer, "dense");
  EXPECT_EQ(invalid_field([&] { (void)densify_packing(start, {.max_sweeps = 0}, ""); }),
            "densify.max_sweeps");
}

TEST(Pipeline, BadKindsAndOptionsNameTheKey) {
  EXPECT_EQ(invalid_field([] { (void)default_packer_options("hexagonal"); }), "packer.kind");
  EXPECT_EQ(invalid_field([] { (void)default_packer_options("x", "gui packer"); }), "gui packer");
  EXPECT_EQ(invalid_field([] { (void)pack(PackerOptions{LatticeOptions{.radius = 0.0}}); }),
            "lattice.radius");
  EXPECT_EQ(invalid_field([] {
              RandomPackOptions options = small_random();
              options.count = 0;
              options.target = PackTarget::kCount;
              (void)pack(PackerOptions{options});
            }),
            "random.count");
  EXPECT_EQ(invalid_field([] {
              DensePackOptions options = small_dense();
              options.densify.gap = 0.001;  // the fill was packed with gap 0
              (void)pack(PackerOptions{options});
            }),
            "densify.gap");
  EXPECT_EQ(invalid_field([] {
              DensePackOptions options = small_dense();
              options.densify.max_sweeps = 0;
              validate(PackerOptions{options});
            }),
            "densify.max_sweeps");
  EXPECT_EQ(invalid_field([] {
              DensePackOptions options = small_dense();
              std::get<RandomPackOptions>(options.fill).volume_fraction = 2.0;
              validate(PackerOptions{options});
            }),
            "random.volume_fraction");
}

}  // namespace
}  // namespace aggpack
