#pragma once
// A study run in parts: each worker (`--case K --of N`, an mpirun rank, Python's share=(K, N): a
// RunShare) runs its share of an ensemble's seeds or a sweep's runs and leaves one run record per
// finished run in DIR/runs/ (RunRecorder); merge_runs() turns the records into the ensemble or
// the sweep table the single-process run gives. Library calls that the CLI (`aggpack repose
// --seeds`, `sweep`, `merge`) and the Python module (repose/sweep with records=, merge) share;
// the summary files and each run's own files stay with the caller. Built with the simulation
// module (AGGPACK_HAS_SIM).

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/sweep.h"

namespace aggpack::study {

/// Writes the run records of one worker's share of a plan into FOLDER/runs/.
class RunRecorder {
 public:
  /// The plan: `options` (its seeds: an ensemble's seed list, or each sweep case's) resolved, so
  /// that records of another configuration are told apart by hash. Refuses (InvalidInput naming
  /// `field`, e.g. "-o out") a folder whose runs/ holds records of another plan or kind, and
  /// creates FOLDER/runs/. `image_width`: what merge draws ensemble.png with (0: its default).
  /// \throw InvalidInput, FormatError (a record it cannot read), IoError.
  RunRecorder(RunKind kind, const SweepOptions& options, std::string folder, int image_width,
              const std::string& field);

  /// The record of a finished ensemble seed / sweep run (the run's place in the plan from its
  /// seed, case index and seed). Atomic. \throw IoError.
  void record(const EnsembleSeed& seed) const;
  void record(const SweepCase& run) const;

  /// A sweep run's file stem, "alpha0.50_mu0.30" (+ "_seed7" with seeds): its record's name,
  /// and the CLI's cases/ files.
  [[nodiscard]] std::string stem(const SweepCase& run) const;
  [[nodiscard]] const RunRecord& plan() const { return plan_; }

 private:
  RunRecord plan_;
  std::string folder_;
  std::map<std::uint64_t, std::size_t> seed_index_;  // seed -> place in the seed list
  bool is_ensemble_sweep_ = false;                   // a sweep with seeds
};

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
