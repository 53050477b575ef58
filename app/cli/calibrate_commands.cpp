// `aggpack calibrate`: particles to a measured target (issue 15, item 1). Finds the Eq. 3 alpha
// whose particles match a measured mean V / V_circumscribed-sphere, Eq. 2 alpha or sphericity.

#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/shape/calibrate.h"
#include "calibrate_plot.h"
#include "commands.h"

namespace aggpack::cli {

namespace {

struct CalibrateFlags {
  CalibrationOptions options;
  double volume_ratio = 0;
  double volume = 0;
  double alpha = 0;
  double sphericity = 0;
  double elongation = 0;
  double flatness = 0;
  std::string sphere = "enclosing";  // which circumscribed sphere --volume(-ratio) refers to
  int samples = 200;
  int grid = 11;
  double seed = 1;  // read as a number, checked to be a whole number >= 0
  std::string table;
  std::string plot;
  int threads = 0;
  bool is_forced = false;
};

// Exactly one target option; --volume is V in m^3 at --diameter, i.e. a volume ratio.
void resolve_target(CalibrateFlags& flags, const CLI::App& command) {
  const char* names[] = {"--volume-ratio", "--volume",     "--alpha",
                         "--sphericity",   "--elongation", "--flatness"};
  int given = 0;
  for (const char* name : names) given += command.count(name) > 0 ? 1 : 0;
  if (given != 1) {
    throw InvalidInput("--volume-ratio/--volume/--alpha/--sphericity/--elongation/--flatness",
                       std::to_string(given) + " given", "exactly one");
  }
  auto& o = flags.options;
  require_positive("--diameter", o.diameter);
  const double sphere = std::numbers::pi / 6.0 * o.diameter * o.diameter * o.diameter;
  if (flags.sphere != "enclosing" && flags.sphere != "control") {
    throw InvalidInput("--sphere", flags.sphere, "enclosing or control");
  }
  const CalibrationTarget volume_target = flags.sphere == "enclosing"
                                              ? CalibrationTarget::kEnclosedVolumeRatio
                                              : CalibrationTarget::kVolumeRatio;
  if (command.count("--volume-ratio") > 0) {
    require_in_range("--volume-ratio", flags.volume_ratio, 1e-9, 1.0);
    o.target = volume_target;
    o.value = flags.volume_ratio;
  } else if (command.count("--volume") > 0) {
    require_in_range("--volume", flags.volume, 1e-30, sphere);
    o.target = volume_target;
    o.value = flags.volume / sphere;
  } else if (command.count("--alpha") > 0) {
    require_in_range("--alpha", flags.alpha, 1e-9, 1.0);
    o.target = CalibrationTarget::kMeasuredAlpha;
    o.value = flags.alpha;
  } else if (command.count("--sphericity") > 0) {
    require_in_range("--sphericity", flags.sphericity, 1e-9, 1.0);
    o.target = CalibrationTarget::kSphericity;
    o.value = flags.sphericity;
  } else if (command.count("--elongation") > 0) {
    require_in_range("--elongation", flags.elongation, 1e-9, 1.0);
    o.target = CalibrationTarget::kElongation;
    o.value = flags.elongation;
  } else {
    require_in_range("--flatness", flags.flatness, 1e-9, 1.0);
    o.target = CalibrationTarget::kFlatness;
    o.value = flags.flatness;
  }
  require_in_range("--edge-ratio", o.edge_ratio, 0.05, 1.5);
  if (flags.samples < 2 || flags.samples > 100000) {
    throw InvalidInput("--samples", std::to_string(flags.samples), "[2, 100000]");
  }
  if (flags.grid < 3 || flags.grid > 101) {
    throw InvalidInput("--grid", std::to_string(flags.grid), "[3, 101]");
  }
  if (!(flags.seed >= 0.0 && flags.seed <= 9007199254740992.0) ||
      flags.seed != std::floor(flags.seed)) {
    throw InvalidInput("--seed", format_value(flags.seed), "a whole number in [0, 2^53]");
  }
  o.samples = static_cast<std::size_t>(flags.samples);
  o.grid_points = static_cast<std::size_t>(flags.grid);
  o.seed = static_cast<std::uint64_t>(flags.seed);
}

void write_table(const std::string& path, const CalibrationOptions& options,
                 const CalibrationResult& result, Overwrite overwrite) {
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  const std::string name = calibration_target_name(options.target);
  out << "alpha," << name << "_mean," << name << "_sd,samples,target\n";
  for (const auto& point : result.evaluated) {
    out << fmt::format("{:.17g},{:.17g},{:.17g},{},{:.17g}\n", point.alpha, point.achieved.mean,
                       point.achieved.standard_deviation, point.achieved.count, options.value);
  }
  file.commit();
}

}  // namespace

void register_calibrate(CLI::App& app) {
  auto flags = std::make_shared<CalibrateFlags>();
  auto& o = flags->options;
  auto* command = app.add_subcommand(
      "calibrate",
      "Find the Eq. 3 alpha whose particles match a measured mean descriptor (V / V_circ, Eq. 2 "
      "alpha, sphericity, elongation or flatness); print the inputs, the achieved mean +- sd and "
      "the config lines.");
  command->add_option("--volume-ratio", flags->volume_ratio,
                      "target mean V / V_circumscribed-sphere (the paper's Table 1 alpha), (0, 1]");
  command->add_option("--volume", flags->volume,
                      "target mean particle volume (m^3) at --diameter (= a volume ratio)");
  command->add_option("--alpha", flags->alpha, "target mean Eq. 2 measured alpha, (0, 1]");
  command->add_option("--sphericity", flags->sphericity, "target mean Eq. 1 sphericity, (0, 1]");
  command->add_option("--elongation", flags->elongation,
                      "target mean elongation (intermediate / long), (0, 1]");
  command->add_option("--flatness", flags->flatness,
                      "target mean flatness (short / intermediate), (0, 1]");
  command->add_option("--diameter", o.diameter, "circumscribed diameter D (m), see --sphere")
      ->capture_default_str();
  command
      ->add_option("--sphere", flags->sphere,
                   "the circumscribed sphere of --volume/--volume-ratio/--diameter: "
                   "'enclosing' (each particle's smallest enclosing sphere, as measured on real "
                   "particles; R is scaled so the mean enclosing diameter is D) or 'control' "
                   "(the generator's sphere of radius R = D / 2)")
      ->capture_default_str();
  command->add_option("--edge-ratio", o.edge_ratio, "edge-length ratio L / R, [0.05, 1.5]")
      ->capture_default_str();
  command->add_option("--samples", flags->samples, "particles per evaluated alpha, [2, 100000]")
      ->capture_default_str();
  command->add_option("--grid", flags->grid, "alpha grid points in [0, 1], [3, 101]")
      ->capture_default_str();
  command->add_option("--seed", flags->seed, "seed of every evaluation's particles")
      ->capture_default_str();
  command->add_option("--table", flags->table, "CSV of the search: alpha, mean, sd");
  command->add_option("--plot", flags->plot, "PNG of the search: mean +- sd vs alpha, target");
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command->add_flag("-f,--force", flags->is_forced, "replace existing output files");
  command->callback([=, &app]() {
    const auto* self = app.get_subcommand("calibrate");
    resolve_target(*flags, *self);
    set_thread_count(flags->threads);
    const Overwrite overwrite = flags->is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    if (!flags->table.empty()) check_writable(flags->table, overwrite);
    if (!flags->plot.empty()) {
      check_writable(flags->plot, overwrite);
    }
    const CalibrationOptions& options = flags->options;
    const CalibrationResult result = calibrate(options);
    const std::string name = calibration_target_name(options.target);
    const double miss = 100.0 * (result.achieved.mean - options.value) / options.value;
    fmt::print("target        {} = {:.6g}\n", name, options.value);
    fmt::print("reachable     [{:.6g}, {:.6g}] over alpha in [0, 1] at L/R = {:.6g}\n",
               result.reachable_minimum, result.reachable_maximum, options.edge_ratio);
    fmt::print("found         alpha = {:.6g} (Eq. 3 input), R = {:.6g} m, L = {:.6g} m\n",
               result.alpha, result.radius, result.edge_length);
    fmt::print("achieved      {} = {:.6g} +- {:.3g} (sd, {} particles, seed {}): {:+.2f} %\n", name,
               result.achieved.mean, result.achieved.standard_deviation, result.achieved.count,
               options.seed, miss);
    fmt::print("volume        {:.6g} +- {:.3g} mm^3 (sphere of diameter D: {:.6g} mm^3)\n",
               result.volume.mean * 1e9, result.volume.standard_deviation * 1e9,
               std::numbers::pi / 6.0 * std::pow(options.diameter, 3) * 1e9);
    fmt::print(
        "enclosing     diameter {:.6g} +- {:.3g} mm (smallest sphere around each particle; "
        "control sphere 2R = {:.6g} mm)\n",
        2e3 * result.enclosing_radius.mean, 2e3 * result.enclosing_radius.standard_deviation,
        2e3 * result.radius);
    for (std::size_t t = 0; t < result.all_descriptors.size(); ++t) {
      if (kCalibrationTargets[t] == options.target) continue;
      fmt::print("also          {} = {:.6g} +- {:.3g}\n",
                 calibration_target_name(kCalibrationTargets[t]), result.all_descriptors[t].mean,
                 result.all_descriptors[t].standard_deviation);
    }
    fmt::print("evaluations   {} (grid {} + bisection)\n", result.evaluated.size(),
               options.grid_points);
    if (std::abs(miss) > 2.0) {
      fmt::print("warning: the closest mean found misses the target by {:.2f} % (> 2 %)\n", miss);
    }
    fmt::print(
        "config lines (under [particles] in repose/sweep configs, [particle] in pack configs):\n"
        "alpha = {:.6g}\nradius = {:.6g}\nedge_length = {:.6g}\n",
        result.alpha, result.radius, result.edge_length);
    if (!flags->table.empty()) {
      write_table(flags->table, options, result, overwrite);
      fmt::print("wrote {}\n", flags->table);
    }
    if (!flags->plot.empty()) {
      write_calibration_plot(flags->plot, options, result);
      fmt::print("wrote {}\n", flags->plot);
    }
  });
}

}  // namespace aggpack::cli
