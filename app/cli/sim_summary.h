#pragma once
// The summaries of `repose --seeds` and `sweep` (ensemble.json|csv|png, sweep.csv|gp|png and the
// printed tables), written by the single-process run and by `aggpack merge` from run records
// (merge_command.cpp). Built only with AGGPACK_HAS_SIM.

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/sweep.h"

namespace aggpack::cli {

/// Creates `folder` if needed; each of `names` in it must not exist unless `is_forced`.
/// \throw IoError.
std::string prepare_folder(const std::string& folder, bool is_forced,
                           const std::vector<std::string>& names);

/// folder / name.
std::string in_folder(const std::string& folder, const std::string& name);

/// Writes ensemble.json, ensemble.csv, ensemble.png (`width` capped at 1600) and prints the
/// per-seed table and the statistics. \throw LimitExceeded when no seed has an angle.
void write_ensemble_summary(const std::string& folder, const ReposeOptions& base,
                            const EnsembleResult& ensemble, int width);

/// Writes sweep.csv and sweep.gp, runs gnuplot for sweep.png unless `is_without_plot`, and
/// prints the table.
void write_sweep_summary(const std::string& folder, const SweepOptions& options,
                         const std::vector<SweepCase>& cases, bool is_without_plot);

/// `aggpack merge FOLDER`: checks the run records of FOLDER/runs/ and writes the summary into
/// `output` (empty: FOLDER); `width` of ensemble.png, 0 = the workers' --width.
/// \throw InvalidInput naming missing runs or records of another plan.
void merge_run_folder(const std::string& folder, const std::string& output, int width,
                      bool is_without_plot, bool is_forced);

/// `aggpack merge` (merge_command.cpp), registered by register_sim.
void register_merge(CLI::App& app);

}  // namespace aggpack::cli
