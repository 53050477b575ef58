#pragma once
// Merging a study run in parts: the run records that workers (`--case K --of N`, mpirun ranks,
// RunShare) left in DIR/runs/ become the ensemble or the sweep table the single-process run gives.
// A library call that `aggpack merge` and the Python module's aggpack.merge() share; writing the
// summary files stays with the caller. Built with the simulation module (AGGPACK_HAS_SIM).

#include <string>
#include <vector>

#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/sweep.h"

namespace aggpack::study {

/// The merged study.
struct MergedRuns {
  RunKind kind = RunKind::kEnsemble;
  SweepOptions plan;             ///< the configuration the workers ran (its seeds, alphas, ...)
  EnsembleResult ensemble;       ///< kind kEnsemble: every seed, summarize_ensemble's statistics
  std::vector<SweepCase> cases;  ///< kind kSweep: the table (summarize_sweep), one row per case
  int image_width = 0;           ///< the workers' --width when in [64, 16384], else 0
  std::size_t run_count = 0;     ///< runs in the plan (all of them present)
};

/// Reads DIR/runs/ (read_run_folder), parses the plan's configuration and merges the runs.
/// \throw InvalidInput naming "merge DIR" when runs are missing (which ones, and which worker
///        owns them), or the records are of different plans; FormatError for a file that is not
///        a record; ConfigError-style InvalidInput for a record whose configuration is not valid.
MergedRuns merge_runs(const std::string& folder);

}  // namespace aggpack::study
