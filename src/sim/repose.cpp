#include "aggpack/sim/repose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "aggpack/core/clock.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/sim/ensemble.h"
#include "repose_detail.h"

namespace aggpack {

namespace {

std::string fmt_fill(const Container& c, std::size_t count) {
  const BoxContainer* box = c.get_if<BoxContainer>();
  return std::to_string(count) + " particles in a " +
         (box != nullptr
              ? "box " + format_value(box->length) + " x " + format_value(box->width) + " m"
              : std::string(container_kind_info(c).name));
}

double largest_size(const Packing& packing) {
  double largest = 0.0;
  for (const auto& particle : packing.particles) {
    const Aabb box = packing.shapes[particle.shape].bounds();
    largest = std::max(largest, particle.scale * box.extent().norm());
  }
  return largest;
}

// The speed 99 % of the pile's particles stay below (the largest when there are fewer than 100):
// centres above fit_lower x crest height, so particles rolling away over the floor are left out
// (as in the surface test); a single particle popping in Bullet's contact solver does not count,
// a collective motion (an avalanche) does.
double pile_speed(const World& world, double floor_height) {
  std::vector<double> speeds;
  speeds.reserve(world.particle_count());
  for (std::size_t i = 0; i < world.particle_count(); ++i) {
    if (world.pose(i).position.z() <= floor_height) continue;
    speeds.push_back(world.linear_velocity(i).norm());
  }
  if (speeds.empty()) return 0.0;
  const auto rank =
      static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(speeds.size()))) - 1;
  std::nth_element(speeds.begin(), speeds.begin() + static_cast<std::ptrdiff_t>(rank),
                   speeds.end());
  return speeds[rank];
}

// Stage 2 waits in two phases. (1) The pile is at rest by the energy criterion, or its surface has
// stopped changing: a few full particles rolling away over the floor at low friction can keep the
// energy up for a long time without changing the pile. The surface counts as unchanged while
// every bin above fit_lower x the pile height stays within surface_tolerance x d of where it was at
// the start of the quiet window. (2) Confirmation (options.confirm_window > 0): for the window
// after (1) passed, angle, crest height and the pile's fastest particle stay within their
// tolerances of the window's start; a violation restarts (1).
bool wait_until_stable(World& world, const ReposeOptions& options, double bin_width,
                       const SettleProgress& progress, ReposeResult::Confirmation& confirmation) {
  const RestCriterion& rest = options.rest;
  const double size = world.median_size();
  const double g = std::max(1e-9, options.physics.gravity.norm());
  const double threshold = rest.kinetic_energy_ratio * world.total_mass() * g * size;
  const double tolerance = options.surface_tolerance * size;
  const std::size_t smoothing = detail::repose_smoothing_bins(options, bin_width);
  confirmation.window = options.confirm_window * std::sqrt(size / g);
  confirmation.speed_limit = options.confirm_speed * std::sqrt(g * size);
  const double height_tolerance = options.confirm_height_tolerance * size;
  const bool is_confirmed = options.confirm_window > 0.0;
  const std::size_t steps = steps_per_check(world, rest);
  const double start = world.time();
  double energy_quiet_since = -1.0;
  SurfaceProfile reference;
  double reference_time = -1.0;
  double confirm_since = -1.0;
  SlopeFit confirm_reference;
  ReposeResult::Confirmation window;  // the current window's largest changes
  while (world.time() - start < rest.max_time) {
    world.step(steps);
    const double now = world.time();
    const double energy = world.kinetic_energy();
    require_finite_state(world, energy, "repose stage 2");
    if (progress) progress(now, energy, threshold);
    if (now - start < rest.min_time) continue;
    bool is_quiet = false;
    if (energy < threshold) {
      if (energy_quiet_since < 0.0) energy_quiet_since = now;
      if (now - energy_quiet_since >= rest.quiet_time) is_quiet = true;
    } else {
      energy_quiet_since = -1.0;
    }
    if (is_quiet && !is_confirmed) return true;
    const SurfaceProfile profile =
        surface_profile(world.packing(), 0.0, options.trough_length, bin_width);
    bool is_same = reference_time >= 0.0;
    if (is_same) {
      const double top = *std::max_element(reference.height.begin(), reference.height.end());
      for (std::size_t i = 0; i < profile.height.size() && is_same; ++i) {
        const double high = std::max(profile.height[i], reference.height[i]);
        if (high >= options.fit_lower * top &&
            std::abs(profile.height[i] - reference.height[i]) > tolerance) {
          is_same = false;
        }
      }
    }
    if (!is_same) {
      reference = profile;
      reference_time = now;
    } else if (now - reference_time >= rest.quiet_time) {
      is_quiet = true;
    }
    if (!is_confirmed) {
      if (is_quiet) return true;
      continue;
    }
    const SlopeFit fit = fit_slope(profile, options.fit_upper, options.fit_lower, smoothing);
    if (confirm_since < 0.0) {
      if (!is_quiet) continue;
      confirm_since = now;
      confirm_reference = fit;
      window = confirmation;
      window.angle_change = 0.0;
      window.height_change = 0.0;
      window.max_speed = 0.0;
    }
    const double speed = pile_speed(world, options.fit_lower * fit.pile_height);
    window.max_speed = std::max(window.max_speed, speed);
    window.height_change =
        std::max(window.height_change, std::abs(fit.pile_height - confirm_reference.pile_height));
    // A fit that becomes (in)valid counts as an unbounded change of the angle.
    const double angle_change = fit.is_valid == confirm_reference.is_valid
                                    ? std::abs(fit.angle_degrees - confirm_reference.angle_degrees)
                                    : std::numeric_limits<double>::infinity();
    window.angle_change = std::max(window.angle_change, angle_change);
    const bool is_fast = speed > confirmation.speed_limit;
    const bool is_sunk = window.height_change > height_tolerance;
    const bool is_turned = window.angle_change > options.confirm_angle_tolerance;
    if (is_fast || is_sunk || is_turned) {
      ++confirmation.restarts;
      confirmation.speed_restarts += is_fast ? 1 : 0;
      confirmation.height_restarts += is_sunk ? 1 : 0;
      confirmation.angle_restarts += is_turned ? 1 : 0;
      confirm_since = -1.0;
      energy_quiet_since = -1.0;
      reference = profile;
      reference_time = now;
      continue;
    }
    if (now - confirm_since >= confirmation.window) {
      window.restarts = confirmation.restarts;
      window.angle_restarts = confirmation.angle_restarts;
      window.height_restarts = confirmation.height_restarts;
      window.speed_restarts = confirmation.speed_restarts;
      confirmation = window;
      return true;
    }
  }
  return false;
}

}  // namespace

void validate(const ReposeOptions& options) {
  require_positive("repose.trough_length", options.trough_length);
  require_positive("repose.trough_width", options.trough_width);
  require_in_range("repose.width_factor", options.width_factor, 1.0, 100.0);
  require_positive("repose.trough_height", options.trough_height);
  require_positive("repose.baffle_thickness", options.baffle_thickness);
  if (!(options.baffle_position > 0.0) ||
      !(options.baffle_position + options.baffle_thickness < options.trough_length)) {
    throw InvalidInput("repose.baffle_position", format_value(options.baffle_position),
                       "(0, trough_length - baffle_thickness)");
  }
  require_positive("repose.baffle_speed", options.baffle_speed);
  require_in_range("repose.baffle_clear_time", options.baffle_clear_time, 0.0, 1e3);
  require_in_range("repose.alpha", options.alpha, 0.0, 1.0);
  require_positive("repose.radius", options.radius);
  require_positive("repose.edge_length", options.edge_length);
  validate(options.form, "repose.");
  require_positive("repose.fill_height", options.fill_height);
  require_in_range("repose.bin_width", options.bin_width, 0.0, options.trough_length);
  require_in_range("repose.fit_upper", options.fit_upper, 1e-6, 1.0);
  require_in_range("repose.fit_lower", options.fit_lower, 0.0, options.fit_upper - 1e-6);
  require_in_range("repose.surface_tolerance", options.surface_tolerance, 0.0, 10.0);
  require_in_range("repose.confirm_window", options.confirm_window, 0.0, 1e4);
  require_positive("repose.confirm_angle_tolerance", options.confirm_angle_tolerance);
  require_in_range("repose.confirm_angle_tolerance", options.confirm_angle_tolerance, 0.0, 90.0);
  require_positive("repose.confirm_height_tolerance", options.confirm_height_tolerance);
  require_in_range("repose.confirm_height_tolerance", options.confirm_height_tolerance, 0.0, 10.0);
  require_positive("repose.confirm_speed", options.confirm_speed);
  require_in_range("repose.confirm_speed", options.confirm_speed, 0.0, 10.0);
  require_in_range("repose.follow_time", options.follow_time, 0.0, 1e3);
  validate(options.physics);
  validate(options.rest);
  require_in_range("repose.yade_young", options.yade.young, 0.0, 1e15);
  require_in_range("repose.yade_damping", options.yade.damping, 0.0, 0.99);
  require_in_range("repose.yade_time_limit", options.yade.time_limit, 0.0, 1e7);
}

namespace detail {

Packing prepare_repose(const ReposeOptions& options, PackResult fill, ReposeResult& result) {
  Packing packing = std::move(fill.packing);
  const BoxContainer* region = packing.container.get_if<BoxContainer>();
  if (region == nullptr || !(region->length <= options.baffle_position) ||
      !(region->width <= options.width()) || packing.particles.empty()) {
    throw InvalidInput("repose fill", fmt_fill(packing.container, packing.particles.size()),
                       "a non-empty box packing within [0, baffle_position] x [0, trough width]");
  }
  const std::string packer = packing.provenance.packer;
  packing.container.shape = BoxContainer{
      .length = options.trough_length, .width = options.width(), .depth = options.trough_height};
  packing.provenance.packer = packer + "+repose";
  result.initial = packing;
  result.particle_count = packing.particles.size();
  result.solid_volume = fill.report.solid_volume;
  double sum = 0.0;
  for (const auto& particle : packing.particles) {
    sum += describe(packing.shapes[particle.shape]).measured_alpha;
  }
  result.mean_measured_alpha = sum / static_cast<double>(packing.particles.size());
  return packing;
}

void finish_repose(const ReposeOptions& options, ReposeResult& result) {
  result.final.provenance.packer = result.initial.provenance.packer;
  result.escaped_particles = 0;
  const double tolerance = 0.01 * result.smallest_size;
  for (std::size_t i = 0; i < result.final.particles.size(); ++i) {
    const Aabb box = result.final.placed(i).bounds();
    if (box.lower.x() < -tolerance || box.upper.x() > options.trough_length + tolerance ||
        box.lower.y() < -tolerance || box.upper.y() > options.width() + tolerance ||
        box.lower.z() < -tolerance) {
      ++result.escaped_particles;
    }
  }
  ReposeMeasurement measured = measure_repose(result.final, options);
  result.profile = std::move(measured.profile);
  result.fit = measured.fit;
  result.sensitivity = fit_sensitivity(result.final, options, result.fit);
}

}  // namespace detail

ReposeResult run_repose(const ReposeOptions& options, PackResult fill,
                        const ReposeProgress& progress) {
  validate(options);
  if (options.engine != ReposeEngine::kBullet) {
    throw InvalidInput("repose.engine", std::string(to_string(options.engine)),
                       "bullet (yade runs through run_repose_yade, aggpack/sim/repose_yade.h)");
  }
  ReposeResult result;
  const auto start = Clock::now();
  const Packing packing = detail::prepare_repose(options, std::move(fill), result);

  // Stage 1: fill and settle behind the baffle. Walls reach above the lattice while it falls.
  const double wall_height = std::max(options.trough_height, options.fill_height);
  World world(packing, options.physics, wall_height);
  result.time_step = world.time_step();
  result.smallest_size = world.smallest_size();
  const double thickness = options.baffle_thickness;
  const std::size_t baffle = world.add_wall(
      {.box = {Vec3(options.baffle_position, 0.0, 0.0),
               Vec3(options.baffle_position + thickness, options.width(), wall_height)},
       .is_kinematic = true});
  RestCriterion stage1 = options.rest;
  const double g = std::max(1e-9, options.physics.gravity.norm());
  stage1.min_time += std::sqrt(2.0 * options.fill_height / g);
  result.is_stage1_at_rest =
      run_until_rest(world, stage1, [&](double time, double energy, double threshold) {
        if (progress) progress(1, time, energy, threshold);
      });
  result.stage1_time = world.time();
  result.settled = world.packing();
  result.stage1_height = packing_height(result.settled);
  result.stage1_seconds = seconds_since(start);

  // Stage 2: move the baffle toward +x until it clears the pile, then wait for rest.
  const auto stage2_start = Clock::now();
  const double stage2_begin = world.time();
  const double far_stop = options.trough_length - thickness;
  const double clear_gap = largest_size(packing);
  world.set_wall_velocity(baffle, Vec3(options.baffle_speed, 0.0, 0.0));
  double untouched_since = world.time();
  const std::size_t check_steps = steps_per_check(world, options.rest);
  // The baffle's travel is bounded in steps too: it stops at the far wall at the latest.
  if (!((far_stop - options.baffle_position) / (options.baffle_speed * world.time_step()) <=
        kMaxSimulationSteps)) {
    throw LimitExceeded(
        "trough.baffle_speed", format_value(options.baffle_speed) + " m/s",
        "a baffle travel of at most 10^8 time steps of " + format_value(world.time_step()) + " s");
  }
  while (true) {
    const double x = world.wall_box(baffle).lower.x();
    const double remaining = far_stop - x;
    // Do not overshoot the far wall: the last move is shortened to land exactly on it.
    const double step_length = options.baffle_speed * world.time_step();
    if (remaining <= step_length * 0.5) {
      world.set_wall_velocity(baffle, Vec3::Zero());
      break;
    }
    const std::size_t steps = std::min<std::size_t>(
        check_steps, static_cast<std::size_t>(std::max(1.0, std::floor(remaining / step_length))));
    world.step(steps);
    const double energy = world.kinetic_energy();
    require_finite_state(world, energy, "repose stage 2");
    if (progress) progress(2, world.time() - stage2_begin, energy, 0.0);
    if (world.is_wall_touched(baffle, 0.0)) {
      untouched_since = world.time();
      continue;
    }
    if (world.time() - untouched_since < options.baffle_clear_time) continue;
    double toe = 0.0;
    for (std::size_t i = 0; i < world.particle_count(); ++i) {
      toe = std::max(toe, world.pose(i).position.x());
    }
    if (world.wall_box(baffle).lower.x() - toe > clear_gap) {
      world.remove_wall(baffle);
      result.is_baffle_removed = true;
      break;
    }
  }
  result.baffle_travel = world.wall_box(baffle).lower.x() - options.baffle_position;
  const double bin_width = detail::repose_bin_width(options);
  result.is_stage2_at_rest = wait_until_stable(
      world, options, bin_width,
      [&](double time, double energy, double threshold) {
        if (progress) progress(2, time - stage2_begin, energy, threshold);
      },
      result.confirmation);
  result.stage2_time = world.time() - stage2_begin;
  result.final = world.packing();
  const OverlapStatistics overlap = world.overlap_statistics();
  result.max_overlap_fraction = overlap.max_depth_fraction;
  result.max_contact_penetration_fraction =
      world.contact_statistics().max_contact_penetration / world.smallest_size();

  detail::finish_repose(options, result);

  // Diagnostic follow-up: the same world, follow_time longer.
  if (options.follow_time > 0.0) {
    const double rest_time = world.time();
    const double total = std::round(options.follow_time / world.time_step());
    if (!(total <= kMaxSimulationSteps)) {
      throw LimitExceeded("rest.follow_time", format_value(options.follow_time) + " s",
                          "at most 10^8 time steps of " + format_value(world.time_step()) + " s");
    }
    for (std::size_t done = 0; done < static_cast<std::size_t>(total);) {
      const std::size_t count = std::min(check_steps, static_cast<std::size_t>(total) - done);
      world.step(count);
      done += count;
      const double energy = world.kinetic_energy();
      require_finite_state(world, energy, "repose follow-up");
      if (progress) progress(2, world.time() - stage2_begin, energy, 0.0);
    }
    result.follow.time = world.time() - rest_time;
    result.follow.fit = measure_repose(world.packing(), options).fit;
  }
  result.stage2_seconds = seconds_since(stage2_start);
  return result;
}

}  // namespace aggpack
