#include "aggpack/sim/sweep.h"

#include <cstdio>
#include <mutex>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

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

std::vector<SweepCase> run_sweep(const SweepOptions& options, const ReposeFill& fill,
                                 const SweepCaseCallback& on_case) {
  validate(options);
  if (!fill) throw InvalidInput("sweep fill", "none", "a function making each case's fill");
  const std::size_t total = options.alphas.size() * options.frictions.size();
  std::vector<SweepCase> cases(total);
  std::mutex mutex;
  std::size_t done = 0;
  auto run_case = [&](std::size_t index) {
    const double alpha = options.alphas[index / options.frictions.size()];
    const double friction = options.frictions[index % options.frictions.size()];
    ReposeOptions repose = options.base;
    repose.alpha = alpha;
    repose.physics.friction = friction;
    if (options.is_wall_friction_coupled) repose.physics.wall_friction = friction;
    const ReposeResult result = run_repose(repose, fill(repose));
    SweepCase& summary = cases[index];
    summary.index = index;
    summary.alpha = alpha;
    summary.friction = friction;
    summary.mean_measured_alpha = result.mean_measured_alpha;
    summary.particle_count = result.particle_count;
    summary.is_valid = result.fit.is_valid;
    summary.angle_degrees = result.fit.angle_degrees;
    summary.r_squared = result.fit.r_squared;
    summary.fit_bins = result.fit.bin_count;
    summary.is_at_rest = result.is_stage1_at_rest && result.is_stage2_at_rest;
    summary.simulated_time = result.stage1_time + result.stage2_time;
    summary.wall_seconds = result.stage1_seconds + result.stage2_seconds;
    const std::lock_guard lock(mutex);
    ++done;
    if (on_case) on_case(summary, result, done, total);
  };
  // Cases take about the same time, and each is single-threaded inside (Bullet's world), so the
  // cores are used by running cases side by side.
  parallel_for_index(0, total, run_case);
  return cases;
}

void write_sweep_csv(const std::string& path, const std::vector<SweepCase>& cases) {
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  auto& out = file.stream();
  out << "alpha,friction,angle_deg,r_squared,fit_bins,valid,at_rest,particles,"
         "measured_alpha,simulated_s\n";
  char line[512];
  for (const auto& c : cases) {
    std::snprintf(line, sizeof line, "%.6g,%.6g,%.6f,%.6f,%zu,%d,%d,%zu,%.6f,%.4f\n", c.alpha,
                  c.friction, c.angle_degrees, c.r_squared, c.fit_bins, c.is_valid ? 1 : 0,
                  c.is_at_rest ? 1 : 0, c.particle_count, c.mean_measured_alpha, c.simulated_time);
    out << line;
  }
  file.commit();
}

}  // namespace aggpack
