#pragma once
// The YADE trough shared by the exported deck (deck_yade.cpp, fixed stage times) and the script
// that `aggpack repose --engine yade` runs (deck_yade_repose.cpp, the rest criteria): the walls and
// the baffle, the polyhedra engines and the time step from the contact stiffness. Python text.
// Not a public header.

#include <string>

namespace aggpack::detail {

/// The trough's planes (output units): floor z, side walls y0/y1, end walls x0/x1, baffle x.
struct YadeTroughPlanes {
  double floor = 0.0;
  double y0 = 0.0;
  double y1 = 0.0;
  double x0 = 0.0;
  double x1 = 0.0;
  double baffle = 0.0;
};

/// `walls = [...]` (utils.wall planes of `material`), `baffle = utils.wall(...)` and their
/// O.bodies.append; `number` writes a value.
std::string yade_walls(const YadeTroughPlanes& planes, const std::string& material,
                       std::string (*number)(double));

/// `O.engines = [...]`: collider, polyhedra functors, the volumetric law, `runners` (PyRunner
/// lines, each "    PyRunner(...),\n"), NewtonIntegrator with `damping` (Python text) and
/// gravity GRAVITY along -z.
std::string yade_engines(const std::string& runners, const std::string& damping);

/// `def stiffness_time_step():` (over particle_ids, with `material`'s young and density).
std::string yade_time_step_function();

}  // namespace aggpack::detail
