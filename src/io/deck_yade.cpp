// YADE deck (.py): the bodies script of export_yade.cpp, then the trough test: floor and walls
// (utils.wall), the baffle as a wall moved by a PyRunner, the polyhedra engines (collider,
// geometry/physics/law functors, Newton integrator with gravity and damping), a time step from
// the particles' mass and contact stiffness, and O.run for the whole test, then a one-line summary.

#include "deck_common.h"
#include "deck_yade_common.h"

namespace aggpack::detail {

void write_deck_yade(const ExportModel& model, std::ostream& out) {
  const std::vector<ParticleBounds> bounds = particle_bounds(model);
  const Trough t = make_trough(model, bounds);
  const double time_step = model.options().deck.time_step;
  out << deck_header(
      model, t, "YADE", "yade -n -x <this file> (or yade <this file> for the GUI)", "# ",
      {"YADE: PolyhedraMat.young is the stiffness of YADE's volumetric polyhedra contact law "
       "(force per overlap volume, N/m^3), not the rock's modulus: YADE's examples use 1e7 .. "
       "1e8; a large value needs a tiny time step. The time step is " +
           (time_step > 0.0 ? deck_number(time_step) + " s [--time-step]"
                            : std::string("0.2 sqrt(m / (young pi r^2)) of the lightest "
                                          "particle (mass m, equivalent radius r) [--time-step]")) +
           "; NewtonIntegrator damping 0.3 (YADE's usual numerical damping) dissipates energy "
           "besides friction.",
       "YADE: floor and walls are utils.wall planes; the baffle is a wall plane moved at the "
       "baffle speed by a PyRunner during step BAFFLE."});
  write_yade(model, out);

  const auto n = [](double value) { return deck_number(value); };
  std::string text =
      "\n# ---- The trough test (aggpack deck) ----\nimport math\nfrom yade import utils\n\n"
      "FRICTION = " +
      n(t.friction) + "\nGRAVITY = " + n(t.gravity) + "\nSETTLE_TIME = " + n(t.settle_time) +
      "\nBAFFLE_TIME = " + n(t.baffle_time) + "\nREST_TIME = " + n(t.rest_time) +
      "\nBAFFLE_SPEED = " + n(t.baffle_speed) + "\nTROUGH_END = " + n(t.upper.x()) +
      "\nTIME_STEP = " + n(time_step) + "  # 0: stiffness_time_step()\n\n" +
      "material.frictionAngle = math.atan(FRICTION)\n"
      "particle_ids = [b.id for b in O.bodies]\n" +
      yade_walls({.floor = t.lower.z(),
                  .y0 = t.lower.y(),
                  .y1 = t.upper.y(),
                  .x0 = t.lower.x(),
                  .x1 = t.upper.x(),
                  .baffle = t.baffle},
                 "material", [](double value) { return deck_number(value); }) +
      "def move_baffle():\n"
      "    # Still in SETTLE, toward +x in BAFFLE (until the trough end), still again in REST.\n"
      "    moving = SETTLE_TIME <= O.time < SETTLE_TIME + BAFFLE_TIME and "
      "baffle.state.pos[0] < TROUGH_END\n"
      "    baffle.state.vel = Vector3(BAFFLE_SPEED if moving else 0.0, 0.0, 0.0)\n\n" +
      yade_engines("    PyRunner(iterPeriod=1, command='move_baffle()'),\n", "0.3") +
      yade_time_step_function() +
      "O.dt = TIME_STEP if TIME_STEP > 0 else stiffness_time_step()\n\n"
      "def mean_height():\n"
      "    return sum(O.bodies[i].state.pos[2] for i in particle_ids) / max(1, "
      "len(particle_ids))\n\n"
      "start_height = mean_height()\n"
      "steps = int(math.ceil((SETTLE_TIME + BAFFLE_TIME + REST_TIME) / O.dt))\n"
      "print('aggpack-yade: running %d steps of %g s' % (steps, O.dt))\n"
      "O.run(steps, True)\n"
      "speed = max(O.bodies[i].state.vel.norm() for i in particle_ids) if particle_ids else 0.0\n"
      "print('aggpack-yade: particles %d bodies %d iterations %d time %.9g mean_z_start %.9g "
      "mean_z_end %.9g max_speed %.9g baffle_x %.9g' % (len(particle_ids), len(O.bodies), "
      "O.iter, O.time, start_height, mean_height(), speed, baffle.state.pos[0]))\n";
  out << text;
}

}  // namespace aggpack::detail
