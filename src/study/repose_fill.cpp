// The fill of the angle-of-repose test, made by the pipeline's pack(): the one place the CLI's
// repose/sweep and the Python module get it from (through the study calls); and the YADE script
// of a repose run (engine yade), the io module's writer fed with the repose options.

#include <cmath>
#include <ostream>

#include "aggpack/io/yade_repose.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/study/repose_study.h"

namespace aggpack::study {

PackResult repose_fill(const ReposeOptions& options) {
  return pack(PackerOptions{repose_fill_options(options)});
}

void write_repose_yade_script(const Packing& initial, const ReposeOptions& options,
                              std::ostream& out) {
  const double g = options.physics.gravity.norm();
  const YadeReposeScript script{
      .trough_length = options.trough_length,
      .trough_width = options.width(),
      .baffle_position = options.baffle_position,
      .baffle_thickness = options.baffle_thickness,
      .baffle_speed = options.baffle_speed,
      .baffle_clear_time = options.baffle_clear_time,
      .density = options.physics.density,
      .young = options.yade.young,
      .friction = options.physics.friction,
      .wall_friction = options.physics.wall_friction.value_or(options.physics.friction),
      .gravity = g,
      .damping = options.yade.damping,
      .time_step = 0.0,
      .kinetic_energy_ratio = options.rest.kinetic_energy_ratio,
      .quiet_time = options.rest.quiet_time,
      .check_interval = options.rest.check_interval,
      // As the Bullet run's stage 1: the fill's free fall first.
      .stage1_min_time = options.rest.min_time + std::sqrt(2.0 * options.fill_height / g),
      .min_time = options.rest.min_time,
      .max_time = options.rest.max_time,
      .confirm_window = options.confirm_window,
      .confirm_speed = options.confirm_speed,
      .fit_lower = options.fit_lower,
  };
  write_yade_repose_script(initial, script, out);
}

}  // namespace aggpack::study
