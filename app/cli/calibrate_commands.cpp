// `aggpack calibrate`: particles to measured targets. Finds the generator inputs whose particles
// match up to three measured mean descriptors (V / V_circ, Eq. 2 alpha, sphericity, elongation,
// flatness) at once.

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/shape/calibrate.h"
#include "calibrate_plot.h"
#include "commands.h"
#include "output_flags.h"

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
  double edge_ratio = 0;  // 0 = searched
  std::string growth = "hull";
  std::string sphere = "enclosing";  // which circumscribed sphere --volume(-ratio) refers to
  int samples = 200;
  std::uint64_t seed = 1;
  std::string table;
  std::string plot;
  int threads = 0;
  bool is_forced = false;
  std::string above_sphere_flag;        // a target typed above its (0, 1] range: searched as 1
  std::vector<std::string> goal_flags;  // the flag each goal came from, in goal order
};

// The target options given (up to three), each checked under its own flag; --volume is V in m^3
// at --diameter, i.e. a volume ratio.
void resolve_goals(CalibrateFlags& flags, const CLI::App& command) {
  auto& o = flags.options;
  require_positive("--diameter", o.diameter);
  if (flags.sphere != "enclosing" && flags.sphere != "control") {
    throw InvalidInput("--sphere", flags.sphere, "enclosing or control");
  }
  const CalibrationTarget volume_target = flags.sphere == "enclosing"
                                              ? CalibrationTarget::kEnclosedVolumeRatio
                                              : CalibrationTarget::kVolumeRatio;
  const double sphere = std::numbers::pi / 6.0 * o.diameter * o.diameter * o.diameter;
  if (command.count("--volume-ratio") > 0 && command.count("--volume") > 0) {
    throw InvalidInput("--volume", format_value(flags.volume),
                       "either --volume (with --diameter) or --volume-ratio, not both");
  }
  o.goals.clear();
  flags.goal_flags.clear();
  const auto add = [&](const char* flag, CalibrationTarget target, double typed, double value,
                       double hi) {
    if (command.count(flag) == 0) return;
    const bool is_volume = std::string_view(flag) == "--volume";
    if (typed > hi && std::isfinite(typed)) {
      // More than the whole sphere (or a ratio above 1): no particle has it. The search is asked
      // for 1 and the refusal names the closest reachable value of this flag, whether the search
      // ends within its tolerance of 1 (above_range_in_user_words) or not
      // (unreached_in_user_words).
      value = 1.0;
      flags.above_sphere_flag = flag;
    } else if (!(typed >= hi * 1e-9 && typed <= hi)) {
      if (!is_volume) require_in_range(flag, typed, hi * 1e-9, hi);
      throw InvalidInput(
          flag, format_value(typed) + " m^3",
          fmt::format("{} to {} m^3 (up to the volume of the sphere of --diameter {} m)",
                      format_value(hi * 1e-9), format_value(hi), format_value(o.diameter)));
    }
    o.goals.push_back({.target = target, .value = value});
    flags.goal_flags.emplace_back(flag);
  };
  add("--volume", volume_target, flags.volume, flags.volume / sphere, sphere);
  if (command.count("--volume") > 0) o.volume = flags.volume;
  add("--volume-ratio", volume_target, flags.volume_ratio, flags.volume_ratio, 1.0);
  add("--alpha", CalibrationTarget::kMeasuredAlpha, flags.alpha, flags.alpha, 1.0);
  add("--sphericity", CalibrationTarget::kSphericity, flags.sphericity, flags.sphericity, 1.0);
  add("--elongation", CalibrationTarget::kElongation, flags.elongation, flags.elongation, 1.0);
  add("--flatness", CalibrationTarget::kFlatness, flags.flatness, flags.flatness, 1.0);
  if (o.goals.empty() || o.goals.size() > 3) {
    throw InvalidInput("--volume/--volume-ratio/--alpha/--sphericity/--elongation/--flatness",
                       std::to_string(o.goals.size()) + " given", "1 to 3 of them");
  }
  if (command.count("--edge-ratio") > 0) {
    require_in_range("--edge-ratio", flags.edge_ratio, 0.05, 1.5);
    o.edge_ratio = flags.edge_ratio;
  }
  const auto growth = find_growth(flags.growth);
  if (!growth) throw InvalidInput("--growth", flags.growth, "hull or midpoint");
  o.form.growth = *growth;
  require_in_range("--min-edge-ratio", o.form.min_edge_ratio, 0.0, 0.5);
  if (flags.samples < 2 || flags.samples > 100000) {
    throw InvalidInput("--samples", std::to_string(flags.samples), "[2, 100000]");
  }
  require_in_range("--tolerance", o.tolerance, 1e-6, 0.2);
  o.samples = static_cast<std::size_t>(flags.samples);
  o.seed = flags.seed;
}

// The flag a goal was given with, for messages in the user's words.
std::string flag_of(const CalibrateFlags& flags, const std::string& target_name) {
  for (std::size_t i = 0; i < flags.options.goals.size(); ++i) {
    if (calibration_target_name(flags.options.goals[i].target) == target_name) {
      return flags.goal_flags[i];
    }
  }
  return target_name;
}

// The value typed for a goal's flag.
double typed_value(const CalibrateFlags& flags, const std::string& flag) {
  return flag == "--volume"         ? flags.volume
         : flag == "--volume-ratio" ? flags.volume_ratio
         : flag == "--alpha"        ? flags.alpha
         : flag == "--sphericity"   ? flags.sphericity
         : flag == "--elongation"   ? flags.elongation
                                    : flags.flatness;
}

// The factor from a volume ratio to the value of `flag`: --volume V at --diameter D is the ratio
// V / (pi/6 D^3); every other target is the ratio itself (1).
double ratio_to_flag(const CalibrateFlags& flags, const std::string& flag) {
  return flag == "--volume" ? std::numbers::pi / 6.0 * std::pow(flags.options.diameter, 3) : 1.0;
}

// calibrate()'s refusal in the user's words: the flag typed, what that flag can reach (for
// --volume in m^3 at the --diameter given), and the closest reachable input with what the
// closest generator inputs achieve.
InvalidInput unreached_in_user_words(const CalibrateFlags& flags,
                                     const CalibrationUnreached& error) {
  const std::string flag = flag_of(flags, error.field());
  if (flag == error.field()) return error;
  const double typed = typed_value(flags, flag);
  const bool is_volume = flag == "--volume";
  const double scale = ratio_to_flag(flags, flag);  // the span is the ratio's times this
  const auto shown = [&](double ratio) { return fmt::format("{:.4g}", ratio * scale); };
  const double nearest =
      std::clamp(typed / scale, error.lowest(), error.highest());  // the closest reachable
  const std::string unit = is_volume ? " m^3" : "";
  const std::string where =
      is_volume ? fmt::format(" at --diameter {}", format_value(flags.options.diameter)) : "";
  // With other targets the typed value may lie inside the span and still not be met with them:
  // then no single closest input of this flag can be named.
  const bool is_inside = typed / scale >= error.lowest() && typed / scale <= error.highest();
  const std::string allowed = fmt::format(
      "{} from {} to {}{}{} (the means the searched inputs reach{}){}; the closest inputs found "
      "({}) give {}{}",
      flag, shown(error.lowest()), shown(error.highest()), unit, where,
      flags.options.goals.size() > 1 ? " one at a time; not together with the other targets" : "",
      is_inside ? std::string() : fmt::format("; closest reachable: {} {}", flag, shown(nearest)),
      error.closest_inputs(), shown(error.closest()), unit);
  return InvalidInput(flag, format_value(typed) + unit, allowed);
}

// A target typed above what any particle has (a volume above its sphere's, a ratio above 1),
// searched as 1: the flag's upper limit and the closest reachable value, which the search found
// within its tolerance of 1, with the inputs that give it.
InvalidInput above_range_in_user_words(const CalibrateFlags& flags,
                                       const CalibrationResult& result) {
  const std::string& flag = flags.above_sphere_flag;
  const auto goal = std::find(flags.goal_flags.begin(), flags.goal_flags.end(), flag);
  const auto i = static_cast<std::size_t>(goal - flags.goal_flags.begin());
  const bool is_volume = flag == "--volume";
  const double scale = ratio_to_flag(flags, flag);
  const std::string unit = is_volume ? " m^3" : "";
  const CalibrationInputs& in = result.inputs;
  return InvalidInput(
      flag, format_value(typed_value(flags, flag)) + unit,
      fmt::format(
          "at most {}{}{}; closest reachable: {} {:.4g}, given by alpha {:.4g}, L/R {:.4g}, "
          "elongation {:.4g}, flatness {:.4g}",
          format_value(scale), unit,
          is_volume ? fmt::format(" (the sphere of --diameter {} m)",
                                  format_value(flags.options.diameter))
                    : "",
          flag, result.achieved.at(i).mean * scale, in.alpha, in.edge_ratio, in.elongation,
          in.flatness));
}

void write_table(const std::string& path, const CalibrationOptions& options,
                 const CalibrationResult& result, Overwrite overwrite) {
  AtomicFile file(path, overwrite);
  auto& out = file.stream();
  out << "evaluation,alpha,edge_ratio,elongation,flatness";
  for (const auto& goal : options.goals) {
    const std::string name = calibration_target_name(goal.target);
    out << "," << name << "_mean," << name << "_sd," << name << "_target";
  }
  out << ",samples\n";
  for (std::size_t i = 0; i < result.evaluated.size(); ++i) {
    const CalibrationPoint& point = result.evaluated[i];
    out << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g}", i, point.inputs.alpha,
                       point.inputs.edge_ratio, point.inputs.elongation, point.inputs.flatness);
    for (const auto& goal : options.goals) {
      for (std::size_t t = 0; t < std::size(kCalibrationTargets); ++t) {
        if (kCalibrationTargets[t] != goal.target) continue;
        out << fmt::format(",{:.17g},{:.17g},{:.17g}", point.descriptors[t].mean,
                           point.descriptors[t].standard_deviation, goal.value);
      }
    }
    out << "," << options.samples << "\n";
  }
  file.commit();
}

void print_result(const CalibrateFlags& flags, const CalibrationResult& result) {
  const CalibrationOptions& options = flags.options;
  const CalibrationInputs& in = result.inputs;
  for (std::size_t i = 0; i < options.goals.size(); ++i) {
    fmt::print("target        {} = {:.6g} ({})\n", calibration_target_name(options.goals[i].target),
               options.goals[i].value, flags.goal_flags[i]);
  }
  fmt::print(
      "found         alpha = {:.4g} (Eq. 3 input), L/R = {:.4g}, elongation = {:.4g}, flatness "
      "= {:.4g}, growth {}; R = {:.4g} m, L = {:.4g} m\n",
      in.alpha, in.edge_ratio, in.elongation, in.flatness, growth_name(options.form.growth),
      result.radius, result.edge_length);
  for (std::size_t i = 0; i < options.goals.size(); ++i) {
    const auto& goal = options.goals[i];
    const auto& achieved = result.achieved[i];
    fmt::print("achieved      {} = {:.4g} +- {:.2g} (sd, {} particles, seed {}): {:+.2f} %\n",
               calibration_target_name(goal.target), achieved.mean, achieved.standard_deviation,
               achieved.count, options.seed, 100.0 * (achieved.mean - goal.value) / goal.value);
  }
  fmt::print("volume        {:.4g} +- {:.2g} mm^3 (sphere of diameter D: {:.4g} mm^3)\n",
             result.volume.mean * 1e9, result.volume.standard_deviation * 1e9,
             std::numbers::pi / 6.0 * std::pow(options.diameter, 3) * 1e9);
  fmt::print(
      "enclosing     diameter {:.4g} +- {:.2g} mm (smallest sphere around each particle; "
      "control sphere 2R = {:.4g} mm)\n",
      2e3 * result.enclosing_radius.mean, 2e3 * result.enclosing_radius.standard_deviation,
      2e3 * result.radius);
  for (std::size_t t = 0; t < result.all_descriptors.size(); ++t) {
    const bool is_goal = std::any_of(options.goals.begin(), options.goals.end(),
                                     [&](auto& g) { return g.target == kCalibrationTargets[t]; });
    if (is_goal) continue;
    fmt::print("also          {} = {:.4g} +- {:.2g}\n",
               calibration_target_name(kCalibrationTargets[t]), result.all_descriptors[t].mean,
               result.all_descriptors[t].standard_deviation);
  }
  fmt::print("evaluations   {} (grid + Nelder-Mead, {} particles each)\n", result.evaluated.size(),
             options.samples);
  fmt::print(
      "config lines (under [particle] in pack, repose and sweep configs):\n"
      "alpha = {:.6g}\nradius = {:.6g}\nedge_length = {:.6g}\ngrowth = \"{}\"\n"
      "elongation = {:.6g}\nflatness = {:.6g}\nmin_edge_ratio = {:.6g}\n",
      in.alpha, result.radius, result.edge_length, growth_name(options.form.growth), in.elongation,
      in.flatness, options.form.min_edge_ratio);
}

}  // namespace

void register_calibrate(CLI::App& app) {
  auto flags = std::make_shared<CalibrateFlags>();
  auto& o = flags->options;
  auto* command = app.add_subcommand(
      "calibrate",
      "Find the generator inputs (Eq. 3 alpha, L/R, and the control ellipsoid's axis ratios when "
      "an elongation or flatness is asked for) whose particles match up to three measured mean "
      "descriptors at once; print the inputs, each target's achieved mean +- sd and miss, and "
      "the config lines.");
  command->add_option("--volume-ratio", flags->volume_ratio,
                      "target mean V / V_circumscribed-sphere, (0, 1]");
  command->add_option("--volume", flags->volume,
                      "target mean particle volume (m^3) at --diameter (= a volume ratio; the "
                      "particles are sized to this mean volume)");
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
  command->add_option("--edge-ratio", flags->edge_ratio,
                      "keep L / R fixed at this, [0.05, 1.5] (default: searched in [0.25, 1.4])");
  command->add_option("--growth", flags->growth, "growth rule: hull or midpoint")
      ->capture_default_str();
  command
      ->add_option("--min-edge-ratio", o.form.min_edge_ratio,
                   "minimum edge length / L of hull growth, [0, 0.5]")
      ->capture_default_str();
  command->add_option("--tolerance", o.tolerance, "relative miss accepted per target, (0, 0.2]")
      ->capture_default_str();
  command->add_option("--samples", flags->samples, "particles per evaluation, [2, 100000]")
      ->capture_default_str();
  command
      ->add_option("--seed", flags->seed,
                   "seed of every evaluation's particles, [0, 2^64-1]; particle i uses stream "
                   "(seed, i)")
      ->check(kNotNegative)
      ->capture_default_str();
  command->add_option("--table", flags->table,
                      "CSV of the search: inputs and each target's mean, sd per evaluation");
  command->add_option("--plot", flags->plot, "PNG of the search: each target's miss (%)");
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command->add_flag("-f,--force", flags->is_forced, "replace existing output files");
  command->callback([=, &app]() {
    const auto* self = app.get_subcommand("calibrate");
    resolve_goals(*flags, *self);
    set_thread_count(flags->threads);
    if (self->count("--table") > 0) check_output_file_flag("--table", flags->table);
    if (self->count("--plot") > 0) check_output_file_flag("--plot", flags->plot);
    const Overwrite overwrite = flags->is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    if (!flags->table.empty()) check_writable(flags->table, overwrite);
    if (!flags->plot.empty()) check_writable(flags->plot, overwrite);
    CalibrationResult result;
    try {
      result = calibrate(flags->options);
    } catch (const CalibrationUnreached& error) {
      throw unreached_in_user_words(*flags, error);
    }
    if (!flags->above_sphere_flag.empty()) throw above_range_in_user_words(*flags, result);
    print_result(*flags, result);
    if (!flags->table.empty()) {
      write_table(flags->table, flags->options, result, overwrite);
      fmt::print("wrote {}\n", flags->table);
    }
    if (!flags->plot.empty()) {
      write_calibration_plot(flags->plot, flags->options, result);
      fmt::print("wrote {}\n", flags->plot);
    }
  });
}

}  // namespace aggpack::cli
