#pragma once
// The paper's sweep of the repose test over shape (alpha) and sliding friction (mu_s): by default
// alpha in {1.0, 0.9, 0.8, 0.7, 0.6} x mu_s in {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6,
// 0.7, 0.8, 0.9, 1.0} = 65 cases: the options, the table and its CSV. The runs are the study
// layer's (aggpack/study/repose_study.h: cases in parallel, each deterministic, so the table does
// not depend on the thread count).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"

namespace aggpack {

struct SweepOptions {
  ReposeOptions base;  ///< every case starts from this; alpha and physics.friction are replaced
  std::vector<double> alphas = {1.0, 0.9, 0.8, 0.7, 0.6};  ///< each in [0, 1], non-empty
  std::vector<double> frictions = {0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4,
                                   0.5,  0.6, 0.7,  0.8, 0.9,  1.0};  ///< each in [0, 10]
  /// Walls take each case's mu_s too (the paper's setting); false keeps base.physics.wall_friction.
  bool is_wall_friction_coupled = true;
  /// Empty: one run per case at base.seed. Else a seed ensemble per case (`sweep --seeds`): each
  /// case's angle is the mean over these seeds' valid runs, with sd and 95 % interval.
  std::vector<std::uint64_t> seeds;
};

/// Throws InvalidInput naming the field unless usable.
void validate(const SweepOptions& options);

/// One case of a sweep.
struct SweepCase {
  std::size_t index = 0;             ///< row-major: alpha index * frictions + friction index
  double alpha = 0.0;                ///< Eq. 3 input alpha
  double friction = 0.0;             ///< mu_s
  double mean_measured_alpha = 0.0;  ///< Eq. 2 alpha of the particles
  std::size_t particle_count = 0;
  bool is_valid = false;  ///< the slope fit succeeded
  double angle_degrees = 0.0;
  double r_squared = 0.0;
  std::size_t fit_bins = 0;
  bool is_at_rest = false;      ///< both stages reached rest
  double simulated_time = 0.0;  ///< s, both stages
  double wall_seconds = 0.0;    ///< wall-clock s (not reproducible)
  std::uint64_t seed = 0;       ///< the run's seed (per-run summaries; the first seed for a case)
  /// Seed ensembles (options.seeds): runs of the case, runs with an angle (angle_degrees and
  /// r_squared are then their means), and the angles' statistics.
  std::size_t seed_count = 1;
  std::size_t seeds_used = 0;
  EnsembleStatistics statistics;
};

/// Called once per finished run (case, or case and seed for ensembles; the study layer's
/// run_sweep runs them), in completion order, from a worker thread but never two at a time.
/// `result` holds the full run (packings, profile) for per-case output. Must not throw.
using SweepCaseCallback = std::function<void(const SweepCase& summary, const ReposeResult& result,
                                             std::size_t done, std::size_t total)>;

/// The sweep's table from all its runs in plan order (what study::run_sweep returns): without
/// seeds the runs themselves, else one row per case with the seeds' means and statistics.
/// \throw InvalidInput when `runs` is not the plan's size.
std::vector<SweepCase> summarize_sweep(const SweepOptions& options, std::vector<SweepCase> runs);

/// Writes the table as CSV (one row per case, columns named in the header; no wall-clock times,
/// so the same sweep always gives the same bytes). \throw IoError.
void write_sweep_csv(const std::string& path, const std::vector<SweepCase>& cases);

}  // namespace aggpack
