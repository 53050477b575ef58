// `aggpack pack` and `aggpack info`: pack particles from a TOML configuration into the native
// packing file, and print the statistics of a saved packing (issue 3).

#include <fmt/args.h>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/overloaded.h"
#include "aggpack/core/text.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/io/packing_stats_json.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/resources.h"
#include "aggpack/pack/statistics.h"
#include "aggpack/pipeline/pipeline.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"

namespace aggpack::cli {

namespace {

struct PackFlags {
  std::string config_path;
  std::vector<std::string> overrides;
  std::optional<std::string> output;
  std::optional<std::string> seed;  // as typed: parse_seed_flag
  std::optional<int> threads;
  bool is_forced = false;
  bool has_xdmf = false;
  int compression = 0;
  std::string progress = "auto";
  bool is_print_config = false;
  bool is_json = false;
};

// What the packer is about to do (the dense kind: its fill), for heavy_run_note.
RunEstimate estimate_of(const PackerOptions& packer) {
  const auto fill = Overloaded{
      [](const RandomPackOptions& options) { return estimate_run(options); },
      [](const LatticeOptions& options) {
        const auto counts = lattice_counts(options);
        return estimate_run(options, static_cast<double>(counts[0]) * counts[1] * counts[2]);
      }};
  return std::visit(
      Overloaded{fill, [&](const DensePackOptions& dense) { return std::visit(fill, dense.fill); }},
      packer);
}

// An output path of the run: a problem with it names where it came from (`key`: "-o/--output",
// "output.stl"; "" for the default name).
void check_output(const std::string& key, const std::string& path, Overwrite overwrite) {
  try {
    if (!key.empty() && key.front() != '-') check_output_file_flag(key, path);
    check_writable(path, overwrite);
  } catch (const IoError& error) {
    if (key.empty() || key.front() == '-') throw;
    throw IoError(key + ": " + error.what());
  }
}

// Re-indents a pretty-printed JSON value so it can sit at `indent` inside another object.
std::string nest_json(const std::string& json, int indent) {
  std::string out;
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const char c : json) {
    out += c;
    if (c == '\n') out += pad;
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

// "box 3 x 1 x 2.8 m, wall gap 0 m": the kind's summary pattern filled with its parameters.
std::string describe_container(const Container& c) {
  const ContainerKindInfo& kind = container_kind_info(c);
  fmt::dynamic_format_arg_store<fmt::format_context> values;
  // 6 significant digits: a typed 0.1 stays 0.1, a computed (enlarged, compressed) extent does
  // not print as 0.16913516956955746.
  const auto rounded = [](double value) { return std::stod(fmt::format("{:.6g}", value)); };
  for (const ContainerParam& param : kind.params) values.push_back(rounded(param.get(c)));
  // Only a periodic box says so: a walled container's summary reads as before.
  const std::string periodic =
      is_periodic(c) ? ", periodic in " + periodic_word(periodic_axes(c)) : "";
  return fmt::vformat(kind.summary, values) + periodic +
         fmt::format(", wall gap {} m", rounded(c.wall_gap));
}

std::string container_json(const Container& c) {
  const ContainerKindInfo& kind = container_kind_info(c);
  std::string json = fmt::format("{{\"kind\": \"{}\"", kind.name);
  for (const ContainerParam& param : kind.params) {
    json += fmt::format(", \"{}_m\": {}", param.name, param.get(c));
  }
  if (is_periodic(c))
    json += fmt::format(", \"periodic\": \"{}\"", periodic_word(periodic_axes(c)));
  return json + fmt::format(", \"wall_gap_m\": {}}}", c.wall_gap);
}

const char* stage_label(PackStage stage) {
  switch (stage) {
    case PackStage::kShapes:
      return "shapes";
    case PackStage::kPlacement:
      return "placing";
    case PackStage::kDensify:
      return "densify";
  }
  return "packing";
}

void warn(const std::string& text) {
  std::fprintf(stderr, "aggpack: warning: %s\n", aggpack::clipped(text, 1000).c_str());
}

// The dense kind's summary: the fill (in the enlarged container for fixed mode), the densifier,
// the final container and fraction against the asked one, the grading per sieve size.
void print_dense_summary(const PipelineResult& result, const std::vector<GradingPoint>& grading) {
  const DenseFill& fill = *result.fill;
  const PackReport& report = result.report;
  fmt::print("fill            {}\n", fill.report.summary());
  if (fill.scale != 1.0) {
    fmt::print("fill container  {} (the given one x {:.4f} in every extent)\n",
               describe_container(fill.container), fill.scale);
  }
  if (result.densify) fmt::print("densify         {}\n", result.densify->summary());
  fmt::print("particles       {}\n", report.placed);
  const Container& given = fill.given;
  const bool is_given = result.packing.container.shape == given.shape;
  fmt::print("container       {}{}\n", describe_container(result.packing.container),
             is_given ? "" : fmt::format(" (given: {})", describe_container(given)));
  fmt::print("solid volume    {:.6g} m^3\n", report.solid_volume);
  fmt::print("solid fraction  {:.4f}{}\n", report.solid_fraction,
             fill.asked_fraction > 0 ? fmt::format(" (asked {:.4f})", fill.asked_fraction) : "");
  if (result.densify && result.densify->bulk_fraction > 0) {
    fmt::print("bulk fraction   {:.4f} in z [{:.6g}, {:.6g}] m, free surface at {:.6g} m\n",
               result.densify->bulk_fraction, result.densify->bulk_lower,
               result.densify->bulk_upper, result.densify->surface_height);
  }
  fmt::print("{}", format_grading(grading));
}

// particle.library as the run loaded it: where from, shapes, skipped files, hull excess.
void print_library(const ShapeLibrary& library) {
  fmt::print("shape library   {}\n", library.summary());
  for (const std::string& line : library.skipped) {
    fmt::print("skipped         {}\n", aggpack::clipped(line, 300));
  }
  fmt::print("convex hulls    {}\n", library.hull_summary());
}

std::string library_json(const ShapeLibrary& library) {
  double mesh = 0.0;
  double hull = 0.0;
  for (const LibraryShape& shape : library.shapes) {
    mesh += shape.mesh_volume;
    hull += shape.hull_volume;
  }
  return fmt::format(
      ",\n  \"library\": {{\"source\": {}, \"shapes\": {}, \"skipped\": {}, \"units\": "
      "\"{}\", \"mesh_volume_m3\": {}, \"hull_volume_m3\": {}}}",
      aggpack::quoted(library.source), library.shapes.size(), library.skipped.size(),
      length_unit_name(library.units), mesh, hull);
}

void run_pack(const PackFlags& flags) {
  std::vector<std::string> overrides = flags.overrides;
  // --seed and --threads are shortcuts for --set and win over it.
  if (flags.seed) {
    overrides.push_back("packer.seed=" + std::to_string(parse_seed_flag("--seed", *flags.seed)));
  }
  const std::string threads_override =
      flags.threads ? "packer.threads=" + std::to_string(*flags.threads) : std::string();
  if (flags.threads) overrides.push_back(threads_override);
  const PackConfig config = [&] {
    try {
      return flags.config_path.empty() ? parse_pack_config("", "defaults", overrides)
                                       : load_pack_config(flags.config_path, overrides);
    } catch (const ConfigError& error) {
      // -j/--threads is typed as a flag: the message names it, not the --set it stands for.
      const std::string origin = "--set " + threads_override + ": ";
      const std::string message = error.what();
      if (!flags.threads || message.rfind(origin, 0) != 0) throw;
      throw ConfigError(error.key(), to_key_names({}, {{"packer.threads", "-j/--threads"}},
                                                  message.substr(origin.size())));
    }
  }();
  require_in_range("--compression", flags.compression, 0, 9);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  for (const auto& text : config.warnings) warn(text);

  // -o "" is refused like in every command (not taken as "no -o").
  if (flags.output) check_output_file_flag("-o/--output", *flags.output);
  const auto native = config.outputs.find("native");
  const std::string output_key = flags.output                     ? "-o/--output"
                                 : native != config.outputs.end() ? "output.native"
                                                                  : "";
  const std::string output = flags.output ? *flags.output
                             : native != config.outputs.end()
                                 ? native->second
                                 : fmt::format("aggpack-seed{}.h5", config.seed());
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  // output.<format> = path: written with the exporters' defaults after the native file (for
  // other options, e.g. mm or C3D10, use `aggpack export` on the native file).
  std::vector<std::pair<std::string, ExportOptions>> exports;
  std::vector<std::string> export_keys;  // "output.stl", for messages
  // Spelled differently ("./run.h5", "run.h5") is still the same file.
  // A path the file system cannot resolve (a name over 255 bytes) is compared as written; the
  // write check below names its problem.
  auto same_file = [](const std::string& a, const std::string& b) {
    std::error_code error_a;
    std::error_code error_b;
    const auto canonical_a = std::filesystem::weakly_canonical(a, error_a);
    const auto canonical_b = std::filesystem::weakly_canonical(b, error_b);
    if (error_a || error_b) {
      return std::filesystem::path(a).lexically_normal() ==
             std::filesystem::path(b).lexically_normal();
    }
    return canonical_a == canonical_b;
  };
  for (const auto& [format, path] : config.outputs) {
    if (format == "native") continue;
    ExportOptions options{.format = parse_export_format(format), .overwrite = overwrite};
    const bool is_taken =
        same_file(path, output) ||
        std::any_of(exports.begin(), exports.end(),
                    // Named capture: clang 14 (clang-tidy) cannot capture a structured binding.
                    [&, &target = path](const auto& e) { return same_file(target, e.first); });
    if (is_taken) {
      throw InvalidInput("output." + format, path,
                         "a path other than the native file's and the other outputs'");
    }
    validate(options, options.format);
    exports.emplace_back(path, options);
    export_keys.push_back("output." + format);
  }
  // --print-config shows only what a run would accept (the checks above), without touching files.
  if (flags.is_print_config) {
    fmt::print("{}", config.resolved_toml);
    return;
  }
  // Fail before the (possibly long) run, not after it: every output path, a file really created
  // in every output folder.
  check_output(output_key, output, overwrite);
  if (flags.has_xdmf) check_output(output_key, xdmf_path_for(output), overwrite);
  for (std::size_t i = 0; i < exports.size(); ++i) {
    check_output(export_keys[i], exports[i].first, overwrite);
  }
  set_thread_count(config.threads);
  // A run estimated above ~10 s or 1 GB says so at once, whatever --progress says.
  announce_heavy_run(estimate_of(config.packer));
  // All or nothing: if an [output] export fails after the native file was written, the files this
  // run created are removed and the ones it replaced (--force) are put back.
  OutputTransaction outputs;
  outputs.add(output);
  if (flags.has_xdmf) outputs.add(xdmf_path_for(output));
  for (const auto& entry : exports) outputs.add(entry.first);

  if (!flags.is_json) {
    fmt::print("aggpack pack: {} packer, seed {}, {}\n", config.packer_name(), config.seed(),
               describe_container(config.container()));
    std::fflush(stdout);
  }
  std::unique_ptr<ProgressBar> bar;
  std::optional<PackStage> stage;
  // A stage's work begins when the previous one last reported (or the run starts): its display's
  // time counts from there, so it agrees with the summary's "s shapes + s placement".
  auto stage_start = std::chrono::steady_clock::now();
  auto last_report = stage_start;
  // The duration each stage's display showed: the summary prints the same numbers.
  std::map<PackStage, double> shown_seconds;
  const auto finish_bar = [&](double seconds) {
    if (!bar) return;
    bar->finish(seconds);
    if (const auto shown = bar->shown_seconds()) shown_seconds[*stage] = *shown;
    bar.reset();
  };
  PackControl control;
  control.on_progress = [&](const PackProgress& progress) {
    if (!stage || *stage != progress.stage) {
      finish_bar(-1.0);  // the previous stage's display, by its clock
      if (stage) stage_start = last_report;
      stage = progress.stage;
      bar = std::make_unique<ProgressBar>(
          stage_label(progress.stage),
          progress.stage == PackStage::kDensify ? "sweeps" : "particles", style);
      bar->set_start(stage_start);
    }
    last_report = std::chrono::steady_clock::now();
    if (progress.stage == PackStage::kShapes) {
      // While shapes grow, `total` is the number grown so far; the final count is not known yet.
      bar->update(progress.fraction, progress.total, 0);
    } else {
      bar->update(progress.fraction, progress.placed, progress.total,
                  progress.solid_fraction > 0
                      ? fmt::format("solid {:.1f} %", 100.0 * progress.solid_fraction)
                      : std::string());
    }
  };
  PipelineResult result = [&] {
    try {
      return pack(config, control);
    } catch (const Error& error) {
      // A value the run itself refuses (a library path that is not there, ...) given with
      // --set: named as the --set typed, as the configuration's own checks name it.
      const std::string* typed =
          error.has_value() ? last_override_of(overrides, error.field()) : nullptr;
      if (typed == nullptr || error.kind() != ErrorKind::kInvalidInput) throw;
      throw ConfigError(error.field(), "--set " + clipped(*typed, 100) + ": ", error.field(),
                        error.value(), error.wording());
    }
  }();
  // The last stage's display ends with the run's own measurement of it.
  if (stage) {
    const PackReport& measured = result.report;
    finish_bar(*stage == PackStage::kShapes    ? measured.shape_seconds
               : *stage == PackStage::kDensify ? (result.densify ? result.densify->seconds : -1.0)
                                               : measured.placement_seconds);
  }
  const auto seconds_of = [&](PackStage which, double measured) {
    const auto found = shown_seconds.find(which);
    return found != shown_seconds.end() ? found->second : measured;
  };
  const double shape_seconds = seconds_of(PackStage::kShapes, result.report.shape_seconds);
  const double placement_seconds =
      seconds_of(PackStage::kPlacement, result.report.placement_seconds);

  Packing& packing = result.packing;
  write(packing, output,
        {.format = ExportFormat::kNative,
         .overwrite = overwrite,
         .compression = flags.compression,
         .write_xdmf = flags.has_xdmf});

  std::vector<std::string> written;
  std::vector<std::string> written_json;
  for (const auto& [path, options] : exports) {
    const ExportSummary summary = write(packing, path, options);
    const bool has_quality = summary.quality.tetrahedra > 0;
    written.push_back(fmt::format("{} ({}, {} nodes, {} elements{})", path,
                                  format_name(summary.format), summary.nodes, summary.elements,
                                  has_quality ? "; " + describe_quality(summary.quality) : ""));
    written_json.push_back(fmt::format(
        "{{\"path\": {}, \"format\": \"{}\", \"nodes\": {}, \"elements\": {}{}}}",
        aggpack::quoted(path), format_name(summary.format), summary.nodes, summary.elements,
        has_quality ? ", \"quality\": " + quality_json(summary.quality) : ""));
  }

  outputs.commit();

  const PackReport& report = result.report;
  // The dense kind: its final packing's grading against the target, per sieve size.
  std::vector<GradingPoint> grading;
  if (const std::optional<Grading> target = config.target_grading(); target && result.fill) {
    grading = achieved_grading(packing, *target);
  }
  if (flags.is_json) {
    std::string exports_json;
    for (const auto& entry : written_json) {
      exports_json += (exports_json.empty() ? "\n    " : ",\n    ") + entry;
    }
    std::string dense_json;
    if (result.fill) {
      dense_json += fmt::format(
          ",\n  \"container\": {},\n  \"fill\": {{\n    \"container\": {},\n    \"scale\": {},\n"
          "    \"asked_fraction\": {},\n    \"report\": {}\n  }}",
          container_json(packing.container), container_json(result.fill->container),
          result.fill->scale, result.fill->asked_fraction,
          nest_json(to_json(result.fill->report, 2), 4));
    }
    if (result.densify) {
      dense_json += ",\n  \"densify\": " + nest_json(to_json(*result.densify, 2), 2);
    }
    if (result.fill) dense_json += ",\n  \"grading\": " + nest_json(to_json(grading, 2), 2);
    if (result.library) dense_json += library_json(*result.library);
    fmt::print("{{\n  \"output\": {},\n  \"report\": {}{}{}\n}}\n", aggpack::quoted(output),
               nest_json(to_json(report, 2), 2), dense_json,
               written_json.empty() ? "" : ",\n  \"exports\": [" + exports_json + "\n  ]");
  } else if (result.fill) {
    print_dense_summary(result, grading);
    fmt::print("time            {} s shapes + {} s placement{}\n", format_seconds(shape_seconds),
               format_seconds(placement_seconds),
               result.densify
                   ? fmt::format(" + {} s densify", format_seconds(result.densify->seconds))
                   : "");
  } else {
    fmt::print("{}\n", report.summary());
    fmt::print("particles       {}\n", report.placed);
    fmt::print("solid volume    {:.6g} m^3\n", report.solid_volume);
    fmt::print("solid fraction  {:.4f}\n", report.solid_fraction);
    fmt::print("time            {} s shapes + {} s placement\n", format_seconds(shape_seconds),
               format_seconds(placement_seconds));
  }
  if (!flags.is_json) {
    if (result.library) print_library(*result.library);
    fmt::print("wrote {}{}\n", output,
               flags.has_xdmf ? " and " + xdmf_path_for(output) : std::string());
    for (const auto& line : written) fmt::print("wrote {}\n", line);
  }
  if (result.fill) {
    for (const std::string& line : dense_shortfalls(result)) warn(line);
  } else if (!report.is_target_reached) {
    warn("target not reached (" + to_string(report.stop_reason) + "): placed " +
         std::to_string(report.placed) + " of " + std::to_string(report.requested) +
         " particles; the file holds what was placed");
  }
}

// particle.library's provenance (Provenance::shape_library): the header line, then the files and
// their content hashes (the first 20; shape k of the file is line k).
void print_shape_library(const std::string& text) {
  std::size_t start = 0;
  std::size_t line = 0;
  constexpr std::size_t kListed = 20;
  std::size_t total = 0;
  for (const char c : text) total += c == '\n' ? 1 : 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string row = text.substr(start, end - start);
    std::replace(row.begin(), row.end(), '\t', ' ');
    if (line == 0) {
      fmt::print("shape library   {}\n", row);
    } else if (line <= kListed) {
      fmt::print("  shape {:<6} {}\n", line - 1, row);
    }
    start = end + 1;
    ++line;
  }
  if (total > kListed + 1) fmt::print("  ... and {} more\n", total - kListed - 1);
}

void run_info(const std::string& path, bool is_json, int bins, bool has_descriptors) {
  require_in_range("--bins", bins, 1, 10000);
  const Packing packing = read_packing(path);
  StatisticsOptions options{.bins = bins, .has_descriptors = has_descriptors};
  // The stored configuration names the target grading; compare against it when it parses.
  bool has_config = false;
  std::string config_problem;
  if (!packing.provenance.config_toml.empty()) {
    try {
      options.target = parse_pack_config(packing.provenance.config_toml, "/provenance/config_toml")
                           .target_grading();
      has_config = true;
    } catch (const Error& error) {
      // Written by another version or tool: statistics without the target.
      config_problem = error.what();
    }
  }
  const PackingStatistics statistics = compute_statistics(packing, options);
  const Provenance& p = packing.provenance;
  if (is_json) {
    fmt::print(
        "{{\n  \"file\": {},\n  \"format_version\": {},\n  \"aggpack_version\": {},\n"
        "  \"packer\": {},\n  \"seed\": {},\n  \"container\": {},\n  \"statistics\": {}\n}}\n",
        aggpack::quoted(path), kNativeFormatVersion, aggpack::quoted(p.aggpack_version),
        aggpack::quoted(p.packer), p.seed, container_json(packing.container),
        nest_json(to_json(statistics, 2), 2));
    return;
  }
  fmt::print("file            {} ({} v{}, written by aggpack {})\n", path, kNativeFormatName,
             kNativeFormatVersion, p.aggpack_version);
  fmt::print("packer          {}, seed {}\n", p.packer.empty() ? "(unknown)" : p.packer, p.seed);
  fmt::print("container       {}\n", describe_container(packing.container));
  if (!p.shape_library.empty()) print_shape_library(p.shape_library);
  if (!has_config && !p.config_toml.empty()) {
    fmt::print(
        "note            stored configuration not readable ({}); no target grading\n",
        config_problem.size() <= 200 ? config_problem : config_problem.substr(0, 200) + "...");
  }
  fmt::print("{}", format_statistics(statistics));
}

}  // namespace

void register_pack(CLI::App& app) {
  auto flags = std::make_shared<PackFlags>();
  auto* command = app.add_subcommand(
      "pack",
      "Pack particles into a container (the paper's lattice placement or random sequential "
      "addition) and write the native packing file (.h5). Without a config: the paper's case, "
      "1,050 particles in a 3.0 x 1.0 x 2.8 m box. Keys: docs/config.md.");
  command->add_option("config", flags->config_path,
                      "TOML configuration file (omit for the paper's case)");
  command
      ->add_option("--set", flags->overrides,
                   "override one config key, KEY=VALUE with a dotted key, e.g. --set "
                   "packer.gap=0.001 (repeatable; applied in order, after the file)")
      ->allow_extra_args(false);
  command->add_option("-o,--output", flags->output,
                      "native packing file to write (default: output.native from the config, "
                      "else aggpack-seed<SEED>.h5)");
  command->add_option("--seed", flags->seed, "master seed, same as --set packer.seed=N");
  command->add_option("-j,--threads", flags->threads,
                      "worker threads, 0 = all cores (same as --set packer.threads=N; results do "
                      "not depend on it)");
  command->add_flag("-f,--force", flags->is_forced, "replace existing output files");
  command->add_flag("--xdmf", flags->has_xdmf,
                    "also store world-coordinate surfaces and write <output>.xdmf for ParaView");
  command
      ->add_option("--compression", flags->compression,
                   "deflate level of the .h5 datasets, 0 (none) .. 9")
      ->capture_default_str();
  command
      ->add_option("--progress", flags->progress,
                   "progress display on stderr: auto (bar on a terminal, else lines), bar, lines, "
                   "none")
      ->capture_default_str();
  command->add_flag("--print-config", flags->is_print_config,
                    "print the resolved configuration (every effective key) and exit");
  command->add_flag("--json", flags->is_json, "print the pack report as JSON on stdout");
  command->callback([flags]() { run_pack(*flags); });
}

void register_info(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto is_json = std::make_shared<bool>(false);
  auto bins = std::make_shared<int>(10);
  auto is_without_descriptors = std::make_shared<bool>(false);
  auto* command = app.add_subcommand(
      "info",
      "Print the statistics of a saved packing: count, solid volume and fraction (global and "
      "along x, y, z), achieved vs target grading, shape-descriptor summaries.");
  command->add_option("file", *path, "native packing file (.h5)")->required();
  command->add_flag("--json", *is_json, "print JSON instead of the readable summary");
  command->add_option("--bins", *bins, "bins per axis for the solid-fraction profiles, [1, 10000]")
      ->capture_default_str();
  command->add_flag("--no-descriptors", *is_without_descriptors,
                    "skip the per-particle shape descriptors (faster for large packings)");
  command->callback([=]() { run_info(*path, *is_json, *bins, !*is_without_descriptors); });
}

}  // namespace aggpack::cli
