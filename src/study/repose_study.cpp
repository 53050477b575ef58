// The repose test's runs as studies: one run, a seed ensemble, a sweep (moved here from the
// simulation module, which now only simulates the fill and trough it is given).

#include "aggpack/study/repose_study.h"

#include <cstddef>
#include <mutex>
#include <string>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

namespace aggpack::study {

namespace {

// The fill a study runs on: the caller's, else the pipeline's lattice fill.
ReposeFill fill_or_default(const ReposeFill& fill) {
  if (fill) return fill;
  return [](const ReposeOptions& options) { return repose_fill(options); };
}

// The checks before a study starts: the simulation's, and the lattice fill's unless the caller
// makes the fill.
void check_before_start(const ReposeOptions& options, const ReposeFill& fill) {
  if (fill) {
    validate(options);
  } else {
    check_repose_inputs(options);
  }
}

}  // namespace

ReposeResult run_repose(const ReposeOptions& options, const ReposeControl& control) {
  check_before_start(options, control.fill);
  const ReposeFill fill = fill_or_default(control.fill);
  if (options.engine == ReposeEngine::kYade) {
    return run_repose_yade(options, fill(options), write_repose_yade_script, control.on_yade);
  }
  return aggpack::run_repose(options, fill(options), control.on_progress);
}

EnsembleResult run_repose_ensemble(const ReposeOptions& base,
                                   const std::vector<std::uint64_t>& seeds,
                                   const StudyControl& control) {
  if (seeds.empty()) throw InvalidInput("--seeds", "[]", "at least one seed");
  if (seeds.size() > kMaxEnsembleSeeds) {
    throw InvalidInput("--seeds", std::to_string(seeds.size()) + " seeds",
                       "at most " + std::to_string(kMaxEnsembleSeeds));
  }
  check_before_start(base, control.fill);
  const ReposeFill fill = fill_or_default(control.fill);
  std::vector<std::uint64_t> owned;
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (control.share == nullptr || control.share->owns(i)) owned.push_back(seeds[i]);
  }
  std::vector<EnsembleSeed> runs(owned.size());
  std::vector<char> has_run(owned.size(), 0);
  std::mutex mutex;
  std::size_t done = 0;
  // One seed per worker, each single-threaded inside (Bullet's world), as the sweep's cases:
  // each slot depends only on its seed, so the ensemble is the same at any thread count.
  parallel_for_index(0, owned.size(), [&](std::size_t index) {
    if (control.is_cancelled()) return;
    EnsembleSeed& summary = runs[index];
    summary.seed = owned[index];
    ReposeOptions options = base;
    options.seed = owned[index];
    ReposeResult result;
    bool has_result = false;
    try {
      result = run_repose_engine(options, fill(options), write_repose_yade_script);
      has_result = true;
      summary.particle_count = result.particle_count;
      summary.is_at_rest = result.is_stage1_at_rest && result.is_stage2_at_rest;
      summary.angle_degrees = result.fit.angle_degrees;
      summary.r_squared = result.fit.r_squared;
      summary.is_valid = result.fit.is_valid;
      if (!result.fit.is_valid) summary.error = "no slope fit: " + result.fit.message;
    } catch (const Error& error) {
      summary.error = error.what();
    }
    has_run[index] = 1;
    const std::lock_guard lock(mutex);
    ++done;
    if (control.on_seed) {
      control.on_seed(summary, has_result ? &result : nullptr, done, owned.size());
    }
  });
  std::vector<EnsembleSeed> finished;
  finished.reserve(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (has_run[i] != 0) finished.push_back(std::move(runs[i]));
  }
  const bool is_cancelled = finished.size() < runs.size();
  EnsembleResult ensemble = summarize_ensemble(std::move(finished));
  ensemble.is_cancelled = is_cancelled;
  return ensemble;
}

SweepRuns run_sweep_runs(const SweepOptions& options, const StudyControl& control) {
  validate(options);
  check_before_start(options.base, control.fill);
  if (options.seeds.size() > kMaxEnsembleSeeds) {
    throw InvalidInput("--seeds", std::to_string(options.seeds.size()) + " seeds",
                       "at most " + std::to_string(kMaxEnsembleSeeds));
  }
  const ReposeFill fill = fill_or_default(control.fill);
  const std::size_t case_count = options.alphas.size() * options.frictions.size();
  const bool is_ensemble = !options.seeds.empty();
  const std::size_t seed_count = is_ensemble ? options.seeds.size() : 1;
  std::vector<std::size_t> owned;
  for (std::size_t i = 0; i < case_count * seed_count; ++i) {
    if (control.share == nullptr || control.share->owns(i)) owned.push_back(i);
  }
  const std::size_t total = owned.size();
  std::vector<SweepCase> runs(total);
  std::vector<char> has_run(total, 0);
  std::mutex mutex;
  std::size_t done = 0;
  auto run_case = [&](std::size_t slot) {
    if (control.is_cancelled()) return;
    const std::size_t index = owned[slot];
    const std::size_t case_index = index / seed_count;
    const double alpha = options.alphas[case_index / options.frictions.size()];
    const double friction = options.frictions[case_index % options.frictions.size()];
    ReposeOptions repose = options.base;
    repose.alpha = alpha;
    repose.physics.friction = friction;
    if (options.is_wall_friction_coupled) repose.physics.wall_friction = friction;
    if (is_ensemble) repose.seed = options.seeds[index % seed_count];
    const ReposeResult result = run_repose_engine(repose, fill(repose), write_repose_yade_script);
    SweepCase& summary = runs[slot];
    summary.index = case_index;
    summary.alpha = alpha;
    summary.friction = friction;
    summary.seed = repose.seed;
    summary.mean_measured_alpha = result.mean_measured_alpha;
    summary.particle_count = result.particle_count;
    summary.is_valid = result.fit.is_valid;
    summary.angle_degrees = result.fit.angle_degrees;
    summary.r_squared = result.fit.r_squared;
    summary.fit_bins = result.fit.bin_count;
    summary.is_at_rest = result.is_stage1_at_rest && result.is_stage2_at_rest;
    summary.simulated_time = result.stage1_time + result.stage2_time;
    summary.wall_seconds = result.stage1_seconds + result.stage2_seconds;
    summary.seeds_used = summary.is_valid ? 1 : 0;
    summary.seed_count = seed_count;  // per run: tells record names apart (cases/ stems)
    has_run[slot] = 1;
    const std::lock_guard lock(mutex);
    ++done;
    if (control.on_run) control.on_run(summary, result, done, total);
  };
  // Runs take about the same time, and each is single-threaded inside (Bullet's world), so the
  // cores are used by running cases (and seeds) side by side.
  parallel_for_index(0, total, run_case);
  SweepRuns result;
  result.runs.reserve(total);
  for (std::size_t i = 0; i < total; ++i) {
    if (has_run[i] != 0) result.runs.push_back(std::move(runs[i]));
  }
  result.is_cancelled = result.runs.size() < total;
  return result;
}

SweepResult run_sweep(const SweepOptions& options, const StudyControl& control) {
  StudyControl whole = control;
  whole.share = nullptr;
  SweepRuns runs = run_sweep_runs(options, whole);
  if (runs.is_cancelled) return {.cases = std::move(runs.runs), .is_cancelled = true};
  return {.cases = summarize_sweep(options, std::move(runs.runs)), .is_cancelled = false};
}

}  // namespace aggpack::study
