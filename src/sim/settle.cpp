#include "aggpack/sim/settle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"

namespace aggpack {

namespace {

double solid_volume(const Packing& packing) {
  std::vector<double> shape_volume(packing.shapes.size(), -1.0);
  double volume = 0.0;
  for (const auto& particle : packing.particles) {
    double& v = shape_volume.at(particle.shape);
    if (v < 0.0) v = mass_properties(packing.shapes[particle.shape]).volume;
    volume += v * particle.scale * particle.scale * particle.scale;
  }
  return volume;
}

// The energy scale of "at rest": sum m g d, the work to lift every particle by its own size.
double energy_scale(const World& world) {
  // m_i and d_i are per particle; d_i = (6 m_i / (pi rho))^(1/3) would need the density, so use
  // the world's sizes through the mass: sum m_i g d_median is close enough for a threshold and
  // keeps the criterion independent of how the packing is graded.
  return world.total_mass() * 9.81 * world.median_size();
}

}  // namespace

void validate(const RestCriterion& criterion) {
  require_in_range("kinetic_energy_ratio", criterion.kinetic_energy_ratio, 1e-12, 1.0);
  require_in_range("quiet_time", criterion.quiet_time, 0.0, 1e6);
  require_positive("check_interval", criterion.check_interval);
  require_in_range("min_time", criterion.min_time, 0.0, 1e6);
  require_positive("max_time", criterion.max_time);
}

double packing_height(const Packing& packing) {
  double top = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Particle& particle = packing.particles[i];
    const ConvexPolyhedron& shape = packing.shapes.at(particle.shape);
    for (const auto& v : shape.vertices()) {
      top = std::max(top, particle.pose.apply(particle.scale * v).z());
    }
  }
  return top;
}

double bulk_solid_fraction(const Packing& packing, double height) {
  if (!(height > 0.0)) return 0.0;
  return solid_volume(packing) / (container_floor_area(packing.container) * height);
}

std::size_t steps_per_check(const World& world, const RestCriterion& criterion) {
  const double step = world.time_step();
  const double total = criterion.max_time / step;
  if (!(step > 0.0) || !(total <= kMaxSimulationSteps)) {
    throw LimitExceeded("max_time", format_value(criterion.max_time) + " s",
                        "at most 10^8 time steps of " + format_value(step) + " s (d_min " +
                            format_value(world.smallest_size()) +
                            " m); lower max_time or raise "
                            "the time step");
  }
  return static_cast<std::size_t>(
      std::clamp(std::round(criterion.check_interval / step), 1.0, kMaxSimulationSteps));
}

void require_finite_state(const World& world, double kinetic_energy, const char* what) {
  if (std::isfinite(kinetic_energy) && world.is_finite()) return;
  throw Error(ErrorKind::kLimitExceeded,
              std::string(what) + ": the simulation diverged at t = " + format_value(world.time()) +
                  " s (step " + std::to_string(world.step_count()) + "): kinetic energy " +
                  format_value(kinetic_energy) +
                  " J or a particle's position or velocity is not finite; stopped");
}

bool run_until_rest(World& world, const RestCriterion& criterion, const SettleProgress& progress) {
  validate(criterion);
  const double threshold = criterion.kinetic_energy_ratio * energy_scale(world);
  const std::size_t steps = steps_per_check(world, criterion);
  const double start = world.time();
  double quiet_since = -1.0;
  while (world.time() - start < criterion.max_time) {
    world.step(steps);
    const double energy = world.kinetic_energy();
    require_finite_state(world, energy, "settling");
    if (progress) progress(world.time(), energy, threshold);
    if (world.time() - start < criterion.min_time) continue;
    if (energy < threshold) {
      if (quiet_since < 0.0) quiet_since = world.time();
      if (world.time() - quiet_since >= criterion.quiet_time) return true;
    } else {
      quiet_since = -1.0;
    }
  }
  return false;
}

SettleResult settle(const Packing& packing, const SettleOptions& options,
                    const SettleProgress& progress) {
  validate(options.rest);
  require_in_range("containment_tolerance", options.containment_tolerance, 0.0, 1.0);
  validate(packing.container);
  refuse_periodic(packing.container, "aggpack settle");
  const auto start = std::chrono::steady_clock::now();
  World world(packing, options.physics);

  SettleReport report;
  report.smallest_size = world.smallest_size();
  report.time_step = world.time_step();
  report.solid_volume = solid_volume(packing);
  report.height_before = packing_height(packing);
  report.solid_fraction_before = bulk_solid_fraction(packing, report.height_before);

  RestCriterion rest = options.rest;
  // Nothing can be at rest before the highest particle has had time to reach the floor.
  const double g = std::max(1e-9, options.physics.gravity.norm());
  // (Capped at the criterion's own range: a particle placed absurdly high then only means that the
  // run is not at rest when max_time ends.)
  rest.min_time = std::min(1e6, rest.min_time + std::sqrt(2.0 * report.height_before / g));
  report.is_at_rest = run_until_rest(world, rest, progress);

  SettleResult result{.packing = world.packing(), .report = {}};
  report.simulated_time = world.time();
  report.steps = world.step_count();
  report.kinetic_energy = world.kinetic_energy();
  report.kinetic_energy_threshold = rest.kinetic_energy_ratio * energy_scale(world);
  report.height_after = packing_height(result.packing);
  report.solid_fraction_after = bulk_solid_fraction(result.packing, report.height_after);
  const OverlapStatistics overlap = world.overlap_statistics();
  report.overlapping_pairs = overlap.overlapping_pairs;
  report.max_overlap = overlap.max_depth;
  report.max_overlap_fraction = overlap.max_depth_fraction;
  report.max_contact_penetration = world.contact_statistics().max_contact_penetration;

  const double tolerance = options.containment_tolerance * world.smallest_size();
  report.min_wall_clearance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < result.packing.particles.size(); ++i) {
    const Particle& particle = result.packing.particles[i];
    const ConvexPolyhedron& shape = result.packing.shapes[particle.shape];
    double clearance = std::numeric_limits<double>::infinity();
    for (const auto& v : shape.vertices()) {
      clearance = std::min(clearance, wall_clearance(result.packing.container,
                                                     particle.pose.apply(particle.scale * v)));
    }
    report.min_wall_clearance = std::min(report.min_wall_clearance, clearance);
    if (clearance < -tolerance) ++report.escaped_particles;
  }
  result.packing.provenance.packer += "+settled";
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.report = report;
  return result;
}

}  // namespace aggpack
