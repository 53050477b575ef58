// The pack configuration: the schema's reader and writer (aggpack/config/schema.h) applied to
// pack_schema(), plus the rules that tie several keys together and the packers' own validation,
// whose messages name the config keys through the schema's field bindings.

#include "aggpack/config/config.h"

#include "aggpack/io/export.h"

namespace aggpack {

namespace {

// Rules between keys that no single key's range can state.
void check_cross_key_rules(const PackConfig& config, const GivenValues& given) {
  const auto value_of = [&](const char* key) {
    return std::get<double>(pack_schema().find(key)->binding.get(config));
  };
  if (const auto* lattice = find_options<LatticeOptions>(config.packer)) {
    if (lattice->edge_length == 0) {
      fail_key(given, "particle.edge_length", "particle.edge_length", "0",
               {Sentence::kEdgeLengthLattice, {}});
    }
    return;
  }
  const auto* random = find_options<RandomPackOptions>(config.packer);
  if (random == nullptr) return;
  const Grading& g = random->grading;
  if (g.kind == GradingKind::kUniform && g.radius_max < g.radius_min) {
    fail_key(given,
             given.count("particle.radius_max") > 0 ? "particle.radius_max" : "particle.radius_min",
             "particle.radius_max", format_value(value_of("particle.radius_max")),
             {Sentence::kAtLeastKeyMetres,
              {"particle.radius_min", format_value(value_of("particle.radius_min"))}});
  } else if (g.kind == GradingKind::kFuller && g.size_max <= g.size_min) {
    fail_key(given, "grading.size_max", "grading.size_max", format_value(g.size_max),
             {Sentence::kAboveKeyMetres, {"grading.size_min", format_value(g.size_min)}});
  } else if (g.kind == GradingKind::kSieve && given.count("grading.sieve") == 0) {
    throw ConfigError("grading.sieve", Wording{Sentence::kSieveNeeded, {}});
  }
}

}  // namespace

const std::vector<std::string>& output_formats() { return output_format_names(); }

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> keys = [] {
    std::vector<ConfigKey> list;
    const auto& schema = pack_schema();
    const auto views = key_views(schema);
    for (std::size_t i = 0; i < schema.keys.size(); ++i) {
      const auto& key = schema.keys[i];
      list.push_back(
          {key.name, type_name(key.type), key.unit,
           default_text(views[i], *key.default_value, key.default_from, key.default_text),
           allowed_text(views[i]), key.scope.text, key.doc});
    }
    return list;
  }();
  return keys;
}

std::uint64_t PackConfig::seed() const { return packer_seed(packer); }

const Container& PackConfig::container() const { return packer_container(packer); }

std::optional<Grading> PackConfig::target_grading() const { return packer_grading(packer); }

std::string PackConfig::packer_name() const { return packer_kind_name(packer); }

PackConfig resolve_pack_config(const GivenValues& given) {
  const auto& schema = pack_schema();
  PackConfig config;
  resolve(schema, given, config);
  check_cross_key_rules(config, given);
  config.warnings = scope_warnings(schema, given, config);
  with_key_names(key_views(schema), schema.aliases, [&] { validate(config.packer); });
  config.resolved_toml = "# aggpack " AGGPACK_VERSION
                         " resolved pack configuration: every key that has an effect, at its "
                         "value\n\n" +
                         write_values(schema, config, WriteStyle::kCanonical);
  return config;
}

PackConfig parse_pack_config(std::string_view text, std::string_view source_name,
                             const std::vector<std::string>& overrides) {
  const auto& schema = pack_schema();
  return resolve_pack_config(
      read_values(schema.tables, key_views(schema), text, source_name, overrides));
}

PackConfig load_pack_config(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_pack_config(read_config_file(path), path, overrides);
}

}  // namespace aggpack
