#pragma once
// Sub-command registration for the aggpack CLI. Each register_* adds one sub-command to the app
// and sets its callback; callbacks throw aggpack::Error on bad input.

#include <CLI/CLI.hpp>
#include <string>

#include "aggpack/mesh/quality.h"

namespace aggpack::cli {

void register_particle(CLI::App& app);
void register_shapes(CLI::App& app);
void register_calibrate(CLI::App& app);  // calibrate_commands.cpp
void register_pack(CLI::App& app);
void register_info(CLI::App& app);
void register_densify(CLI::App& app);    // densify_commands.cpp
void register_render(CLI::App& app);     // render_commands.cpp, when built with AGGPACK_HAS_RENDER
void register_export(CLI::App& app);     // export_commands.cpp
void register_mesomodel(CLI::App& app);  // mesomodel_commands.cpp
void register_config_keys(CLI::App& app);  // config_commands.cpp
void register_sim(CLI::App& app);     // sim_commands.cpp (settle, repose, sweep), AGGPACK_HAS_SIM
void register_settle(CLI::App& app);  // settle_commands.cpp, called by register_sim

/// "min dihedral angle 29.30 deg, max aspect ratio 2.69 (...), 0 of 38668 below 10 deg", the
/// tetrahedron quality of an export (export_commands.cpp).
std::string describe_quality(const TetQuality& quality);
/// The same as a JSON object: {"tetrahedra", "min_dihedral_deg", "max_aspect_ratio",
/// "below_10_deg"}.
std::string quality_json(const TetQuality& quality);

/// Limits the worker threads for the rest of the process (0 = all cores).
void set_thread_count(int threads);

}  // namespace aggpack::cli
