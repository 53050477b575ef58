// The "dense" packer kind in the configuration: packer.kind = dense with its fill (packer.fill)
// and the [densify] keys; one packer.seed for both stages; the resolved TOML reads back to the
// same options; a bad densify key is named.

#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"

namespace aggpack {
namespace {

const std::string kDense =
    "[container]\nlength = 0.4\nwidth = 0.4\ndepth = 0.4\n"
    "[particle]\nradius = 0.05\nedge_length = 0.0\n"
    "[packer]\nkind = \"dense\"\nseed = 42\ngap = 0.001\ntarget_fraction = 0.22\n"
    "[densify]\nmode = \"fixed\"\ntarget_fraction = 0.3\nmax_sweeps = 123\n"
    "rotation_probability = 0.25\nstall_sweeps = 50\n";

std::string error_key(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    (void)parse_pack_config(text, "dense.toml", overrides);
  } catch (const ConfigError& error) {
    return error.key();
  }
  return "(accepted)";
}

TEST(DenseConfig, KindFillAndDensifyKeysParse) {
  const PackConfig config = parse_pack_config(kDense, "dense.toml");
  ASSERT_TRUE(std::holds_alternative<DensePackOptions>(config.packer));
  const auto& dense = std::get<DensePackOptions>(config.packer);
  ASSERT_TRUE(std::holds_alternative<RandomPackOptions>(dense.fill));
  const auto& fill = std::get<RandomPackOptions>(dense.fill);
  EXPECT_EQ(fill.container.get_if<BoxContainer>()->length, 0.4);
  EXPECT_EQ(fill.grading.radius_min, 0.05);
  EXPECT_EQ(fill.volume_fraction, 0.22);
  EXPECT_EQ(fill.gap, 0.001);
  EXPECT_EQ(dense.densify.mode, DensifyMode::kFixed);
  EXPECT_EQ(dense.densify.target_fraction, 0.3);
  EXPECT_EQ(dense.densify.max_sweeps, 123u);
  EXPECT_EQ(dense.densify.rotation_probability, 0.25);
  EXPECT_EQ(dense.densify.stall_sweeps, 50u);
  EXPECT_EQ(dense.densify.gap, 0.001);  // densify.gap defaults to packer.gap
  // One packer.seed: the fill's, and a different, derived one for the densifier.
  EXPECT_EQ(fill.seed, 42u);
  EXPECT_EQ(dense.densify.seed, derived_densify_seed(42));
  EXPECT_NE(dense.densify.seed, 42u);
  EXPECT_EQ(config.seed(), 42u);
  EXPECT_EQ(config.packer_name(), "dense");
  EXPECT_EQ(config.container().get_if<BoxContainer>()->length, 0.4);
  ASSERT_TRUE(config.target_grading().has_value());
  EXPECT_TRUE(config.warnings.empty()) << config.warnings.front();
}

TEST(DenseConfig, LatticeFillTakesTheLatticeKeys) {
  const PackConfig config =
      parse_pack_config("", "t",
                        {"packer.kind=dense", "packer.fill=lattice", "packer.spacing=0.19",
                         "container.length=0.6", "densify.mode=bed", "densify.bed_cooling=0.5"});
  const auto& dense = std::get<DensePackOptions>(config.packer);
  ASSERT_TRUE(std::holds_alternative<LatticeOptions>(dense.fill));
  EXPECT_EQ(std::get<LatticeOptions>(dense.fill).spacing, 0.19);
  EXPECT_EQ(std::get<LatticeOptions>(dense.fill).container.get_if<BoxContainer>()->length, 0.6);
  EXPECT_EQ(dense.densify.mode, DensifyMode::kBed);
  EXPECT_EQ(dense.densify.bed_cooling, 0.5);
  EXPECT_FALSE(config.target_grading().has_value());
  // The random packer's keys and the fixed mode's keys do nothing here: warnings.
  const PackConfig warned =
      parse_pack_config("", "t",
                        {"packer.kind=dense", "packer.fill=lattice", "grading.kind=fuller",
                         "densify.mode=bed", "densify.target_fraction=0.5"});
  ASSERT_EQ(warned.warnings.size(), 2u);
  EXPECT_NE(warned.warnings[0].find("densify.target_fraction is ignored"), std::string::npos);
  EXPECT_NE(warned.warnings[1].find("grading.kind is ignored"), std::string::npos);
  // And densify keys with another kind.
  const PackConfig lattice = parse_pack_config("", "t", {"densify.max_sweeps=5"});
  ASSERT_EQ(lattice.warnings.size(), 1u);
  EXPECT_NE(lattice.warnings[0].find("used only when packer.kind = dense"), std::string::npos);
}

TEST(DenseConfig, ResolvedTomlReadsBackToTheSameConfiguration) {
  for (const auto& overrides :
       std::vector<std::vector<std::string>>{{},
                                             {"packer.fill=lattice", "particle.edge_length=0.05",
                                              "densify.mode=bed", "densify.max_seconds=2.5"}}) {
    const PackConfig config = parse_pack_config(kDense, "dense.toml", overrides);
    EXPECT_NE(config.resolved_toml.find("[densify]"), std::string::npos);
    EXPECT_NE(config.resolved_toml.find("kind = \"dense\""), std::string::npos);
    const PackConfig again = parse_pack_config(config.resolved_toml, "resolved");
    EXPECT_EQ(again.resolved_toml, config.resolved_toml);
    const auto& a = std::get<DensePackOptions>(config.packer);
    const auto& b = std::get<DensePackOptions>(again.packer);
    EXPECT_EQ(a.fill.index(), b.fill.index());
    EXPECT_EQ(a.densify.seed, b.densify.seed);
    EXPECT_EQ(a.densify.gap, b.densify.gap);
    EXPECT_EQ(a.densify.mode, b.densify.mode);
    EXPECT_EQ(a.densify.max_sweeps, b.densify.max_sweeps);
    EXPECT_EQ(a.densify.max_seconds, b.densify.max_seconds);
    EXPECT_EQ(a.densify.max_compression, b.densify.max_compression);
    if (a.densify.mode == DensifyMode::kFixed) {
      EXPECT_EQ(a.densify.target_fraction, b.densify.target_fraction);
    }
    EXPECT_EQ(again.seed(), config.seed());
  }
}

TEST(DenseConfig, BadDensifyValuesNameTheKey) {
  EXPECT_EQ(error_key(kDense, {"densify.max_sweeps=0"}), "densify.max_sweeps");
  EXPECT_EQ(error_key(kDense, {"densify.target_fraction=0.95"}), "densify.target_fraction");
  EXPECT_EQ(error_key(kDense, {"densify.bed_cooling=1.5"}), "densify.bed_cooling");
  EXPECT_EQ(error_key(kDense, {"densify.rotation_step=4"}), "densify.rotation_step");
  EXPECT_EQ(error_key(kDense, {"densify.mode=bedd"}), "densify.mode");
  EXPECT_EQ(error_key(kDense, {"packer.fill=hexagonal"}), "packer.fill");
  EXPECT_EQ(error_key(kDense, {"packer.kind=denser"}), "packer.kind");
  // A rule of the dense kind's validate(): the densifier may not keep a larger gap than the fill.
  EXPECT_EQ(error_key(kDense, {"densify.gap=0.002"}), "densify.gap");
  try {
    (void)parse_pack_config(kDense, "dense.toml", {"densify.max_sweeps=0"});
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("densify.max_sweeps = 0"), std::string::npos) << message;
    EXPECT_NE(message.find("[1, 1e9]"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace aggpack
