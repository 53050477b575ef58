// `aggpack repose` and `aggpack sweep`: the paper's angle-of-repose trough test and its
// alpha x mu_s sweep, on Bullet (issue 6); `settle` is in settle_commands.cpp. Their keys are
// declared in sweep_schema() (aggpack/config/repose_config.h).
// Built only with AGGPACK_HAS_SIM (cmake/sim.cmake).

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/sweep.h"
#include "commands.h"
#include "progress.h"

#include "aggpack/io/native.h"

extern char** environ;

namespace aggpack::cli {

namespace {

// Removes an output folder this run created if the run fails before writing into it.
class CreatedFolder {
 public:
  explicit CreatedFolder(const std::string& folder) : folder_(folder) {
    std::error_code error;
    is_created_ = !std::filesystem::exists(std::filesystem::symlink_status(folder, error));
  }
  CreatedFolder(const CreatedFolder&) = delete;
  CreatedFolder& operator=(const CreatedFolder&) = delete;
  ~CreatedFolder() {
    if (!is_created_ || is_kept_) return;
    std::error_code error;
    std::filesystem::remove(std::filesystem::path(folder_) / "cases", error);  // only if empty
    std::filesystem::remove(folder_, error);                                   // only if empty
  }
  void keep() { is_kept_ = true; }

 private:
  std::string folder_;
  bool is_created_ = false;
  bool is_kept_ = false;
};

struct ReposeFlags {
  std::string config_path;
  std::vector<std::string> overrides;
  std::string output = "repose-out";
  std::optional<double> friction;
  std::optional<double> alpha;
  std::optional<std::uint64_t> seed;
  std::string seeds;  ///< repose only: an ensemble, "1-16" or "1,4,9"
  bool has_seeds = false;
  int threads = 0;
  int image_width = 1600;
  std::string progress = "auto";
  bool is_print_config = false;
  bool is_forced = false;
  bool is_without_plot = false;
  bool has_packing = false;
};

SweepOptions resolve(const ReposeFlags& flags) {
  SweepOptions options = load_sweep_config(flags.config_path, flags.overrides);
  if (flags.friction) options.base.physics.friction = *flags.friction;
  if (flags.alpha) options.base.alpha = *flags.alpha;
  if (flags.seed) options.base.seed = *flags.seed;
  return options;
}

void add_config_options(CLI::App& command, ReposeFlags& flags) {
  command.add_option("config", flags.config_path,
                     "TOML file with [trough] [particles] [physics] [rest] [measure] [sweep] "
                     "tables (omit for the paper's case; see --print-config)");
  command.add_option("--set", flags.overrides, "override a key: --set physics.friction=0.3")
      ->take_all();
  command.add_option("--mu", flags.friction,
                     "sliding friction mu_s, same as --set physics.friction");
  command.add_option("--alpha", flags.alpha, "shape control alpha, same as --set particles.alpha");
  command.add_option("--seed", flags.seed, "master seed, same as --set particles.seed");
  command.add_option("-o,--output", flags.output, "output folder (created if missing)")
      ->capture_default_str();
  command.add_option("--width", flags.image_width, "side-view PNG width in pixels, [64, 16384]")
      ->capture_default_str();
  command.add_option("--progress", flags.progress, "auto, bar, lines or none")
      ->capture_default_str();
  command.add_flag("--print-config", flags.is_print_config,
                   "print the resolved configuration (every key, unit, default) and exit");
  command.add_flag("-f,--force", flags.is_forced, "replace existing output files");
}

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

void print_result(const ReposeResult& r) {
  fmt::print("particles            {} (mean measured alpha {:.3f}), solid {:.4g} m^3\n",
             r.particle_count, r.mean_measured_alpha, r.solid_volume);
  fmt::print("time step            {:.4g} s (d_min {:.4g} m)\n", r.time_step, r.smallest_size);
  fmt::print("stage 1 (settle)     {:.2f} s simulated, {}, pile height {:.3f} m, {:.1f} s wall\n",
             r.stage1_time, r.is_stage1_at_rest ? "at rest" : "NOT at rest (max_time)",
             r.stage1_height, r.stage1_seconds);
  fmt::print(
      "stage 2 (baffle)     {:.2f} s simulated, baffle moved {:.3f} m ({}), {}, {:.1f} s wall\n",
      r.stage2_time, r.baffle_travel, r.is_baffle_removed ? "then removed" : "to the far wall",
      r.is_stage2_at_rest ? "stable" : "NOT stable (max_time)", r.stage2_seconds);
  fmt::print(
      "final pile           max overlap {:.3f}% of d_min, max contact penetration {:.3f}%, "
      "{} particles outside\n",
      100.0 * r.max_overlap_fraction, 100.0 * r.max_contact_penetration_fraction,
      r.escaped_particles);
  if (r.fit.is_valid) {
    fmt::print(
        "angle of repose      {:.2f} deg (R^2 {:.3f}, {} bins from x = {:.3f} to {:.3f} m, "
        "pile height {:.3f} m)\n",
        r.fit.angle_degrees, r.fit.r_squared, r.fit.bin_count, r.profile.centre(r.fit.first_bin),
        r.profile.centre(r.fit.last_bin), r.fit.pile_height);
    fmt::print(
        "fit sensitivity      max deviation {:.2f} deg (fit window +-0.05: {:.2f}, bin width "
        "x0.5-2: "
        "{:.2f})\n",
        r.sensitivity.max_deviation, r.sensitivity.max_deviation_window,
        r.sensitivity.max_deviation_bins);
  } else {
    fmt::print("angle of repose      not measured: {}\n", r.fit.message);
  }
  if (r.confirmation.window > 0.0) {
    fmt::print("rest confirmation    {:.2f} s window {}, {} restarts\n", r.confirmation.window,
               r.is_stage2_at_rest ? "passed" : "not passed", r.confirmation.restarts);
  }
  if (r.follow.time > 0.0 && r.follow.fit.is_valid) {
    fmt::print("follow-up            {:.2f} s later: angle {:.2f} deg, pile height {:.3f} m\n",
               r.follow.time, r.follow.fit.angle_degrees, r.follow.fit.pile_height);
  }
}

// The paper's lattice fill of a repose case, made by the pipeline.
PackResult repose_fill(const ReposeOptions& options) {
  return pack(PackerOptions{repose_fill_options(options)});
}

// `repose --seeds`: one run per seed in DIR/seed-<k>/, the angles and their statistics in
// DIR/ensemble.json|csv|png. Seeds run in parallel, each single-threaded (as the sweep's cases).
void run_ensemble_command(const ReposeFlags& flags, const SweepOptions& options) {
  const std::vector<std::uint64_t> seeds = parse_seed_list(flags.seeds, "--seeds");
  set_thread_count(flags.threads);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  const std::vector<std::string> seed_files = {"repose.json", "profile.csv", "side.png",
                                               "final.h5"};
  CreatedFolder created(flags.output);
  const std::string folder = prepare_folder(flags.output, flags.is_forced,
                                            {"ensemble.json", "ensemble.csv", "ensemble.png"});
  for (const auto seed : seeds) {
    std::vector<std::string> names;
    for (const auto& name : seed_files) names.push_back(fmt::format("seed-{}/{}", seed, name));
    // A seed's folder is made when its run ends; an existing one must not hold its files.
    if (!std::filesystem::exists(in_folder(folder, fmt::format("seed-{}", seed)))) continue;
    for (const auto& name : names) {
      check_writable(in_folder(folder, name),
                     flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid);
    }
  }
  fmt::print("ensemble: {} seeds\n", seeds.size());
  ProgressBar bar("ensemble", "seeds", style);
  EnsembleResult ensemble;
  with_sweep_key_names([&] {
    ensemble = run_ensemble(
        options.base, seeds, repose_fill,
        [&](const EnsembleSeed& s, const ReposeResult* result, std::size_t done,
            std::size_t total) {
          if (result != nullptr) {
            const std::string sub = in_folder(folder, fmt::format("seed-{}", s.seed));
            try {
              std::filesystem::create_directories(sub);
              ReposeOptions repose = options.base;
              repose.seed = s.seed;
              write_repose_json(in_folder(sub, "repose.json"), repose, *result);
              write_profile_csv(in_folder(sub, "profile.csv"), *result);
              write_side_view_png(in_folder(sub, "side.png"), result->final, result->profile,
                                  result->fit, std::min(flags.image_width, 1200));
              write_packing(result->final, in_folder(sub, "final.h5"));
            } catch (const std::exception& error) {
              std::fprintf(stderr, "aggpack: warning: seed %llu: %s\n",
                           static_cast<unsigned long long>(s.seed), error.what());
            }
          }
          bar.update(static_cast<double>(done) / static_cast<double>(total), done, total,
                     s.is_valid ? fmt::format("seed {}: {:.2f} deg", s.seed, s.angle_degrees)
                                : fmt::format("seed {}: failed", s.seed));
        });
  });
  bar.finish();
  created.keep();
  write_ensemble_json(in_folder(folder, "ensemble.json"), options.base, ensemble);
  write_ensemble_csv(in_folder(folder, "ensemble.csv"), ensemble);
  write_ensemble_png(in_folder(folder, "ensemble.png"), ensemble,
                     std::min(flags.image_width, 1600));
  fmt::print("{:>8} {:>9} {:>7} {:>6}\n", "seed", "angle", "R^2", "rest");
  for (const auto& s : ensemble.seeds) {
    if (s.is_valid) {
      fmt::print("{:>8} {:9.2f} {:7.3f} {:>6}\n", s.seed, s.angle_degrees, s.r_squared,
                 s.is_at_rest ? "yes" : "no");
    } else {
      fmt::print("{:>8} {:>9} {}\n", s.seed, "FAILED", s.error);
    }
  }
  const EnsembleStatistics& st = ensemble.statistics;
  if (st.has_interval) {
    fmt::print(
        "angle of repose      {:.2f} deg mean, sd {:.2f}, 95% CI [{:.2f}, {:.2f}] "
        "(+/- {:.2f}, t {:.3f}), {} of {} seeds\n",
        st.mean, st.std_dev, st.lower(), st.upper(), st.half_width, st.t_quantile, st.count,
        ensemble.seeds.size());
  } else {
    fmt::print("angle of repose      {} of {} seeds measured: no confidence interval (needs 2)\n",
               st.count, ensemble.seeds.size());
  }
  fmt::print("wrote {}/ensemble.json, ensemble.csv, ensemble.png and seed-<k>/\n", folder);
  if (st.count == 0) {
    throw LimitExceeded("--seeds", flags.seeds, "at least one seed with a measured angle");
  }
}

void run_repose_command(const ReposeFlags& flags) {
  const SweepOptions options = resolve(flags);
  // Everything the run checks, --print-config included, before any folder is created.
  with_sweep_key_names([&] { validate(options.base); });
  if (flags.is_print_config) {
    fmt::print("{}", resolved_sweep_config(options));
    return;
  }
  if (flags.image_width < 64 || flags.image_width > 16384) {
    throw InvalidInput("--width", std::to_string(flags.image_width), "[64, 16384]");
  }
  if (flags.has_seeds) {
    run_ensemble_command(flags, options);
    return;
  }
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  CreatedFolder created(flags.output);
  std::vector<std::string> names = {"repose.json", "profile.csv", "side.png"};
  names.push_back("final.h5");
  const std::string folder = prepare_folder(flags.output, flags.is_forced, names);
  double last_print = -1.0;
  int last_stage = 0;
  ReposeResult result;
  with_sweep_key_names([&] {
    result = run_repose(options.base, repose_fill(options.base),
                        [&](int stage, double time, double energy, double threshold) {
                          if (style == ProgressStyle::kNone) return;
                          if (stage != last_stage || time - last_print >= 0.5) {
                            last_stage = stage;
                            last_print = time;
                            std::fprintf(stderr, "stage %d  t = %6.2f s  kinetic energy %.3g J%s\n",
                                         stage, time, energy,
                                         threshold > 0.0
                                             ? fmt::format(" (rest < {:.3g})", threshold).c_str()
                                             : "  (baffle moving)");
                          }
                        });
  });
  print_result(result);
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

// The sweep plot: angle against mu_s, one line per alpha (gnuplot, run when it is installed).
std::string gnuplot_script(const std::vector<double>& alphas, bool has_error_bars) {
  std::string script =
      "# angle of repose against sliding friction, one curve per alpha (aggpack sweep)\n"
      "set terminal pngcairo size 1000,700 font ',12'\n"
      "set output 'sweep.png'\n"
      "set datafile separator ','\n"
      "set key top left title 'alpha'\n"
      "set xlabel 'sliding friction {/Symbol m}_s'\n"
      "set ylabel 'angle of repose (deg)'\n"
      "set grid\n"
      "plot ";
  for (std::size_t i = 0; i < alphas.size(); ++i) {
    script += fmt::format(
        "{}'sweep.csv' every ::1 using ($1 == {} && $6 == 1 ? $2 : 1/0):3{} with {} "
        "lw 2 pt 7 title '{}'",
        i > 0 ? ", \\\n     " : "", alphas[i], has_error_bars ? ":14:15" : "",
        has_error_bars ? "yerrorlines" : "linespoints", alphas[i]);
  }
  return script + "\n";
}

bool run_gnuplot(const std::string& folder) {
  const std::string command = "gnuplot";
  const std::string script = "sweep.gp";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // gnuplot resolves the script's file names relative to its working directory.
  const std::string previous = std::filesystem::current_path().string();
  std::filesystem::current_path(folder);
  std::vector<char*> argv = {const_cast<char*>(command.c_str()), const_cast<char*>(script.c_str()),
                             nullptr};
  pid_t pid = 0;
  const int status = posix_spawnp(&pid, command.c_str(), &actions, nullptr, argv.data(), environ);
  std::filesystem::current_path(previous);
  posix_spawn_file_actions_destroy(&actions);
  if (status != 0) return false;
  int exit_status = 0;
  if (waitpid(pid, &exit_status, 0) < 0) return false;
  return WIFEXITED(exit_status) && WEXITSTATUS(exit_status) == 0;
}

void run_sweep_command(const ReposeFlags& flags) {
  SweepOptions options = resolve(flags);
  with_sweep_key_names([&] { validate(options); });
  if (flags.has_seeds) options.seeds = parse_seed_list(flags.seeds, "--seeds");
  const bool is_ensemble = !options.seeds.empty();
  if (flags.is_print_config) {
    fmt::print("{}", resolved_sweep_config(options));
    return;
  }
  set_thread_count(flags.threads);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  CreatedFolder created(flags.output);
  const std::string folder =
      prepare_folder(flags.output, flags.is_forced, {"sweep.csv", "sweep.gp", "sweep.png"});
  std::filesystem::create_directories(std::filesystem::path(folder) / "cases");
  const std::size_t total = options.alphas.size() * options.frictions.size();
  fmt::print("sweep: {} alpha x {} mu_s = {} cases", options.alphas.size(),
             options.frictions.size(), total);
  fmt::print("{}\n", is_ensemble ? fmt::format(" x {} seeds", options.seeds.size()) : "");
  ProgressBar bar("sweep", "cases", style);
  const auto cases = run_sweep(
      options, repose_fill,
      [&](const SweepCase& c, const ReposeResult& result, std::size_t done, std::size_t count) {
        const std::string stem = fmt::format("alpha{:.2f}_mu{:.2f}", c.alpha, c.friction) +
                                 (is_ensemble ? fmt::format("_seed{}", c.seed) : std::string());
        try {
          ReposeOptions repose = options.base;
          repose.seed = c.seed;
          repose.alpha = c.alpha;
          repose.physics.friction = c.friction;
          if (options.is_wall_friction_coupled) repose.physics.wall_friction = c.friction;
          write_repose_json(in_folder(folder, "cases/" + stem + ".json"), repose, result);
          write_side_view_png(in_folder(folder, "cases/" + stem + ".png"), result.final,
                              result.profile, result.fit, std::min(flags.image_width, 1200));
        } catch (const Error& error) {
          std::fprintf(stderr, "aggpack: warning: case %s: %s\n", stem.c_str(), error.what());
        }
        bar.update(static_cast<double>(done) / static_cast<double>(count), done, count,
                   fmt::format("alpha {:.2f} mu {:.2f}: {:.1f} deg", c.alpha, c.friction,
                               c.angle_degrees));
      });
  bar.finish();
  created.keep();
  write_sweep_csv(in_folder(folder, "sweep.csv"), cases);
  fmt::print("{:>6} {:>6} {:>9} {:>7} {:>6}{}\n", "alpha", "mu_s", "angle", "R^2", "rest",
             is_ensemble ? "  95% CI        seeds" : "");
  for (const auto& c : cases) {
    fmt::print("{:6.2f} {:6.2f} {:>9} {:7.3f} {:>6}", c.alpha, c.friction,
               c.is_valid ? fmt::format("{:.2f}", c.angle_degrees) : std::string("-"), c.r_squared,
               c.is_at_rest ? "yes" : "no");
    if (is_ensemble) {
      fmt::print("  {:<14} {}/{}",
                 c.statistics.has_interval
                     ? fmt::format("[{:.2f}, {:.2f}]", c.statistics.lower(), c.statistics.upper())
                     : std::string("-"),
                 c.seeds_used, c.seed_count);
    }
    fmt::print("\n");
  }
  {
    AtomicFile script(in_folder(folder, "sweep.gp"), Overwrite::kAllow, std::ios::out);
    script.stream() << gnuplot_script(options.alphas, is_ensemble);
    script.commit();
  }
  if (!flags.is_without_plot && run_gnuplot(folder)) {
    fmt::print("wrote {}/sweep.csv, sweep.gp, sweep.png and cases/\n", folder);
  } else {
    fmt::print("wrote {}/sweep.csv, sweep.gp and cases/ (plot: cd {} && gnuplot sweep.gp)\n",
               folder, folder);
  }
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
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
