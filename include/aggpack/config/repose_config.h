#pragma once
// The repose and sweep configuration (`aggpack repose|sweep [CONFIG.toml] [--set key=value]`):
// tables [trough] [particle] [physics] [rest] [measure] [sweep], every key declared once in
// sweep_schema() (src/config/repose_config.cpp) and read, written and reported through the same
// schema machinery as the pack configuration. Needs the simulation module (AGGPACK_HAS_SIM).

#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/sim/sweep.h"

namespace aggpack {

/// Every repose and sweep key, bound to SweepOptions (repose keys to SweepOptions::base).
const Schema<SweepOptions>& sweep_schema();

/// Parses TOML text and `--set` overrides into sweep options (unset keys at SweepOptions{}'s
/// defaults). The table [particle] was [particles] before and is still read under that name;
/// `notes` (when given) then gets one line saying so, for the caller to show.
/// \throw FormatError, ConfigError naming the key as typed.
SweepOptions parse_sweep_config(std::string_view text, std::string_view source_name = "config",
                                const std::vector<std::string>& overrides = {},
                                std::vector<std::string>* notes = nullptr);

/// Reads `path` (empty = no file: the defaults) and calls parse_sweep_config. \throw IoError.
SweepOptions load_sweep_config(const std::string& path,
                               const std::vector<std::string>& overrides = {},
                               std::vector<std::string>* notes = nullptr);

/// Every key at its value, "key = value  # doc (unit)", one [table] per group.
std::string resolved_sweep_config(const SweepOptions& options);

/// Runs `check` (a validate() or run of the sim module); an error about an options field is
/// rethrown naming the config key ("repose.baffle_speed" -> "trough.baffle_speed").
void with_sweep_key_names(const std::function<void()>& check);

/// The docs/config.md table of one repose/sweep table ("trough", "physics", ...).
std::string sweep_keys_markdown(const std::string& table);

}  // namespace aggpack
