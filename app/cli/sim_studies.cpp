// Seed ensembles (`repose --seeds`) and sweeps (`aggpack sweep`) of the repose test: the runs
// come from the study layer (aggpack/study/repose_study.h, as Python's); here are their folders,
// run records and progress bars, split over `--case K --of N` workers or mpirun ranks, then the
// summary (sim_summary.h). Built only with AGGPACK_HAS_SIM (cmake/sim.cmake).

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/sweep.h"
#include "aggpack/study/repose_study.h"
#include "aggpack/study/run_parts.h"
#include "commands.h"
#include "heavy_runs.h"
#include "mpi_world.h"
#include "progress.h"
#include "sim_flags.h"
#include "sim_summary.h"

#include "aggpack/io/native.h"

namespace aggpack::cli {

namespace {

// `repose --seeds`: one run per seed in DIR/seed-<k>/ and its record in DIR/runs/seed-<k>.json,
// the angles and their statistics in DIR/ensemble.json|csv|png. Seeds run in parallel, each
// single-threaded (as the sweep's cases). With --case K --of N only worker K's seeds run and the
// summary is left to `aggpack merge` (`is_merged_later`: also under mpirun).
EnsembleResult run_ensemble_part(const ReposeFlags& flags, const SweepOptions& options,
                                 const RunShare& share, bool is_merged_later) {
  const std::vector<std::uint64_t>& seeds = options.seeds;
  set_thread_count(flags.threads);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  const std::vector<std::string> seed_files = {"repose.json", "profile.csv", "side.png",
                                               "final.h5"};
  CreatedFolder created(flags.output);
  const std::string folder = prepare_folder(
      flags.output, flags.is_forced,
      is_merged_later ? std::vector<std::string>{}
                      : std::vector<std::string>{"ensemble.json", "ensemble.csv", "ensemble.png"});
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (!share.owns(i)) continue;
    if (std::filesystem::exists(in_folder(folder, "runs"))) {
      check_writable(in_folder(folder, fmt::format("runs/seed-{}.json", seeds[i])), overwrite);
    }
    // A seed's folder is made when its run ends; an existing one must not hold its files.
    if (!std::filesystem::exists(in_folder(folder, fmt::format("seed-{}", seeds[i])))) continue;
    for (const auto& name : seed_files) {
      check_writable(in_folder(folder, fmt::format("seed-{}/{}", seeds[i], name)), overwrite);
    }
  }
  announce_repose(options.base, share, seeds.size());
  const study::RunRecorder recorder(RunKind::kEnsemble, options, folder, flags.image_width,
                                    "-o " + folder);
  fmt::print("ensemble: {} seeds{}\n", seeds.size(),
             share.is_split() ? fmt::format(" (worker {} of {})", share.worker, share.of) : "");
  ProgressBar bar("ensemble", "seeds", style);
  // The bar from the start (0 of this process's seeds), not first when a whole run has ended.
  std::size_t owned = 0;
  for (std::size_t i = 0; i < seeds.size(); ++i) owned += share.owns(i) ? 1 : 0;
  bar.update(0.0, 0, owned);
  study::StudyControl control;
  control.share = &share;
  control.on_seed = [&](const EnsembleSeed& s, const ReposeResult* result, std::size_t done,
                        std::size_t total) {
    try {
      if (result != nullptr) {
        const std::string sub = in_folder(folder, fmt::format("seed-{}", s.seed));
        std::filesystem::create_directories(sub);
        ReposeOptions repose = options.base;
        repose.seed = s.seed;
        write_repose_json(in_folder(sub, "repose.json"), repose, *result);
        write_profile_csv(in_folder(sub, "profile.csv"), *result);
        write_side_view_png(in_folder(sub, "side.png"), result->final, result->profile, result->fit,
                            std::min(flags.image_width, 1200));
        write_packing(result->final, in_folder(sub, "final.h5"));
      }
      recorder.record(s);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "aggpack: warning: seed %llu: %s\n",
                   static_cast<unsigned long long>(s.seed), error.what());
    }
    bar.update(static_cast<double>(done) / static_cast<double>(total), done, total,
               s.is_valid ? fmt::format("seed {}: {:.2f} deg", s.seed, s.angle_degrees)
                          : fmt::format("seed {}: failed", s.seed));
  };
  EnsembleResult ensemble;
  with_sweep_key_names(
      [&] { ensemble = study::run_repose_ensemble(options.base, seeds, control); });
  bar.finish();
  created.keep();
  if (share.is_split()) print_share(share, ensemble.seeds.size(), seeds.size(), folder);
  return ensemble;
}

}  // namespace

// The ensemble in this process (`--case K --of N`: its share), or over the ranks of mpirun.
void run_ensemble_command(const ReposeFlags& flags, const SweepOptions& options,
                          const RunShare& given) {
  if (given.is_split()) {
    run_ensemble_part(flags, options, given, true);
    return;
  }
  bool is_mpi = false;
  EnsembleResult ensemble;
  run_on_mpi_world(
      [&](const MpiWorld& world) {
        is_mpi = world.is_split();
        const RunShare share = is_mpi ? RunShare{world.rank + 1, world.size} : RunShare{};
        ensemble = run_ensemble_part(flags, options, share, false);
      },
      [&] {
        if (is_mpi) {
          merge_run_folder(flags.output, "", flags.image_width, false, flags.is_forced);
        } else {
          write_ensemble_summary(flags.output, options.base, ensemble, flags.image_width);
        }
      });
}

namespace {

// The runs of a sweep (`share`'s only when split), as run_ensemble_part.
std::vector<SweepCase> run_sweep_part(const ReposeFlags& flags, const SweepOptions& options,
                                      const RunShare& share, bool is_merged_later) {
  const bool is_ensemble = !options.seeds.empty();
  set_thread_count(flags.threads);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  CreatedFolder created(flags.output);
  const std::string folder = prepare_folder(
      flags.output, flags.is_forced,
      is_merged_later ? std::vector<std::string>{}
                      : std::vector<std::string>{"sweep.csv", "sweep.gp", "sweep.png"});
  std::filesystem::create_directories(std::filesystem::path(folder) / "cases");
  const std::size_t seed_count = is_ensemble ? options.seeds.size() : 1;
  const std::size_t total = options.alphas.size() * options.frictions.size();
  fmt::print("sweep: {} alpha x {} mu_s = {} cases", options.alphas.size(),
             options.frictions.size(), total);
  fmt::print("{}{}\n", is_ensemble ? fmt::format(" x {} seeds", options.seeds.size()) : "",
             share.is_split() ? fmt::format(" (worker {} of {})", share.worker, share.of) : "");
  announce_repose(options.base, share, total * seed_count);
  const study::RunRecorder recorder(RunKind::kSweep, options, folder, flags.image_width,
                                    "-o " + folder);
  ProgressBar bar("sweep", "cases", style);
  // The bar from the start (0 of this process's runs), not first when a whole run has ended.
  std::size_t owned = 0;
  for (std::size_t i = 0; i < total * seed_count; ++i) owned += share.owns(i) ? 1 : 0;
  bar.update(0.0, 0, owned);
  study::StudyControl control;
  control.share = &share;
  control.on_run = [&](const SweepCase& c, const ReposeResult& result, std::size_t done,
                       std::size_t count) {
    const std::string stem = recorder.stem(c);
    try {
      ReposeOptions repose = options.base;
      repose.seed = c.seed;
      repose.alpha = c.alpha;
      repose.physics.friction = c.friction;
      if (options.is_wall_friction_coupled) repose.physics.wall_friction = c.friction;
      write_repose_json(in_folder(folder, "cases/" + stem + ".json"), repose, result);
      write_side_view_png(in_folder(folder, "cases/" + stem + ".png"), result.final, result.profile,
                          result.fit, std::min(flags.image_width, 1200));
      recorder.record(c);
    } catch (const Error& error) {
      std::fprintf(stderr, "aggpack: warning: case %s: %s\n", stem.c_str(), error.what());
    }
    bar.update(
        static_cast<double>(done) / static_cast<double>(count), done, count,
        fmt::format("alpha {:.2f} mu {:.2f}: {:.1f} deg", c.alpha, c.friction, c.angle_degrees));
  };
  std::vector<SweepCase> runs;
  with_sweep_key_names([&] { runs = study::run_sweep_runs(options, control).runs; });
  bar.finish();
  created.keep();
  if (share.is_split()) print_share(share, runs.size(), total * seed_count, folder);
  return runs;
}

}  // namespace

void run_sweep_command(const ReposeFlags& flags) {
  const SweepOptions options = resolve_repose_flags(flags);
  with_sweep_key_names([&] {
    validate(options);
    study::check_repose_inputs(options.base);
  });
  const RunShare given = parse_run_share(flags.worker, flags.of);
  if (flags.is_print_config) {
    fmt::print("{}", resolved_sweep_config(options));
    return;
  }
  if (given.is_split()) {
    run_sweep_part(flags, options, given, true);
    return;
  }
  bool is_mpi = false;
  std::vector<SweepCase> runs;
  run_on_mpi_world(
      [&](const MpiWorld& world) {
        is_mpi = world.is_split();
        const RunShare share = is_mpi ? RunShare{world.rank + 1, world.size} : RunShare{};
        runs = run_sweep_part(flags, options, share, false);
      },
      [&] {
        if (is_mpi) {
          merge_run_folder(flags.output, "", flags.image_width, flags.is_without_plot,
                           flags.is_forced);
        } else {
          write_sweep_summary(flags.output, options, summarize_sweep(options, std::move(runs)),
                              flags.is_without_plot);
        }
      });
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
