// `aggpack merge DIR`: the summary of an ensemble or sweep from the run records its workers
// (`--case K --of N`) left in DIR/runs/, and the summary writers the single-process runs share.
// Built only with AGGPACK_HAS_SIM.

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>
#include <spawn.h>
#include <sys/wait.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/study/run_parts.h"
#include "commands.h"
#include "output_flags.h"
#include "sim_summary.h"

extern char** environ;

namespace aggpack::cli {

namespace {

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

}  // namespace

void write_ensemble_summary(const std::string& folder, const ReposeOptions& base,
                            const EnsembleResult& ensemble, int width) {
  write_ensemble_json(in_folder(folder, "ensemble.json"), base, ensemble);
  write_ensemble_csv(in_folder(folder, "ensemble.csv"), ensemble);
  write_ensemble_png(in_folder(folder, "ensemble.png"), ensemble, std::min(width, 1600));
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
    std::vector<std::uint64_t> seeds;
    for (const auto& s : ensemble.seeds) seeds.push_back(s.seed);
    throw LimitExceeded("--seeds", format_seed_list(seeds),
                        "at least one seed with a measured angle");
  }
}

void write_sweep_summary(const std::string& folder, const SweepOptions& options,
                         const std::vector<SweepCase>& cases, bool is_without_plot) {
  const bool is_ensemble = !options.seeds.empty();
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
  if (!is_without_plot && run_gnuplot(folder)) {
    fmt::print("wrote {}/sweep.csv, sweep.gp, sweep.png and cases/\n", folder);
  } else {
    fmt::print("wrote {}/sweep.csv, sweep.gp and cases/ (plot: cd {} && gnuplot sweep.gp)\n",
               folder, folder);
  }
}

namespace {

struct MergeFlags {
  std::string folder;
  std::string output;
  int image_width = 0;  ///< 0: the workers' --width (from the records), else 1600
  bool is_without_plot = false;
  bool is_forced = false;
};

}  // namespace

void merge_run_folder(const std::string& folder, const std::string& output_folder, int width,
                      bool is_without_plot, bool is_forced) {
  const MergeFlags flags{.folder = folder,
                         .output = output_folder,
                         .image_width = width,
                         .is_without_plot = is_without_plot,
                         .is_forced = is_forced};
  if (flags.image_width != 0 && (flags.image_width < 64 || flags.image_width > 16384)) {
    throw InvalidInput("--width", std::to_string(flags.image_width), "[64, 16384]");
  }
  const study::MergedRuns merged = study::merge_runs(flags.folder);
  int image_width = flags.image_width;
  if (image_width == 0) image_width = merged.image_width != 0 ? merged.image_width : 1600;
  const std::string output = flags.output.empty() ? flags.folder : flags.output;
  if (merged.kind == RunKind::kEnsemble) {
    prepare_folder(output, flags.is_forced, {"ensemble.json", "ensemble.csv", "ensemble.png"});
    fmt::print("merge: ensemble of {} seeds\n", merged.ensemble.seeds.size());
    write_ensemble_summary(output, merged.plan.base, merged.ensemble, image_width);
    return;
  }
  prepare_folder(output, flags.is_forced, {"sweep.csv", "sweep.gp", "sweep.png"});
  fmt::print("merge: sweep of {} cases x {} seeds\n", merged.cases.size(),
             std::max<std::size_t>(1, merged.plan.seeds.size()));
  write_sweep_summary(output, merged.plan, merged.cases, flags.is_without_plot);
}

void register_merge(CLI::App& app) {
  auto flags = std::make_shared<MergeFlags>();
  auto* command = app.add_subcommand(
      "merge",
      "Summary of an ensemble or sweep run in parts (repose --seeds / sweep with --case K --of "
      "N): reads DIR/runs/*.json, checks they are one configuration and complete, and writes "
      "ensemble.json|csv|png or sweep.csv|gp|png as the single-process run does.");
  command->add_option("folder", flags->folder, "the workers' shared output folder")->required();
  command->add_option("-o,--output", flags->output, "where the summary goes (default: the folder)");
  command->add_option("--width", flags->image_width,
                      "ensemble.png width in pixels, [64, 16384] (default: the workers' --width)");
  command->add_flag("--no-plot", flags->is_without_plot, "sweep: do not run gnuplot");
  command->add_flag("-f,--force", flags->is_forced, "replace an existing summary");
  command->callback([flags, command]() {
    if (command->count("--output") > 0) check_output_folder_flag("-o/--output", flags->output);
    merge_run_folder(flags->folder, flags->output, flags->image_width, flags->is_without_plot,
                     flags->is_forced);
  });
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
