// Pack configuration: defaults = the paper's case, every example parses, overrides, and one clear
// error per kind of bad configuration, each naming the key.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/lattice_packer.h"
#include "support/paths.h"

namespace aggpack {
namespace {

// Parses and expects a ConfigError for `key` whose message contains every part of `expected`.
void expect_config_error(const std::string& text, const std::string& key,
                         const std::vector<std::string>& expected,
                         const std::vector<std::string>& overrides = {}) {
  try {
    parse_pack_config(text, "test.toml", overrides);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), key) << error.what();
    EXPECT_EQ(error.kind(), ErrorKind::kInvalidInput);
    for (const auto& part : expected) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
          << "'" << part << "' not in: " << error.what();
    }
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(Config, EmptyConfigIsThePapersCase) {
  const PackConfig config = parse_pack_config("");
  ASSERT_TRUE(std::holds_alternative<LatticeOptions>(config.packer));
  const LatticeOptions& o = std::get<LatticeOptions>(config.packer);
  EXPECT_EQ(o.alpha, 0.5);
  EXPECT_EQ(o.radius, 0.1);
  EXPECT_EQ(o.edge_length, 0.1);
  ASSERT_NE(o.container.get_if<BoxContainer>(), nullptr);
  EXPECT_EQ(o.container.get_if<BoxContainer>()->length, 3.0);
  EXPECT_EQ(o.container.get_if<BoxContainer>()->width, 1.0);
  EXPECT_EQ(o.container.get_if<BoxContainer>()->depth, 2.8);
  EXPECT_EQ(o.seed, 1U);
  EXPECT_EQ(config.seed(), 1U);
  EXPECT_EQ(config.packer_name(), "lattice");
  EXPECT_FALSE(config.target_grading().has_value());
  EXPECT_TRUE(config.warnings.empty());
  EXPECT_EQ(lattice_counts(o), (std::array<std::uint32_t, 3>{15, 5, 14}));  // 1,050 sites
}

TEST(Config, PaperExampleEqualsTheDefaults) {
  const PackConfig example = load_pack_config(test::source_dir() + "/examples/paper.toml");
  EXPECT_EQ(example.resolved_toml, parse_pack_config("").resolved_toml);
}

TEST(Config, EveryExampleParsesAndItsResolvedTextIsAFixedPoint) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() + "/examples")) {
    // Pack configs; repose-*.toml and sweep-*.toml are `aggpack repose` / `sweep` configs
    // (tested by test_sim).
    if (entry.path().extension() != ".toml" ||
        entry.path().filename().string().rfind("repose", 0) == 0 ||
        entry.path().filename().string().rfind("sweep", 0) == 0) {
      continue;
    }
    ++count;
    SCOPED_TRACE(entry.path().string());
    const PackConfig config = load_pack_config(entry.path().string());
    EXPECT_TRUE(config.warnings.empty()) << config.warnings.front();
    const PackConfig again = parse_pack_config(config.resolved_toml, "resolved");
    EXPECT_EQ(again.resolved_toml, config.resolved_toml);
    EXPECT_EQ(again.seed(), config.seed());
    EXPECT_EQ(again.packer_name(), config.packer_name());
  }
  EXPECT_GE(count, 3);
}

TEST(Config, ExamplesHaveTheDocumentedSettings) {
  const std::string root = test::source_dir() + "/examples/";
  const PackConfig concrete = load_pack_config(root + "concrete-fuller.toml");
  ASSERT_TRUE(std::holds_alternative<RandomPackOptions>(concrete.packer));
  EXPECT_EQ(std::get<RandomPackOptions>(concrete.packer).grading.kind, GradingKind::kFuller);
  EXPECT_EQ(std::get<RandomPackOptions>(concrete.packer).grading.size_min, 0.005);
  EXPECT_EQ(std::get<RandomPackOptions>(concrete.packer).grading.size_max, 0.02);
  EXPECT_EQ(std::get<RandomPackOptions>(concrete.packer).target, PackTarget::kVolumeFraction);
  EXPECT_EQ(std::get<RandomPackOptions>(concrete.packer).volume_fraction, 0.30);
  const PackConfig triaxial = load_pack_config(root + "triaxial-cylinder.toml");
  ASSERT_TRUE(std::holds_alternative<RandomPackOptions>(triaxial.packer));
  EXPECT_NE(triaxial.container().get_if<CylinderContainer>(), nullptr);
  EXPECT_EQ(std::get<RandomPackOptions>(triaxial.packer).grading.kind, GradingKind::kSieve);
  ASSERT_EQ(std::get<RandomPackOptions>(triaxial.packer).grading.sieve.size(), 4U);
  EXPECT_EQ(std::get<RandomPackOptions>(triaxial.packer).grading.sieve[2].size, 0.0112);
  EXPECT_EQ(std::get<RandomPackOptions>(triaxial.packer).grading.sieve[2].percent_passing, 50.0);
  EXPECT_EQ(triaxial.seed(), 7U);
}

TEST(Config, ResolvedTextKeepsDoublesExactly) {
  const double length = 0.1 + 0.2;  // 0.30000000000000004
  const PackConfig config =
      parse_pack_config("[container]\nlength = 0.30000000000000004\n", "test.toml");
  EXPECT_EQ(std::get<LatticeOptions>(config.packer).container.get_if<BoxContainer>()->length,
            length);
  const PackConfig again = parse_pack_config(config.resolved_toml);
  EXPECT_EQ(std::get<LatticeOptions>(again.packer).container.get_if<BoxContainer>()->length,
            length);
  EXPECT_NE(config.resolved_toml.find("length = 0.30000000000000004"), std::string::npos);
}

TEST(Config, ThreadsAreReadButNotStored) {
  const PackConfig config = parse_pack_config("[packer]\nthreads = 2\nseed = 99\n");
  EXPECT_EQ(config.threads, 2);
  EXPECT_EQ(config.resolved_toml.find("threads"), std::string::npos);
  EXPECT_NE(config.resolved_toml.find("seed = 99"), std::string::npos);
  EXPECT_EQ(parse_pack_config("[packer]\nthreads = 1\nseed = 99\n").resolved_toml,
            config.resolved_toml);
}

TEST(Config, OverrideValuesThatLookNumericMustBeValidToml) {
  try {
    parse_pack_config("", "test.toml", {"packer.seed=18446744073709551615"});  // > 2^63 - 1
    ADD_FAILURE() << "accepted";
  } catch (const FormatError& error) {
    EXPECT_NE(std::string(error.what()).find("--set packer.seed=18446744073709551615: "),
              std::string::npos)
        << error.what();
  }
  // A bare word is a string; so is a path.
  EXPECT_EQ(parse_pack_config("", "t", {"output.stl=/tmp/run.stl"}).outputs.at("stl"),
            "/tmp/run.stl");
}

TEST(Config, OverridesBuildARandomSieveConfiguration) {
  const PackConfig config = parse_pack_config(
      "[packer]\ngap = 0.5\n", "test.toml",
      {"packer.gap=0.001", "packer.kind=random", "grading.kind = \"sieve\"",
       "grading.sieve=[[0.01, 0], [0.02, 60], [0.04, 100]]", "particle.edge_length=0",
       "packer.target_count=25", "container.kind=cylinder", "container.radius=0.2",
       "container.height=0.3", "packer.seed=12345"});
  ASSERT_TRUE(std::holds_alternative<RandomPackOptions>(config.packer));
  const RandomPackOptions& o = std::get<RandomPackOptions>(config.packer);
  EXPECT_EQ(o.gap, 0.001);
  EXPECT_EQ(o.grading.kind, GradingKind::kSieve);
  ASSERT_EQ(o.grading.sieve.size(), 3U);
  EXPECT_EQ(o.grading.sieve[1].percent_passing, 60.0);
  EXPECT_EQ(o.shape.edge_length, 0.0);
  EXPECT_EQ(o.target, PackTarget::kCount);
  EXPECT_EQ(o.count, 25U);
  ASSERT_NE(o.container.get_if<CylinderContainer>(), nullptr);
  EXPECT_EQ(o.container.get_if<CylinderContainer>()->radius, 0.2);
  EXPECT_EQ(config.seed(), 12345U);
  ASSERT_TRUE(config.target_grading().has_value());
  EXPECT_TRUE(config.warnings.empty()) << config.warnings.front();
}

TEST(Config, UnknownKeyGetsASuggestion) {
  expect_config_error("[packer]\nkind = \"lattice\"\ngapp = 0.001\n", "packer.gapp",
                      {"test.toml:3: unknown key 'packer.gapp'; did you mean 'packer.gap'?"});
  expect_config_error("seed = 3\n", "seed", {"unknown key 'seed'; did you mean 'packer.seed'?"});
  expect_config_error("[partcle]\nalpha = 0.3\n", "partcle.alpha",
                      {"did you mean 'particle.alpha'?"});
  expect_config_error("[container]\nalpha = 0.3\n", "container.alpha",
                      {"did you mean 'particle.alpha'?"});
  expect_config_error("[packer]\nzzzzzzzz = 1\n", "packer.zzzzzzzz",
                      {"unknown key 'packer.zzzzzzzz' (see docs/config.md"});
  expect_config_error("[pakcer]\n", "pakcer", {"unknown table [pakcer]; did you mean [packer]?"});
  expect_config_error(
      "", "packer.sed",
      {"--set packer.sed=4: unknown key 'packer.sed'", "did you mean 'packer.seed'?"},
      {"packer.sed=4"});
  expect_config_error("[output]\nstll = \"a.stl\"\n", "output.stll",
                      {"unknown output format 'stll'", "did you mean 'output.stl'?"});
}

TEST(Config, WrongTypeNamesTheKeyAndTheValue) {
  expect_config_error("[packer]\nkind = \"random\"\ntarget_count = 1.5\n", "packer.target_count",
                      {"test.toml:3: packer.target_count must be an integer (got a float 1.5)"});
  expect_config_error("[container]\nlength = \"3\"\n", "container.length",
                      {"container.length must be a number in m (got a string \"3\")"});
  expect_config_error(
      "[packer]\nkind = 3\n", "packer.kind",
      {"packer.kind must be a string, one of lattice | random | dense (got an integer 3)"});
  expect_config_error("", "packer.gap", {"--set packer.gap=abc", "must be a number"},
                      {"packer.gap=abc"});
  expect_config_error("[output]\nstl = 5\n", "output.stl", {"must be a non-empty string"});
}

TEST(Config, OutOfRangeNamesTheKeyValueAndRange) {
  expect_config_error("[particle]\nalpha = 1.5\n", "particle.alpha",
                      {"test.toml:2: invalid particle.alpha = 1.5 (allowed: [0, 1])"});
  expect_config_error("[container]\nlength = -1.0\n", "container.length",
                      {"invalid container.length = -1 (allowed: (0, 1e6] m)"});
  expect_config_error("[container]\nwidth = nan\n", "container.width",
                      {"invalid container.width = nan"});
  expect_config_error("[packer]\nthreads = -1\n", "packer.threads",
                      {"invalid packer.threads = -1 (allowed: [0, 4096])"});
  expect_config_error("[packer]\nseed = -5\n", "packer.seed",
                      {"invalid packer.seed = -5 (allowed: [0, 2^63 - 1])"});
  expect_config_error("[packer]\nkind = \"random\"\ntarget_fraction = 0.95\n",
                      "packer.target_fraction",
                      {"invalid packer.target_fraction = 0.95 (allowed: (0, 0.9])"});
  expect_config_error("[particle]\nmax_vertices = 3\n", "particle.max_vertices",
                      {"invalid particle.max_vertices = 3 (allowed: [6, 1e6])"});
  expect_config_error("[particle]\nedge_length = 0.0\n", "particle.edge_length",
                      {"invalid particle.edge_length = 0", "packer.kind = lattice"});
}

TEST(Config, BadWordGetsASuggestion) {
  expect_config_error("[packer]\nkind = \"latice\"\n", "packer.kind",
                      {"invalid packer.kind = \"latice\" (allowed: lattice | random | dense); did "
                       "you mean 'lattice'?"});
  expect_config_error("[packer]\nkind = \"random\"\n[grading]\nkind = \"fuler\"\n", "grading.kind",
                      {"did you mean 'fuller'?"});
  expect_config_error("[container]\nkind = \"sphere\"\n", "container.kind",
                      {"invalid container.kind = \"sphere\" (allowed: box | cylinder)"});
}

TEST(Config, SyntaxErrorIsFormatErrorWithLineAndColumn) {
  try {
    parse_pack_config("[packer]\ngap = = 1\n", "bad.toml");
    ADD_FAILURE() << "accepted";
  } catch (const FormatError& error) {
    EXPECT_NE(std::string(error.what()).find("bad.toml:2:"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("TOML syntax error"), std::string::npos);
  }
  expect_config_error("", "", {"expected key=value"}, {"packer.gap"});
  expect_config_error("", "packer.gap", {"missing value for packer.gap"}, {"packer.gap="});
}

TEST(Config, CrossFieldRulesNameTheKey) {
  expect_config_error("[packer]\nkind = \"random\"\ntarget_count = 5\ntarget_fraction = 0.2\n",
                      "packer.target_fraction", {"either packer.target_count or"});
  expect_config_error("[packer]\nkind = \"random\"\n[particle]\nradius_min = 0.2\n",
                      "particle.radius_min",
                      {"invalid particle.radius_max = 0.1", ">= particle.radius_min = 0.2"});
  expect_config_error(
      "[packer]\nkind = \"random\"\n[grading]\nkind = \"fuller\"\nsize_min = 0.03\n",
      "grading.size_max", {"invalid grading.size_max = 0.02 (allowed: > grading.size_min"});
  expect_config_error("[packer]\nkind = \"random\"\n[grading]\nkind = \"sieve\"\n", "grading.sieve",
                      {"needs grading.sieve"});
  expect_config_error(
      "[packer]\nkind = \"random\"\n[grading]\nkind = \"sieve\"\nsieve = [[0.01, 0], [0.02]]\n",
      "grading.sieve", {"grading.sieve[1] must be an array of [size_m, percent_passing] pairs"});
  expect_config_error(
      "[packer]\nkind = \"random\"\n[grading]\nkind = \"sieve\"\nsieve = [[0.01, 0], [0.02, "
      "120]]\n",
      "grading.sieve", {"invalid grading.sieve[1] percent passing = 120 (allowed: [0, 100] %)"});
}

// Rules only the packers know (checked by their validate()) come back with the config's names.
TEST(Config, PackerValidationUsesConfigKeyNames) {
  try {
    parse_pack_config("[packer]\nspacing = 0.05\n");  // below R = 0.1
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), "packer.spacing") << error.what();
    EXPECT_NE(std::string(error.what()).find("packer.spacing"), std::string::npos);
  }
  try {
    parse_pack_config("[container]\nwall_gap = 0.6\n");  // leaves no interior in a 1 m width
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), "container.wall_gap") << error.what();
  }
  try {
    parse_pack_config(
        "[packer]\nkind = \"random\"\n[grading]\nkind = \"sieve\"\n"
        "sieve = [[0.02, 0], [0.01, 100]]\n");
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key().rfind("grading.sieve", 0), 0U) << error.what();
  }
}

TEST(Config, KeysOutsideTheirScopeGiveWarnings) {
  const PackConfig config = parse_pack_config(
      "[container]\nradius = 0.2\n[grading]\nexponent = 0.4\n[packer]\ntarget_count = 10\n",
      "test.toml");
  ASSERT_EQ(config.warnings.size(), 3U);
  EXPECT_EQ(config.warnings[0],
            "test.toml:2: container.radius is ignored (used only when container.kind = cylinder)");
  EXPECT_NE(config.warnings[1].find("grading.exponent is ignored"), std::string::npos);
  EXPECT_NE(config.warnings[2].find("packer.target_count is ignored"), std::string::npos);
}

TEST(Config, OutputTableIsStored) {
  const PackConfig config =
      parse_pack_config("[output]\nnative = \"run.h5\"\nstl = \"run.stl\"\n", "test.toml");
  EXPECT_EQ(config.outputs.at("native"), "run.h5");
  EXPECT_EQ(config.outputs.at("stl"), "run.stl");
  EXPECT_NE(config.resolved_toml.find("[output]\nnative = \"run.h5\"\nstl = \"run.stl\"\n"),
            std::string::npos);
}

TEST(Config, MissingConfigFileIsIoError) {
  EXPECT_THROW(load_pack_config("/nonexistent/aggpack.toml"), IoError);
}

TEST(Config, EveryKeyIsDocumented) {
  const std::string docs = read_file(test::source_dir() + "/docs/config.md");
  ASSERT_FALSE(docs.empty());
  for (const auto& key : config_keys()) {
    EXPECT_NE(docs.find("`" + key.name + "`"), std::string::npos) << key.name << " undocumented";
    EXPECT_FALSE(key.default_value.empty()) << key.name;
    EXPECT_FALSE(key.allowed.empty()) << key.name;
  }
}

}  // namespace
}  // namespace aggpack
