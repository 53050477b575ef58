// Every key of the repose / sweep configuration, declared once (see aggpack/config/schema.h).
// Ranges are those of the sim module's validators; the validators' field names are listed per key
// so that their messages name the key.

#ifdef AGGPACK_HAS_SIM

#include "aggpack/config/repose_config.h"

#include <algorithm>
#include <iterator>

#include "aggpack/sim/distributed.h"
#include "binding.h"
#include "library_keys.h"

namespace aggpack {

namespace {

using config_detail::library_option_keys;
using config_detail::members;
using SweepKey = Key<SweepOptions>;

// The particle.library_* keys apply only with a library.
const Scope<SweepOptions> kLibrary{
    .text = "particle.library given",
    .applies = [](const SweepOptions& o) { return o.base.library.is_used(); }};

// A float key of the repose options.
template <typename Access>
SweepKey number(const char* name, const char* unit, Range range, const char* doc, Access access,
                std::vector<std::string> fields, std::string note = {}) {
  return {.name = name,
          .unit = unit,
          .range = range,
          .note = {Sentence::kText, {std::move(note)}},
          .doc = doc,
          .binding = members<SweepOptions>(access),
          .fields = std::move(fields)};
}

std::vector<SweepKey> keys() {
  std::vector<SweepKey> all = {
      number("trough.length", "m", open_closed(0, kMaxMagnitude), "trough length (x)",
             [](auto& o) -> auto& { return o.base.trough_length; }, {"repose.trough_length"}),
      number("trough.width", "m", open_closed(0, kMaxMagnitude), "trough width (y)",
             [](auto& o) -> auto& { return o.base.trough_width; },
             {"repose.trough_width", "container.width"}),
      number("trough.width_factor", "-", closed(1, 100),
             "multiplies trough.width and the fill's width: a wider trough (less wall effect, "
             "more particles), the pile's side view unchanged",
             [](auto& o) -> auto& { return o.base.width_factor; }, {"repose.width_factor"}),
      number("trough.height", "m", open_closed(0, kMaxMagnitude),
             "trough wall height (walls reach the fill top during stage 1)",
             [](auto& o) -> auto& { return o.base.trough_height; }, {"repose.trough_height"}),
      number(
          "trough.baffle_position", "m", open_closed(0, kMaxMagnitude),
          "x of the baffle; particles fill [0, baffle_position]",
          [](auto& o) -> auto& { return o.base.baffle_position; },
          {"repose.baffle_position", "container.length"}, "< trough.length"),
      number("trough.baffle_thickness", "m", open_closed(0, kMaxMagnitude), "baffle thickness",
             [](auto& o) -> auto& { return o.base.baffle_thickness; }, {"repose.baffle_thickness"}),
      number("trough.baffle_speed", "m/s", open_closed(0, kMaxMagnitude),
             "baffle speed toward +x in stage 2",
             [](auto& o) -> auto& { return o.base.baffle_speed; }, {"repose.baffle_speed"}),
      number("trough.baffle_clear_time", "s", closed(0, 1e3),
             "baffle removed once untouched this long and clear of the pile",
             [](auto& o) -> auto& { return o.base.baffle_clear_time; },
             {"repose.baffle_clear_time"}),
      number("particle.alpha", "-", closed(0, 1), "Eq. 3 shape control alpha, [0, 1]",
             [](auto& o) -> auto& { return o.base.alpha; },
             {"repose.alpha", "lattice.alpha", "alpha"}),
      number("particle.radius", "m", open_closed(0, kMaxMagnitude),
             "control radius R; lattice spacing 2R", [](auto& o) -> auto& { return o.base.radius; },
             {"repose.radius", "lattice.radius", "radius"}),
      number("particle.edge_length", "m", open_closed(0, kMaxMagnitude), "maximum edge length L",
             [](auto& o) -> auto& { return o.base.edge_length; },
             {"repose.edge_length", "lattice.edge_length", "lattice.max_vertices", "edge_length",
              "max_vertices"}),
      {.name = "particle.growth",
       .type = ValueType::kWord,
       .words = {growth_name(Growth::kHull), growth_name(Growth::kMidpoint)},
       .doc = "where growth puts a new vertex: hull (the paper's words) or midpoint (aggpack "
              "0.1's rule); see particle.growth",
       .binding = members<SweepOptions>([](auto& o) -> auto& { return o.base.form.growth; })},
      number("particle.elongation", "-", closed(0.1, 1),
             "control ellipsoid's intermediate / long semi-axis (1 = sphere)",
             [](auto& o) -> auto& { return o.base.form.elongation; }, {"repose.elongation"}),
      number("particle.flatness", "-", closed(0.1, 1),
             "control ellipsoid's short / intermediate semi-axis (1 = sphere)",
             [](auto& o) -> auto& { return o.base.form.flatness; }, {"repose.flatness"}),
      number("particle.min_edge_ratio", "-", closed(0, 0.5),
             "minimum edge length / L of hull growth (see particle.min_edge_ratio)",
             [](auto& o) -> auto& { return o.base.form.min_edge_ratio; },
             {"repose.min_edge_ratio"}),
      number("particle.fill_height", "m", open_closed(0, kMaxMagnitude),
             "height of the lattice region", [](auto& o) -> auto& { return o.base.fill_height; },
             {"repose.fill_height", "container.depth"}),
      {.name = "particle.seed",
       .type = ValueType::kInteger,
       .unit = "-",
       .range = {.lo = 0, .hi = 9223372036854775807.0, .hi_text = "2^63 - 1"},
       .doc = "master seed; particle i uses stream (seed, i)",
       .binding = members<SweepOptions>([](auto& o) -> auto& { return o.base.seed; })},
      {.name = "particle.random_orientation",
       .type = ValueType::kBool,
       .unit = "-",
       .doc = "turn each particle randomly about its lattice site",
       .binding =
           members<SweepOptions>([](auto& o) -> auto& { return o.base.is_orientation_random; })},
      // particle.library (its options below, as particle.library's: library_keys.h); the
      // lattice fill's checks name particle.library_*, renamed here by `fields`.
      {.name = "particle.library",
       .type = ValueType::kPathList,
       .written = kLibrary,
       .doc = "a folder of particle meshes (.stl, .obj, .ply), one such file, or an array of "
              "folders and files: every lattice site holds one of them (its convex hull, "
              "enclosing radius particle.radius, randomly turned) instead of a grown particle; "
              "unset = grown particles",
       .binding = members<SweepOptions>([](auto& o) -> auto& { return o.base.library.paths; }),
       .presence = Presence::kOptional,
       .default_text = {Sentence::kDefaultNone, {}},
       .fields = {"particle.library"}},
      number("physics.density", "kg/m^3", open_closed(0, kMaxMagnitude), "particle density",
             [](auto& o) -> auto& { return o.base.physics.density; }, {"density"}),
      number("physics.friction", "-", closed(0, 10), "sliding friction mu_s particle-particle",
             [](auto& o) -> auto& { return o.base.physics.friction; }, {"friction"}),
      {.name = "physics.wall_friction",
       .unit = "-",
       .range = closed(-1, 10),
       .note = {Sentence::kText, {"< 0 = same as physics.friction"}},
       .doc = "sliding friction particle-wall; -1 = same as physics.friction",
       .binding = {.get = [](const SweepOptions& o) -> Value {
                     return o.base.physics.wall_friction.value_or(-1.0);
                   },
                   .set =
                       [](SweepOptions& o, const Value& value) {
                         const double mu = std::get<double>(value);
                         o.base.physics.wall_friction =
                             mu < 0.0 ? std::nullopt : std::optional<double>(mu);
                       }},
       .fields = {"wall_friction"}},
      number("physics.restitution", "-", closed(0, 1), "coefficient of restitution, [0, 1]",
             [](auto& o) -> auto& { return o.base.physics.restitution; }, {"restitution"}),
      number("physics.rolling_friction", "-", closed(0, 1),
             "rolling friction mu_r (torque <= mu_r r F_n), 0 = off",
             [](auto& o) -> auto& { return o.base.physics.rolling_friction; },
             {"rolling_friction"}),
      number("physics.time_step", "s", closed(0, 1), "time step, 0 = automatic",
             [](auto& o) -> auto& { return o.base.physics.time_step; }, {"time_step"}),
      number("physics.time_step_factor", "-", closed(1e-6, 1),
             "automatic time step = factor * sqrt(d_min / g)",
             [](auto& o) -> auto& { return o.base.physics.time_step_factor; },
             {"time_step_factor"}),
      {.name = "physics.solver_iterations",
       .type = ValueType::kInteger,
       .unit = "-",
       .range = closed(1, 1000),
       .doc = "solver iterations per step, [1, 1000]",
       .binding =
           members<SweepOptions>([](auto& o) -> auto& { return o.base.physics.solver_iterations; }),
       .fields = {"solver_iterations"}},
      number("physics.margin_fraction", "-", closed(1e-4, 0.1), "collision margin / d_min",
             [](auto& o) -> auto& { return o.base.physics.margin_fraction; }, {"margin_fraction"}),
      {.name = "physics.solver",
       .type = ValueType::kWord,
       .words = {"gauss-seidel", "blocked"},
       .doc = "velocity solver: gauss-seidel = Bullet's sweeps over all contacts; blocked = the "
              "same sweeps in cache-sized blocks of contacts (faster on large piles, other "
              "trajectories)",
       .binding = {.get = [](const SweepOptions& o) -> Value {
                     return std::string(to_string(o.base.physics.solver));
                   },
                   .set =
                       [](SweepOptions& o, const Value& value) {
                         o.base.physics.solver =
                             solver_kind_from_string(std::get<std::string>(value));
                       }},
       .fields = {"solver"}},
      {.name = "physics.solver_block_contacts",
       .type = ValueType::kInteger,
       .unit = "-",
       .range = closed(1, 1000000),
       .doc = "blocked solver: contact points per block",
       .binding = members<SweepOptions>(
           [](auto& o) -> auto& { return o.base.physics.solver_block_contacts; }),
       .fields = {"solver_block_contacts"}},
      {.name = "physics.solver_block_sweeps",
       .type = ValueType::kInteger,
       .unit = "-",
       .range = closed(1, 1000),
       .doc = "blocked solver: sweeps of a block before the next",
       .binding = members<SweepOptions>(
           [](auto& o) -> auto& { return o.base.physics.solver_block_sweeps; }),
       .fields = {"solver_block_sweeps"}},
      {.name = "physics.engine",
       .type = ValueType::kWord,
       .words = {"bullet", "yade"},
       .doc = "physics engine: bullet (built in) or yade (Debian's yade as a subprocess: "
              "polyhedra, volumetric contact law; far slower, see the [yade] keys)",
       .binding = {.get = [](const SweepOptions& o) -> Value {
                     return std::string(to_string(o.base.engine));
                   },
                   .set =
                       [](SweepOptions& o, const Value& value) {
                         o.base.engine = repose_engine_from_string(std::get<std::string>(value));
                       }},
       .fields = {"repose.engine"}},
      number("yade.young", "N/m^3", closed(0, 1e15),
             "YADE's contact stiffness (PolyhedraMat.young: force per overlap volume); 0 = "
             "density g fill_height / (0.005 d), a static overlap of about 0.5 % of d",
             [](auto& o) -> auto& { return o.base.yade.young; }, {"repose.yade_young"}),
      number("yade.damping", "-", closed(0, 0.99),
             "YADE's NewtonIntegrator (local, Cundall) damping",
             [](auto& o) -> auto& { return o.base.yade.damping; }, {"repose.yade_damping"}),
      number("yade.time_limit", "s", closed(0, 1e7),
             "wall-clock seconds one YADE run may take, 0 = no limit",
             [](auto& o) -> auto& { return o.base.yade.time_limit; }, {"repose.yade_time_limit"}),
      number("rest.kinetic_energy_ratio", "-", closed(1e-12, 1),
             "at rest when kinetic energy < ratio * M g d",
             [](auto& o) -> auto& { return o.base.rest.kinetic_energy_ratio; },
             {"kinetic_energy_ratio"}),
      number("rest.quiet_time", "s", closed(0, kMaxMagnitude), "time the rest criterion must hold",
             [](auto& o) -> auto& { return o.base.rest.quiet_time; }, {"quiet_time"}),
      number("rest.check_interval", "s", open_closed(0, kMaxMagnitude), "time between rest checks",
             [](auto& o) -> auto& { return o.base.rest.check_interval; }, {"check_interval"}),
      number("rest.max_time", "s", open_closed(0, kMaxMagnitude), "simulated time limit per stage",
             [](auto& o) -> auto& { return o.base.rest.max_time; }, {"max_time"}),
      number("rest.confirm_window", "sqrt(d/g)", closed(0, 1e4),
             "stage 2: after the energy/surface tests, follow the pile this long (x sqrt(d/g), d "
             "median size) before it counts as at rest; 0 = off",
             [](auto& o) -> auto& { return o.base.confirm_window; }, {"repose.confirm_window"}),
      number("rest.confirm_angle_tolerance", "deg", open_closed(0, 90),
             "largest change of the angle over the confirmation window",
             [](auto& o) -> auto& { return o.base.confirm_angle_tolerance; },
             {"repose.confirm_angle_tolerance"}),
      number("rest.confirm_height_tolerance", "-", open_closed(0, 10),
             "largest change of the crest height over the window, x d",
             [](auto& o) -> auto& { return o.base.confirm_height_tolerance; },
             {"repose.confirm_height_tolerance"}),
      number("rest.confirm_speed", "-", open_closed(0, 10),
             "speed 99 % of the pile stay below during the window, x sqrt(g d)",
             [](auto& o) -> auto& { return o.base.confirm_speed; }, {"repose.confirm_speed"}),
      number("rest.follow_time", "s", closed(0, 1e3),
             "diagnostic: follow the pile this long after rest and measure again (follow_up)",
             [](auto& o) -> auto& { return o.base.follow_time; }, {"repose.follow_time"}),
      number(
          "measure.bin_width", "m", closed(0, kMaxMagnitude), "profile bin width, 0 = radius / 2",
          [](auto& o) -> auto& { return o.base.bin_width; }, {"repose.bin_width"},
          "<= trough.length"),
      number("measure.fit_upper", "-", closed(1e-6, 1), "slope region below this x pile height",
             [](auto& o) -> auto& { return o.base.fit_upper; }, {"repose.fit_upper"}),
      number(
          "measure.fit_lower", "-", closed(0, 1), "slope region above this x pile height",
          [](auto& o) -> auto& { return o.base.fit_lower; }, {"repose.fit_lower"},
          "< measure.fit_upper"),
      number("measure.surface_tolerance", "-", closed(0, 10),
             "stage 2 ends when the surface moves less than this x d",
             [](auto& o) -> auto& { return o.base.surface_tolerance; },
             {"repose.surface_tolerance"}),
      {.name = "sweep.alphas",
       .type = ValueType::kNumberList,
       .unit = "-",
       .range = closed(0, 1),
       .note = {Sentence::kText, {"at least one value"}},
       .doc = "alpha values of the sweep",
       .binding = members<SweepOptions>([](auto& o) -> auto& { return o.alphas; })},
      {.name = "sweep.frictions",
       .type = ValueType::kNumberList,
       .unit = "-",
       .range = closed(0, 10),
       .note = {Sentence::kText, {"at least one value"}},
       .doc = "mu_s values of the sweep",
       .binding = members<SweepOptions>([](auto& o) -> auto& { return o.frictions; })},
      {.name = "sweep.wall_friction_coupled",
       .type = ValueType::kBool,
       .unit = "-",
       .doc = "walls take each case's mu_s",
       .binding =
           members<SweepOptions>([](auto& o) -> auto& { return o.is_wall_friction_coupled; })},
  };
  // particle.library's options, declared with particle.library's (library_keys.h), after it.
  auto options = library_option_keys<SweepOptions>(
      "particle.", kLibrary, "the fill needs at least as many shapes as lattice sites",
      [](auto member) {
        return members<SweepOptions>([member](auto& o) -> auto& { return member(o.base.library); });
      });
  const auto library = std::find_if(
      all.begin(), all.end(), [](const SweepKey& key) { return key.name == "particle.library"; });
  all.insert(library + 1, std::make_move_iterator(options.begin()),
             std::make_move_iterator(options.end()));
  return all;
}

}  // namespace

namespace {

// [ensemble] (issue 15 items 2 and 6): the seed list, so that an ensemble is reproducible from
// the config file alone (`--seeds` overrides it).
std::vector<SweepKey> ensemble_keys() {
  return {
      {.name = "ensemble.seeds",
       .type = ValueType::kPath,
       .unit = "-",
       .note = {Sentence::kText,
                {"a non-empty seed list: 1-16, 1,4,9 or 1-4,9 (at most 10000 seeds)"}},
       .written = {.text = "given",
                   .applies = [](const SweepOptions& o) { return !o.seeds.empty(); }},
       .doc = "seed ensemble: `repose` runs once per seed (ensemble.json), `sweep` once per "
              "case and seed; unset = one run at particle.seed",
       .binding = {.get = [](const SweepOptions& o) -> Value { return format_seed_list(o.seeds); },
                   .set =
                       [](SweepOptions& o, const Value& value) {
                         // Empty: the default, no ensemble (a given value is non-empty).
                         const auto& text = std::get<std::string>(value);
                         o.seeds = text.empty() ? std::vector<std::uint64_t>{}
                                                : parse_seed_list(text, "ensemble.seeds");
                       }},
       .default_text = {Sentence::kDefaultUnset, {}}}};
}

}  // namespace

const Schema<SweepOptions>& sweep_schema() {
  static const Schema<SweepOptions> schema = [] {
    Schema<SweepOptions> s;
    s.tables = {{.name = "trough"},   {.name = "particle", .former_name = "particles"},
                {.name = "physics"},  {.name = "rest"},
                {.name = "measure"},  {.name = "sweep"},
                {.name = "ensemble"}, {.name = "yade"}};
    s.keys = keys();
    for (auto& key : ensemble_keys()) s.keys.push_back(std::move(key));
    s.aliases = {{"min_time", "fall time from particle.fill_height"}};
    config_detail::fill_defaults(s, SweepOptions{});
    return s;
  }();
  return schema;
}

SweepOptions parse_sweep_config(std::string_view text, std::string_view source_name,
                                const std::vector<std::string>& overrides,
                                std::vector<std::string>* notes) {
  const auto& schema = sweep_schema();
  const GivenValues given =
      read_values(schema.tables, key_views(schema), text, source_name, overrides, notes);
  SweepOptions options;
  resolve(schema, given, options);
  return options;
}

SweepOptions load_sweep_config(const std::string& path, const std::vector<std::string>& overrides,
                               std::vector<std::string>* notes) {
  if (path.empty()) return parse_sweep_config("", "defaults", overrides, notes);
  return parse_sweep_config(read_config_file(path), path, overrides, notes);
}

std::string resolved_sweep_config(const SweepOptions& options) {
  return write_values(sweep_schema(), options, WriteStyle::kCommented);
}

void with_sweep_key_names(const std::function<void()>& check) {
  const auto& schema = sweep_schema();
  with_key_names(key_views(schema), schema.aliases, check);
}

std::string sweep_keys_markdown(const std::string& table) {
  return markdown_table(sweep_schema(), table);
}

}  // namespace aggpack

#endif  // AGGPACK_HAS_SIM
