// The fill of the angle-of-repose test, made by the pipeline's pack(): the one place the CLI's
// repose/sweep and the Python module get it from (through the study calls), with the checks a run
// makes before it starts; and the YADE script of a repose run (engine yade), the io module's
// writer fed with the repose options.

#include <cmath>
#include <cstddef>
#include <ostream>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/io/shape_library_files.h"
#include "aggpack/io/yade_repose.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/study/repose_study.h"

namespace aggpack::study {

namespace {

// Sites of the lattice packer: x fastest, then y, then z; along each axis
// n = floor((extent - 2 R) / 2R) + 1 sites centred in the box (lattice_packer.h).
void turn_about_sites(Packing& packing, const LatticeOptions& lattice) {
  const auto counts = lattice_counts(lattice);
  const double spacing = 2.0 * lattice.radius;
  const Vec3 extent = lattice.container.bounds().extent();
  Vec3 start;
  for (int axis = 0; axis < 3; ++axis) {
    start[axis] = 0.5 * (extent[axis] - (counts[static_cast<std::size_t>(axis)] - 1.0) * spacing);
  }
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const std::size_t ix = i % counts[0];
    const std::size_t iy = (i / counts[0]) % counts[1];
    const std::size_t iz = i / (static_cast<std::size_t>(counts[0]) * counts[1]);
    const Vec3 site = start + spacing * Vec3(static_cast<double>(ix), static_cast<double>(iy),
                                             static_cast<double>(iz));
    Particle& particle = packing.particles[i];
    if ((particle.pose.position - site).norm() > lattice.radius) {
      throw InvalidInput("repose lattice site " + std::to_string(i), "mismatch",
                         "particles numbered as lattice_packer.h documents");
    }
    Rng rng(lattice.seed ^ 0x726f74ULL, i);
    const Quat turn = Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized();
    particle.pose.position = site + turn * (particle.pose.position - site);
    particle.pose.rotation = (turn * particle.pose.rotation).normalized();
  }
}

}  // namespace

LatticeOptions repose_fill_options(const ReposeOptions& options) {
  LatticeOptions lattice;
  lattice.container.shape = BoxContainer{
      .length = options.baffle_position, .width = options.width(), .depth = options.fill_height};
  lattice.container.wall_gap = 0.0;
  lattice.alpha = options.alpha;
  lattice.radius = options.radius;
  lattice.edge_length = options.edge_length;
  lattice.form = options.form;
  lattice.files.options = options.library;
  lattice.seed = options.seed;
  return lattice;
}

void check_repose_inputs(const ReposeOptions& options) {
  validate(options);
  validate(repose_fill_options(options));
  if (options.library.is_used()) check_library_paths(options.library);
}

PackResult repose_fill(const ReposeOptions& options) {
  const LatticeOptions lattice = repose_fill_options(options);
  PackResult fill = pack(PackerOptions{lattice});
  if (options.is_orientation_random) turn_about_sites(fill.packing, lattice);
  return fill;
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
