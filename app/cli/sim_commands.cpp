// `aggpack repose` and `aggpack sweep`: the paper's angle-of-repose trough test and its
// alpha x mu_s sweep, on Bullet (issue 6); `settle` is in settle_commands.cpp. Their keys are
// declared in sweep_schema() (aggpack/config/repose_config.h). Seed ensembles and sweeps run in
// sim_studies.cpp, the printed summaries are in sim_print.cpp.
// Built only with AGGPACK_HAS_SIM (cmake/sim.cmake).

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/study/repose_study.h"
#include "commands.h"
#include "heavy_runs.h"
#include "output_flags.h"
#include "progress.h"
#include "sim_flags.h"
#include "sim_summary.h"

#include "aggpack/io/native.h"

namespace aggpack::cli {

SweepOptions resolve_repose_flags(const ReposeFlags& flags) {
  check_output_folder_flag("-o/--output", flags.output);
  // Notes (a former table name) come before any error, which names the key as it is now.
  std::vector<std::string> notes;
  const auto show_notes = [&notes] {
    for (const std::string& note : notes) {
      std::fprintf(stderr, "aggpack: note: %s\n", clipped(note, 1000).c_str());
    }
  };
  SweepOptions options;
  try {
    options = load_sweep_config(flags.config_path, flags.overrides, &notes);
  } catch (...) {
    show_notes();
    throw;
  }
  show_notes();
  if (flags.engine) {
    if (*flags.engine != "bullet" && *flags.engine != "yade") {
      throw InvalidInput("--engine", clipped(*flags.engine, 40), "bullet or yade");
    }
    options.base.engine = repose_engine_from_string(*flags.engine);
  }
  if (flags.time_limit) {
    if (!(*flags.time_limit >= 0.0 && *flags.time_limit <= 1e7)) {
      throw InvalidInput("--time-limit", format_value(*flags.time_limit), "[0, 1e7] s");
    }
    options.base.yade.time_limit = *flags.time_limit;
  }
  if (flags.friction) options.base.physics.friction = *flags.friction;
  if (flags.alpha) options.base.alpha = *flags.alpha;
  if (flags.friction || flags.alpha) {
    // --mu and --alpha stand for keys but were typed as flags: their messages name the flags.
    std::map<std::string, std::string> flag_names;
    if (flags.friction) flag_names.emplace("physics.friction", "--mu");
    if (flags.alpha) flag_names.emplace("particle.alpha", "--alpha");
    with_key_names({}, flag_names, [&] {
      with_sweep_key_names([&] { study::check_repose_inputs(options.base); });
    });
  }
  if (flags.seed) {
    options.base.seed = parse_seed_flag("--seed", *flags.seed);
    options.seeds.clear();  // --seed: one run at that seed, whatever ensemble.seeds says
  }
  if (flags.has_seeds) options.seeds = parse_seed_list(flags.seeds, "--seeds");
  return options;
}

namespace {

void add_config_options(CLI::App& command, ReposeFlags& flags) {
  command.add_option("config", flags.config_path,
                     "TOML file with [trough] [particle] [physics] [rest] [measure] [sweep] "
                     "tables (omit for the paper's case; see --print-config)");
  command.add_option("--set", flags.overrides, "override a key: --set physics.friction=0.3")
      ->take_all();
  command.add_option("--mu", flags.friction,
                     "sliding friction mu_s, same as --set physics.friction");
  command.add_option("--alpha", flags.alpha, "shape control alpha, same as --set particle.alpha");
  command.add_option("--seed", flags.seed, "master seed, same as --set particle.seed");
  command.add_option(
      "--engine", flags.engine,
      "physics engine: bullet (built in) or yade (Debian's yade as a subprocess, "
      "same fill, trough and measurement; far slower: docs/physics.md), same as --set "
      "physics.engine");
  command.add_option("--time-limit", flags.time_limit,
                     "yade: wall-clock seconds one run may take (0 = none), same as --set "
                     "yade.time_limit");
  command.add_option("-o,--output", flags.output, "output folder (created if missing)")
      ->capture_default_str();
  command.add_option("--width", flags.image_width, "side-view PNG width in pixels, [64, 16384]")
      ->capture_default_str();
  command.add_option("--progress", flags.progress, "auto, bar, lines or none")
      ->capture_default_str();
  command.add_flag("--print-config", flags.is_print_config,
                   "print the resolved configuration (every key, unit, default) and exit");
  command.add_flag("-f,--force", flags.is_forced, "replace existing output files");
  command.add_option("--case", flags.worker,
                     "with --of N: run only worker K's share (1-based, K in [1, N]; run i of the "
                     "plan goes to worker (i mod N) + 1), write its run records, no summary; "
                     "then `aggpack merge DIR`");
  command.add_option("--of", flags.of, "number of workers for --case, [1, 100000]");
}

}  // namespace

std::string prepare_folder(const std::string& folder, bool is_forced,
                           const std::vector<std::string>& names) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error || !std::filesystem::is_directory(folder)) {
    throw IoError("cannot create output folder " + folder);
  }
  for (const auto& name : names) {
    check_writable((std::filesystem::path(folder) / name).string(),
                   is_forced ? Overwrite::kAllow : Overwrite::kForbid);
  }
  return folder;
}

std::string in_folder(const std::string& folder, const std::string& name) {
  return (std::filesystem::path(folder) / name).string();
}

namespace {

void run_repose_command(const ReposeFlags& flags) {
  const SweepOptions options = resolve_repose_flags(flags);
  // Everything the run checks, --print-config included, before any folder is created.
  with_sweep_key_names([&] { study::check_repose_inputs(options.base); });
  if (flags.is_print_config) {
    fmt::print("{}", resolved_sweep_config(options));
    return;
  }
  if (flags.image_width < 64 || flags.image_width > 16384) {
    throw InvalidInput("--width", std::to_string(flags.image_width), "[64, 16384]");
  }
  const RunShare share = parse_run_share(flags.worker, flags.of);
  if (!options.seeds.empty()) {
    run_ensemble_command(flags, options, share);
    return;
  }
  if (share.is_split()) {
    throw InvalidInput("--case", *flags.worker,
                       "only with a seed ensemble (--seeds or ensemble.seeds)");
  }
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  announce_repose(options.base, {}, 1);
  CreatedFolder created(flags.output);
  std::vector<std::string> names = {"repose.json", "profile.csv", "side.png"};
  names.push_back("final.h5");
  const std::string folder = prepare_folder(flags.output, flags.is_forced, names);
  // One display per stage, counted in simulated milliseconds (rate: simulated time per wall
  // second); each stage is bounded by rest.max_time, so the ETA is an upper bound.
  const double max_time = options.base.rest.max_time;
  std::unique_ptr<ProgressBar> bar;
  int last_stage = 0;
  ReposeResult result;
  study::ReposeControl control;
  control.on_progress = [&](int stage, double time, double energy, double threshold) {
    if (stage != last_stage) {
      bar.reset();  // ends the previous stage's display
      last_stage = stage;
      bar = std::make_unique<ProgressBar>(stage == 1 ? "stage 1 (settle)" : "stage 2 (baffle)",
                                          "ms simulated", style);
      bar->set_eta_is_bound(true);
    }
    bar->update(time / max_time, static_cast<std::uint64_t>(time * 1e3 + 0.5),
                static_cast<std::uint64_t>(max_time * 1e3 + 0.5),
                threshold > 0.0 ? fmt::format("kinetic energy {:.2g} J (at rest below {:.2g} J)",
                                              energy, threshold)
                                : fmt::format("kinetic energy {:.2g} J, baffle moving", energy));
  };
  control.on_yade = [&](const YadeProgress& p) {
    if (style != ProgressStyle::kNone) print_yade_progress(p, options.base);
  };
  with_sweep_key_names([&] { result = study::run_repose(options.base, control); });
  bar.reset();
  print_repose_result(result);
  // All or nothing, as `pack`: a failed write (disk full) removes the files of this run.
  OutputTransaction outputs;
  for (const auto& name : names) outputs.add(in_folder(folder, name));
  write_repose_json(in_folder(folder, "repose.json"), options.base, result);
  write_profile_csv(in_folder(folder, "profile.csv"), result);
  write_side_view_png(in_folder(folder, "side.png"), result.final, result.profile, result.fit,
                      flags.image_width);
  write_packing(result.final, in_folder(folder, "final.h5"));
  outputs.commit();
  created.keep();
  fmt::print("wrote {}/repose.json, profile.csv, side.png, final.h5\n", folder);
}

}  // namespace

void register_sim(CLI::App& app) {
  register_settle(app);
  {
    auto flags = std::make_shared<ReposeFlags>();
    auto* command = app.add_subcommand(
        "repose",
        "The paper's angle-of-repose test: lattice fill behind a baffle, settle, move "
        "the baffle away, measure the slope (profile + least-squares line). Default: "
        "the paper's case (trough 6 x 1 x 1 m, alpha 0.5, R 0.1 m, L 0.1 m, 1,050 "
        "particles). Writes repose.json, profile.csv, side.png (and final.h5).");
    add_config_options(*command, *flags);
    command
        ->add_option("--seeds", flags->seeds,
                     "seed ensemble: run once per master seed (1-16, 1,4,9 or 1-4,9; at most "
                     "10000) in parallel; writes ensemble.json|csv|png (each angle, mean, sd, 95% "
                     "CI) and seed-<k>/")
        ->excludes("--seed");
    command
        ->add_option("-j,--threads", flags->threads,
                     "worker threads for --seeds (0 = all cores); results do not depend on it")
        ->capture_default_str();
    command->callback([flags, command]() {
      flags->has_seeds = command->count("--seeds") > 0;
      run_repose_command(*flags);
    });
  }
  {
    auto flags = std::make_shared<ReposeFlags>();
    flags->output = "sweep-out";
    auto* command = app.add_subcommand(
        "sweep",
        "The repose test over alpha x mu_s (default: the paper's 5 x 13 = 65 cases), "
        "cases in parallel; writes sweep.csv, sweep.gp, sweep.png (gnuplot) and "
        "cases/*.json|png.");
    add_config_options(*command, *flags);
    command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
        ->capture_default_str();
    command->add_flag("--no-plot", flags->is_without_plot, "do not run gnuplot");
    command
        ->add_option("--seeds", flags->seeds,
                     "a seed ensemble per case (1-4, 1,4,9): sweep.csv gets the mean, sd and 95% "
                     "CI, sweep.png error bars; cases/*_seed<k>.json|png")
        ->excludes("--seed");
    command->callback([flags, command]() {
      flags->has_seeds = command->count("--seeds") > 0;
      run_sweep_command(*flags);
    });
  }
  register_merge(app);
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
