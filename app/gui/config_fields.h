#pragma once
// The panel's pack configuration, derived from the schema (aggpack/config/config.h): a value for
// every pack key the panel can edit, the keys that apply to the current choice of packer,
// container and grading, and the validated PackConfig built from them through the schema's
// setters (no TOML text in between).

#include <map>
#include <set>
#include <string>
#include <vector>

#include "aggpack/config/config.h"

namespace aggpack::gui {

class ConfigFields {
 public:
  /// Fields holding the values of a resolved configuration (and, when it has no sieve table, one
  /// ready for grading.kind = sieve).
  static ConfigFields from_config(const PackConfig& config);

  /// Whether the panel shows `key` at all (file paths and keys that are never stored, such as
  /// packer.threads, are not shown).
  static bool is_editable(const Key<PackConfig>& key);

  /// Whether the panel holds a value for `key`.
  [[nodiscard]] bool has(const std::string& key) const { return values_.count(key) > 0; }
  [[nodiscard]] Value& value(const std::string& key) { return values_.at(key); }
  [[nodiscard]] const Value& value(const std::string& key) const { return values_.at(key); }

  /// Optional keys (Presence::kOptional, e.g. packer.target_count) are given only when on.
  [[nodiscard]] bool is_on(const std::string& key) const { return on_.count(key) > 0; }
  void set_on(const std::string& key, bool is_on);

  /// The keys that have an effect with the current choices, at their values (origin "gui").
  [[nodiscard]] GivenValues given() const;
  /// The configuration resolved from given() without validation: which keys apply.
  [[nodiscard]] PackConfig draft() const;
  /// The validated configuration. \throw ConfigError, Error as parse_pack_config.
  [[nodiscard]] PackConfig build() const;
  /// given() as `--set` entries without spaces ("packer.kind=\"random\"", "packer.seed=7").
  [[nodiscard]] std::vector<std::string> set_entries() const;

 private:
  std::map<std::string, Value> values_;
  std::set<std::string> on_;
};

}  // namespace aggpack::gui
