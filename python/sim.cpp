// Physics (aggpack/sim, Bullet), when the module is built with it (AGGPACK_BUILD_SIM): settle(),
// repose() and sweep(), as `aggpack settle|repose|sweep` run them, results as dicts.
// aggpack.has_sim says whether they exist.

#include <pybind11/stl.h>

#include <exception>
#include <memory>
#include <optional>
#include <string>

#include "bindings.h"

#ifdef AGGPACK_HAS_SIM
#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/sim/settle.h"
#include "aggpack/sim/sweep.h"
#endif

namespace aggpack::python {

#ifdef AGGPACK_HAS_SIM
namespace {

py::dict settle_dict(const SettleReport& r) {
  py::dict d;
  d["is_at_rest"] = r.is_at_rest;
  d["simulated_time"] = r.simulated_time;
  d["steps"] = r.steps;
  d["time_step"] = r.time_step;
  d["wall_seconds"] = r.wall_seconds;
  d["kinetic_energy"] = r.kinetic_energy;
  d["kinetic_energy_threshold"] = r.kinetic_energy_threshold;
  d["solid_volume"] = r.solid_volume;
  d["height_before"] = r.height_before;
  d["height_after"] = r.height_after;
  d["solid_fraction_before"] = r.solid_fraction_before;
  d["solid_fraction_after"] = r.solid_fraction_after;
  d["overlapping_pairs"] = r.overlapping_pairs;
  d["max_overlap"] = r.max_overlap;
  d["max_overlap_fraction"] = r.max_overlap_fraction;
  d["escaped_particles"] = r.escaped_particles;
  return d;
}

py::dict fit_dict(const SlopeFit& fit) {
  py::dict d;
  d["is_valid"] = fit.is_valid;
  d["message"] = fit.message;
  d["angle_degrees"] = fit.angle_degrees;
  d["slope"] = fit.slope;
  d["intercept"] = fit.intercept;
  d["r_squared"] = fit.r_squared;
  d["pile_height"] = fit.pile_height;
  d["first_bin"] = fit.first_bin;
  d["last_bin"] = fit.last_bin;
  return d;
}

std::shared_ptr<PyPacking> wrap(Packing packing) {
  auto result = std::make_shared<PyPacking>();
  result->packing = std::move(packing);
  return result;
}

// Sweep options from None / dict / TOML text, with the CLI's keys and messages.
SweepOptions sweep_options(const py::object& config, const std::vector<std::string>& overrides) {
  std::string text;
  std::string source = "config";
  if (py::isinstance<py::dict>(config)) {
    // The same dict -> TOML conversion as PackConfig.from_dict.
    text = py::module_::import("aggpack").attr("_dict_to_toml")(config).cast<std::string>();
    source = "config dict";
  } else if (py::isinstance<py::str>(config)) {
    text = config.cast<std::string>();
  } else if (!config.is_none()) {
    throw InvalidInput("config", py::repr(config).cast<std::string>(),
                       "None (the paper's case), a dict or a TOML string");
  }
  SweepOptions options = parse_sweep_config(text, source, overrides);
  with_sweep_key_names([&] { validate(options); });
  return options;
}

}  // namespace
#endif

void register_sim(py::module_& m) {
#ifdef AGGPACK_HAS_SIM
  m.attr("has_sim") = true;
  auto packing = m.attr("Packing").cast<py::class_<PyPacking, std::shared_ptr<PyPacking>>>();
  packing.def(
      "settle",
      [](const PyPacking& p, double friction, std::optional<double> wall_friction,
         double restitution, double rolling_friction, double density, double time_step,
         double time_step_factor, int solver_iterations, double kinetic_energy_ratio,
         double quiet_time, double max_time) {
        SettleOptions options;
        options.physics.friction = friction;
        options.physics.wall_friction = wall_friction;
        options.physics.restitution = restitution;
        options.physics.rolling_friction = rolling_friction;
        options.physics.density = density;
        options.physics.time_step = time_step;
        options.physics.time_step_factor = time_step_factor;
        options.physics.solver_iterations = solver_iterations;
        options.rest.kinetic_energy_ratio = kinetic_energy_ratio;
        options.rest.quiet_time = quiet_time;
        options.rest.max_time = max_time;
        std::optional<SettleResult> result;
        {
          const py::gil_scoped_release release;
          result = settle(p.packing, options);
        }
        auto settled = wrap(std::move(result->packing));
        settled->target = p.target;
        return py::make_tuple(settled, settle_dict(result->report));
      },
      py::kw_only(), py::arg("friction") = 0.5, py::arg("wall_friction") = py::none(),
      py::arg("restitution") = 0.1, py::arg("rolling_friction") = 0.0, py::arg("density") = 2650.0,
      py::arg("time_step") = 0.0, py::arg("time_step_factor") = 0.04,
      py::arg("solver_iterations") = 100, py::arg("kinetic_energy_ratio") = 3e-5,
      py::arg("quiet_time") = 0.25, py::arg("max_time") = 30.0,
      R"doc(Gravity settling (Bullet), as `aggpack settle`: the particles fall in the container
(floor and side walls, open top) until at rest. Deterministic. Releases the GIL; cannot be
cancelled (bound it with max_time).

Keywords (the CLI's flag in brackets): friction 0.5 [--mu], wall_friction None = friction
[--mu-wall], restitution 0.1, rolling_friction 0.0, density 2650 kg/m^3, time_step 0 = automatic
(s) [--dt], time_step_factor 0.04, solver_iterations 100, kinetic_energy_ratio 3e-5 (rest when
the kinetic energy stays below this x M g d), quiet_time 0.25 s, max_time 30 s (simulated).

Returns (settled Packing, report dict: is_at_rest, simulated_time s, steps, time_step s,
wall_seconds, kinetic_energy J, solid_fraction_before/after (bulk), height_before/after m,
overlapping_pairs, max_overlap m, escaped_particles, ...). Raises InvalidInput naming the keyword.)doc");

  m.def(
      "repose",
      [](const py::object& config, const std::vector<std::string>& overrides) {
        const SweepOptions options = sweep_options(config, overrides);
        std::optional<ReposeResult> result;
        {
          const py::gil_scoped_release release;
          with_sweep_key_names(
              [&] {  // physics.engine = "yade" runs YADE (aggpack/sim/repose_yade.h)
                result = run_repose_engine(options.base, repose_fill(options.base),
                                           write_repose_yade_script);
              });
        }
        py::dict d;
        d["angle_degrees"] = result->fit.angle_degrees;
        d["fit"] = fit_dict(result->fit);
        d["particle_count"] = result->particle_count;
        d["solid_volume"] = result->solid_volume;
        d["mean_measured_alpha"] = result->mean_measured_alpha;
        d["time_step"] = result->time_step;
        d["is_stage1_at_rest"] = result->is_stage1_at_rest;
        d["stage1_time"] = result->stage1_time;
        d["is_stage2_at_rest"] = result->is_stage2_at_rest;
        d["stage2_time"] = result->stage2_time;
        d["baffle_travel"] = result->baffle_travel;
        d["escaped_particles"] = result->escaped_particles;
        py::dict profile;
        std::vector<double> x(result->profile.height.size());
        for (std::size_t i = 0; i < x.size(); ++i) x[i] = result->profile.centre(i);
        profile["x"] = to_numpy(std::move(x));
        profile["height"] = to_numpy(std::vector<double>(result->profile.height));
        d["profile"] = profile;
        d["initial"] = wrap(std::move(result->initial));
        d["settled"] = wrap(std::move(result->settled));
        d["final"] = wrap(std::move(result->final));
        return d;
      },
      py::arg("config") = py::none(), py::arg("overrides") = std::vector<std::string>{},
      R"doc(The angle-of-repose trough test, as `aggpack repose [CONFIG.toml] --set ...`: the
paper's lattice fill behind the baffle, stage 1 settles it, stage 2 moves the baffle away, the
pile's slope is fitted. config: None (the paper's case), a dict or TOML text with the tables of
docs/config.md ([trough] [particles] [physics] [rest] [measure]); overrides: "key=value" strings.
Releases the GIL; minutes for the paper's 1,050 particles.

Returns a dict: angle_degrees, fit (is_valid, angle_degrees, slope, r_squared, pile_height, ...),
particle_count, solid_volume m^3, mean_measured_alpha, stage times (s), profile {x, height} (m,
float64 arrays), and the packings initial, settled, final. Raises ConfigError naming the key.)doc");

  m.def(
      "sweep",
      [](const py::object& config, const std::vector<std::string>& overrides) {
        const SweepOptions options = sweep_options(config, overrides);
        std::vector<SweepCase> cases;
        {
          const py::gil_scoped_release release;
          with_sweep_key_names(
              [&] { cases = run_sweep(options, repose_fill, {}, write_repose_yade_script); });
        }
        py::list rows;
        for (const SweepCase& c : cases) {
          py::dict d;
          d["index"] = c.index;
          d["alpha"] = c.alpha;
          d["friction"] = c.friction;
          d["mean_measured_alpha"] = c.mean_measured_alpha;
          d["particle_count"] = c.particle_count;
          d["is_valid"] = c.is_valid;
          d["angle_degrees"] = c.angle_degrees;
          d["r_squared"] = c.r_squared;
          d["is_at_rest"] = c.is_at_rest;
          d["simulated_time"] = c.simulated_time;
          d["seed"] = c.seed;
          rows.append(d);
        }
        return rows;
      },
      py::arg("config") = py::none(), py::arg("overrides") = std::vector<std::string>{},
      R"doc(The repose test over every (alpha, mu_s) case, as `aggpack sweep` (config and
overrides as repose(), plus the [sweep] table: alphas, frictions). Returns one dict per case in
index order: alpha, friction, angle_degrees, r_squared, is_valid, is_at_rest, particle_count,
mean_measured_alpha, simulated_time, seed. Releases the GIL; long.)doc");
#else
  m.attr("has_sim") = false;
#endif
}

}  // namespace aggpack::python
