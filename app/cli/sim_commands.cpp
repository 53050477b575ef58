// `aggpack settle`, `aggpack repose` and `aggpack sweep`: gravity settling of a saved packing,
// the paper's angle-of-repose trough test and its alpha x mu_s sweep, on Bullet (issue 6).
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

#include <toml++/toml.h>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/settle.h"
#include "aggpack/sim/sweep.h"
#include "commands.h"
#include "progress.h"

#include "aggpack/io/native.h"

extern char** environ;

namespace aggpack::cli {

namespace {

// ---- repose / sweep configuration: one TOML table per group, every key typed and documented --

struct ConfigKey {
  const char* name;  // "trough.length"
  const char* unit;  // "m", "-", ...
  const char* help;
  std::function<std::string(const SweepOptions&)> show;        // value as TOML
  std::function<void(SweepOptions&, const std::string&)> set;  // from TOML text
};

double parse_double(const std::string& key, const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  throw InvalidInput(key, clipped(text), "a number");
}

bool parse_bool(const std::string& key, const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  throw InvalidInput(key, clipped(text), "true or false");
}

std::vector<double> parse_list(const std::string& key, std::string text) {
  if (text.size() < 2 || text.front() != '[' || text.back() != ']') {
    throw InvalidInput(key, clipped(text), "a list of numbers, e.g. [0.1, 0.2]");
  }
  text = text.substr(1, text.size() - 2);
  std::vector<double> values;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    std::string item = text.substr(start, comma - start);
    item.erase(0, item.find_first_not_of(" \t\n"));
    item.erase(item.find_last_not_of(" \t\n") + 1);
    if (!item.empty()) values.push_back(parse_double(key, item));
    start = comma + 1;
  }
  return values;
}

std::string show_double(double value) { return fmt::format("{}", value); }

std::string show_list(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    text += (i > 0 ? ", " : "") + show_double(values[i]);
  }
  return text + "]";
}

#define AGGPACK_DOUBLE_KEY(key, unit, help, member)                                          \
  ConfigKey {                                                                                \
    key, unit, help, [](const SweepOptions& o) { return show_double(o.member); },            \
        [](SweepOptions& o, const std::string& text) { o.member = parse_double(key, text); } \
  }

const std::vector<ConfigKey>& config_keys() {
  static const std::vector<ConfigKey> keys = {
      AGGPACK_DOUBLE_KEY("trough.length", "m", "trough length (x)", base.trough_length),
      AGGPACK_DOUBLE_KEY("trough.width", "m", "trough width (y)", base.trough_width),
      AGGPACK_DOUBLE_KEY("trough.height", "m",
                         "trough wall height (walls reach the fill top during stage 1)",
                         base.trough_height),
      AGGPACK_DOUBLE_KEY("trough.baffle_position", "m",
                         "x of the baffle; particles fill [0, baffle_position]",
                         base.baffle_position),
      AGGPACK_DOUBLE_KEY("trough.baffle_thickness", "m", "baffle thickness", base.baffle_thickness),
      AGGPACK_DOUBLE_KEY("trough.baffle_speed", "m/s", "baffle speed toward +x in stage 2",
                         base.baffle_speed),
      AGGPACK_DOUBLE_KEY("trough.baffle_clear_time", "s",
                         "baffle removed once untouched this long and clear of the pile",
                         base.baffle_clear_time),
      AGGPACK_DOUBLE_KEY("particles.alpha", "-", "Eq. 3 shape control alpha, [0, 1]", base.alpha),
      AGGPACK_DOUBLE_KEY("particles.radius", "m", "control radius R; lattice spacing 2R",
                         base.radius),
      AGGPACK_DOUBLE_KEY("particles.edge_length", "m", "maximum edge length L", base.edge_length),
      AGGPACK_DOUBLE_KEY("particles.fill_height", "m", "height of the lattice region",
                         base.fill_height),
      ConfigKey{"particles.seed", "-", "master seed; particle i uses stream (seed, i)",
                [](const SweepOptions& o) { return std::to_string(o.base.seed); },
                [](SweepOptions& o, const std::string& text) {
                  const double value = parse_double("particles.seed", text);
                  if (value < 0.0 || value != std::floor(value) || value > 9.0e15) {
                    throw InvalidInput("particles.seed", text, "an integer >= 0");
                  }
                  o.base.seed = static_cast<std::uint64_t>(value);
                }},
      ConfigKey{"particles.random_orientation", "-",
                "turn each particle randomly about its lattice site",
                [](const SweepOptions& o) {
                  return std::string(o.base.is_orientation_random ? "true" : "false");
                },
                [](SweepOptions& o, const std::string& text) {
                  o.base.is_orientation_random = parse_bool("particles.random_orientation", text);
                }},
      AGGPACK_DOUBLE_KEY("physics.density", "kg/m^3", "particle density", base.physics.density),
      AGGPACK_DOUBLE_KEY("physics.friction", "-", "sliding friction mu_s particle-particle",
                         base.physics.friction),
      ConfigKey{"physics.wall_friction", "-",
                "sliding friction particle-wall; -1 = same as physics.friction",
                [](const SweepOptions& o) {
                  return show_double(o.base.physics.wall_friction.value_or(-1.0));
                },
                [](SweepOptions& o, const std::string& text) {
                  const double value = parse_double("physics.wall_friction", text);
                  o.base.physics.wall_friction =
                      value < 0.0 ? std::nullopt : std::optional<double>(value);
                }},
      AGGPACK_DOUBLE_KEY("physics.restitution", "-", "coefficient of restitution, [0, 1]",
                         base.physics.restitution),
      AGGPACK_DOUBLE_KEY("physics.rolling_friction", "-",
                         "rolling friction mu_r (torque <= mu_r r F_n), 0 = off",
                         base.physics.rolling_friction),
      AGGPACK_DOUBLE_KEY("physics.time_step", "s", "time step, 0 = automatic",
                         base.physics.time_step),
      AGGPACK_DOUBLE_KEY("physics.time_step_factor", "-",
                         "automatic time step = factor * sqrt(d_min / g)",
                         base.physics.time_step_factor),
      ConfigKey{
          "physics.solver_iterations", "-", "solver iterations per step, [1, 1000]",
          [](const SweepOptions& o) { return std::to_string(o.base.physics.solver_iterations); },
          [](SweepOptions& o, const std::string& text) {
            const double value = parse_double("physics.solver_iterations", text);
            if (value != std::floor(value) || value < 1.0 || value > 1000.0) {
              throw InvalidInput("physics.solver_iterations", text, "an integer in [1, 1000]");
            }
            o.base.physics.solver_iterations = static_cast<int>(value);
          }},
      AGGPACK_DOUBLE_KEY("physics.margin_fraction", "-", "collision margin / d_min",
                         base.physics.margin_fraction),
      AGGPACK_DOUBLE_KEY("rest.kinetic_energy_ratio", "-",
                         "at rest when kinetic energy < ratio * M g d",
                         base.rest.kinetic_energy_ratio),
      AGGPACK_DOUBLE_KEY("rest.quiet_time", "s", "time the rest criterion must hold",
                         base.rest.quiet_time),
      AGGPACK_DOUBLE_KEY("rest.check_interval", "s", "time between rest checks",
                         base.rest.check_interval),
      AGGPACK_DOUBLE_KEY("rest.max_time", "s", "simulated time limit per stage",
                         base.rest.max_time),
      AGGPACK_DOUBLE_KEY("measure.bin_width", "m", "profile bin width, 0 = radius / 2",
                         base.bin_width),
      AGGPACK_DOUBLE_KEY("measure.fit_upper", "-", "slope region below this x pile height",
                         base.fit_upper),
      AGGPACK_DOUBLE_KEY("measure.fit_lower", "-", "slope region above this x pile height",
                         base.fit_lower),
      AGGPACK_DOUBLE_KEY("measure.surface_tolerance", "-",
                         "stage 2 ends when the surface moves less than this x d",
                         base.surface_tolerance),
      ConfigKey{"sweep.alphas", "-", "alpha values of the sweep",
                [](const SweepOptions& o) { return show_list(o.alphas); },
                [](SweepOptions& o, const std::string& text) {
                  o.alphas = parse_list("sweep.alphas", text);
                }},
      ConfigKey{"sweep.frictions", "-", "mu_s values of the sweep",
                [](const SweepOptions& o) { return show_list(o.frictions); },
                [](SweepOptions& o, const std::string& text) {
                  o.frictions = parse_list("sweep.frictions", text);
                }},
      ConfigKey{"sweep.wall_friction_coupled", "-", "walls take each case's mu_s",
                [](const SweepOptions& o) {
                  return std::string(o.is_wall_friction_coupled ? "true" : "false");
                },
                [](SweepOptions& o, const std::string& text) {
                  o.is_wall_friction_coupled = parse_bool("sweep.wall_friction_coupled", text);
                }},
  };
  return keys;
}

#undef AGGPACK_DOUBLE_KEY

void set_key(SweepOptions& options, const std::string& key, const std::string& value) {
  for (const auto& entry : config_keys()) {
    if (key == entry.name) {
      entry.set(options, value);
      return;
    }
  }
  std::string best;
  std::size_t best_distance = 1000;
  for (const auto& entry : config_keys()) {
    if (key.size() > 64) break;  // no typo of a known key; and edit distance is quadratic
    const std::size_t d = edit_distance(key, entry.name);
    if (d < best_distance) {
      best_distance = d;
      best = entry.name;
    }
  }
  throw InvalidInput("config key", clipped(key),
                     best_distance <= 4 ? "a known key; did you mean " + best + "?"
                                        : "a known key (see --print-config)");
}

std::string resolved_config(const SweepOptions& options) {
  std::string text;
  std::string section;
  for (const auto& entry : config_keys()) {
    const std::string name = entry.name;
    const std::string group = name.substr(0, name.find('.'));
    if (group != section) {
      text += (section.empty() ? "" : "\n") + ("[" + group + "]\n");
      section = group;
    }
    text += fmt::format("{} = {}  # {} ({})\n", name.substr(name.find('.') + 1),
                        entry.show(options), entry.help, entry.unit);
  }
  return text;
}

void load_config(SweepOptions& options, const std::string& path) {
  toml::table table;
  try {
    table = toml::parse_file(path);
  } catch (const toml::parse_error& error) {
    if (!std::filesystem::exists(path)) throw IoError("cannot read " + path);
    throw FormatError(fmt::format("{}: {}", path, error.description()));
  }
  for (const auto& [group, node] : table) {
    const auto* inner = node.as_table();
    if (inner == nullptr) {
      throw InvalidInput("config key", std::string(group.str()), "a [group] table");
    }
    for (const auto& [key, value] : *inner) {
      std::string text;
      if (const auto* array = value.as_array()) {
        text = "[";
        for (std::size_t i = 0; i < array->size(); ++i) {
          const auto number = array->get(i)->value<double>();
          if (!number) {
            throw InvalidInput(std::string(group.str()) + "." + std::string(key.str()),
                               "non-numeric list", "a list of numbers");
          }
          text += (i > 0 ? "," : "") + fmt::format("{}", *number);
        }
        text += "]";
      } else if (const auto flag = value.value<bool>(); flag && value.is_boolean()) {
        text = *flag ? "true" : "false";
      } else if (const auto number = value.value<double>()) {
        text = fmt::format("{}", *number);
      } else {
        throw InvalidInput(std::string(group.str()) + "." + std::string(key.str()),
                           "non-numeric value", "a number, boolean or list of numbers");
      }
      set_key(options, std::string(group.str()) + "." + std::string(key.str()), text);
    }
  }
}

// The library names options by their fields ("repose.baffle_position", "friction", "min_time");
// messages must name what the user typed: a config key or a flag.
const std::map<std::string, std::string>& repose_key_names() {
  static const std::map<std::string, std::string> names = {
      {"repose.trough_length", "trough.length"},
      {"repose.trough_width", "trough.width"},
      {"repose.trough_height", "trough.height"},
      {"repose.baffle_position", "trough.baffle_position"},
      {"repose.baffle_thickness", "trough.baffle_thickness"},
      {"repose.baffle_speed", "trough.baffle_speed"},
      {"repose.baffle_clear_time", "trough.baffle_clear_time"},
      {"repose.alpha", "particles.alpha"},
      {"repose.radius", "particles.radius"},
      {"repose.edge_length", "particles.edge_length"},
      {"repose.fill_height", "particles.fill_height"},
      {"repose.bin_width", "measure.bin_width"},
      {"repose.fit_upper", "measure.fit_upper"},
      {"repose.fit_lower", "measure.fit_lower"},
      {"repose.surface_tolerance", "measure.surface_tolerance"},
      {"density", "physics.density"},
      {"friction", "physics.friction"},
      {"wall_friction", "physics.wall_friction"},
      {"restitution", "physics.restitution"},
      {"rolling_friction", "physics.rolling_friction"},
      {"time_step", "physics.time_step"},
      {"time_step_factor", "physics.time_step_factor"},
      {"margin_fraction", "physics.margin_fraction"},
      {"kinetic_energy_ratio", "rest.kinetic_energy_ratio"},
      {"quiet_time", "rest.quiet_time"},
      {"check_interval", "rest.check_interval"},
      {"max_time", "rest.max_time"},
      {"min_time", "fall time from particles.fill_height"},
      // the lattice fill behind the baffle
      {"container.length", "trough.baffle_position"},
      {"container.width", "trough.width"},
      {"container.depth", "particles.fill_height"},
      {"lattice.alpha", "particles.alpha"},
      {"lattice.radius", "particles.radius"},
      {"lattice.edge_length", "particles.edge_length"},
      {"lattice.max_vertices", "particles.edge_length"},
      {"alpha", "particles.alpha"},
      {"radius", "particles.radius"},
      {"edge_length", "particles.edge_length"},
      {"max_vertices", "particles.edge_length"},
  };
  return names;
}

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

// Runs `check`; an InvalidInput or LimitExceeded about a field in `names` is rethrown naming
// the user's key instead.
template <typename Check>
void with_user_names(const std::map<std::string, std::string>& names, Check&& check) {
  try {
    check();
  } catch (const Error& error) {
    if (error.kind() != ErrorKind::kInvalidInput && error.kind() != ErrorKind::kLimitExceeded) {
      throw;
    }
    const std::string message = error.what();
    for (const char* lead : {"invalid ", "limit exceeded for "}) {
      if (message.rfind(lead, 0) != 0) continue;
      const std::size_t start = std::string(lead).size();
      const std::size_t end = message.find(" = ", start);
      if (end == std::string::npos) continue;
      const auto found = names.find(message.substr(start, end - start));
      if (found == names.end()) continue;
      throw Error(error.kind(), lead + found->second + message.substr(end));
    }
    throw;
  }
}

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
  int threads = 0;
  int image_width = 1600;
  std::string progress = "auto";
  bool is_print_config = false;
  bool is_forced = false;
  bool is_without_plot = false;
  bool has_packing = false;
};

SweepOptions resolve(const ReposeFlags& flags) {
  SweepOptions options;
  if (!flags.config_path.empty()) {
    load_config(options, flags.config_path);
  }
  for (const auto& assignment : flags.overrides) {
    const auto equals = assignment.find('=');
    if (equals == std::string::npos || assignment.find_first_of("\n\r") != std::string::npos) {
      throw InvalidInput("--set", clipped(assignment),
                         "one line key=value, e.g. physics.friction=0.3");
    }
    set_key(options, assignment.substr(0, equals), assignment.substr(equals + 1));
  }
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
  } else {
    fmt::print("angle of repose      not measured: {}\n", r.fit.message);
  }
}

void run_repose_command(const ReposeFlags& flags) {
  const SweepOptions options = resolve(flags);
  // Everything the run checks, --print-config included, before any folder is created.
  with_user_names(repose_key_names(), [&] { validate(options.base); });
  if (flags.is_print_config) {
    fmt::print("{}", resolved_config(options));
    return;
  }
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  if (flags.image_width < 64 || flags.image_width > 16384) {
    throw InvalidInput("--width", std::to_string(flags.image_width), "[64, 16384]");
  }
  CreatedFolder created(flags.output);
  std::vector<std::string> names = {"repose.json", "profile.csv", "side.png"};
  names.push_back("final.h5");
  const std::string folder = prepare_folder(flags.output, flags.is_forced, names);
  double last_print = -1.0;
  int last_stage = 0;
  ReposeResult result;
  with_user_names(repose_key_names(), [&] {
    result = run_repose(options.base, [&](int stage, double time, double energy, double threshold) {
      if (style == ProgressStyle::kNone) return;
      if (stage != last_stage || time - last_print >= 0.5) {
        last_stage = stage;
        last_print = time;
        std::fprintf(stderr, "stage %d  t = %6.2f s  kinetic energy %.3g J%s\n", stage, time,
                     energy,
                     threshold > 0.0 ? fmt::format(" (rest < {:.3g})", threshold).c_str()
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
  write_packing(in_folder(folder, "final.h5"), result.final);
  outputs.commit();
  created.keep();
  fmt::print("wrote {}/repose.json, profile.csv, side.png, final.h5\n", folder);
}

// The sweep plot: angle against mu_s, one line per alpha (gnuplot, run when it is installed).
std::string gnuplot_script(const std::vector<double>& alphas) {
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
        "{}'sweep.csv' every ::1 using ($1 == {} && $6 == 1 ? $2 : 1/0):3 with linespoints "
        "lw 2 pt 7 title '{}'",
        i > 0 ? ", \\\n     " : "", alphas[i], alphas[i]);
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
  const SweepOptions options = resolve(flags);
  with_user_names(repose_key_names(), [&] { validate(options); });
  if (flags.is_print_config) {
    fmt::print("{}", resolved_config(options));
    return;
  }
  set_thread_count(flags.threads);
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  CreatedFolder created(flags.output);
  const std::string folder =
      prepare_folder(flags.output, flags.is_forced, {"sweep.csv", "sweep.gp", "sweep.png"});
  std::filesystem::create_directories(std::filesystem::path(folder) / "cases");
  const std::size_t total = options.alphas.size() * options.frictions.size();
  fmt::print("sweep: {} alpha x {} mu_s = {} cases\n", options.alphas.size(),
             options.frictions.size(), total);
  ProgressBar bar("sweep", "cases", style);
  const auto cases = run_sweep(options, [&](const SweepCase& c, const ReposeResult& result,
                                            std::size_t done, std::size_t count) {
    const std::string stem = fmt::format("alpha{:.2f}_mu{:.2f}", c.alpha, c.friction);
    try {
      ReposeOptions repose = options.base;
      repose.alpha = c.alpha;
      repose.physics.friction = c.friction;
      if (options.is_wall_friction_coupled) repose.physics.wall_friction = c.friction;
      write_repose_json(in_folder(folder, "cases/" + stem + ".json"), repose, result);
      write_side_view_png(in_folder(folder, "cases/" + stem + ".png"), result.final, result.profile,
                          result.fit, std::min(flags.image_width, 1200));
    } catch (const Error& error) {
      std::fprintf(stderr, "aggpack: warning: case %s: %s\n", stem.c_str(), error.what());
    }
    bar.update(
        static_cast<double>(done) / static_cast<double>(count), done, count,
        fmt::format("alpha {:.2f} mu {:.2f}: {:.1f} deg", c.alpha, c.friction, c.angle_degrees));
  });
  bar.finish();
  created.keep();
  write_sweep_csv(in_folder(folder, "sweep.csv"), cases);
  fmt::print("{:>6} {:>6} {:>9} {:>7} {:>6}\n", "alpha", "mu_s", "angle", "R^2", "rest");
  for (const auto& c : cases) {
    fmt::print("{:6.2f} {:6.2f} {:>9} {:7.3f} {:>6}\n", c.alpha, c.friction,
               c.is_valid ? fmt::format("{:.2f}", c.angle_degrees) : std::string("-"), c.r_squared,
               c.is_at_rest ? "yes" : "no");
  }
  {
    AtomicFile script(in_folder(folder, "sweep.gp"), Overwrite::kAllow, std::ios::out);
    script.stream() << gnuplot_script(options.alphas);
    script.commit();
  }
  if (!flags.is_without_plot && run_gnuplot(folder)) {
    fmt::print("wrote {}/sweep.csv, sweep.gp, sweep.png and cases/\n", folder);
  } else {
    fmt::print("wrote {}/sweep.csv, sweep.gp and cases/ (plot: cd {} && gnuplot sweep.gp)\n",
               folder, folder);
  }
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
  SettleOptions options = flags.options;
  if (flags.wall_friction) options.physics.wall_friction = *flags.wall_friction;
  with_user_names(settle_flag_names(), [&] {
    validate(options.physics);
    validate(options.rest);
  });
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  const Overwrite overwrite = flags.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  check_writable(flags.output, overwrite);
  const Packing packing = read_packing(flags.input);
  fmt::print("settling {} particles from {}\n", packing.particles.size(), flags.input);
  double last_print = -1.0;
  SettleResult result;
  try {
    with_user_names(settle_flag_names(), [&] {
      result = settle(packing, options, [&](double time, double energy, double threshold) {
        if (style == ProgressStyle::kNone || time - last_print < 0.5) return;
        last_print = time;
        std::fprintf(stderr, "t = %6.2f s  kinetic energy %.3g J (rest < %.3g)\n", time, energy,
                     threshold);
      });
    });
  } catch (const Error& error) {
    // The packing's own values (a particle size, a diverging state): name the file.
    if (error.kind() == ErrorKind::kIoError) throw;
    throw Error(error.kind(), flags.input + ": " + error.what());
  }
  const SettleReport& r = result.report;
  write_packing(flags.output, result.packing, {.overwrite = overwrite});
  fmt::print("{} after {:.2f} s simulated ({} steps of {:.4g} s, {:.1f} s wall)\n",
             r.is_at_rest ? "at rest" : "NOT at rest (max time reached)", r.simulated_time, r.steps,
             r.time_step, r.wall_seconds);
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

void register_sim(CLI::App& app) {
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
  {
    auto flags = std::make_shared<ReposeFlags>();
    auto* command = app.add_subcommand(
        "repose",
        "The paper's angle-of-repose test: lattice fill behind a baffle, settle, move "
        "the baffle away, measure the slope (profile + least-squares line). Default: "
        "the paper's case (trough 6 x 1 x 1 m, alpha 0.5, R 0.1 m, L 0.1 m, 1,050 "
        "particles). Writes repose.json, profile.csv, side.png (and final.h5).");
    add_config_options(*command, *flags);
    command->callback([flags]() { run_repose_command(*flags); });
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
    command->callback([flags]() { run_sweep_command(*flags); });
  }
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
