// The schema is the one declaration of every key: defaults come from the options structs, every
// numeric key's range check names the key, its value and its range, and docs/config.md's tables
// are generated from it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/config/docs.h"
#include "aggpack/config/schema.h"
#include "aggpack/io/export.h"
#include "aggpack/pack/container.h"
#ifdef AGGPACK_HAS_SIM
#include "aggpack/config/repose_config.h"
#include "support/paths.h"
#endif

namespace aggpack {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every defaulted key of `schema` resolves (no value given) to its declared default, and that
// default is the options struct's own (binding.get of a default-constructed target).
template <typename Target, typename Resolve>
void expect_defaults_from_struct(const Schema<Target>& schema, const Target& defaults,
                                 Resolve resolved_for) {
  for (const auto& key : schema.keys) {
    ASSERT_TRUE(key.default_value.has_value()) << key.name;
    if (key.presence == Presence::kOptional || !key.default_from.empty()) continue;
    EXPECT_EQ(*key.default_value, key.binding.get(defaults)) << key.name;
    EXPECT_EQ(key.binding.get(resolved_for(key)), *key.default_value) << key.name;
  }
}

TEST(ConfigSchema, PackDefaultsAreTheOptionsStructDefaults) {
  const PackConfig lattice = parse_pack_config("");
  const PackConfig random = parse_pack_config("", "t", {"packer.kind=random"});
  const PackConfig dense = parse_pack_config("", "t", {"packer.kind=dense"});
  expect_defaults_from_struct(pack_schema(), PackConfig{}, [&](const Key<PackConfig>& key) {
    return key.scope(lattice) ? lattice : key.scope(random) ? random : dense;
  });
  // Spot checks against the structs themselves (not through the schema).
  EXPECT_EQ(std::get<LatticeOptions>(lattice.packer).radius, LatticeOptions{}.radius);
  EXPECT_EQ(std::get<LatticeOptions>(lattice.packer).max_vertices, LatticeOptions{}.max_vertices);
  EXPECT_EQ(std::get<RandomPackOptions>(random.packer).max_total_attempts,
            RandomPackOptions{}.max_total_attempts);
  EXPECT_EQ(std::get<RandomPackOptions>(random.packer).volume_fraction,
            RandomPackOptions{}.volume_fraction);
  EXPECT_EQ(std::get<RandomPackOptions>(random.packer).grading.exponent, Grading{}.exponent);
  // particle.radius_min / radius_max default to particle.radius.
  EXPECT_EQ(std::get<RandomPackOptions>(
                parse_pack_config("", "t", {"packer.kind=random", "particle.radius=0.2"}).packer)
                .grading.radius_min,
            0.2);
  // The dense kind: DensePackOptions{}'s fill and densifier options.
  const auto& d = std::get<DensePackOptions>(dense.packer);
  EXPECT_TRUE(std::holds_alternative<RandomPackOptions>(d.fill));
  EXPECT_EQ(d.densify.max_sweeps, DensifyOptions{}.max_sweeps);
  EXPECT_EQ(d.densify.bed_cooling, DensifyOptions{}.bed_cooling);
  EXPECT_EQ(d.densify.mode, DensifyMode::kFixed);
  EXPECT_EQ(std::get<RandomPackOptions>(d.fill).volume_fraction,
            RandomPackOptions{}.volume_fraction);
}

TEST(ConfigSchema, PackerKindWordsAreThePackerKinds) {
  const auto* kind = pack_schema().find("packer.kind");
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->words, packer_kind_names());
  EXPECT_TRUE(kind->is_kind);
  for (const auto& word : packer_kind_names()) {
    EXPECT_EQ(parse_pack_config("", "t", {"packer.kind=" + word}).packer_name(), word);
  }
}

TEST(ConfigSchema, ContainerKeysComeFromContainerKinds) {
  for (const auto& info : container_kinds()) {
    // Particles small enough for every kind's default container.
    const PackConfig config = parse_pack_config(
        "", "t", {std::string("container.kind=") + info.name, "particle.radius=0.01"});
    for (const auto& param : info.params) {
      const auto* key = pack_schema().find(std::string("container.") + param.name);
      ASSERT_NE(key, nullptr) << param.name;
      EXPECT_EQ(std::get<double>(*key->default_value), param.get(info.defaults)) << param.name;
      EXPECT_TRUE(info.holds(config.container())) << info.name;
      EXPECT_EQ(param.get(config.container()), param.get(info.defaults)) << param.name;
      EXPECT_EQ(key->doc, param.description);
    }
  }
}

TEST(ConfigSchema, OutputKeysComeFromTheFormatList) {
  for (const auto& format : output_format_names()) {
    EXPECT_NE(pack_schema().find("output." + format), nullptr) << format;
  }
}

// A value below the range of `key` (every range here has a finite lower end).
template <typename Target>
std::string value_below(const Key<Target>& key) {
  const double lo = key.range.lo;
  const double below = key.range.lo_end == End::kOpen ? lo : lo - 1.0;
  if (key.type == ValueType::kInteger) return std::to_string(static_cast<long long>(below));
  const std::string text = format_value(below);
  return key.type == ValueType::kNumberList ? "[" + text + "]" : text;
}

template <typename Target, typename Parse>
void expect_out_of_range_names_key(const Schema<Target>& schema, Parse parse) {
  int checked = 0;
  for (const auto& key : schema.keys) {
    if (key.type != ValueType::kFloat && key.type != ValueType::kInteger &&
        key.type != ValueType::kNumberList) {
      continue;
    }
    const std::string value = value_below(key);
    const std::string value_shown =
        key.type == ValueType::kNumberList ? value.substr(1, value.size() - 2) : value;
    try {
      parse(key.name + "=" + value);
      ADD_FAILURE() << key.name << " accepted " << value;
    } catch (const ConfigError& error) {
      const std::string message = error.what();
      EXPECT_EQ(error.key(), key.name) << message;
      EXPECT_NE(message.find("--set " + key.name + "=" + value + ": "), std::string::npos)
          << message;
      EXPECT_NE(message.find("invalid " + key.name + " = " + value_shown +
                             " (allowed: " + key.range.text()),
                std::string::npos)
          << message;
    }
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(ConfigSchema, EveryPackNumberOutOfRangeNamesKeyValueAndRange) {
  expect_out_of_range_names_key(pack_schema(), [](const std::string& assignment) {
    (void)parse_pack_config("", "t", {assignment});
  });
}

TEST(ConfigDocs, TablesMatchTheSchema) {
  const std::string path = test::source_dir() + "/docs/config.md";
  const std::string doc = read_text(path);
  ASSERT_FALSE(doc.empty());
  const std::string generated = regenerate_config_doc(doc);
  if (const char* regenerate = std::getenv("AGGPACK_REGENERATE_DOCS");
      regenerate != nullptr && std::string(regenerate) == "1" && generated != doc) {
    std::ofstream(path, std::ios::binary) << generated;
  }
  EXPECT_EQ(doc, generated) << "docs/config.md differs from the schema; run `aggpack config-keys "
                               "--update-doc docs/config.md`";
  for (const auto& table : documented_tables()) {
    EXPECT_NE(doc.find("<!-- generated: aggpack config-keys --markdown " + table + " -->"),
              std::string::npos)
        << table << " has no generated table in docs/config.md";
  }
  for (const auto& key : pack_schema().keys) {
    EXPECT_NE(doc.find("`" + key.name + "`"), std::string::npos) << key.name;
  }
}

TEST(ConfigDocs, RegenerateReplacesOnlyTheBlocks) {
  const std::string doc =
      "intro\n<!-- generated: aggpack config-keys --markdown grading -->\nstale\n"
      "<!-- end generated -->\noutro\n";
  const std::string generated = regenerate_config_doc(doc);
  EXPECT_EQ(generated.find("stale"), std::string::npos);
  EXPECT_EQ(generated.rfind("intro\n", 0), 0U);
  EXPECT_NE(generated.find("| `grading.exponent` | float | - | `0.5` | (0, 10] |"),
            std::string::npos)
      << generated;
  EXPECT_NE(generated.find("<!-- end generated -->\noutro\n"), std::string::npos);
  EXPECT_THROW(regenerate_config_doc("<!-- generated: aggpack config-keys --markdown packer -->\n"),
               FormatError);
}

#ifdef AGGPACK_HAS_SIM
// examples/repose-*.toml and sweep-*.toml: each parses, validates, and its resolved text parses
// back to the same resolved text (the pack examples are checked in config_test.cpp).
TEST(ConfigSchema, EveryReposeAndSweepExampleParsesToAFixedPoint) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() + "/examples")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".toml" ||
        (name.rfind("repose", 0) != 0 && name.rfind("sweep", 0) != 0)) {
      continue;
    }
    ++count;
    SCOPED_TRACE(name);
    const SweepOptions options = load_sweep_config(entry.path().string());
    with_sweep_key_names([&] { validate(options); });
    const std::string resolved = resolved_sweep_config(options);
    EXPECT_EQ(resolved_sweep_config(parse_sweep_config(resolved, "resolved")), resolved);
  }
  EXPECT_GE(count, 3);
}

TEST(ConfigSchema, SweepDefaultsAreTheOptionsStructDefaults) {
  const SweepOptions resolved = parse_sweep_config("");
  expect_defaults_from_struct(sweep_schema(), SweepOptions{},
                              [&](const Key<SweepOptions>&) { return resolved; });
}

TEST(ConfigSchema, EverySweepNumberOutOfRangeNamesKeyValueAndRange) {
  expect_out_of_range_names_key(sweep_schema(), [](const std::string& assignment) {
    (void)parse_sweep_config("", "t", {assignment});
  });
}

// The example: the key the user typed, not the options field ("repose.baffle_speed").
TEST(ConfigSchema, ReposeSetNamesTheTypedKey) {
  try {
    (void)parse_sweep_config("", "t", {"trough.baffle_speed=-1"});
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), "trough.baffle_speed");
    EXPECT_EQ(std::string(error.what()),
              "--set trough.baffle_speed=-1: invalid trough.baffle_speed = -1 (allowed: (0, 1e6] "
              "m/s)");
  }
  // A rule only the validator knows (baffle inside the trough) also names the key.
  const SweepOptions options = parse_sweep_config("", "t", {"trough.baffle_position=7"});
  try {
    with_sweep_key_names([&] { validate(options.base); });
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), "trough.baffle_position") << error.what();
    EXPECT_EQ(std::string(error.what()).find("repose."), std::string::npos) << error.what();
  }
  // Wrong type and unknown key.
  EXPECT_THROW((void)parse_sweep_config("", "t", {"trough.baffle_speed=fast"}), ConfigError);
  try {
    (void)parse_sweep_config("[trough]\nbaffle_sped = 1\n", "r.toml");
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()),
              "r.toml:2: unknown key 'trough.baffle_sped'; did you mean 'trough.baffle_speed'?");
  }
}

TEST(ConfigSchema, SweepConfigRoundTrips) {
  const SweepOptions options = parse_sweep_config(
      "[physics]\nfriction = 0.3\nwall_friction = 0.2\n[sweep]\nalphas = [0.5, 0.7]\n"
      "wall_friction_coupled = false\n[particle]\nseed = 7\nrandom_orientation = false\n",
      "s.toml");
  EXPECT_EQ(options.base.physics.friction, 0.3);
  EXPECT_EQ(options.base.physics.wall_friction, 0.2);
  EXPECT_EQ(options.alphas, (std::vector<double>{0.5, 0.7}));
  EXPECT_FALSE(options.is_wall_friction_coupled);
  EXPECT_FALSE(options.base.is_orientation_random);
  EXPECT_EQ(options.base.seed, 7U);
  const std::string text = resolved_sweep_config(options);
  EXPECT_NE(text.find("friction = 0.3  # sliding friction mu_s particle-particle (-)\n"),
            std::string::npos)
      << text;
  // The commented form reads back to the same options.
  EXPECT_EQ(resolved_sweep_config(parse_sweep_config(text, "again")), text);
}

// [particle] was [particles] in repose and sweep configs: the old name is read as the new one,
// with one note naming where; both names for one key in a file is refused; an override of
// either name wins over the file.
TEST(ConfigSchema, FormerParticlesTableIsReadWithANote) {
  const std::string now = "[particle]\nseed = 7\nalpha = 0.3\n";
  const std::string before = "[particles]\nseed = 7\nalpha = 0.3\n";
  std::vector<std::string> notes;
  const SweepOptions current = parse_sweep_config(now, "new.toml", {}, &notes);
  EXPECT_TRUE(notes.empty());
  const SweepOptions old = parse_sweep_config(before, "old.toml", {}, &notes);
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_EQ(notes[0],
            "old.toml:2: [particles] is now [particle]: read as [particle] (rename it; the old "
            "name will go)");
  EXPECT_EQ(resolved_sweep_config(old), resolved_sweep_config(current));
  EXPECT_EQ(old.base.seed, 7U);
  EXPECT_EQ(old.base.alpha, 0.3);
  notes.clear();
  const SweepOptions set = parse_sweep_config(now, "new.toml", {"particles.seed=9"}, &notes);
  EXPECT_EQ(set.base.seed, 9U);
  EXPECT_EQ(notes.size(), 1U);
  EXPECT_EQ(parse_sweep_config(before, "old.toml", {"particle.seed=11"}).base.seed, 11U);
  try {
    (void)parse_sweep_config("[particles]\nseed = 1\n[particle]\nseed = 2\n", "both.toml");
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& error) {
    EXPECT_EQ(error.key(), "particle.seed");
    EXPECT_NE(std::string(error.what()).find("given twice"), std::string::npos) << error.what();
  }
  // An unknown key under the old name is named as the new table's.
  EXPECT_THROW((void)parse_sweep_config("[particles]\nseeed = 1\n", "typo.toml"), ConfigError);
}
#endif

TEST(ConfigOverrides, KeyIsTrimmedAndTheLastOverrideOfAKeyIsFound) {
  EXPECT_EQ(override_key("packer.gap=0.001"), "packer.gap");
  EXPECT_EQ(override_key(" \tpacker.gap \t= 0.001"), "packer.gap");
  EXPECT_EQ(override_key("particle.library=a=b.stl"), "particle.library");
  EXPECT_EQ(override_key("no equals sign"), "");
  EXPECT_EQ(override_key("   =1"), "");
  const std::vector<std::string> overrides = {"packer.gap=1", "packer.seed=2", " packer.gap =3",
                                              "packer.gap"};
  const std::string* last = last_override_of(overrides, "packer.gap");
  ASSERT_NE(last, nullptr);
  EXPECT_EQ(last, &overrides[2]);
  EXPECT_EQ(last_override_of(overrides, "packer.seed"), &overrides[1]);
  EXPECT_EQ(last_override_of(overrides, "packer"), nullptr);
  EXPECT_EQ(last_override_of({}, "packer.gap"), nullptr);
}

}  // namespace
}  // namespace aggpack
