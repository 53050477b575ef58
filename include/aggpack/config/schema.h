#pragma once
// The configuration schema: every key of a configuration (pack, repose/sweep) is declared ONCE, as
// a Key<Target>: its name, type, unit, range, when it applies, one doc line, and a binding (get /
// set) to the options-struct member it sets. The default is read from the options struct through
// that binding, never typed again. Everything else derives from the declaration:
//  - reading TOML and `--set key=value` (read_values: types, ranges, words, unknown keys with
//    a suggestion; every message names the key the user typed),
//  - resolving (resolve: given values, else defaults, through the setters),
//  - the resolved-config writer (write_values), config_keys() and the docs/config.md tables
//    (markdown_table), the GUI's fields,
//  - the validators' messages (with_key_names: the options' own field names, declared per key
//    in Key::fields, are rewritten to the key names).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/pack/grading.h"

namespace aggpack {

/// A configuration that cannot be used: an unknown key (with a suggestion), a value of the wrong
/// type, out of range or not one of the allowed words. Kind kInvalidInput. The message starts with
/// where the value came from ("paper.toml:5: ", "--set packer.gap=-1: ") and names the key, the
/// value and what is allowed.
class ConfigError : public Error {
 public:
  ConfigError(std::string key, const std::string& message)
      : Error(ErrorKind::kInvalidInput, message), key_(std::move(key)) {}
  /// A message in one sentence (error_words.h).
  ConfigError(std::string key, Wording wording)
      : Error(ErrorKind::kInvalidInput, std::move(wording)), key_(std::move(key)) {}
  /// A refused value: "WHERE: invalid FIELD = VALUE (allowed: ALLOWED)" (`where` is "" or ends in
  /// ": "; `field` is the key, or the key a rule between keys names first), with its parts
  /// (has_value(), field(), value(), wording() = allowed).
  ConfigError(std::string key, const std::string& where, const std::string& field,
              const std::string& value, const Wording& allowed)
      : Error(ErrorKind::kInvalidInput,
              where + "invalid " + field + " = " + value + " (allowed: " + english(allowed) + ")",
              field, value, allowed),
        key_(std::move(key)) {}
  /// The dotted key at fault ("packer.gap"), or "" for a syntax error.
  [[nodiscard]] const std::string& key() const { return key_; }

 private:
  std::string key_;
};

enum class ValueType {
  kFloat,       ///< a number (TOML float or integer)
  kInteger,     ///< a TOML integer
  kWord,        ///< a string, one of Key::words
  kBool,        ///< true / false
  kNumberList,  ///< [x, y, ...], every element in the range
  kSieve,       ///< [[size, percent_passing], ...]
  kPath,        ///< a non-empty string (a file path)
  kPathList     ///< a non-empty path, or an array of them (read as a list of one or more)
};

/// Sieve rows compare by value (for Value's ==).
inline bool operator==(const SieveRow& a, const SieveRow& b) {
  return a.size == b.size && a.percent_passing == b.percent_passing;
}

/// A value of any key type.
using Value = std::variant<double, std::int64_t, std::string, bool, std::vector<double>,
                           std::vector<SieveRow>, std::vector<std::string>>;

/// Whether an end of a range belongs to it.
enum class End { kClosed, kOpen };

/// The allowed interval of a number (or of every element of a list).
struct Range {
  double lo = 0.0;
  double hi = 0.0;
  End lo_end = End::kClosed;
  End hi_end = End::kClosed;
  const char* hi_text = nullptr;  ///< shown instead of hi ("2^63 - 1"), or null

  [[nodiscard]] bool contains(double value) const;
  /// "[0, 1]", "(0, 1e6]".
  [[nodiscard]] std::string text() const;
};
/// [lo, hi]
constexpr Range closed(double lo, double hi) { return {.lo = lo, .hi = hi}; }
/// (lo, hi]
constexpr Range open_closed(double lo, double hi) {
  return {.lo = lo, .hi = hi, .lo_end = End::kOpen};
}

/// The largest length (m), speed (m/s) or time (s) a key accepts: 1e6 (1000 km); any larger
/// value is a unit mistake.
inline constexpr double kMaxMagnitude = 1e6;

/// Whether a key that is not given takes its default (kDefaulted) or stays unset (kOptional:
/// its setter is not called, e.g. output paths, packer.target_count, grading.sieve).
enum class Presence { kDefaulted, kOptional };

/// When a key has an effect, as a rule over the resolved target and its text for the docs.
template <typename Target>
struct Scope {
  std::string text = "always";                   ///< "container.kind = box"
  std::function<bool(const Target&)> applies{};  ///< empty = always
  [[nodiscard]] bool operator()(const Target& target) const { return !applies || applies(target); }
};

/// Get and set of one key on its target (the options struct it configures).
template <typename Target>
struct Binding {
  std::function<Value(const Target&)> get;
  std::function<void(Target&, const Value&)> set;
};

/// One declared key. See the file comment.
template <typename Target>
struct Key {
  std::string name;  ///< dotted: "packer.gap"
  ValueType type = ValueType::kFloat;
  std::string unit;                ///< "m", "-", "" (none)
  Range range{};                   ///< numbers and lists
  std::vector<std::string> words;  ///< kWord: the allowed words
  /// A rule the range cannot say ("< half the smallest extent"), in words (error_words.h), or
  /// none (kText of "").
  Wording note{};
  Scope<Target> scope{};  ///< when it has an effect (else: a warning when given)
  /// When the resolved-config writer writes it; empty text (the default) = as `scope`.
  Scope<Target> written{.text = ""};
  std::string doc;          ///< one line
  Binding<Target> binding;  ///< get / set on the options struct
  /// The default: binding.get of the options struct's defaults (filled in when the schema is
  /// built, unless the declaration names another source such as a container kind's defaults).
  std::optional<Value> default_value;
  Presence presence = Presence::kDefaulted;
  std::string default_from;  ///< another key whose value is the default ("particle.radius")
  /// Words shown instead of default_value ("(unset)"), or none (kText of "").
  Wording default_text{};
  /// A key that must not be given together with this one while this one applies
  /// ("packer.target_fraction" for packer.target_count), or empty.
  std::string excludes;
  std::vector<std::string> fields;  ///< the options' validators' names for it ("lattice.radius")
  /// A key that picks the options struct other keys bind to (packer.kind, packer.fill): resolve()
  /// sets such keys first, in schema order, then the others.
  bool is_kind = false;
};

/// A table of a schema ("container"). `member_word` names its keys in messages when they are a
/// family ("output format"); empty for ordinary tables.
struct TableInfo {
  std::string name;
  std::string member_word;
  /// A name the table had before, still read: its keys are read as this table's, with a one-line
  /// note (read_values). Empty: none.
  std::string former_name{};
};

/// How the resolved configuration is written.
enum class WriteStyle {
  kCanonical,  ///< "key = value"; floats always with a point or exponent (read back bit-exact)
  kCommented   ///< "key = value  # doc (unit)"; floats shortest ("6", "0.05")
};

/// A whole configuration: its tables and keys in documentation order.
template <typename Target>
struct Schema {
  std::vector<TableInfo> tables;
  std::vector<Key<Target>> keys;
  /// Validator names that are not keys, mapped to what the user should read ("min_time" ->
  /// "fall time from particle.fill_height").
  std::map<std::string, std::string> aliases;

  [[nodiscard]] const Key<Target>* find(std::string_view name) const {
    for (const auto& key : keys) {
      if (key.name == name) return &key;
    }
    return nullptr;
  }
};

/// The target-independent part of a key, for the non-template reader and writer.
struct KeyView {
  const std::string* name;
  ValueType type;
  const std::string* unit;
  const Range* range;
  const std::vector<std::string>* words;
  const Wording* note;
  const std::vector<std::string>* fields;
};

template <typename Target>
std::vector<KeyView> key_views(const Schema<Target>& schema) {
  std::vector<KeyView> views;
  views.reserve(schema.keys.size());
  for (const auto& k : schema.keys) {
    views.push_back({&k.name, k.type, &k.unit, &k.range, &k.words, &k.note, &k.fields});
  }
  return views;
}

/// A value the user gave, with where it came from ("paper.toml:5", "--set packer.gap=1").
struct GivenValue {
  Value value;
  std::string origin;
  std::size_t order = 0;  ///< line in the file; overrides after every line
};
using GivenValues = std::map<std::string, GivenValue>;

/// Parses TOML text, applies `--set` overrides ("dotted.key=value", the value in TOML syntax; a
/// bare word is taken as a string) in order, and converts every leaf to its key's type, checking
/// types, ranges and words. A table given under its former name (TableInfo::former_name, in the
/// file or in an override) is read as the table, and `notes` (when given) gets one line saying so,
/// where it was first used. \throw FormatError (TOML syntax), ConfigError (unknown table or key,
/// wrong type, out of range, bad word, malformed override).
GivenValues read_values(const std::vector<TableInfo>& tables, const std::vector<KeyView>& keys,
                        std::string_view text, std::string_view source_name,
                        const std::vector<std::string>& overrides,
                        std::vector<std::string>* notes = nullptr);

/// The key of a `--set` text: "dotted.key=value" -> "dotted.key", blanks around it trimmed; empty
/// without '='. read_values applies an override to this key.
std::string override_key(std::string_view text);
/// The last of `overrides` that sets `key` (it is the one that counts), or nullptr.
const std::string* last_override_of(const std::vector<std::string>& overrides,
                                    std::string_view key);

/// Reads a whole file as text. \throw IoError.
std::string read_config_file(const std::string& path);

/// Throws ConfigError for `key`, the message prefixed with where the key was given (if given).
[[noreturn]] void fail_key(const GivenValues& given, const std::string& key,
                           const std::string& message);
/// Throws ConfigError for `key` refusing `field` = `value` (see ConfigError), prefixed so.
[[noreturn]] void fail_key(const GivenValues& given, const std::string& key,
                           const std::string& field, const std::string& value,
                           const Wording& allowed);

/// The allowed part of a key without its note: its range (numbers), its words, or what a path is.
Wording allowed_rule(const KeyView& key);

/// "allowed" text of a key: allowed_rule, then ", " and its note (a path key with a note: the
/// note alone, it says what the string is).
std::string allowed_text(const KeyView& key);

/// One "key = value" line's value text.
std::string value_text(const Value& value, ValueType type, WriteStyle style);

/// Runs `check`; an InvalidInput or LimitExceeded naming an options field declared by a key
/// (Key::fields) or an alias is rethrown naming the key: InvalidInput as ConfigError.
void with_key_names(const std::vector<KeyView>& keys,
                    const std::map<std::string, std::string>& aliases,
                    const std::function<void()>& check);

/// Rewrites the options' field names in a validator message to key names (see with_key_names).
std::string to_key_names(const std::vector<KeyView>& keys,
                         const std::map<std::string, std::string>& aliases, std::string message);

/// Sets every key of `schema` on `target`: the given value, else the value of default_from, else
/// the default (Presence::kOptional keys that are not given are left alone). Keys are set in
/// schema order, the kind keys (Key::is_kind) first.
template <typename Target>
void resolve(const Schema<Target>& schema, const GivenValues& given, Target& target) {
  std::map<std::string, Value> resolved;
  std::vector<const Key<Target>*> order;
  for (const auto& key : schema.keys) {
    if (key.is_kind) order.push_back(&key);
  }
  for (const auto& key : schema.keys) {
    if (!key.is_kind) order.push_back(&key);
  }
  for (const auto* k : order) {
    const Key<Target>& key = *k;
    const auto found = given.find(key.name);
    Value value;
    if (found != given.end()) {
      value = found->second.value;
    } else if (!key.default_from.empty()) {
      value = resolved.at(key.default_from);
    } else if (key.presence == Presence::kOptional) {
      continue;
    } else {
      value = *key.default_value;
    }
    key.binding.set(target, value);
    resolved[key.name] = std::move(value);
  }
  for (const auto& key : schema.keys) {
    if (!key.excludes.empty() && given.count(key.name) > 0 && given.count(key.excludes) > 0 &&
        key.scope(target)) {
      fail_key(given, key.excludes,
               "give either " + key.name + " or " + key.excludes + ", not both");
    }
  }
}

/// One warning per given key that has no effect on `target` (in key-name order).
template <typename Target>
std::vector<std::string> scope_warnings(const Schema<Target>& schema, const GivenValues& given,
                                        const Target& target) {
  std::vector<std::string> warnings;
  for (const auto& [name, value] : given) {
    const Key<Target>* key = schema.find(name);
    if (key != nullptr && !key->scope(target)) {
      warnings.push_back(value.origin + ": " + name + " is ignored (used only when " +
                         key->scope.text + ")");
    }
  }
  return warnings;
}

/// The resolved configuration: every key whose `written` rule holds, at its value, one
/// "[table]" section per table in schema order; the keys of a family table (TableInfo::
/// member_word, e.g. [output]) in name order, the others in schema order.
template <typename Target>
std::string write_values(const Schema<Target>& schema, const Target& target, WriteStyle style) {
  const auto table_of = [](const std::string& name) { return name.substr(0, name.find('.')); };
  std::vector<const Key<Target>*> written;
  for (const auto& key : schema.keys) {
    const Scope<Target>& rule = !key.written.text.empty() ? key.written : key.scope;
    if (rule(target)) written.push_back(&key);
  }
  for (const auto& table : schema.tables) {
    if (table.member_word.empty()) continue;
    const auto first = std::find_if(written.begin(), written.end(),
                                    [&](const auto* k) { return table_of(k->name) == table.name; });
    const auto last = std::find_if(first, written.end(),
                                   [&](const auto* k) { return table_of(k->name) != table.name; });
    std::sort(first, last, [](const auto* a, const auto* b) { return a->name < b->name; });
  }
  std::string text;
  std::string section;
  for (const auto* key : written) {
    const auto dot = key->name.find('.');
    const std::string group = key->name.substr(0, dot);
    if (group != section) {
      if (!text.empty()) text += '\n';
      text += "[" + group + "]\n";
      section = group;
    }
    text +=
        key->name.substr(dot + 1) + " = " + value_text(key->binding.get(target), key->type, style);
    if (style == WriteStyle::kCommented) text += "  # " + key->doc + " (" + key->unit + ")";
    text += '\n';
  }
  return text;
}

/// The docs/config.md table of one schema table: key, type, unit, default, allowed, used when,
/// meaning.
template <typename Target>
std::string markdown_table(const Schema<Target>& schema, const std::string& table);

/// Text of a key's default for docs and config_keys(): `shown` in English when it has words.
std::string default_text(const KeyView& key, const Value& default_value,
                         const std::string& default_from, const Wording& shown);

/// Type name for docs ("float", "integer", "string", "boolean", "array").
const char* type_name(ValueType type);

template <typename Target>
std::string markdown_table(const Schema<Target>& schema, const std::string& table) {
  std::string text =
      "| key | type | unit | default | allowed | used when | meaning |\n"
      "|---|---|---|---|---|---|---|\n";
  const auto views = key_views(schema);
  for (std::size_t i = 0; i < schema.keys.size(); ++i) {
    const auto& key = schema.keys[i];
    if (key.name.substr(0, key.name.find('.')) != table) continue;
    std::string allowed = allowed_text(views[i]);
    std::string cells[] = {
        "`" + key.name + "`",
        type_name(key.type),
        key.unit == "-" ? "-" : key.unit,
        default_text(views[i], *key.default_value, key.default_from, key.default_text),
        allowed,
        key.scope.text,
        key.doc};
    std::string row = "|";
    for (auto& cell : cells) {
      for (std::size_t at = cell.find('|'); at != std::string::npos; at = cell.find('|', at + 2)) {
        cell.replace(at, 1, "\\|");
      }
      row += " " + cell + " |";
    }
    text += row + "\n";
  }
  return text;
}

}  // namespace aggpack
