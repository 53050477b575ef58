#pragma once
// The pack configuration: a TOML file (toml++) plus `--set key=value` overrides, validated key by
// key and turned into the packers' option structs. Every key is declared once in pack_schema()
// (src/config/pack_schema.cpp); config_keys() and the tables of docs/config.md come from it. An
// empty configuration is the paper's stacking case (lattice placement, alpha 0.5, R 0.1 m, L 0.1 m,
// box 3.0 x 1.0 x 2.8 m).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/grading.h"
#include "aggpack/pack/packer_kinds.h"

namespace aggpack {

/// One documented configuration key.
struct ConfigKey {
  std::string name;           ///< dotted key, e.g. "packer.gap"
  std::string type;           ///< "float", "integer", "string", "array"
  std::string unit;           ///< "m", "-", "%", "" (none)
  std::string default_value;  ///< as it would be written in TOML, or a description
  std::string allowed;        ///< allowed values or range
  std::string used_when;      ///< which packer / container / grading reads it
  std::string description;    ///< one line
};

/// Every key the configuration accepts, in documentation order. `output.<format>` stands for one
/// key per export format (see output_formats()).
const std::vector<ConfigKey>& config_keys();

/// Format names accepted as keys of the [output] table ("native", "stl", ...).
const std::vector<std::string>& output_formats();

/// A resolved, validated configuration.
struct PackConfig {
  /// The chosen packer kind's options (packer.kind; the first kind, lattice, by default). Keys
  /// bind to the options structs the kind holds (find_options(), aggpack/pack/packer_kinds.h).
  PackerOptions packer{};
  int threads = 0;  ///< packer.threads: worker threads, 0 = all cores (no effect on results)
  /// The [output] table: format name -> path. "native" is the .h5 file `aggpack pack` writes when
  /// no -o is given; the others are for the exporters.
  std::map<std::string, std::string> outputs;
  /// Keys that were given but have no effect with the chosen packer / container / grading, one
  /// line each ("grading.exponent is ignored: grading.kind is uniform").
  std::vector<std::string> warnings;
  /// The complete configuration with every key at its effective value (canonical TOML, without
  /// packer.threads, which cannot change results). Parsing it again gives the same PackConfig.
  std::string resolved_toml;

  /// The chosen packer's seed.
  [[nodiscard]] std::uint64_t seed() const;
  /// The chosen packer's container.
  [[nodiscard]] const Container& container() const;
  /// The target grading to compare a packing with: the random packer's grading (also as a dense
  /// fill), none for lattice.
  [[nodiscard]] std::optional<Grading> target_grading() const;
  /// The kind's word: "lattice", "random", "dense" (packer_kind_names()).
  [[nodiscard]] std::string packer_name() const;
};

/// Every pack key, declared once: name, type, unit, range, scope, doc line and the binding to the
/// PackConfig member it sets (its default is that member's default). Documentation order.
const Schema<PackConfig>& pack_schema();

/// Resolves given values (from read_values, or typed by a front end such as the GUI, origin in
/// GivenValue::origin) into a validated configuration: defaults, cross-key rules, scope warnings,
/// the packers' own validation (messages naming the keys) and resolved_toml.
/// \throw ConfigError, Error of kind kLimitExceeded, as parse_pack_config.
PackConfig resolve_pack_config(const GivenValues& given);

/// The docs/config.md table of one pack table ("container", "particle", "grading", "packer",
/// "output").
std::string pack_keys_markdown(const std::string& table);

/// Parses TOML text, applies the overrides ("dotted.key=value", the value in TOML syntax; a bare
/// word is taken as a string) in order, and validates every key.
/// `source_name` names the text in error messages (usually the file name).
/// \throw FormatError (TOML syntax error, with line and column; an override value that starts
///        like a number, array or quoted string but is not valid TOML); ConfigError (unknown key,
///        wrong type, out of range, bad word, an override without '=' or value, and the packers'
///        own cross-field rules, renamed to config keys); Error of kind kLimitExceeded (vertex cap
///        too small for the radius and edge length).
PackConfig parse_pack_config(std::string_view text, std::string_view source_name = "config",
                             const std::vector<std::string>& overrides = {});

/// Reads `path` and calls parse_pack_config. \throw IoError if it cannot be read; as above.
PackConfig load_pack_config(const std::string& path,
                            const std::vector<std::string>& overrides = {});

}  // namespace aggpack
