// `aggpack repose` and `aggpack sweep`: the paper's angle-of-repose trough test and its
// alpha x mu_s sweep, on Bullet (issue 6); `settle` is in settle_commands.cpp. Their keys are
// declared in sweep_schema() (aggpack/config/repose_config.h).
// Built only with AGGPACK_HAS_SIM (cmake/sim.cmake).

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/sim/sweep.h"
#include "commands.h"
#include "heavy_runs.h"
#include "mpi_world.h"
#include "output_flags.h"
#include "progress.h"
#include "sim_summary.h"

#include "aggpack/io/native.h"

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
    std::filesystem::remove(std::filesystem::path(folder_) / "runs", error);   // only if empty
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
  std::optional<std::string> engine;  ///< --engine, same as --set physics.engine
  std::optional<double> time_limit;   ///< --time-limit, same as --set yade.time_limit
  std::string seeds;                  ///< an ensemble, "1-16" or "1,4,9" (overrides ensemble.seeds)
  bool has_seeds = false;
  std::optional<std::string> worker;  ///< --case K
  std::optional<std::string> of;      ///< --of N
  int threads = 0;
  int image_width = 1600;
  std::string progress = "auto";
  bool is_print_config = false;
  bool is_forced = false;
  bool is_without_plot = false;
  bool has_packing = false;
};

SweepOptions resolve(const ReposeFlags& flags) {
  check_output_folder_flag("-o/--output", flags.output);
  SweepOptions options = load_sweep_config(flags.config_path, flags.overrides);
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
    if (flags.alpha) flag_names.emplace("particles.alpha", "--alpha");
    with_key_names({}, flag_names, [&] { with_sweep_key_names([&] { validate(options.base); }); });
  }
  if (flags.seed) {
    options.base.seed = *flags.seed;
    options.seeds.clear();  // --seed: one run at that seed, whatever ensemble.seeds says
  }
  if (flags.has_seeds) options.seeds = parse_seed_list(flags.seeds, "--seeds");
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

void print_result(const ReposeResult& r) {
  fmt::print("particles            {} (mean measured alpha {:.3f}), solid {:.4g} m^3\n",
             r.particle_count, r.mean_measured_alpha, r.solid_volume);
  fmt::print("time step            {:.4g} s (d_min {:.4g} m)\n", r.time_step, r.smallest_size);
  if (r.yade_iterations > 0) {
    fmt::print(
        "engine               yade: {} iterations, contact stiffness {:.3g} N/m^3, {} s CPU\n",
        r.yade_iterations, r.yade_young, format_seconds(r.engine_cpu_seconds));
  }
  fmt::print("stage 1 (settle)     {:.2f} s simulated, {}, pile height {:.3f} m, {} s wall\n",
             r.stage1_time, r.is_stage1_at_rest ? "at rest" : "NOT at rest (max_time)",
             r.stage1_height, format_seconds(r.stage1_seconds));
  fmt::print(
      "stage 2 (baffle)     {:.2f} s simulated, baffle moved {:.3f} m ({}), {}, {} s wall\n",
      r.stage2_time, r.baffle_travel, r.is_baffle_removed ? "then removed" : "to the far wall",
      r.is_stage2_at_rest ? "stable" : "NOT stable (max_time)", format_seconds(r.stage2_seconds));
  if (r.yade_iterations > 0) {
    fmt::print("final pile           {} particles outside\n", r.escaped_particles);
  } else {
    fmt::print(
        "final pile           max overlap {:.3f}% of d_min, max contact penetration {:.3f}%, "
        "{} particles outside\n",
        100.0 * r.max_overlap_fraction, 100.0 * r.max_contact_penetration_fraction,
        r.escaped_particles);
  }
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

// The plan of a distributed run: the resolved configuration (with the seed list) and its hash.
RunRecord plan_record(RunKind kind, const SweepOptions& options, std::size_t run_count,
                      int image_width) {
  RunRecord record;
  record.image_width = image_width;
  record.kind = kind;
  record.config = resolved_sweep_config(options);
  record.hash = config_hash(record.config);
  record.run_count = run_count;
  return record;
}

// Workers share a folder: one whose runs/ holds records of another plan (configuration, seed
// list or kind) is refused before anything runs, so that a folder never mixes plans.
void check_same_plan(const std::string& folder, const RunRecord& plan) {
  const std::filesystem::path runs = std::filesystem::path(folder) / "runs";
  std::error_code error;
  if (!std::filesystem::is_directory(runs, error)) return;
  for (const auto& entry : std::filesystem::directory_iterator(runs, error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.front() == '.' || entry.path().extension() != ".json") continue;
    const RunRecord other = read_run_record(entry.path().string());
    if (other.kind != plan.kind || other.hash != plan.hash) {
      throw InvalidInput(
          "-o " + folder,
          "a folder holding " + entry.path().string() + " (configuration " + other.hash + ")",
          "a new folder, or one of the same configuration and seed list (this "
          "run's configuration is " +
              plan.hash + ")");
    }
  }
}

void print_share(const RunShare& share, std::size_t owned, std::size_t total,
                 const std::string& folder) {
  fmt::print(
      "worker {} of {}: {} of {} runs done, records in {}/runs/; when every worker is done: "
      "aggpack merge {}\n",
      share.worker, share.of, owned, total, folder, folder);
}

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
  std::map<std::uint64_t, std::size_t> run_index;
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    run_index[seeds[i]] = i;
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
  const RunRecord plan = plan_record(RunKind::kEnsemble, options, seeds.size(), flags.image_width);
  check_same_plan(folder, plan);
  std::filesystem::create_directories(in_folder(folder, "runs"));
  fmt::print("ensemble: {} seeds{}\n", seeds.size(),
             share.is_split() ? fmt::format(" (worker {} of {})", share.worker, share.of) : "");
  ProgressBar bar("ensemble", "seeds", style);
  EnsembleResult ensemble;
  with_sweep_key_names([&] {
    ensemble = run_ensemble(
        options.base, seeds, repose_fill,
        [&](const EnsembleSeed& s, const ReposeResult* result, std::size_t done,
            std::size_t total) {
          try {
            if (result != nullptr) {
              const std::string sub = in_folder(folder, fmt::format("seed-{}", s.seed));
              std::filesystem::create_directories(sub);
              ReposeOptions repose = options.base;
              repose.seed = s.seed;
              write_repose_json(in_folder(sub, "repose.json"), repose, *result);
              write_profile_csv(in_folder(sub, "profile.csv"), *result);
              write_side_view_png(in_folder(sub, "side.png"), result->final, result->profile,
                                  result->fit, std::min(flags.image_width, 1200));
              write_packing(result->final, in_folder(sub, "final.h5"));
            }
            RunRecord record = plan;
            record.run_index = run_index.at(s.seed);
            record.ensemble = s;
            write_run_record(in_folder(folder, "runs/" + run_record_name(record)), record);
          } catch (const std::exception& error) {
            std::fprintf(stderr, "aggpack: warning: seed %llu: %s\n",
                         static_cast<unsigned long long>(s.seed), error.what());
          }
          bar.update(static_cast<double>(done) / static_cast<double>(total), done, total,
                     s.is_valid ? fmt::format("seed {}: {:.2f} deg", s.seed, s.angle_degrees)
                                : fmt::format("seed {}: failed", s.seed));
        },
        &share, write_repose_yade_script);
  });
  bar.finish();
  created.keep();
  if (share.is_split()) print_share(share, ensemble.seeds.size(), seeds.size(), folder);
  return ensemble;
}

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

// A YADE progress line: simulated time, the rate (simulated per wall-clock second) and a rough
// ETA from an expected length of the run (the fill's fall and quiet time, half the baffle's
// travel, the quiet time and the confirmation window), which the run may well exceed.
void print_yade_progress(const YadeProgress& p, const ReposeOptions& o) {
  const double g = std::max(1e-9, o.physics.gravity.norm());
  const double earliest = std::sqrt(2.0 * o.fill_height / g) +
                          2.0 * (o.rest.min_time + o.rest.quiet_time) +
                          (o.trough_length - o.baffle_position) / o.baffle_speed * 0.5 +
                          o.confirm_window * std::sqrt(2.0 * o.radius / g);
  const double rate = p.wall_seconds > 0.0 ? p.total_time / p.wall_seconds : 0.0;
  const std::string eta = rate > 0.0 && earliest > p.total_time
                              ? fmt::format(", ETA ~{:.0f} s", (earliest - p.total_time) / rate)
                              : std::string();
  std::fprintf(stderr,
               "yade stage %d  t = %7.3f s (total %.3f s)  kinetic energy %.3g J  %.3g "
               "simulated s per s, %.0f s wall%s\n",
               p.stage, p.time, p.total_time, p.energy, rate, p.wall_seconds, eta.c_str());
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
  with_sweep_key_names([&] {
    if (options.base.engine == ReposeEngine::kYade) {
      result = run_repose_yade(options.base, repose_fill(options.base), write_repose_yade_script,
                               [&](const YadeProgress& p) {
                                 if (style != ProgressStyle::kNone)
                                   print_yade_progress(p, options.base);
                               });
      return;
    }
    result = run_repose(
        options.base, repose_fill(options.base),
        [&](int stage, double time, double energy, double threshold) {
          if (stage != last_stage) {
            bar.reset();  // ends the previous stage's display
            last_stage = stage;
            bar = std::make_unique<ProgressBar>(
                stage == 1 ? "stage 1 (settle)" : "stage 2 (baffle)", "ms simulated", style);
            bar->set_eta_is_bound(true);
          }
          bar->update(time / max_time, static_cast<std::uint64_t>(time * 1e3 + 0.5),
                      static_cast<std::uint64_t>(max_time * 1e3 + 0.5),
                      threshold > 0.0
                          ? fmt::format("kinetic energy {:.2g} J (at rest below {:.2g} J)", energy,
                                        threshold)
                          : fmt::format("kinetic energy {:.2g} J, baffle moving", energy));
        });
  });
  bar.reset();
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
  std::filesystem::create_directories(std::filesystem::path(folder) / "runs");
  const std::size_t seed_count = is_ensemble ? options.seeds.size() : 1;
  const std::size_t total = options.alphas.size() * options.frictions.size();
  fmt::print("sweep: {} alpha x {} mu_s = {} cases", options.alphas.size(),
             options.frictions.size(), total);
  fmt::print("{}{}\n", is_ensemble ? fmt::format(" x {} seeds", options.seeds.size()) : "",
             share.is_split() ? fmt::format(" (worker {} of {})", share.worker, share.of) : "");
  announce_repose(options.base, share, total * seed_count);
  const RunRecord plan =
      plan_record(RunKind::kSweep, options, total * seed_count, flags.image_width);
  check_same_plan(folder, plan);
  std::map<std::uint64_t, std::size_t> seed_index;
  for (std::size_t k = 0; k < options.seeds.size(); ++k) seed_index[options.seeds[k]] = k;
  ProgressBar bar("sweep", "cases", style);
  std::vector<SweepCase> runs;
  with_sweep_key_names([&] {
    runs = run_sweep_runs(
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
            RunRecord record = plan;
            record.run_index = c.index * seed_count + (is_ensemble ? seed_index.at(c.seed) : 0);
            record.sweep = c;
            write_run_record(in_folder(folder, "runs/" + stem + ".json"), record);
          } catch (const Error& error) {
            std::fprintf(stderr, "aggpack: warning: case %s: %s\n", stem.c_str(), error.what());
          }
          bar.update(static_cast<double>(done) / static_cast<double>(count), done, count,
                     fmt::format("alpha {:.2f} mu {:.2f}: {:.1f} deg", c.alpha, c.friction,
                                 c.angle_degrees));
        },
        &share, write_repose_yade_script);
  });
  bar.finish();
  created.keep();
  if (share.is_split()) print_share(share, runs.size(), total * seed_count, folder);
  return runs;
}

void run_sweep_command(const ReposeFlags& flags) {
  const SweepOptions options = resolve(flags);
  with_sweep_key_names([&] { validate(options); });
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
