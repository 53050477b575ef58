// container.periodic: its words, where it applies, what the resolved text keeps, and the errors
// (each naming the key, the value and what is allowed).

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"

namespace aggpack {
namespace {

const char* const kPeriodicRandomToml =
    "[container]\nlength = 0.2\nwidth = 0.2\ndepth = 0.2\n"
    "[packer]\nkind = \"random\"\n[particle]\nradius_min = 0.01\nradius_max = 0.02\n";

// The ConfigError of parsing `text` with `overrides`, or none.
std::string periodic_config_error(const std::string& text,
                                  const std::vector<std::string>& overrides, std::string& key) {
  try {
    (void)parse_pack_config(text, "test.toml", overrides);
  } catch (const ConfigError& error) {
    key = error.key();
    return error.what();
  }
  return "accepted";
}

TEST(PeriodicConfig, WordsSetTheAxesAndOnlyAPeriodicBoxWritesThem) {
  const PackConfig walled = parse_pack_config(kPeriodicRandomToml, "test.toml");
  EXPECT_FALSE(is_periodic(walled.container()));
  EXPECT_EQ(walled.resolved_toml.find("periodic"), std::string::npos) << walled.resolved_toml;
  const PackConfig some =
      parse_pack_config(kPeriodicRandomToml, "test.toml", {"container.periodic=xz"});
  EXPECT_EQ(periodic_axes(some.container()), (std::array<bool, 3>{true, false, true}));
  EXPECT_NE(some.resolved_toml.find("periodic = \"xz\""), std::string::npos) << some.resolved_toml;
  // The resolved text is a fixed point.
  EXPECT_EQ(parse_pack_config(some.resolved_toml, "resolved").resolved_toml, some.resolved_toml);
  const PackConfig none =
      parse_pack_config(kPeriodicRandomToml, "test.toml", {"container.periodic=none"});
  EXPECT_EQ(none.resolved_toml, walled.resolved_toml);
}

TEST(PeriodicConfig, BadValuesNameTheKeyValueAndAllowedWords) {
  std::string key;
  std::string text = periodic_config_error(kPeriodicRandomToml, {"container.periodic=xyzz"}, key);
  EXPECT_EQ(key, "container.periodic");
  EXPECT_NE(text.find("invalid container.periodic = \"xyzz\" (allowed: none | x | y | z | xy | xz "
                      "| yz | xyz)"),
            std::string::npos)
      << text;
  text =
      periodic_config_error("[container]\nperiodic = true\n[packer]\nkind = \"random\"\n", {}, key);
  EXPECT_EQ(key, "container.periodic") << text;
  // The default packer (lattice) does not take a periodic box.
  text = periodic_config_error("[container]\nperiodic = \"z\"\n", {}, key);
  EXPECT_EQ(key, "container.periodic") << text;
  EXPECT_NE(text.find("packer.kind = lattice does not take periodic containers yet"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
}

TEST(PeriodicConfig, OnACylinderItIsAWarning) {
  const PackConfig config = parse_pack_config(
      "[container]\nkind = \"cylinder\"\nperiodic = \"z\"\n[packer]\nkind = \"random\"\n",
      "test.toml");
  EXPECT_FALSE(is_periodic(config.container()));
  ASSERT_EQ(config.warnings.size(), 1u);
  EXPECT_NE(config.warnings[0].find("container.periodic"), std::string::npos) << config.warnings[0];
}

}  // namespace
}  // namespace aggpack
