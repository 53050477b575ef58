#include "config_fields.h"

#include <algorithm>

namespace aggpack::gui {

namespace {

// The sieve table offered when the grading is switched to sieve: the middle of the ASTM C33 size
// No. 67 band (coarse concrete aggregate, 4.75-25 mm; 2.36 mm row left out) scaled by 8, so the
// top size 0.2 m is 1/5 of the default box's narrowest side (ACI 318's limit for the largest
// aggregate) and equals the lattice default 2 R.
const std::vector<SieveRow> kDefaultSieve = {{.size = 0.038, .percent_passing = 5.0},
                                             {.size = 0.076, .percent_passing = 37.5},
                                             {.size = 0.152, .percent_passing = 95.0},
                                             {.size = 0.2, .percent_passing = 100.0}};

}  // namespace

bool ConfigFields::is_editable(const Key<PackConfig>& key) {
  return key.type != ValueType::kPath && key.written.text != "never";
}

ConfigFields ConfigFields::from_config(const PackConfig& config) {
  ConfigFields fields;
  for (const auto& key : pack_schema().keys) {
    if (!is_editable(key)) continue;
    fields.values_[key.name] = key.binding.get(config);
    const auto& written = key.written.text.empty() ? key.scope : key.written;
    if (key.presence == Presence::kOptional && written(config)) fields.on_.insert(key.name);
  }
  auto& sieve = std::get<std::vector<SieveRow>>(fields.values_.at("grading.sieve"));
  if (sieve.empty()) sieve = kDefaultSieve;
  return fields;
}

void ConfigFields::set_on(const std::string& key, bool is_on) {
  if (is_on) {
    on_.insert(key);
  } else {
    on_.erase(key);
  }
}

GivenValues ConfigFields::given() const {
  const auto& schema = pack_schema();
  GivenValues all;
  for (const auto& key : schema.keys) {
    if (!is_editable(key)) continue;
    // An optional key only when switched on (a sieve table is always there to give).
    if (key.presence == Presence::kOptional && key.type != ValueType::kSieve && !is_on(key.name)) {
      continue;
    }
    // A key whose default is another key's value only when it differs from it.
    if (!key.default_from.empty() && values_.at(key.name) == values_.at(key.default_from)) {
      continue;
    }
    all[key.name] = {.value = values_.at(key.name), .origin = "gui", .order = 0};
  }
  for (const auto& key : schema.keys) {
    if (!key.excludes.empty() && all.count(key.name) > 0) all.erase(key.excludes);
  }
  PackConfig config;
  resolve(schema, all, config);
  GivenValues applied;
  for (auto& [name, value] : all) {
    if (schema.find(name)->scope(config)) applied.emplace(name, std::move(value));
  }
  return applied;
}

PackConfig ConfigFields::draft() const {
  PackConfig config;
  resolve(pack_schema(), given(), config);
  return config;
}

PackConfig ConfigFields::build() const { return resolve_pack_config(given()); }

std::vector<std::string> ConfigFields::set_entries() const {
  std::vector<std::string> entries;
  for (const auto& [name, given] : given()) {
    std::string text =
        value_text(given.value, pack_schema().find(name)->type, WriteStyle::kCanonical);
    text.erase(std::remove(text.begin(), text.end(), ' '), text.end());
    entries.push_back(name + "=" + text);
  }
  return entries;
}

}  // namespace aggpack::gui
