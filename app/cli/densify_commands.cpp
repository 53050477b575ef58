// `aggpack densify IN.h5 -o OUT.h5`: the densifying packer (HPMC compression or gravity bed) on a
// saved packing (issue 14). Thin front end over aggpack/pack/dense_packer.h.

#include <fmt/core.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/grading.h"
#include "aggpack/pack/statistics.h"
#include "aggpack/pipeline/pipeline.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"

namespace aggpack::cli {

namespace {

struct DensifyFlags {
  std::string input;
  std::string output;
  std::string mode = "fixed";
  double target_fraction = 0.0;
  std::string target_container;
  std::optional<double> gap;
  std::uint64_t sweeps = 2000;
  double max_time = 0.0;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string progress = "auto";
  bool is_forced = false;
  std::string trace;
  bool has_trace = false;  // --trace given (--trace '' is refused, not taken as none)
  double bed_temperature = DensifyOptions{}.bed_temperature;
  double bed_cooling = DensifyOptions{}.bed_cooling;
};

// "L,W,D" for a box, "R,H" for a cylinder (metres), same kind as the input's container.
Container parse_target_container(const std::string& text, const Container& start) {
  std::vector<double> values;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t comma = text.find(',', begin);
    if (comma == std::string::npos) comma = text.size();
    const std::string item = text.substr(begin, comma - begin);
    try {
      std::size_t used = 0;
      const double value = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(value)) throw std::invalid_argument(item);
      values.push_back(value);
    } catch (const std::exception&) {
      values.clear();
      break;
    }
    begin = comma + 1;
  }
  // One value per parameter of the input's kind, in order ("LENGTH,WIDTH,DEPTH" for a box).
  const ContainerKindInfo& kind = container_kind_info(start);
  if (values.size() != kind.params.size()) {
    std::string names;
    for (const ContainerParam& param : kind.params) {
      if (!names.empty()) names += ",";
      for (const char* c = param.name; *c != '\0'; ++c) {
        names += static_cast<char>(std::toupper(static_cast<unsigned char>(*c)));
      }
    }
    throw InvalidInput("--target-container", text,
                       names + " in metres (the input holds a " + kind.name + ")");
  }
  Container target = start;
  for (std::size_t i = 0; i < values.size(); ++i) kind.params[i].set(target, values[i]);
  return target;
}

// The packer gap the input was made with (packer.gap of its stored configuration), else 0.
double stored_gap(const Packing& packing) {
  if (packing.provenance.config_toml.empty()) return 0.0;
  try {
    const PackConfig config =
        parse_pack_config(packing.provenance.config_toml, "/provenance/config_toml");
    if (const auto* dense = std::get_if<DensePackOptions>(&config.packer)) {
      return dense->densify.gap;
    }
    const auto* random = std::get_if<RandomPackOptions>(&config.packer);
    return random != nullptr ? random->gap : 0.0;
  } catch (const Error&) {
    return 0.0;
  }
}

// The target grading of the input's stored configuration, if it names one.
std::optional<Grading> stored_grading(const Packing& packing) {
  if (packing.provenance.config_toml.empty()) return std::nullopt;
  try {
    return parse_pack_config(packing.provenance.config_toml, "/provenance/config_toml")
        .target_grading();
  } catch (const Error&) {
    return std::nullopt;
  }
}

// The densify run, as TOML comments appended to the stored configuration (the pack keys stay
// parseable by `aggpack info`; issue 13 gives densify its own config table).
std::string provenance_lines(const DensifyFlags& flags, const DensifyOptions& options) {
  std::string text = "\n# aggpack densify (packer = \"dense\") applied to " + flags.input + ":\n";
  text += fmt::format("# densify.mode = \"{}\"\n", to_string(options.mode));
  text += fmt::format("# densify.target_fraction = {}\n", options.target_fraction);
  if (options.target_container) {
    text += fmt::format("# densify.target_container = \"{}\"\n", flags.target_container);
  }
  text += fmt::format("# densify.gap = {}\n", options.gap);
  text += fmt::format("# densify.seed = {}\n", options.seed);
  text += fmt::format("# densify.max_sweeps = {}\n", options.max_sweeps);
  text += fmt::format("# densify.max_seconds = {}\n", options.max_seconds);
  if (options.mode == DensifyMode::kBed) {
    text += fmt::format("# densify.bed_temperature = {}\n", options.bed_temperature);
    text += fmt::format("# densify.bed_cooling = {}\n", options.bed_cooling);
  }
  return text;
}

// densify takes flags: the library's option names (densify.max_sweeps, ...) become the flags.
std::map<std::string, std::string> densify_flag_names() {
  std::map<std::string, std::string> names = {
      {"densify.target_fraction", "--target-fraction"},
      {"densify.target_container", "--target-container"},
      {"densify.target_container.wall_gap", "--target-container (wall gap)"},
      {"densify.gap", "--gap"},
      {"densify.max_sweeps", "--sweeps"},
      {"densify.max_seconds", "--max-time"},
      {"densify.bed_temperature", "--bed-temperature"},
      {"densify.bed_cooling", "--bed-cooling"},
  };
  for (const ContainerKindInfo& kind : container_kinds()) {
    for (const ContainerParam& param : kind.params) {
      names.emplace(std::string("densify.target_container.") + param.name,
                    std::string("--target-container (") + param.name + ")");
    }
  }
  return names;
}

void run_densify(const DensifyFlags& flags) {
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  if (flags.threads < 0) throw InvalidInput("-j/--threads", std::to_string(flags.threads), ">= 0");
  check_output_file_flag("-o/--output", flags.output);
  if (flags.has_trace) check_output_file_flag("--trace", flags.trace);
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  check_writable(flags.output, overwrite);
  Packing start = read_packing(flags.input);
  const std::optional<Grading> target = stored_grading(start);
  DensifyOptions options;
  options.mode = parse_densify_mode("--mode", flags.mode);
  options.target_fraction = flags.target_fraction;
  if (!flags.target_container.empty()) {
    options.target_container = parse_target_container(flags.target_container, start.container);
  }
  options.gap = flags.gap ? *flags.gap : stored_gap(start);
  options.seed = flags.seed;
  options.max_sweeps = flags.sweeps;
  options.max_seconds = flags.max_time;
  options.bed_temperature = flags.bed_temperature;
  options.bed_cooling = flags.bed_cooling;
  const std::map<std::string, std::string> flag_names = densify_flag_names();
  with_key_names({}, flag_names, [&] { validate(options); });
  set_thread_count(flags.threads);
  announce_heavy_run(estimate_densify(static_cast<double>(start.particles.size()),
                                      static_cast<double>(options.max_sweeps), options.max_seconds,
                                      allowed_threads()));

  fmt::print("aggpack densify: {} mode, {} particles, gap {} m, seed {}\n", to_string(options.mode),
             start.particles.size(), options.gap, options.seed);
  std::fflush(stdout);
  std::unique_ptr<ProgressBar> bar;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> trace(nullptr, &std::fclose);
  if (!flags.trace.empty()) {
    check_writable(flags.trace, Overwrite::kAllow);
    trace.reset(std::fopen(flags.trace.c_str(), "w"));
    if (!trace) throw IoError("cannot write " + flags.trace);
    std::fprintf(trace.get(), "# seconds sweeps solid_fraction cpu_seconds\n");
  }
  const auto began = std::chrono::steady_clock::now();
  PackControl control;
  control.on_progress = [&](const PackProgress& progress) {
    if (trace) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
      // CPU time of the whole process (every thread): the fair clock on a shared machine.
      const double cpu = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
      std::fprintf(trace.get(), "%.3f %llu %.6f %.3f\n", seconds,
                   static_cast<unsigned long long>(progress.placed), progress.solid_fraction, cpu);
    }
    if (!bar) {
      bar = std::make_unique<ProgressBar>("densify", "sweeps", style);
      bar->set_start(began);  // the work began before its first report
    }
    bar->update(progress.fraction, progress.placed, progress.total,
                fmt::format("solid {:.2f} %", 100.0 * progress.solid_fraction));
  };
  PipelineResult result;
  with_key_names({}, flag_names, [&] {
    result = densify_packing(std::move(start), options, provenance_lines(flags, options), control);
  });
  const DensifyReport& report = *result.densify;
  // One measurement: the display's final line shows the run's time, as the summary does.
  if (bar) bar->finish(report.seconds);
  bar.reset();
  write_packing(result.packing, flags.output, {.overwrite = overwrite});
  fmt::print("{}: {}\n", to_string(options.mode), report.summary());
  fmt::print("solid fraction  {:.4f} (start {:.4f})\n", report.solid_fraction,
             report.start_fraction);
  if (options.mode == DensifyMode::kBed) {
    fmt::print("bulk fraction   {:.4f} in z [{:.6g}, {:.6g}] m, free surface at {:.6g} m\n",
               report.bulk_fraction, report.bulk_lower, report.bulk_upper, report.surface_height);
  }
  fmt::print("moves           {} tried, {} accepted; {} container shrinks\n", report.moves_tried,
             report.moves_accepted, report.compressions);
  fmt::print("verified        {} close pairs by the exact test, min distance {:.6g} m\n",
             report.verified_pairs, report.min_distance);
  // The grading of the final packing against the input's target, per sieve size (shapes and
  // sizes never change, so it is the input's).
  if (target) fmt::print("{}", format_grading(achieved_grading(result.packing, *target)));
  fmt::print("wrote {}\n", flags.output);
}

}  // namespace

void register_densify(CLI::App& app) {
  auto flags = std::make_shared<DensifyFlags>();
  auto* command = app.add_subcommand(
      "densify",
      "Densify a saved packing by hard-particle Monte Carlo (exact, overlap-free at every step): "
      "compress it toward a target container / fraction (--mode fixed) or let it sink as a "
      "gravity bed (--mode bed). Docs: docs/densify.md.");
  command->add_option("input", flags->input, "native packing file to start from (.h5)")->required();
  command->add_option("-o,--output", flags->output, "native packing file to write")->required();
  command->add_option("--mode", flags->mode, "fixed (compress) or bed (gravity bed)")
      ->capture_default_str();
  command->add_option("--target-fraction", flags->target_fraction,
                      "fixed: stop at this solid fraction, [0, 0.95); 0 = none; without "
                      "--target-container the container shrinks uniformly to reach it");
  command->add_option("--target-container", flags->target_container,
                      "fixed: compress toward this container: L,W,D (box) or R,H (cylinder) in m, "
                      "no extent larger than the input's");
  command
      ->add_option("--bed-temperature", flags->bed_temperature,
                   "bed: initial temperature, >= 0 (a mean particle rising one bounding radius is "
                   "accepted with probability exp(-1/T))")
      ->capture_default_str();
  command
      ->add_option("--bed-cooling", flags->bed_cooling, "bed: temperature factor per sweep, (0, 1]")
      ->capture_default_str();
  command->add_option("--gap", flags->gap,
                      "minimum particle distance (m), >= 0 (default: packer.gap of the input)");
  command->add_option("--sweeps", flags->sweeps, "sweep budget, [1, 1e9]")->capture_default_str();
  command->add_option("--max-time", flags->max_time,
                      "wall-time budget (s), 0 = none (a run stopped by time is not reproducible)");
  command->add_option("--seed", flags->seed, "seed of the Monte Carlo streams")
      ->capture_default_str();
  command->add_option("-j,--threads", flags->threads,
                      "worker threads, 0 = all cores (results do not depend on it)");
  command->add_option("--progress", flags->progress, "auto, bar, lines, none")
      ->capture_default_str();
  command->add_flag("-f,--force", flags->is_forced, "replace an existing output file");
  command->add_option("--trace", flags->trace,
                      "write 'seconds sweeps solid_fraction' lines (every progress update) to "
                      "this file, for a fraction-vs-time plot");
  command->callback([flags, command]() {
    flags->has_trace = command->count("--trace") > 0;
    run_densify(*flags);
  });
}

}  // namespace aggpack::cli
