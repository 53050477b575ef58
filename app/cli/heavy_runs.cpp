// Built only with AGGPACK_HAS_SIM (cmake/sim.cmake), as the commands that use it.
#ifdef AGGPACK_HAS_SIM

#include "heavy_runs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "aggpack/core/parallel.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/study/repose_study.h"
#include "progress.h"

namespace aggpack::cli {

RunEstimate estimate_settle(const Packing& packing, const SettleOptions& options) {
  std::vector<double> volumes(packing.shapes.size());
  double shape_bytes = 0.0;
  for (std::size_t k = 0; k < packing.shapes.size(); ++k) {
    volumes[k] = mass_properties(packing.shapes[k]).volume;
    shape_bytes += heap_bytes(packing.shapes[k]);
  }
  double d_min = std::numeric_limits<double>::infinity();
  for (const Particle& particle : packing.particles) {
    if (particle.shape >= volumes.size()) continue;  // read_packing has refused such files
    d_min = std::min(d_min,
                     particle.scale * std::cbrt(6.0 * volumes[particle.shape] / std::numbers::pi));
  }
  if (!std::isfinite(d_min)) return {};
  const double time_step = options.physics.time_step > 0.0
                               ? options.physics.time_step
                               : automatic_time_step(d_min, options.physics.time_step_factor);
  const double steps = expected_steps(packing_height(packing), options.rest.min_time,
                                      options.rest.quiet_time, options.rest.max_time, time_step);
  return estimate_simulation(static_cast<double>(packing.particles.size()), shape_bytes, steps, 1.0,
                             1);
}

RunEstimate estimate_repose(const ReposeOptions& options, double runs, int parallel) {
  const LatticeOptions fill = study::repose_fill_options(options);
  const auto counts = lattice_counts(fill);
  const double sites = static_cast<double>(counts[0]) * counts[1] * counts[2];
  const double time_step =
      options.physics.time_step > 0.0
          ? options.physics.time_step
          : automatic_time_step(options.radius, options.physics.time_step_factor);
  const RestCriterion& rest = options.rest;
  // Stage 2: the baffle moves until the pile no longer touches it (a few particle sizes: 2.8 x 2R
  // in the CLI's tiny trough test), then the wait for rest.
  const double travel =
      std::clamp(options.trough_length - options.baffle_position, 0.0, 6.0 * options.radius) /
      options.baffle_speed;
  const double steps = expected_steps(options.fill_height, rest.min_time, rest.quiet_time,
                                      rest.max_time, time_step) +
                       expected_steps(0.0, travel + options.baffle_clear_time, rest.quiet_time,
                                      rest.max_time + travel, time_step);
  // A grown particle's vertices and triangles: ~100 vertices (RESULTS.md) at 24 + 12 bytes each.
  constexpr double kShapeBytes = 100 * 24.0 + 200 * 12.0;
  return estimate_simulation(sites, sites * kShapeBytes, steps, runs, parallel);
}

void announce_repose(const ReposeOptions& options, const RunShare& share, std::size_t runs) {
  std::size_t owned = 0;
  for (std::size_t i = 0; i < runs; ++i) owned += share.owns(i) ? 1 : 0;
  announce_heavy_run(
      estimate_repose(options, static_cast<double>(owned), runs > 1 ? allowed_threads() : 1));
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
