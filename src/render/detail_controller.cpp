// Adaptive level of detail for moving views. See detail_controller.h.

#include "aggpack/render/detail_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

constexpr std::size_t kNoLimit = std::numeric_limits<std::size_t>::max();

std::size_t scaled(std::size_t value, double factor) {
  const double result = std::floor(static_cast<double>(value) * factor);
  return result >= static_cast<double>(kNoLimit) ? kNoLimit : static_cast<std::size_t>(result);
}

}  // namespace

DetailController::DetailController(double target_seconds, std::size_t full_budget,
                                   std::size_t min_particles)
    : target_seconds_(target_seconds), full_budget_(full_budget), min_particles_(min_particles) {
  if (!(target_seconds > 0.0)) {
    throw InvalidInput("target_seconds", std::to_string(target_seconds), "> 0");
  }
  reset();
}

void DetailController::set_full_budget(std::size_t full_budget) {
  full_budget_ = full_budget;
  if (full_budget_ > 0 && (level_.triangle_budget == 0 || level_.triangle_budget > full_budget_)) {
    level_.triangle_budget = full_budget_;
  }
}

void DetailController::reset() { level_ = DetailLevel{full_budget_, 0, 1.0}; }

void DetailController::update(double frame_seconds, std::size_t triangles_drawn,
                              std::size_t particles_drawn) {
  if (!(frame_seconds > 0.0) || !std::isfinite(frame_seconds)) return;
  const double factor = std::clamp(target_seconds_ / frame_seconds, 0.5, 2.0);
  if (frame_seconds > target_seconds_) {
    // Lighter: fewer mesh triangles first (from what was drawn, so an unlimited budget or one
    // the frame did not use up falls at once), then fewer particles.
    if (level_.triangle_budget != 1 && triangles_drawn > 0) {
      level_.triangle_budget = std::max<std::size_t>(1, scaled(triangles_drawn, factor));
    } else if (level_.resolution_scale > kMinResolutionScale) {
      // Pixel work goes with the square of the scale, but is only part of the frame: steps of
      // at least 10 % so the level does not creep towards the target from above.
      level_.triangle_budget = 1;
      level_.resolution_scale =
          std::max(kMinResolutionScale, level_.resolution_scale * std::min(factor, 0.9));
    } else {
      level_.triangle_budget = 1;
      const std::size_t particles = level_.max_particles > 0
                                        ? std::min(level_.max_particles, particles_drawn)
                                        : particles_drawn;
      level_.max_particles = std::max(min_particles_, scaled(particles, factor));
    }
  } else if (frame_seconds < 0.75 * target_seconds_) {
    // Heavier: all particles again first, then more triangles.
    if (level_.max_particles > 0) {
      const std::size_t next = scaled(level_.max_particles, factor);
      // Uncapped once the cap no longer binds (the frame drew fewer than it allowed).
      level_.max_particles = particles_drawn < level_.max_particles ? 0 : next;
    } else if (level_.resolution_scale < 1.0) {
      level_.resolution_scale = std::min(1.0, level_.resolution_scale * std::sqrt(factor));
    } else if (level_.triangle_budget != full_budget_) {
      // Triangles drawn fell short of the budget: nothing more to gain by raising it.
      if (triangles_drawn < level_.triangle_budget / 2 && level_.triangle_budget > 1) return;
      const std::size_t next = std::max<std::size_t>(scaled(level_.triangle_budget, factor),
                                                     level_.triangle_budget + 1000);
      level_.triangle_budget = full_budget_ > 0 ? std::min(next, full_budget_) : next;
    }
  }
}

}  // namespace aggpack
