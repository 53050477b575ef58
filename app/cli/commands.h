#pragma once
// Sub-command registration for the aggpack CLI. Each register_* adds one sub-command to the app
// and sets its callback; callbacks throw aggpack::Error on bad input.

#include <CLI/CLI.hpp>
#include <string>

#include "aggpack/mesh/mesomodel.h"
#include "aggpack/mesh/quality.h"

namespace aggpack::cli {

// Unsigned options: CLI11 would wrap "-1" to 2^64-1, so negative text is rejected first (CLI11's
// NonNegativeNumber would print DBL_MAX as the range).
inline const CLI::Validator kNotNegative(
    [](std::string& text) {
      const auto first = text.find_first_not_of(" \t");
      if (first != std::string::npos && text[first] == '-') return "must be >= 0, got " + text;
      return std::string();
    },
    "");

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

/// `aggpack render --mesomodel-cut`: what to mesh and cut, and where to write the picture.
struct MesomodelCutRequest {
  std::string input;      ///< native packing (.h5)
  std::string output;     ///< PNG ("" = the input's name with .png)
  std::string plane;      ///< "z=0.05" (parse_cut_plane)
  MesoOptions meso;       ///< build_mesomodel options
  int width = 1600;       ///< pixels, >= 200
  std::string size_text;  ///< the --size text, for the error message
  bool is_tinted = true;
  bool is_forced = false;
};
/// Meshes the packing (build_mesomodel), cuts it and writes the PNG (mesomodel_cut_render.cpp,
/// software drawing: no OpenGL). \throw InvalidInput naming the flag, as build_mesomodel.
void render_mesomodel_cut(const MesomodelCutRequest& request);

/// Limits the worker threads for the rest of the process (0 = all cores).
void set_thread_count(int threads);

}  // namespace aggpack::cli
