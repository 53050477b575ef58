// `aggpack settle`: gravity settling of a saved packing in its container (Bullet, issue 6).
// Built only with AGGPACK_HAS_SIM (cmake/sim.cmake); registered by register_sim.

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/io/native.h"
#include "aggpack/sim/settle.h"
#include "commands.h"
#include "heavy_runs.h"
#include "output_flags.h"
#include "progress.h"

namespace aggpack::cli {

namespace {

// settle takes flags, not config keys: messages name the flag the user typed.
const std::map<std::string, std::string>& settle_flag_names() {
  static const std::map<std::string, std::string> names = {
      {"density", "--density"},
      {"friction", "--mu"},
      {"wall_friction", "--mu-wall"},
      {"restitution", "--restitution"},
      {"rolling_friction", "--rolling"},
      {"time_step", "--dt"},
      {"time_step_factor", "--dt-factor"},
      {"solver_iterations", "--iterations"},
      {"kinetic_energy_ratio", "--energy-ratio"},
      {"quiet_time", "--quiet-time"},
      {"max_time", "--max-time"},
      {"min_time", "fall time from the packing's height"},
  };
  return names;
}

struct SettleFlags {
  std::string input;
  std::string output;
  SettleOptions options;
  std::optional<double> wall_friction;
  std::string progress = "auto";
  bool is_forced = false;
};

void run_settle_command(const SettleFlags& flags) {
  check_output_file_flag("-o/--output", flags.output);
  SettleOptions options = flags.options;
  if (flags.wall_friction) options.physics.wall_friction = *flags.wall_friction;
  with_key_names({}, settle_flag_names(), [&] {
    validate(options.physics);
    validate(options.rest);
  });
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  check_writable(flags.output, overwrite);
  const Packing packing = read_packing(flags.input);
  announce_heavy_run(estimate_settle(packing, options));
  fmt::print(
      "settling {} particles from {} until at rest (kinetic energy below --energy-ratio for "
      "--quiet-time), at most {} s simulated (--max-time)\n",
      packing.particles.size(), flags.input, format_value(options.rest.max_time));
  std::fflush(stdout);
  SettleResult result;
  try {
    // Simulated milliseconds as the counted unit: the rate is simulated time per wall second,
    // the ETA an upper bound (the run ends at rest, usually long before --max-time).
    ProgressBar bar("settling", "ms simulated", style);
    bar.set_eta_is_bound(true);
    with_key_names({}, settle_flag_names(), [&] {
      result = settle(packing, options, [&](double time, double energy, double threshold) {
        bar.update(
            time / options.rest.max_time, static_cast<std::uint64_t>(time * 1e3 + 0.5),
            static_cast<std::uint64_t>(options.rest.max_time * 1e3 + 0.5),
            fmt::format("kinetic energy {:.2g} J (at rest below {:.2g} J)", energy, threshold));
      });
    });
  } catch (const Error& error) {
    // The packing's own values (a particle size, a diverging state): name the file.
    if (error.kind() == ErrorKind::kIoError) throw;
    throw Error(error.kind(), flags.input + ": " + error.what());
  }
  const SettleReport& r = result.report;
  write_packing(result.packing, flags.output, {.overwrite = overwrite});
  fmt::print("{} after {:.2f} s simulated ({} steps of {:.4g} s, {} s wall)\n",
             r.is_at_rest ? "at rest" : "NOT at rest (max time reached)", r.simulated_time, r.steps,
             r.time_step, format_seconds(r.wall_seconds));
  fmt::print(
      "solid fraction       {:.4f} -> {:.4f} (bulk: solid {:.4g} m^3 / footprint x height "
      "{:.4g} -> {:.4g} m)\n",
      r.solid_fraction_before, r.solid_fraction_after, r.solid_volume, r.height_before,
      r.height_after);
  fmt::print(
      "largest overlap      {:.4g} m = {:.3f}% of d_min ({} touching pairs); deepest "
      "contact {:.4g} m\n",
      r.max_overlap, 100.0 * r.max_overlap_fraction, r.overlapping_pairs,
      r.max_contact_penetration);
  fmt::print(
      "containment          {} particles left the container (min wall clearance {:.3g} "
      "m)\n",
      r.escaped_particles, r.min_wall_clearance);
  fmt::print("wrote {}\n", flags.output);
}

}  // namespace

void register_settle(CLI::App& app) {
  {
    auto flags = std::make_shared<SettleFlags>();
    auto& physics = flags->options.physics;
    auto& rest = flags->options.rest;
    auto* command = app.add_subcommand(
        "settle",
        "Let a saved packing fall under gravity in its container (Bullet) until it is "
        "at rest; write the dense packing and report solid fraction before/after, the "
        "largest overlap and containment.");
    command->add_option("input", flags->input, "native packing file (.h5)")->required();
    command->add_option("-o,--output", flags->output, "settled packing file (.h5)")->required();
    command->add_option("--mu", physics.friction, "sliding friction particle-particle, [0, 10]")
        ->capture_default_str();
    command->add_option("--mu-wall", flags->wall_friction,
                        "sliding friction particle-wall, [0, 10] (default: --mu)");
    command->add_option("--restitution", physics.restitution, "restitution, [0, 1]")
        ->capture_default_str();
    command
        ->add_option("--rolling", physics.rolling_friction,
                     "rolling friction mu_r, [0, 1] (0 = off)")
        ->capture_default_str();
    command->add_option("--density", physics.density, "particle density (kg/m^3)")
        ->capture_default_str();
    command->add_option("--dt", physics.time_step, "time step (s), 0 = automatic")
        ->capture_default_str();
    command
        ->add_option("--dt-factor", physics.time_step_factor,
                     "automatic time step = factor * sqrt(d_min / g)")
        ->capture_default_str();
    command->add_option("--iterations", physics.solver_iterations, "solver iterations, [1, 1000]")
        ->capture_default_str();
    command
        ->add_option("--energy-ratio", rest.kinetic_energy_ratio,
                     "at rest when kinetic energy < ratio * M g d for --quiet-time")
        ->capture_default_str();
    command->add_option("--quiet-time", rest.quiet_time, "s the rest criterion must hold")
        ->capture_default_str();
    command->add_option("--max-time", rest.max_time, "simulated time limit (s)")
        ->capture_default_str();
    command->add_option("--progress", flags->progress, "auto, bar, lines or none")
        ->capture_default_str();
    command->add_flag("-f,--force", flags->is_forced, "replace an existing output file");
    command->callback([flags]() { run_settle_command(*flags); });
  }
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
