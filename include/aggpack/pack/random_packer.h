#pragma once
// Random sequential addition (take-and-place) packer: graded sizes, largest first, random
// positions and orientations, a hierarchical-grid broad phase and the exact GJK test.

#include <cstdint>

#include "aggpack/pack/grading.h"
#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"
#include "aggpack/shape/generator.h"
#include "aggpack/shape/shape_library.h"

namespace aggpack {

/// How the particles of a random packing are shaped.
struct ShapeOptions {
  double alpha = 0.5;  ///< Eq. 3 shape control, [0, 1]
  /// Absolute growth edge length L (m). 0 = relative: L = edge_length_ratio * r for a particle of
  /// control radius r (so every size gets the same shape statistics). > 0 = the same L for all
  /// sizes (the paper's control; small particles then stay close to octahedra).
  double edge_length = 0.0;
  double edge_length_ratio = 1.0;      ///< L / r when edge_length == 0, in [0.05, 10]
  std::uint32_t max_vertices = 20000;  ///< vertex cap per particle, [6, 10^6]
  /// Shape library size K. 0 = a unique shape per particle. K > 0 = K shapes grown once at unit
  /// radius and reused, scaled to each particle's size and randomly oriented (Particle::scale);
  /// needed for ~10^6 particles (memory and time). Requires edge_length == 0. [0, 10^6]
  std::uint32_t library_size = 0;
  GrowthForm form{};  ///< growth rule and control-surface axis ratios
  /// Shapes from mesh files (particle.library) instead of grown ones: each particle is a library
  /// shape drawn from its stream (or, use-once, a seeded permutation), scaled so that its
  /// enclosing diameter is the drawn sieve size, randomly oriented. The pipeline loads
  /// `files.loaded` from `files.options.path`; the alpha, L and growth options do not apply.
  ShapeFiles files{};
};

/// The growth controls of a particle of control radius `radius` (m): L absolute or relative.
GrowthParams growth_params(const ShapeOptions& shape, double radius);

/// What the random packer aims for.
enum class PackTarget {
  kCount,          ///< place `count` particles
  kVolumeFraction  ///< place particles until their solid volume reaches `volume_fraction`
};

/// Options of the random packer. Lengths in metres.
struct RandomPackOptions {
  Container container{};  ///< default: box 3.0 x 1.0 x 2.8 m, wall_gap 0
  Grading grading{};      ///< default: uniform r = 0.1 m (single size)
  ShapeOptions shape{};
  PackTarget target = PackTarget::kVolumeFraction;
  std::uint64_t count = 1000;  ///< kCount: particles to place, [1, 10^8]
  /// kVolumeFraction: solid volume / container volume to reach, (0, 0.9]. The size list is drawn
  /// until its exact solid volume reaches this; if some particles cannot be placed the run ends
  /// below it and says so.
  double volume_fraction = 0.35;
  double gap = 0.0;  ///< minimum distance between particles (m), >= 0
  /// Candidate poses tried per particle before it is skipped (rejected), [1, 10^9].
  std::uint64_t max_attempts_per_particle = 5000;
  /// Total candidate poses for the whole run, [1, 10^12]; the run stops when they are used up.
  std::uint64_t max_total_attempts = 200000000;
  /// Stop when this many particles in a row were rejected (the packing is jammed for the
  /// remaining sizes), [1, 10^9].
  std::uint64_t max_consecutive_failures = 100;
  std::uint64_t seed = 1;  ///< master seed: size/shape of draw i from Rng(seed, i)
};

/// Throws InvalidInput naming the field ("random.count", "random.volume_fraction", "random.gap",
/// "shape.alpha", "shape.library_size", "grading.size_min", "container.radius", ...) unless the
/// options are usable; LimitExceeded if the vertex cap is too small for the relative edge length
/// or the largest absolute one, or if the size list would exceed 10^8 particles.
void validate(const RandomPackOptions& options);

/// Runs random sequential addition:
///  1. draws the size list (control diameters from the grading's number density, draw i from
///     stream (seed, i)) -- `count` sizes, or until the exact solid volume reaches the target --
///     and grows the shapes (in parallel; each from its own stream);
///  2. sorts it largest first (ties by draw index) and places the particles in that order: each
///     candidate pose is a uniform random centre in the container's centre region and a uniform
///     random rotation from the stream of (particle, attempt); a candidate is accepted if it lies
///     in the container minus wall_gap and is at least `gap` from every placed particle
///     (hierarchical uniform grid, then the exact test is_separated). The first accepted attempt
///     in attempt order wins, so the result does not depend on the thread count.
/// Stops at the target, when the attempt budget is used up, after max_consecutive_failures
/// rejections in a row, or on cancel -- and reports what it reached (never loops forever).
/// \throw InvalidInput, LimitExceeded (as validate()).
PackResult pack_random(const RandomPackOptions& options, const PackControl& control = {});

}  // namespace aggpack
