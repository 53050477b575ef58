// `aggpack config-keys`: every configuration key from the schemas (pack, repose, sweep), as a
// list, as the markdown tables of docs/config.md, or rewriting those tables in place.

#include <fmt/core.h>

#include <map>
#include <memory>
#include <string>

#include "aggpack/config/config.h"
#include "aggpack/config/docs.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "commands.h"
#include "output_flags.h"

namespace aggpack::cli {

namespace {

struct ConfigKeysFlags {
  std::string markdown_table;
  bool has_markdown = false;
  std::string update_doc;
  bool has_update_doc = false;  // given, even as "" (refused, not ignored)
};

void run_config_keys(const ConfigKeysFlags& flags) {
  if (flags.has_update_doc) {
    const std::string before = read_config_file(flags.update_doc);
    const std::string after = regenerate_config_doc(before);
    if (after == before) {
      fmt::print("{} is up to date\n", flags.update_doc);
      return;
    }
    AtomicFile file(flags.update_doc, Overwrite::kAllow, std::ios::out | std::ios::binary);
    file.stream() << after;
    file.commit();
    fmt::print("updated the key tables of {}\n", flags.update_doc);
    return;
  }
  if (flags.has_markdown) {
    // The table as typed: --markdown names it ('' is a table name too, and none).
    static const std::map<std::string, std::string> flag_names = {{"table", "--markdown"}};
    // An empty name is refused as "" (as every empty value is shown).
    const std::string table = flags.markdown_table.empty() ? "\"\"" : flags.markdown_table;
    std::string text;
    with_key_names({}, flag_names, [&] { text = config_keys_markdown(table); });
    fmt::print("{}", text);
    return;
  }
  for (const auto& key : config_keys()) {
    fmt::print("{}  {}{}  default {}  allowed {}  used when {}\n", key.name, key.type,
               key.unit.empty() ? "" : " (" + key.unit + ")", key.default_value, key.allowed,
               key.used_when);
  }
}

}  // namespace

void register_config_keys(CLI::App& app) {
  auto flags = std::make_shared<ConfigKeysFlags>();
  auto* command = app.add_subcommand(
      "config-keys",
      "List every pack configuration key (type, unit, default, range, when it applies), print "
      "the markdown table of one table, or regenerate the tables of docs/config.md.");
  command->add_option("--markdown", flags->markdown_table,
                      "print the docs table of TABLE: a pack table (container, particle, grading, "
                      "packer, densify, output) or repose.TABLE for the repose and sweep "
                      "configuration's (repose.trough, repose.particle, repose.physics, ...)");
  command->add_option("--update-doc", flags->update_doc,
                      "rewrite the generated tables of this file (docs/config.md)");
  command->callback([flags, command]() {
    flags->has_update_doc = command->count("--update-doc") > 0;
    flags->has_markdown = command->count("--markdown") > 0;
    if (flags->has_update_doc) check_output_file_flag("--update-doc", flags->update_doc);
    run_config_keys(*flags);
  });
}

}  // namespace aggpack::cli
