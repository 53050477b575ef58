#pragma once
// Seed ensembles of the repose test (issue 15 item 2): the same case run once per master seed
// (particle.seed: the fill's shapes and turns), each angle reported, and their mean, sample
// standard deviation and the 95 % confidence interval of the mean (Student t, n - 1 degrees of
// freedom): seed lists, statistics and the ensemble's files. The runs are the study layer's
// (aggpack/study/repose_study.h: seeds side by side, one per worker, each single-threaded, so the
// ensemble does not depend on the thread count).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "aggpack/sim/repose.h"

namespace aggpack {

/// Most seeds one ensemble may hold.
inline constexpr std::size_t kMaxEnsembleSeeds = 10000;

/// Parses "1-16", "1,4,9" or a mix ("1-4,9"): seeds in the given order, no duplicates.
/// \throw InvalidInput naming `field` (the CLI passes "--seeds") for empty, non-numeric, reversed
/// or duplicate values and for more than kMaxEnsembleSeeds seeds.
std::vector<std::uint64_t> parse_seed_list(const std::string& text,
                                           const std::string& field = "--seeds");

/// The p-quantile of Student's t distribution with `dof` degrees of freedom (p in (0, 1),
/// dof >= 1), by bisection on the exact CDF (regularized incomplete beta); |error| < 1e-10.
/// \throw InvalidInput outside those ranges.
double student_t_quantile(double p, double dof);

/// Mean, sample standard deviation and 95 % confidence interval of the mean of some values.
struct EnsembleStatistics {
  std::size_t count = 0;      ///< values used
  double mean = 0.0;          ///< 0 when count = 0
  double std_dev = 0.0;       ///< sample (n - 1); 0 when count < 2
  double t_quantile = 0.0;    ///< t_0.975(count - 1); 0 when count < 2
  double half_width = 0.0;    ///< t * std_dev / sqrt(count); 0 when count < 2
  bool has_interval = false;  ///< count >= 2
  [[nodiscard]] double lower() const { return mean - half_width; }
  [[nodiscard]] double upper() const { return mean + half_width; }
};

/// Statistics of `values` (the 95 % interval; `confidence` in (0, 1) for another level).
EnsembleStatistics ensemble_statistics(const std::vector<double>& values, double confidence = 0.95);

/// One seed's run.
struct EnsembleSeed {
  std::uint64_t seed = 0;
  bool is_valid = false;  ///< the run finished and its slope fit succeeded (used in statistics)
  std::string error;      ///< why not valid (the run's error or the fit's message), else empty
  double angle_degrees = 0.0;
  double r_squared = 0.0;
  std::size_t particle_count = 0;
  bool is_at_rest = false;  ///< both stages reached rest
};

/// The whole ensemble: seeds in the order given, and statistics over the valid ones.
struct EnsembleResult {
  std::vector<EnsembleSeed> seeds;
  EnsembleStatistics statistics;
  bool is_cancelled = false;  ///< the run was cancelled: seeds that did not run are left out
  [[nodiscard]] std::size_t failed_count() const { return seeds.size() - statistics.count; }
};

/// Called once per finished seed with its full result (nullptr when the run threw), in
/// completion order, from a worker thread but never two at a time (aggpack/study/
/// repose_study.h's run_repose_ensemble runs the seeds). Must not throw.
using EnsembleSeedCallback = std::function<void(
    const EnsembleSeed& summary, const ReposeResult* result, std::size_t done, std::size_t total)>;

/// The ensemble of finished seeds (in plan order): the statistics over the valid ones.
EnsembleResult summarize_ensemble(std::vector<EnsembleSeed> seeds);

/// JSON: options of the base case, seeds (angle, valid, error...), statistics. \throw IoError.
void write_ensemble_json(const std::string& path, const ReposeOptions& base,
                         const EnsembleResult& ensemble);
/// CSV: one row per seed (seed,angle_deg,r_squared,valid,at_rest,particles,error) then the rows
/// "mean", "std_dev", "ci95_lower", "ci95_upper" in the seed column's place. \throw IoError.
void write_ensemble_csv(const std::string& path, const EnsembleResult& ensemble);
/// PNG: angle per seed (one point each, failed seeds marked on the axis), the mean as a line and
/// the 95 % interval as a band. `width` in pixels, [64, 16384]. \throw InvalidInput, IoError.
void write_ensemble_png(const std::string& path, const EnsembleResult& ensemble, int width = 1000);

}  // namespace aggpack
