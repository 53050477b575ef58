// docs/config.md's key tables from the schemas.

#include "aggpack/config/docs.h"

#include <algorithm>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#ifdef AGGPACK_HAS_SIM
#include "aggpack/config/repose_config.h"
#endif

namespace aggpack {

namespace {

template <typename Target>
std::vector<std::string> table_names(const Schema<Target>& schema) {
  std::vector<std::string> names;
  for (const auto& table : schema.tables) names.push_back(table.name);
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

constexpr std::string_view kBegin = "<!-- generated: aggpack config-keys --markdown ";
constexpr std::string_view kEnd = "<!-- end generated -->";
// The repose/sweep configuration's tables are named "repose.TABLE" here: both configurations
// have a [particle] table.
const std::string kReposePrefix = "repose.";

}  // namespace

std::vector<std::string> documented_tables() {
  std::vector<std::string> names = table_names(pack_schema());
#ifdef AGGPACK_HAS_SIM
  for (const auto& name : table_names(sweep_schema())) names.push_back(kReposePrefix + name);
#endif
  return names;
}

std::string config_keys_markdown(const std::string& table) {
  if (contains(table_names(pack_schema()), table)) return pack_keys_markdown(table);
#ifdef AGGPACK_HAS_SIM
  if (table.rfind(kReposePrefix, 0) == 0 &&
      contains(table_names(sweep_schema()), table.substr(kReposePrefix.size()))) {
    return sweep_keys_markdown(table.substr(kReposePrefix.size()));
  }
#endif
  std::string allowed;
  for (const auto& name : documented_tables()) allowed += (allowed.empty() ? "" : ", ") + name;
  throw InvalidInput("table", table, allowed);
}

std::string regenerate_config_doc(std::string_view doc) {
  const std::vector<std::string> known = documented_tables();
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t begin = doc.find(kBegin, at);
    if (begin == std::string_view::npos) break;
    const std::size_t line_end = doc.find('\n', begin);
    const std::size_t end = doc.find(kEnd, begin);
    if (line_end == std::string_view::npos || end == std::string_view::npos || end < line_end) {
      throw FormatError("generated table at byte " + std::to_string(begin) + " has no line \"" +
                        std::string(kEnd) + "\"");
    }
    std::string_view name = doc.substr(begin + kBegin.size(), line_end - begin - kBegin.size());
    name = name.substr(0, name.find(" -->"));
    out += doc.substr(at, line_end + 1 - at);
    if (contains(known, std::string(name))) {
      out += config_keys_markdown(std::string(name));
    } else {
      out += doc.substr(line_end + 1, end - line_end - 1);
    }
    at = end;
  }
  out += doc.substr(at);
  return out;
}

}  // namespace aggpack
