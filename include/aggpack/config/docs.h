#pragma once
// The key tables of docs/config.md, generated from the schemas (pack_schema(), sweep_schema()).
// Regenerate the file with `aggpack config-keys --update-doc docs/config.md`; the test
// ConfigDocs.TablesMatchTheSchema fails while the file and the schemas differ.

#include <string>
#include <string_view>
#include <vector>

namespace aggpack {

/// The names of the tables that have generated docs: the pack tables, then (with the simulation
/// module) the repose / sweep tables.
std::vector<std::string> documented_tables();

/// The markdown table of one schema table: a pack table ("container", ...) or "repose.TABLE" for
/// the repose/sweep configuration's ("repose.trough", "repose.particle", ...).
/// \throw InvalidInput for a table no schema has.
std::string config_keys_markdown(const std::string& table);

/// `doc` with every block between a line "<!-- generated: aggpack config-keys --markdown TABLE
/// -->" and the next line "<!-- end generated -->" replaced by config_keys_markdown(TABLE).
/// Blocks of tables this build has no schema for (repose without the simulation module) are
/// left as they are. \throw FormatError for a block without its end line.
std::string regenerate_config_doc(std::string_view doc);

}  // namespace aggpack
