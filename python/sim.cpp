// Physics (aggpack/sim, Bullet), when the module is built with it (AGGPACK_BUILD_SIM):
// Packing.settle(), as `aggpack settle` runs it, the report as a dict (repose() and sweep() are
// in study.cpp). aggpack.has_sim says whether they exist.

#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>

#include "bindings.h"

#ifdef AGGPACK_HAS_SIM
#include "aggpack/sim/settle.h"
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

std::shared_ptr<PyPacking> wrap(Packing packing) {
  auto result = std::make_shared<PyPacking>();
  result->packing = std::move(packing);
  return result;
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

#else
  m.attr("has_sim") = false;
#endif
}

}  // namespace aggpack::python
