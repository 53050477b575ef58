#include "aggpack/io/config.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "aggpack/core/text.h"
#include "aggpack/io/export.h"
#include "aggpack/pack/container.h"

namespace aggpack {

namespace {

// ---- the key table --------------------------------------------------------------------------

enum class Type { kFloat, kInteger, kWord, kSieve, kPath };

// Which resolved configuration reads a key. Keys given explicitly outside their scope produce a
// warning (not an error), so that `--set packer.kind=random` on a lattice file still works; their
// values are still checked (an invalid one is an error).
enum class Scope {
  kAlways,
  kBox,
  kCylinder,
  kLattice,
  kRandom,
  kLatticeOrUniform,  // particle.radius: the lattice radius, or the uniform grading's default
  kUniform,           // random packer with grading.kind = uniform
  kFuller,            // random packer with grading.kind = fuller
  kSieve,             // random packer with grading.kind = sieve
  kRelativeEdge       // random packer with particle.edge_length = 0
};

struct Spec {
  const char* name;
  Type type;
  const char* unit;
  double lo;
  double hi;
  bool is_lo_open;  // lo itself not allowed
  std::vector<const char*> words;
  const char* default_text;
  const char* allowed;
  Scope scope;
  const char* description;
};

constexpr double kHuge = 1e6;  // 1000 km: any larger length is a unit mistake
constexpr double kMaxSeed = 9223372036854775807.0;

const std::vector<Spec>& specs() {
  static const std::vector<Spec> table = {
      {"container.kind",
       Type::kWord,
       "",
       0,
       0,
       false,
       {"box", "cylinder"},
       "\"box\"",
       "box | cylinder",
       Scope::kAlways,
       "container shape: box [0,length]x[0,width]x[0,depth], or cylinder about the z axis"},
      {"container.length",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "3.0",
       "(0, 1e6]",
       Scope::kBox,
       "box extent along x"},
      {"container.width",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "1.0",
       "(0, 1e6]",
       Scope::kBox,
       "box extent along y"},
      {"container.depth",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "2.8",
       "(0, 1e6]",
       Scope::kBox,
       "box extent along z (vertical)"},
      {"container.radius",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "0.05",
       "(0, 1e6]",
       Scope::kCylinder,
       "cylinder radius (axis x = y = 0)"},
      {"container.height",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "0.1",
       "(0, 1e6]",
       Scope::kCylinder,
       "cylinder height (z from 0)"},
      {"container.wall_gap",
       Type::kFloat,
       "m",
       0,
       kHuge,
       false,
       {},
       "0.0",
       "[0, 1e6], < half the smallest extent",
       Scope::kAlways,
       "minimum distance from every particle to every wall"},
      {"particle.alpha",
       Type::kFloat,
       "-",
       0,
       1,
       false,
       {},
       "0.5",
       "[0, 1]",
       Scope::kAlways,
       "Eq. 3 shape control: 1 = regular, full shapes; 0 = sharp, flat shapes"},
      {"particle.radius",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "0.1",
       "(0, 1e6]",
       Scope::kLatticeOrUniform,
       "control radius R (lattice: every particle; random: default of radius_min/radius_max)"},
      {"particle.radius_min",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "particle.radius",
       "(0, 1e6], <= radius_max",
       Scope::kUniform,
       "smallest control radius of the uniform grading (uniform by number)"},
      {"particle.radius_max",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "particle.radius",
       "(0, 1e6], >= radius_min",
       Scope::kUniform,
       "largest control radius of the uniform grading"},
      {"particle.edge_length",
       Type::kFloat,
       "m",
       0,
       kHuge,
       false,
       {},
       "0.1",
       "(0, 1e6]; 0 allowed with packer.kind = random",
       Scope::kAlways,
       "growth edge-length control L; 0 = relative, L = edge_length_ratio * r (random packer)"},
      {"particle.edge_length_ratio",
       Type::kFloat,
       "-",
       0.05,
       10,
       false,
       {},
       "1.0",
       "[0.05, 10]",
       Scope::kRelativeEdge,
       "L / r for each particle when particle.edge_length = 0"},
      {"particle.max_vertices",
       Type::kInteger,
       "",
       6,
       1e6,
       false,
       {},
       "20000",
       "[6, 1000000]",
       Scope::kAlways,
       "vertex cap per particle (rejects an L too small for the radius)"},
      {"grading.kind",
       Type::kWord,
       "",
       0,
       0,
       false,
       {"uniform", "fuller", "sieve"},
       "\"uniform\"",
       "uniform | fuller | sieve",
       Scope::kRandom,
       "size distribution of the random packer (sizes are control diameters d = 2 r)"},
      {"grading.size_min",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "0.005",
       "(0, 1e6], < size_max",
       Scope::kFuller,
       "Fuller curve: smallest control diameter d_min"},
      {"grading.size_max",
       Type::kFloat,
       "m",
       0,
       kHuge,
       true,
       {},
       "0.02",
       "(0, 1e6], > size_min",
       Scope::kFuller,
       "Fuller curve: largest control diameter d_max"},
      {"grading.exponent",
       Type::kFloat,
       "-",
       0,
       10,
       true,
       {},
       "0.5",
       "(0, 10]",
       Scope::kFuller,
       "Fuller curve exponent q: P(d) = (d^q - d_min^q) / (d_max^q - d_min^q)"},
      {"grading.sieve",
       Type::kSieve,
       "m, %",
       0,
       0,
       false,
       {},
       "(none)",
       ">= 2 rows [size, percent passing]; sizes increasing, percents non-decreasing, last 100",
       Scope::kSieve,
       "sieve table by volume, e.g. [[0.005, 0], [0.01, 40], [0.02, 100]]"},
      {"packer.kind",
       Type::kWord,
       "",
       0,
       0,
       false,
       {"lattice", "random"},
       "\"lattice\"",
       "lattice | random",
       Scope::kAlways,
       "lattice = the paper's regular placement with growth in place; random = random sequential "
       "addition with a grading"},
      {"packer.seed",
       Type::kInteger,
       "",
       0,
       kMaxSeed,
       false,
       {},
       "1",
       "[0, 2^63 - 1]",
       Scope::kAlways,
       "master seed; particle i draws from its own stream (seed, i)"},
      {"packer.threads",
       Type::kInteger,
       "",
       0,
       4096,
       false,
       {},
       "0",
       "[0, 4096]",
       Scope::kAlways,
       "worker threads, 0 = all cores; results do not depend on it (not stored in the file)"},
      {"packer.gap",
       Type::kFloat,
       "m",
       0,
       kHuge,
       false,
       {},
       "0.0",
       "[0, 1e6]",
       Scope::kAlways,
       "minimum distance between particles"},
      {"packer.spacing",
       Type::kFloat,
       "m",
       0,
       kHuge,
       false,
       {},
       "0.0",
       "0, or [particle.radius, 1e6]",
       Scope::kLattice,
       "lattice centre spacing; 0 = 2 R + gap (particles cannot touch); smaller values turn on "
       "the paper's contact check"},
      {"packer.target_count",
       Type::kInteger,
       "",
       1,
       1e8,
       false,
       {},
       "(unset)",
       "[1, 1e8]",
       Scope::kRandom,
       "place this many particles (instead of target_fraction)"},
      {"packer.target_fraction",
       Type::kFloat,
       "-",
       0,
       0.9,
       true,
       {},
       "0.35",
       "(0, 0.9]",
       Scope::kRandom,
       "place particles until solid volume / container volume reaches this"},
      {"packer.attempts",
       Type::kInteger,
       "",
       1,
       1e9,
       false,
       {},
       "5000",
       "[1, 1e9]",
       Scope::kRandom,
       "candidate poses per particle before it is skipped"},
      {"packer.max_total_attempts",
       Type::kInteger,
       "",
       1,
       1e12,
       false,
       {},
       "200000000",
       "[1, 1e12]",
       Scope::kRandom,
       "candidate poses for the whole run; stops when used up"},
      {"packer.max_consecutive_failures",
       Type::kInteger,
       "",
       1,
       1e9,
       false,
       {},
       "100",
       "[1, 1e9]",
       Scope::kRandom,
       "stop after this many particles in a row could not be placed"},
      {"packer.shape_library",
       Type::kInteger,
       "",
       0,
       1e6,
       false,
       {},
       "0",
       "[0, 1e6]",
       Scope::kRandom,
       "0 = a unique shape per particle; K > 0 = K unit shapes reused, scaled and rotated "
       "(for ~10^6 particles; needs particle.edge_length = 0)"},
  };
  return table;
}

const Spec* find_spec(std::string_view name) {
  for (const auto& spec : specs()) {
    if (name == spec.name) return &spec;
  }
  return nullptr;
}

const char* scope_text(Scope scope) {
  switch (scope) {
    case Scope::kAlways:
      return "always";
    case Scope::kBox:
      return "container.kind = box";
    case Scope::kCylinder:
      return "container.kind = cylinder";
    case Scope::kLattice:
      return "packer.kind = lattice";
    case Scope::kRandom:
      return "packer.kind = random";
    case Scope::kLatticeOrUniform:
      return "lattice, or random with grading.kind = uniform";
    case Scope::kUniform:
      return "random with grading.kind = uniform";
    case Scope::kFuller:
      return "random with grading.kind = fuller";
    case Scope::kSieve:
      return "random with grading.kind = sieve";
    case Scope::kRelativeEdge:
      return "random with particle.edge_length = 0";
  }
  return "";
}

// ---- helpers ----------------------------------------------------------------------------------

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

std::vector<std::string> known_keys() {
  std::vector<std::string> keys;
  for (const auto& spec : specs()) keys.emplace_back(spec.name);
  for (const auto& format : output_formats()) keys.push_back("output." + format);
  return keys;
}

// "did you mean" for a full dotted key, strongest evidence first: a small typo in the whole key;
// the same key name in another table ("seed" -> "packer.seed", "container.alpha" ->
// "particle.alpha"); a misspelt table with a correct key ("partcle.alpha"); a larger typo.
std::string suggest_key(std::string_view key) {
  if (key.size() > 64) return "";  // no typo of a known key; and edit distance is quadratic
  const auto keys = known_keys();
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
    const std::vector<std::string> tables = {"container", "particle", "grading", "packer",
                                             "output"};
    const std::string table = closest(key.substr(0, dot), tables);
    const std::string candidate = table + std::string(key.substr(dot));
    if (!table.empty() && std::find(keys.begin(), keys.end(), candidate) != keys.end()) {
      return candidate;
    }
  }
  return best_distance <= std::max<std::size_t>(2, key.size() / 3) ? best : "";
}

std::string format_double(double value) {
  // Shortest round-trip text; plain decimals ("0.0005") unless they get long (1e-12, 3e+20).
  char buffer[512];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  std::string text(buffer, result.ptr);
  if (result.ec != std::errc() || text.size() > 12) {
    result = std::to_chars(buffer, buffer + sizeof buffer, value);
    text.assign(buffer, result.ptr);
  }
  // TOML needs a float to look like one ("3" is an integer).
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
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

// ---- reading the tree -------------------------------------------------------------------------

struct Leaf {
  const toml::node* node = nullptr;
  std::string origin;  // "paper.toml:5" or "--set packer.gap=1"
  std::size_t order = 0;
};

class Resolver {
 public:
  Resolver(std::map<std::string, Leaf> leaves) : leaves_(std::move(leaves)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const auto found = leaves_.find(key);
    const std::string where = found != leaves_.end() ? found->second.origin + ": " : "";
    throw ConfigError(key, where + message);
  }

  [[nodiscard]] bool has(const std::string& key) const { return leaves_.count(key) > 0; }
  [[nodiscard]] const std::map<std::string, Leaf>& leaves() const { return leaves_; }

  double number(const std::string& key, double fallback) const {
    const Spec& spec = *find_spec(key);
    const auto found = leaves_.find(key);
    if (found == leaves_.end()) return fallback;
    const toml::node& node = *found->second.node;
    double value = 0;
    if (const auto* f = node.as_floating_point()) {
      value = f->get();
    } else if (const auto* i = node.as_integer()) {
      value = static_cast<double>(i->get());
    } else {
      fail(key, key + " must be a number in " + spec.unit + " (got " + type_phrase(node) + " " +
                    node_text(node) + ")");
    }
    check_range(spec, key, value, format_value(value));
    return value;
  }

  std::int64_t integer(const std::string& key, std::int64_t fallback) const {
    const Spec& spec = *find_spec(key);
    const auto found = leaves_.find(key);
    if (found == leaves_.end()) return fallback;
    const toml::node& node = *found->second.node;
    const auto* value = node.as_integer();
    if (value == nullptr) {
      fail(key,
           key + " must be an integer (got " + type_phrase(node) + " " + node_text(node) + ")");
    }
    check_range(spec, key, static_cast<double>(value->get()), std::to_string(value->get()));
    return value->get();
  }

  std::string word(const std::string& key, const std::string& fallback) const {
    const Spec& spec = *find_spec(key);
    const auto found = leaves_.find(key);
    if (found == leaves_.end()) return fallback;
    const toml::node& node = *found->second.node;
    const auto* value = node.as_string();
    if (value == nullptr) {
      fail(key, key + " must be a string, one of " + spec.allowed + " (got " + type_phrase(node) +
                    " " + node_text(node) + ")");
    }
    const std::string text = value->get();
    std::vector<std::string> words(spec.words.begin(), spec.words.end());
    if (std::find(words.begin(), words.end(), text) == words.end()) {
      const std::string suggestion = closest(text, words);
      fail(key, "invalid " + key + " = " + aggpack::quoted(shortened(text)) +
                    " (allowed: " + spec.allowed + ")" +
                    (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?"));
    }
    return text;
  }

  std::vector<SieveRow> sieve(const std::string& key) const {
    const auto found = leaves_.find(key);
    if (found == leaves_.end()) {
      throw ConfigError(key,
                        "grading.kind = \"sieve\" needs grading.sieve = [[size_m, "
                        "percent_passing], ...] (at least 2 rows)");
    }
    const toml::node& node = *found->second.node;
    const std::string shape_hint =
        " must be an array of [size_m, percent_passing] pairs, e.g. [[0.005, 0], [0.02, 100]]";
    const auto* rows = node.as_array();
    if (rows == nullptr) fail(key, key + shape_hint + " (got " + type_phrase(node) + ")");
    std::vector<SieveRow> table;
    for (std::size_t r = 0; r < rows->size(); ++r) {
      const auto* row = (*rows)[r].as_array();
      const std::string row_name = key + "[" + std::to_string(r) + "]";
      if (row == nullptr || row->size() != 2) fail(key, row_name + shape_hint);
      double values[2] = {};
      for (std::size_t c = 0; c < 2; ++c) {
        const toml::node& cell = *row->get(c);
        if (const auto* f = cell.as_floating_point()) {
          values[c] = f->get();
        } else if (const auto* i = cell.as_integer()) {
          values[c] = static_cast<double>(i->get());
        } else {
          fail(key,
               row_name + shape_hint + " (got " + type_phrase(cell) + " " + node_text(cell) + ")");
        }
      }
      if (!(values[0] > 0 && values[0] <= kHuge)) {
        fail(key, "invalid " + row_name + " size = " + format_value(values[0]) +
                      " (allowed: (0, 1e6] m)");
      }
      if (!(values[1] >= 0 && values[1] <= 100)) {
        fail(key, "invalid " + row_name + " percent passing = " + format_value(values[1]) +
                      " (allowed: [0, 100] %)");
      }
      table.push_back({.size = values[0], .percent_passing = values[1]});
    }
    return table;
  }

 private:
  void check_range(const Spec& spec, const std::string& key, double value,
                   const std::string& text) const {
    const bool is_ok = std::isfinite(value) &&
                       (spec.is_lo_open ? value > spec.lo : value >= spec.lo) && value <= spec.hi;
    if (!is_ok) {
      fail(key, "invalid " + key + " = " + text + " (allowed: " + spec.allowed +
                    (std::string(spec.unit) == "" || std::string(spec.unit) == "-"
                         ? std::string()
                         : std::string(" ") + spec.unit) +
                    ")");
    }
  }

  std::map<std::string, Leaf> leaves_;
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
  auto trim = [](std::string s) {
    const auto first = s.find_first_not_of(" \t");
    const auto last = s.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : s.substr(first, last - first + 1);
  };
  const std::string key = trim(text.substr(0, equals));
  const std::string value_text = trim(text.substr(equals + 1));
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
  if (parts.back().empty())
    throw ConfigError(key, origin + ": malformed key '" + clipped(key) + "'");
  parsed.get("value")->visit(
      [&](const auto& value) { table->insert_or_assign(parts.back(), value); });
  origins[key] = origin;
}

// ---- translation of the packers' own validation messages to config keys -------------------------

std::string to_config_names(std::string message) {
  static const std::vector<std::pair<std::string, std::string>> names = {
      // the shape generator's own names (vertex cap check)
      {"limit exceeded for edge_length =", "limit exceeded for particle.edge_length ="},
      {"limit exceeded for max_vertices =", "limit exceeded for particle.max_vertices ="},
      {"shape.edge_length_ratio", "particle.edge_length_ratio"},
      {"random.max_attempts_per_particle", "packer.attempts"},
      {"random.max_consecutive_failures", "packer.max_consecutive_failures"},
      {"random.max_total_attempts", "packer.max_total_attempts"},
      {"random.volume_fraction", "packer.target_fraction"},
      {"shape.library_size", "packer.shape_library"},
      {"lattice.max_vertices", "particle.max_vertices"},
      {"shape.max_vertices", "particle.max_vertices"},
      {"lattice.edge_length", "particle.edge_length"},
      {"shape.edge_length", "particle.edge_length"},
      {"grading.radius_min", "particle.radius_min"},
      {"grading.radius_max", "particle.radius_max"},
      {"lattice.spacing", "packer.spacing"},
      {"lattice.radius", "particle.radius"},
      {"lattice.alpha", "particle.alpha"},
      {"shape.alpha", "particle.alpha"},
      {"random.count", "packer.target_count"},
      {"lattice.seed", "packer.seed"},
      {"random.seed", "packer.seed"},
      {"lattice.gap", "packer.gap"},
      {"random.gap", "packer.gap"},
  };
  for (const auto& [from, to] : names) {
    for (auto at = message.find(from); at != std::string::npos; at = message.find(from, at)) {
      message.replace(at, from.size(), to);
      at += to.size();
    }
  }
  return message;
}

template <typename Options>
void validate_with_config_names(const Options& options) {
  try {
    validate(options);
  } catch (const InvalidInput& error) {
    throw ConfigError(to_config_names(error.field()), to_config_names(error.what()));
  } catch (const Error& error) {
    throw Error(error.kind(), to_config_names(error.what()));
  }
}

// ---- the resolved configuration as TOML ---------------------------------------------------------

class TomlWriter {
 public:
  void table(const char* name) {
    if (!text_.empty()) text_ += '\n';
    text_ += std::string("[") + name + "]\n";
  }
  void number(const char* key, double value) { line(key, format_double(value)); }
  void integer(const char* key, std::uint64_t value) { line(key, std::to_string(value)); }
  void word(const char* key, std::string_view value) { line(key, aggpack::quoted(value)); }
  void line(const char* key, const std::string& value) {
    text_ += std::string(key) + " = " + value + "\n";
  }
  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  std::string text_;
};

std::string resolved_text(const PackConfig& config) {
  const bool is_lattice = config.packer == PackerKind::kLattice;
  const Container& c = config.container();
  TomlWriter out;
  out.table("container");
  const ContainerKindInfo& kind = container_kind_info(c);
  out.word("kind", kind.name);
  for (const ContainerParam& param : kind.params) out.number(param.name, param.get(c));
  out.number("wall_gap", c.wall_gap);

  out.table("particle");
  if (is_lattice) {
    const LatticeOptions& o = config.lattice;
    out.number("alpha", o.alpha);
    out.number("radius", o.radius);
    out.number("edge_length", o.edge_length);
    out.integer("max_vertices", o.max_vertices);
  } else {
    const RandomPackOptions& o = config.random;
    out.number("alpha", o.shape.alpha);
    if (o.grading.kind == GradingKind::kUniform) {
      out.number("radius_min", o.grading.radius_min);
      out.number("radius_max", o.grading.radius_max);
    }
    out.number("edge_length", o.shape.edge_length);
    if (o.shape.edge_length == 0) out.number("edge_length_ratio", o.shape.edge_length_ratio);
    out.integer("max_vertices", o.shape.max_vertices);

    out.table("grading");
    const Grading& g = o.grading;
    out.word("kind", to_string(g.kind));
    if (g.kind == GradingKind::kFuller) {
      out.number("size_min", g.size_min);
      out.number("size_max", g.size_max);
      out.number("exponent", g.exponent);
    } else if (g.kind == GradingKind::kSieve) {
      std::string rows = "[";
      for (std::size_t r = 0; r < g.sieve.size(); ++r) {
        rows += (r == 0 ? "[" : ", [") + format_double(g.sieve[r].size) + ", " +
                format_double(g.sieve[r].percent_passing) + "]";
      }
      out.line("sieve", rows + "]");
    }
  }

  out.table("packer");
  out.word("kind", is_lattice ? "lattice" : "random");
  out.integer("seed", config.seed());
  if (is_lattice) {
    out.number("gap", config.lattice.gap);
    out.number("spacing", config.lattice.spacing);
  } else {
    const RandomPackOptions& o = config.random;
    out.number("gap", o.gap);
    if (o.target == PackTarget::kCount) {
      out.integer("target_count", o.count);
    } else {
      out.number("target_fraction", o.volume_fraction);
    }
    out.integer("attempts", o.max_attempts_per_particle);
    out.integer("max_total_attempts", o.max_total_attempts);
    out.integer("max_consecutive_failures", o.max_consecutive_failures);
    out.integer("shape_library", o.shape.library_size);
  }

  if (!config.outputs.empty()) {
    out.table("output");
    for (const auto& [format, path] : config.outputs) out.word(format.c_str(), path);
  }
  return "# aggpack " AGGPACK_VERSION
         " resolved pack configuration: every key that has an effect, at its value\n\n" +
         out.text();
}

bool is_in_scope(Scope scope, const PackConfig& config, bool is_relative_edge) {
  const bool is_random = config.packer == PackerKind::kRandom;
  const GradingKind grading = config.random.grading.kind;
  switch (scope) {
    case Scope::kAlways:
      return true;
    case Scope::kBox:
      return config.container().get_if<BoxContainer>() != nullptr;
    case Scope::kCylinder:
      return config.container().get_if<CylinderContainer>() != nullptr;
    case Scope::kLattice:
      return !is_random;
    case Scope::kRandom:
      return is_random;
    case Scope::kLatticeOrUniform:
      return !is_random || grading == GradingKind::kUniform;
    case Scope::kUniform:
      return is_random && grading == GradingKind::kUniform;
    case Scope::kFuller:
      return is_random && grading == GradingKind::kFuller;
    case Scope::kSieve:
      return is_random && grading == GradingKind::kSieve;
    case Scope::kRelativeEdge:
      return is_random && is_relative_edge;
  }
  return true;
}

}  // namespace

// ---- public -------------------------------------------------------------------------------------

const std::vector<std::string>& output_formats() { return output_format_names(); }

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> keys = [] {
    std::vector<ConfigKey> list;
    for (const auto& spec : specs()) {
      const char* type = spec.type == Type::kFloat     ? "float"
                         : spec.type == Type::kInteger ? "integer"
                         : spec.type == Type::kSieve   ? "array"
                                                       : "string";
      list.push_back({spec.name, type, spec.unit, spec.default_text, spec.allowed,
                      scope_text(spec.scope), spec.description});
    }
    std::string formats;  // from the format table (export.h)
    for (const auto& name : output_formats()) formats += (formats.empty() ? "" : ", ") + name;
    list.push_back({"output.<format>", "string", "", "(none)", "format: " + formats, "always",
                    "file to write in that format; output.native is the .h5 written when -o is "
                    "not given (the other formats are written by the exporters)"});
    return list;
  }();
  return keys;
}

std::uint64_t PackConfig::seed() const {
  return packer == PackerKind::kLattice ? lattice.seed : random.seed;
}

const Container& PackConfig::container() const {
  return packer == PackerKind::kLattice ? lattice.container : random.container;
}

std::optional<Grading> PackConfig::target_grading() const {
  if (packer == PackerKind::kLattice) return std::nullopt;
  return random.grading;
}

std::string PackConfig::packer_name() const {
  return packer == PackerKind::kLattice ? "lattice" : "random";
}

PackConfig parse_pack_config(std::string_view text, std::string_view source_name,
                             const std::vector<std::string>& overrides) {
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

  // Unknown keys first, in the order they appear, each with a suggestion.
  std::vector<std::pair<std::size_t, std::string>> ordered;
  for (const auto& [name, leaf] : leaves) ordered.emplace_back(leaf.order, name);
  std::sort(ordered.begin(), ordered.end());
  const std::vector<std::string> tables = {"container", "particle", "grading", "packer", "output"};
  for (const auto& [name, where] : empty_tables) {
    if (std::find(tables.begin(), tables.end(), name) == tables.end()) {
      const std::string suggestion = closest(name, tables);
      throw ConfigError(name,
                        where + ": unknown table [" + clipped(name) + "]" +
                            (suggestion.empty() ? "" : "; did you mean [" + suggestion + "]?"));
    }
  }
  for (const auto& [order, name] : ordered) {
    const Leaf& leaf = leaves.at(name);
    if (name.rfind("output.", 0) == 0 && name.find('.', 7) == std::string::npos) {
      const std::string format = name.substr(7);
      const auto& formats = output_formats();
      if (std::find(formats.begin(), formats.end(), format) == formats.end()) {
        const std::string suggestion = closest(format, formats);
        throw ConfigError(
            name, leaf.origin + ": unknown output format '" + clipped(format) +
                      "' (allowed: native, stl, obj, vtu, dat, inp, msh, k, apdl, "
                      "yade)" +
                      (suggestion.empty() ? "" : "; did you mean 'output." + suggestion + "'?"));
      }
      const auto* path = leaf.node->as_string();
      if (path == nullptr || path->get().empty()) {
        throw ConfigError(name,
                          leaf.origin + ": " + name + " must be a non-empty string (a file path)");
      }
      continue;
    }
    if (find_spec(name) == nullptr) {
      const std::string suggestion = suggest_key(name);
      throw ConfigError(name, leaf.origin + ": unknown key '" + clipped(name) + "'" +
                                  (suggestion.empty() ? " (see docs/config.md for every key)"
                                                      : "; did you mean '" + suggestion + "'?"));
    }
  }

  const Resolver values(std::move(leaves));
  PackConfig config;
  config.packer = values.word("packer.kind", "lattice") == "random" ? PackerKind::kRandom
                                                                    : PackerKind::kLattice;
  config.threads = static_cast<int>(values.integer("packer.threads", 0));

  Container container;
  container = find_container_kind(values.word("container.kind", "box"))->defaults;
  for (const ContainerKindInfo& kind : container_kinds()) {
    for (const ContainerParam& param : kind.params) {
      param.set(container,
                values.number(std::string("container.") + param.name, param.get(kind.defaults)));
    }
  }
  container.wall_gap = values.number("container.wall_gap", 0.0);

  const double alpha = values.number("particle.alpha", 0.5);
  const double radius = values.number("particle.radius", 0.1);
  const double edge_length = values.number("particle.edge_length", 0.1);
  const double edge_length_ratio = values.number("particle.edge_length_ratio", 1.0);
  const auto max_vertices =
      static_cast<std::uint32_t>(values.integer("particle.max_vertices", 20000));
  const auto seed = static_cast<std::uint64_t>(values.integer("packer.seed", 1));
  const double gap = values.number("packer.gap", 0.0);

  if (config.packer == PackerKind::kLattice) {
    if (edge_length == 0) {
      values.fail("particle.edge_length",
                  "invalid particle.edge_length = 0 (allowed: > 0 with packer.kind = lattice; "
                  "0 = relative edge length exists only for the random packer)");
    }
    config.lattice = {.container = container,
                      .alpha = alpha,
                      .radius = radius,
                      .edge_length = edge_length,
                      .gap = gap,
                      .spacing = values.number("packer.spacing", 0.0),
                      .max_vertices = max_vertices,
                      .seed = seed};
  } else {
    RandomPackOptions& o = config.random;
    o.container = container;
    o.shape = {
        .alpha = alpha,
        .edge_length = edge_length,
        .edge_length_ratio = edge_length_ratio,
        .max_vertices = max_vertices,
        .library_size = static_cast<std::uint32_t>(values.integer("packer.shape_library", 0))};
    const std::string grading = values.word("grading.kind", "uniform");
    Grading& g = o.grading;
    if (grading == "uniform") {
      g.kind = GradingKind::kUniform;
      g.radius_min = values.number("particle.radius_min", radius);
      g.radius_max = values.number("particle.radius_max", radius);
      if (g.radius_max < g.radius_min) {
        values.fail(
            values.has("particle.radius_max") ? "particle.radius_max" : "particle.radius_min",
            "invalid particle.radius_max = " + format_value(g.radius_max) +
                " (allowed: >= particle.radius_min = " + format_value(g.radius_min) + " m)");
      }
    } else if (grading == "fuller") {
      g.kind = GradingKind::kFuller;
      g.size_min = values.number("grading.size_min", 0.005);
      g.size_max = values.number("grading.size_max", 0.02);
      g.exponent = values.number("grading.exponent", 0.5);
      if (g.size_max <= g.size_min) {
        values.fail("grading.size_max",
                    "invalid grading.size_max = " + format_value(g.size_max) +
                        " (allowed: > grading.size_min = " + format_value(g.size_min) + " m)");
      }
    } else {
      g.kind = GradingKind::kSieve;
      g.sieve = values.sieve("grading.sieve");
    }
    const bool has_count = values.has("packer.target_count");
    const bool has_fraction = values.has("packer.target_fraction");
    if (has_count && has_fraction) {
      values.fail("packer.target_fraction",
                  "give either packer.target_count or packer.target_fraction, not both");
    }
    o.target = has_count ? PackTarget::kCount : PackTarget::kVolumeFraction;
    o.count = static_cast<std::uint64_t>(values.integer("packer.target_count", 1000));
    o.volume_fraction = values.number("packer.target_fraction", 0.35);
    o.gap = gap;
    o.max_attempts_per_particle =
        static_cast<std::uint64_t>(values.integer("packer.attempts", 5000));
    o.max_total_attempts =
        static_cast<std::uint64_t>(values.integer("packer.max_total_attempts", 200000000));
    o.max_consecutive_failures =
        static_cast<std::uint64_t>(values.integer("packer.max_consecutive_failures", 100));
    o.seed = seed;
  }

  for (const auto& [name, leaf] : values.leaves()) {
    if (name.rfind("output.", 0) == 0) {
      config.outputs[name.substr(7)] = leaf.node->as_string()->get();
      continue;
    }
    const Spec& spec = *find_spec(name);
    const bool is_relative_edge = config.packer == PackerKind::kRandom && edge_length == 0;
    if (!is_in_scope(spec.scope, config, is_relative_edge)) {
      // Ignored, but still checked: a typo or a wrong value is an error whatever the packer.
      switch (spec.type) {
        case Type::kFloat:
          (void)values.number(name, 0.0);
          break;
        case Type::kInteger:
          (void)values.integer(name, 0);
          break;
        case Type::kWord:
          (void)values.word(name, "");
          break;
        case Type::kSieve:
          (void)values.sieve(name);
          break;
        case Type::kPath:
          break;
      }
      config.warnings.push_back(leaf.origin + ": " + name + " is ignored (used only when " +
                                scope_text(spec.scope) + ")");
    }
  }

  if (config.packer == PackerKind::kLattice) {
    validate_with_config_names(config.lattice);
  } else {
    validate_with_config_names(config.random);
  }
  config.resolved_toml = resolved_text(config);
  return config;
}

PackConfig load_pack_config(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read config " + path + ": no such file or no permission");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError("cannot read config " + path);
  return parse_pack_config(text.str(), path, overrides);
}

}  // namespace aggpack
