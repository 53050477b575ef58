#include "aggpack/sim/sweep.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/sim/distributed.h"

namespace aggpack {

void validate(const SweepOptions& options) {
  if (options.alphas.empty()) throw InvalidInput("sweep.alphas", "[]", "at least one value");
  if (options.frictions.empty()) {
    throw InvalidInput("sweep.frictions", "[]", "at least one value");
  }
  for (const double alpha : options.alphas) require_in_range("sweep.alphas", alpha, 0.0, 1.0);
  for (const double mu : options.frictions) require_in_range("sweep.frictions", mu, 0.0, 10.0);
  validate(options.base);
}

std::vector<SweepCase> summarize_sweep(const SweepOptions& options, std::vector<SweepCase> runs) {
  const std::size_t case_count = options.alphas.size() * options.frictions.size();
  const bool is_ensemble = !options.seeds.empty();
  const std::size_t seed_count = is_ensemble ? options.seeds.size() : 1;
  if (runs.size() != case_count * seed_count) {
    throw InvalidInput("sweep runs", std::to_string(runs.size()),
                       std::to_string(case_count * seed_count) + " (cases x seeds)");
  }
  if (!is_ensemble) return runs;
  // One row per case: means over the seeds' valid runs, in seed order.
  std::vector<SweepCase> cases(case_count);
  for (std::size_t c = 0; c < case_count; ++c) {
    SweepCase& row = cases[c];
    row = runs[c * seed_count];
    row.seed_count = seed_count;
    std::vector<double> angles;
    double r_squared = 0.0;
    double measured_alpha = 0.0;
    std::size_t bins = 0;
    row.is_at_rest = true;
    row.simulated_time = 0.0;
    row.wall_seconds = 0.0;
    for (std::size_t k = 0; k < seed_count; ++k) {
      const SweepCase& run = runs[c * seed_count + k];
      row.is_at_rest = row.is_at_rest && run.is_at_rest;
      row.simulated_time += run.simulated_time;
      row.wall_seconds += run.wall_seconds;
      measured_alpha += run.mean_measured_alpha;
      if (!run.is_valid) continue;
      angles.push_back(run.angle_degrees);
      r_squared += run.r_squared;
      bins += run.fit_bins;
    }
    row.statistics = ensemble_statistics(angles);
    row.seeds_used = angles.size();
    row.is_valid = !angles.empty();
    row.angle_degrees = row.statistics.mean;
    const double used = std::max<double>(1.0, static_cast<double>(angles.size()));
    row.r_squared = r_squared / used;
    row.fit_bins = static_cast<std::size_t>(static_cast<double>(bins) / used + 0.5);
    row.mean_measured_alpha = measured_alpha / static_cast<double>(seed_count);
  }
  return cases;
}

void write_sweep_csv(const std::string& path, const std::vector<SweepCase>& cases) {
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  auto& out = file.stream();
  const bool is_ensemble = !cases.empty() && cases.front().seed_count > 1;
  out << "alpha,friction,angle_deg,r_squared,fit_bins,valid,at_rest,particles,"
         "measured_alpha,simulated_s"
      << (is_ensemble ? ",seeds,seeds_used,std_dev_deg,ci95_lower_deg,ci95_upper_deg" : "") << '\n';
  char line[512];
  for (const auto& c : cases) {
    std::snprintf(line, sizeof line, "%.6g,%.6g,%.6f,%.6f,%zu,%d,%d,%zu,%.6f,%.4f", c.alpha,
                  c.friction, c.angle_degrees, c.r_squared, c.fit_bins, c.is_valid ? 1 : 0,
                  c.is_at_rest ? 1 : 0, c.particle_count, c.mean_measured_alpha, c.simulated_time);
    out << line;
    if (is_ensemble) {
      const EnsembleStatistics& st = c.statistics;
      // Without an interval (fewer than 2 angles) the band is the mean itself.
      std::snprintf(line, sizeof line, ",%zu,%zu,%.6f,%.6f,%.6f", c.seed_count, c.seeds_used,
                    st.std_dev, st.lower(), st.upper());
      out << line;
    }
    out << '\n';
  }
  file.commit();
}

}  // namespace aggpack
