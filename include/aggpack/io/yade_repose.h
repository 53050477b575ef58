#pragma once
// The YADE script of `aggpack repose --engine yade`: the repose test's fill rebuilt as YADE
// polyhedra (the export's bodies), the deck's trough, walls, engines and time step
// (src/io/deck_yade_common.h), and in place of the deck's fixed stage times the repose test's own
// stages and rest criteria run by a PyRunner (aggpack/sim/repose.h): settle until the kinetic
// energy stays low, move the baffle until it is untouched and clear of the pile (then remove it),
// wait for rest and confirm it. The script prints progress lines and writes every particle's pose
// after stage 1 and at the end to a text file; the sim module runs it (repose_yade.h).

#include <iosfwd>
#include <string>

#include "aggpack/pack/packing.h"

namespace aggpack {

/// Everything the script needs besides the particles. SI units; the trough is x in
/// [0, trough_length], y in [0, trough_width], floor z = 0.
struct YadeReposeScript {
  double trough_length = 6.0;
  double trough_width = 1.0;
  double baffle_position = 3.0;  ///< x of the baffle's face (particles behind it)
  double baffle_thickness = 0.05;
  double baffle_speed = 0.5;
  double baffle_clear_time = 0.2;
  double density = 2700.0;
  /// PolyhedraMat.young: the volumetric law's stiffness, force per overlap volume (N/m^3).
  double young = 1e7;
  double friction = 0.5;       ///< particle-particle mu_s (frictionAngle atan(mu))
  double wall_friction = 0.5;  ///< particle-wall mu_s
  double gravity = 9.81;       ///< along -z
  double damping = 0.3;        ///< NewtonIntegrator's (Cundall's local) damping, [0, 1)
  double time_step = 0.0;      ///< s; 0 = 0.2 sqrt(m / (young pi r^2)) of the lightest particle
  // Rest criteria (aggpack/sim/settle.h RestCriterion, aggpack/sim/repose.h ReposeOptions).
  double kinetic_energy_ratio = 3e-5;  ///< at rest below ratio x M g d (d median size)
  double quiet_time = 0.25;
  double check_interval = 0.02;
  double stage1_min_time = 0.0;           ///< s before stage 1 tests rest (min_time + free fall)
  double min_time = 0.0;                  ///< s after the baffle before stage 2 tests rest
  double max_time = 30.0;                 ///< s per stage
  double confirm_window = 30.0;           ///< x sqrt(d / g); 0 = off
  double confirm_speed = 0.05;            ///< x sqrt(g d)
  double fit_lower = 0.2;                 ///< pile particles: centres above this x crest height
  double progress_seconds = 2.0;          ///< wall-clock s between progress lines
  std::string result_file = "poses.txt";  ///< written in the working folder
};

/// Writes the script. Particles keep their order (body i = particle i).
/// \throw InvalidInput for an empty packing.
void write_yade_repose_script(const Packing& initial, const YadeReposeScript& script,
                              std::ostream& out);

}  // namespace aggpack
