// Reading a configuration: TOML text and `--set key=value` overrides into typed values of the
// schema's keys, checking types, ranges and words; every message names the key the user typed.

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <toml++/toml.h>

#include "aggpack/config/schema.h"
#include "aggpack/core/text.h"

namespace aggpack {

namespace {

// `text` without the blanks (spaces, tabs) at its two ends.
std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  const auto last = text.find_last_not_of(" \t");
  return first == std::string_view::npos ? std::string()
                                         : std::string(text.substr(first, last - first + 1));
}

std::string last_component(std::string_view name) {
  const auto dot = name.rfind('.');
  return std::string(dot == std::string_view::npos ? name : name.substr(dot + 1));
}

// The closest candidate within a typo's distance, or "" if none is close.
std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
  if (word.size() > 64) return "";  // no typo of a known name; and edit distance is quadratic
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const auto& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  return best_distance <= limit ? best : "";
}

// "did you mean" for a full dotted key, strongest evidence first: a small typo in the whole key;
// the same key name in another table ("seed" -> "packer.seed", "container.alpha" ->
// "particle.alpha"); a misspelt table with a correct key ("partcle.alpha"); a larger typo.
std::string suggest_key(std::string_view key, const std::vector<std::string>& keys,
                        const std::vector<std::string>& tables) {
  if (key.size() > 64) return "";  // no typo of a known key; and edit distance is quadratic
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  std::string best;
  for (const auto& known : keys) {
    const std::size_t distance = edit_distance(key, known);
    if (distance < best_distance) {
      best_distance = distance;
      best = known;
    }
  }
  if (best_distance <= 2) return best;
  const std::string last = last_component(key);
  std::vector<std::string> with_same_last;
  for (const auto& known : keys) {
    if (last_component(known) == last) with_same_last.push_back(known);
  }
  if (with_same_last.size() == 1) return with_same_last.front();
  const auto dot = key.find('.');
  if (dot != std::string_view::npos) {
    const std::string table = closest(key.substr(0, dot), tables);
    const std::string candidate = table + std::string(key.substr(dot));
    if (!table.empty() && std::find(keys.begin(), keys.end(), candidate) != keys.end()) {
      return candidate;
    }
  }
  return best_distance <= std::max<std::size_t>(2, key.size() / 3) ? best : "";
}

std::string node_text(const toml::node& node) {
  if (const auto* value = node.as_floating_point()) return format_value(value->get());
  if (const auto* value = node.as_integer()) return std::to_string(value->get());
  if (const auto* value = node.as_string()) return aggpack::quoted(shortened(value->get()));
  if (const auto* value = node.as_boolean()) return value->get() ? "true" : "false";
  std::ostringstream out;
  if (const auto* array = node.as_array()) {
    out << *array;
  } else if (const auto* table = node.as_table()) {
    out << "{" << table->size() << " keys}";
  } else {
    out << "(a date/time)";
  }
  return out.str();
}

const char* type_phrase(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    default:
      return "a date/time";
  }
}

std::string got(const toml::node& node) {
  return " (got " + std::string(type_phrase(node)) + " " + node_text(node) + ")";
}

std::string unit_suffix(const std::string& unit) {
  return unit.empty() || unit == "-" ? std::string() : " " + unit;
}

// ---- reading the tree -------------------------------------------------------------------------

struct Leaf {
  const toml::node* node = nullptr;
  std::string origin;  // "paper.toml:5" or "--set packer.gap=1"
  std::size_t order = 0;
  bool is_override = false;  // given by --set (it comes after every file value)
};

void collect(const toml::table& table, const std::string& prefix, const std::string& source,
             std::map<std::string, Leaf>& leaves, const std::map<std::string, std::string>& origins,
             std::vector<std::pair<std::string, std::string>>& empty_tables) {
  if (table.empty() && !prefix.empty()) {
    empty_tables.emplace_back(prefix, source + ":" + std::to_string(table.source().begin.line));
  }
  for (const auto& [key, node] : table) {
    const std::string name =
        prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (const auto* sub = node.as_table()) {
      collect(*sub, name, source, leaves, origins, empty_tables);
      continue;
    }
    Leaf leaf{.node = &node, .origin = {}, .order = 0};
    if (const auto found = origins.find(name); found != origins.end()) {
      leaf.origin = found->second;
      leaf.order = std::numeric_limits<std::uint32_t>::max();
      leaf.is_override = true;
    } else {
      leaf.origin = source + ":" + std::to_string(node.source().begin.line);
      leaf.order = node.source().begin.line;
    }
    leaves.emplace(name, std::move(leaf));
  }
}

// Applies "dotted.key=value" to the tree. The value is TOML ("0.002", "[[0.01, 50]]", "\"box\"");
// a bare word that is not valid TOML is taken as a string, so `--set packer.kind=random` works.
void apply_override(toml::table& root, const std::string& text,
                    std::map<std::string, std::string>& origins) {
  const std::string origin = "--set " + clipped(text, 100);
  if (text.find_first_of("\n\r") != std::string::npos) {
    throw ConfigError("", origin + ": a --set value must be one line (it contains a line break)");
  }
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw ConfigError("", origin + ": expected key=value (e.g. --set packer.gap=0.001)");
  }
  const std::string key = override_key(text);
  const std::string value_text = trimmed(std::string_view(text).substr(equals + 1));
  if (value_text.empty()) throw ConfigError(key, origin + ": missing value for " + clipped(key));

  toml::table parsed;
  try {
    parsed = toml::parse("value = " + value_text);
  } catch (const toml::parse_error& error) {
    // Something that starts like a number, array, table or quoted string must be valid TOML;
    // anything else (a word, a path) is taken as a string.
    if (std::string_view("0123456789+-[{\"'").find(value_text.front()) != std::string::npos) {
      throw FormatError(origin + ": not a valid TOML value (" + std::string(error.description()) +
                        ")");
    }
    parsed = toml::table{{"value", value_text}};
  }

  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = key.find('.', start);
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  toml::table* table = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].empty()) throw ConfigError(key, origin + ": malformed key '" + clipped(key) + "'");
    auto* node = table->get(parts[i]);
    if (node == nullptr) {
      table = table->insert(parts[i], toml::table{}).first->second.as_table();
    } else if (node->is_table()) {
      table = node->as_table();
    } else {
      throw ConfigError(key, origin + ": '" + clipped(parts[i]) + "' is not a table");
    }
  }
  if (parts.back().empty()) {
    throw ConfigError(key, origin + ": malformed key '" + clipped(key) + "'");
  }
  parsed.get("value")->visit(
      [&](const auto& value) { table->insert_or_assign(parts.back(), value); });
  origins[key] = origin;
}

// ---- converting one leaf to its key's type ------------------------------------------------------

class Converter {
 public:
  Converter(const KeyView& key, const Leaf& leaf) : key_(key), leaf_(leaf) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw ConfigError(*key_.name, leaf_.origin + ": " + message);
  }

  Value convert() const {
    const toml::node& node = *leaf_.node;
    const std::string& name = *key_.name;
    switch (key_.type) {
      case ValueType::kFloat: {
        const auto value = number(node);
        if (!value) fail(name + " must be a number in " + *key_.unit + got(node));
        check_range(name, *value, format_value(*value));
        return *value;
      }
      case ValueType::kInteger: {
        const auto* value = node.as_integer();
        if (value == nullptr) fail(name + " must be an integer" + got(node));
        check_range(name, static_cast<double>(value->get()), std::to_string(value->get()));
        return static_cast<std::int64_t>(value->get());
      }
      case ValueType::kWord: {
        const std::string allowed = allowed_text(key_);
        const auto* value = node.as_string();
        if (value == nullptr) fail(name + " must be a string, one of " + allowed + got(node));
        const std::string text = value->get();
        const auto& words = *key_.words;
        if (std::find(words.begin(), words.end(), text) == words.end()) {
          const std::string suggestion = closest(text, words);
          fail("invalid " + name + " = " + aggpack::quoted(shortened(text)) + " (allowed: " +
               allowed + ")" + (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"));
        }
        return text;
      }
      case ValueType::kBool: {
        const auto* value = node.as_boolean();
        if (value == nullptr) fail(name + " must be true or false" + got(node));
        return value->get();
      }
      case ValueType::kNumberList: {
        const auto* items = node.as_array();
        if (items == nullptr)
          fail(name + " must be an array of numbers, e.g. [0.1, 0.2]" + got(node));
        std::vector<double> values;
        for (std::size_t i = 0; i < items->size(); ++i) {
          const auto value = number(*items->get(i));
          if (!value) {
            fail(name + "[" + std::to_string(i) + "] must be a number" + got(*items->get(i)));
          }
          check_range(name, *value, format_value(*value));
          values.push_back(*value);
        }
        return values;
      }
      case ValueType::kSieve:
        return sieve(node);
      case ValueType::kPath: {
        const auto* path = node.as_string();
        if (path == nullptr || path->get().empty()) {
          fail(name + " must be a non-empty string (a file path)");
        }
        return path->get();
      }
      case ValueType::kPathList: {
        const std::string expected =
            " must be a non-empty path or an array of them, e.g. [\"a.stl\", \"rocks/\"]";
        if (const auto* path = node.as_string()) {
          if (path->get().empty()) fail(name + expected);
          return std::vector<std::string>{path->get()};
        }
        const auto* items = node.as_array();
        if (items == nullptr || items->empty()) fail(name + expected + got(node));
        std::vector<std::string> paths;
        for (std::size_t i = 0; i < items->size(); ++i) {
          const auto* path = items->get(i)->as_string();
          if (path == nullptr || path->get().empty()) {
            fail(name + "[" + std::to_string(i) + "] must be a non-empty string (a file path)" +
                 got(*items->get(i)));
          }
          paths.push_back(path->get());
        }
        return paths;
      }
    }
    fail(name + ": unknown type");
  }

 private:
  static std::optional<double> number(const toml::node& node) {
    if (const auto* f = node.as_floating_point()) return f->get();
    if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
    return std::nullopt;
  }

  void check_range(const std::string& name, double value, const std::string& text) const {
    if (!key_.range->contains(value)) {
      fail("invalid " + name + " = " + text + " (allowed: " + key_.range->text() +
           unit_suffix(*key_.unit) + (has_words(*key_.note) ? ", " + english(*key_.note) : "") +
           ")");
    }
  }

  std::vector<SieveRow> sieve(const toml::node& node) const {
    const std::string& key = *key_.name;
    const std::string shape_hint =
        " must be an array of [size_m, percent_passing] pairs, e.g. [[0.005, 0], [0.02, 100]]";
    const auto* rows = node.as_array();
    if (rows == nullptr) fail(key + shape_hint + " (got " + type_phrase(node) + ")");
    std::vector<SieveRow> table;
    for (std::size_t r = 0; r < rows->size(); ++r) {
      const auto* row = (*rows)[r].as_array();
      const std::string row_name = key + "[" + std::to_string(r) + "]";
      if (row == nullptr || row->size() != 2) fail(row_name + shape_hint);
      double values[2] = {};
      for (std::size_t c = 0; c < 2; ++c) {
        const auto value = number(*row->get(c));
        if (!value) fail(row_name + shape_hint + got(*row->get(c)));
        values[c] = *value;
      }
      if (!key_.range->contains(values[0])) {
        fail("invalid " + row_name + " size = " + format_value(values[0]) +
             " (allowed: " + key_.range->text() + " m)");
      }
      if (!(values[1] >= 0 && values[1] <= 100)) {
        fail("invalid " + row_name + " percent passing = " + format_value(values[1]) +
             " (allowed: [0, 100] %)");
      }
      table.push_back({.size = values[0], .percent_passing = values[1]});
    }
    return table;
  }

  const KeyView& key_;
  const Leaf& leaf_;
};

// Keys given under a table's former name become the table's (an override, given after every
// line, wins over the file's value of the same key); one note per former name.
void read_former_tables(const std::vector<TableInfo>& tables, std::map<std::string, Leaf>& leaves,
                        std::vector<std::pair<std::string, std::string>>& empty_tables,
                        std::vector<std::string>* notes) {
  for (const TableInfo& table : tables) {
    if (table.former_name.empty()) continue;
    const std::string old_prefix = table.former_name + ".";
    std::vector<std::pair<std::string, Leaf>> moved;
    for (auto it = leaves.begin(); it != leaves.end();) {
      if (it->first.rfind(old_prefix, 0) == 0) {
        moved.emplace_back(table.name + "." + it->first.substr(old_prefix.size()), it->second);
        it = leaves.erase(it);
      } else {
        ++it;
      }
    }
    const Leaf* first = nullptr;
    for (const auto& [name, leaf] : moved) {
      if (first == nullptr || leaf.order < first->order) first = &leaf;
      const auto [existing, is_new] = leaves.try_emplace(name, leaf);
      if (is_new) continue;
      // Both names in the file: which one counts is not clear. An override wins (it comes last).
      if (!leaf.is_override && !existing->second.is_override) {
        throw ConfigError(name, leaf.origin + ": " + name + " given twice, in [" +
                                    table.former_name + "] and in [" + table.name + "] (keep [" +
                                    table.name + "])");
      }
      if (leaf.order > existing->second.order) existing->second = leaf;
    }
    std::string where;
    for (auto& [name, origin] : empty_tables) {
      if (name != table.former_name) continue;
      name = table.name;
      where = origin;
    }
    if (first != nullptr) where = first->origin;
    if (notes != nullptr && !where.empty()) {
      notes->push_back(where + ": [" + table.former_name + "] is now [" + table.name +
                       "]: read as [" + table.name + "] (rename it; the old name will go)");
    }
  }
}

}  // namespace

std::string override_key(std::string_view text) {
  const auto equals = text.find('=');
  return equals == std::string_view::npos ? std::string() : trimmed(text.substr(0, equals));
}

const std::string* last_override_of(const std::vector<std::string>& overrides,
                                    std::string_view key) {
  for (auto text = overrides.rbegin(); text != overrides.rend(); ++text) {
    if (text->find('=') != std::string::npos && override_key(*text) == key) return &*text;
  }
  return nullptr;
}

GivenValues read_values(const std::vector<TableInfo>& tables, const std::vector<KeyView>& keys,
                        std::string_view text, std::string_view source_name,
                        const std::vector<std::string>& overrides,
                        std::vector<std::string>* notes) {
  const std::string source(source_name);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& error) {
    throw FormatError(source + ":" + std::to_string(error.source().begin.line) + ":" +
                      std::to_string(error.source().begin.column) +
                      ": TOML syntax error: " + std::string(error.description()));
  }
  std::map<std::string, std::string> origins;
  for (const auto& override_text : overrides) apply_override(root, override_text, origins);

  std::map<std::string, Leaf> leaves;
  std::vector<std::pair<std::string, std::string>> empty_tables;
  collect(root, "", source, leaves, origins, empty_tables);
  read_former_tables(tables, leaves, empty_tables, notes);

  std::vector<std::string> table_names;
  for (const auto& table : tables) table_names.push_back(table.name);
  std::vector<std::string> key_names;
  for (const auto& key : keys) key_names.push_back(*key.name);
  const auto find_key = [&](const std::string& name) -> const KeyView* {
    for (const auto& key : keys) {
      if (*key.name == name) return &key;
    }
    return nullptr;
  };

  // Unknown tables and keys first, in the order they appear, each with a suggestion.
  for (const auto& [name, where] : empty_tables) {
    if (std::find(table_names.begin(), table_names.end(), name) == table_names.end()) {
      const std::string suggestion = closest(name, table_names);
      throw ConfigError(name,
                        where + ": unknown table [" + clipped(name) + "]" +
                            (suggestion.empty() ? "" : "; did you mean [" + suggestion + "]?"));
    }
  }
  std::vector<std::pair<std::size_t, std::string>> ordered;
  for (const auto& [name, leaf] : leaves) ordered.emplace_back(leaf.order, name);
  std::sort(ordered.begin(), ordered.end());
  for (const auto& [order, name] : ordered) {
    if (find_key(name) != nullptr) continue;
    const Leaf& leaf = leaves.at(name);
    const auto dot = name.find('.');
    const std::string table = name.substr(0, dot);
    const auto family = std::find_if(tables.begin(), tables.end(), [&](const TableInfo& t) {
      return t.name == table && !t.member_word.empty();
    });
    if (family != tables.end() && dot != std::string::npos &&
        name.find('.', dot + 1) == std::string::npos) {
      std::vector<std::string> members;
      std::string list;
      for (const auto& key : key_names) {
        if (key.rfind(table + ".", 0) != 0) continue;
        members.push_back(key.substr(dot + 1));
        list += (list.empty() ? "" : ", ") + members.back();
      }
      const std::string member = name.substr(dot + 1);
      const std::string suggestion = closest(member, members);
      throw ConfigError(
          name,
          leaf.origin + ": unknown " + family->member_word + " '" + clipped(member) +
              "' (allowed: " + list + ")" +
              (suggestion.empty() ? "" : "; did you mean '" + table + "." + suggestion + "'?"));
    }
    const std::string suggestion = suggest_key(name, key_names, table_names);
    throw ConfigError(name, leaf.origin + ": unknown key '" + clipped(name) + "'" +
                                (suggestion.empty() ? " (see docs/config.md for every key)"
                                                    : "; did you mean '" + suggestion + "'?"));
  }

  GivenValues given;
  for (const auto& [order, name] : ordered) {
    const Leaf& leaf = leaves.at(name);
    given[name] = {.value = Converter(*find_key(name), leaf).convert(),
                   .origin = leaf.origin,
                   .order = leaf.order};
  }
  return given;
}

std::string read_config_file(const std::string& path) {
  std::error_code status_error;
  if (std::filesystem::is_directory(path, status_error)) {
    throw IoError("cannot read config " + path + ": it is a folder");
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    // The reason in the user's words: a typo (no such file) and a permission are fixed apart.
    const int reason = errno;
    throw IoError("cannot read config " + path + ": " +
                  (reason == ENOENT   ? std::string("no such file")
                   : reason == EACCES ? std::string("permission denied")
                   : reason != 0      ? std::string(std::strerror(reason))
                                      : std::string("cannot open it")));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError("cannot read config " + path);
  return text.str();
}

}  // namespace aggpack
