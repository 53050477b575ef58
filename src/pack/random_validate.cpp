// Checks of RandomPackOptions before any work (the ranges, the container, the grading, the
// memory): validate().

#include <cmath>
#include <numbers>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/pack/resources.h"
#include "aggpack/shape/generator.h"
#include "random_placement.h"

namespace aggpack {

namespace {

using namespace random_detail;  // NOLINT(google-build-using-namespace)

void validate_shape(const ShapeOptions& shape, double largest_radius) {
  require_in_range("shape.alpha", shape.alpha, 0.0, 1.0);
  if (!std::isfinite(shape.edge_length) || shape.edge_length < 0.0) {
    throw InvalidInput("shape.edge_length", format_value(shape.edge_length),
                       Wording{Sentence::kFiniteAtLeastZeroRelative, {"shape.edge_length_ratio"}});
  }
  if (shape.edge_length == 0.0) {
    require_in_range("shape.edge_length_ratio", shape.edge_length_ratio, 0.05, 10.0);
  }
  if (shape.max_vertices < 6 || shape.max_vertices > 1000000) {
    throw InvalidInput("shape.max_vertices", std::to_string(shape.max_vertices), "[6, 1000000]");
  }
  if (shape.library_size > kMaxLibrary) {
    throw InvalidInput("shape.library_size", std::to_string(shape.library_size), "[0, 1000000]");
  }
  if (shape.library_size > 0 && shape.edge_length > 0.0) {
    throw InvalidInput(
        "shape.library_size", std::to_string(shape.library_size),
        Wording{Sentence::kLibraryNeedsRelativeLength,
                {"shape.edge_length", "shape.edge_length", "shape.edge_length_ratio"}});
  }
  if (shape.files.is_used()) {
    if (shape.library_size > 0) {
      throw InvalidInput("shape.library_size", std::to_string(shape.library_size),
                         Wording{Sentence::kLibrarySizeWithFiles, {"particle.library"}});
    }
    return;  // the growth options do not apply (the pipeline loads the files before a run)
  }
  const double estimate =
      shape.edge_length > 0.0
          ? estimated_vertex_count(largest_radius, shape.edge_length, shape.form.growth)
          : estimated_vertex_count(1.0, shape.edge_length_ratio, shape.form.growth);
  if (estimate > shape.max_vertices) {
    const std::string field =
        shape.edge_length > 0.0 ? "shape.edge_length" : "shape.edge_length_ratio";
    throw LimitExceeded(
        field, format_value(shape.edge_length > 0.0 ? shape.edge_length : shape.edge_length_ratio),
        Wording{Sentence::kVerticesNeeded,
                {"shape.max_vertices", std::to_string(shape.max_vertices),
                 format_value(std::round(estimate))}});
  }
}

}  // namespace

void validate(const RandomPackOptions& options) {
  validate(options.container);
  validate(options.grading);
  validate_shape(options.shape, largest_size(options.grading) / 2.0);
  if (options.target == PackTarget::kCount) {
    if (options.count < 1 || options.count > kMaxParticles) {
      throw InvalidInput("random.count", std::to_string(options.count), "[1, 100000000]");
    }
    const ShapeFiles& files = options.shape.files;
    if (files.loaded && files.options.is_use_once && options.count > files.loaded->shapes.size()) {
      throw LimitExceeded(
          "random.count", std::to_string(options.count),
          Wording{Sentence::kCountAtMostLibrary,
                  {std::to_string(files.loaded->shapes.size()), "particle.library_use_once"}});
    }
  } else if (options.target == PackTarget::kVolumeFraction) {
    if (!std::isfinite(options.volume_fraction) || options.volume_fraction <= 0.0 ||
        options.volume_fraction > 0.9) {
      throw InvalidInput("random.volume_fraction", format_value(options.volume_fraction),
                         "(0, 0.9]");
    }
  } else {
    throw InvalidInput("random.target", std::to_string(static_cast<int>(options.target)),
                       "count or volume_fraction");
  }
  if (!std::isfinite(options.gap) || options.gap < 0.0) {
    throw InvalidInput("random.gap", format_value(options.gap),
                       Wording{Sentence::kFiniteAtLeastZero, {}});
  }
  if (options.max_attempts_per_particle < 1 || options.max_attempts_per_particle > 1000000000ULL) {
    throw InvalidInput("random.max_attempts_per_particle",
                       std::to_string(options.max_attempts_per_particle), "[1, 1000000000]");
  }
  if (options.max_total_attempts < 1 || options.max_total_attempts > 1000000000000ULL) {
    throw InvalidInput("random.max_total_attempts", std::to_string(options.max_total_attempts),
                       "[1, 1000000000000]");
  }
  if (options.max_consecutive_failures < 1 || options.max_consecutive_failures > 1000000000ULL) {
    throw InvalidInput("random.max_consecutive_failures",
                       std::to_string(options.max_consecutive_failures), "[1, 1000000000]");
  }
  // Every grown particle contains the octahedron of its six base vertices, each at least
  // r (alpha + 0.2 (1 - alpha)) from the centre (Eq. 3), and so a ball of that radius / sqrt(3).
  // If even the smallest such ball plus the wall gaps does not fit, nothing can be placed.
  const Aabb bounds = options.container.bounds();
  const double interior = bounds.extent().minCoeff() - 2.0 * options.container.wall_gap;
  const double smallest_ball = smallest_size(options.grading) / 2.0 *
                               (options.shape.alpha + 0.2 * (1.0 - options.shape.alpha)) /
                               std::sqrt(3.0);
  if (2.0 * smallest_ball > interior) {
    throw InvalidInput(
        Wording{Sentence::kText, {"grading"}},
        Wording{Sentence::kSmallestSize, {format_value(smallest_size(options.grading))}},
        Wording{Sentence::kGradingFitsInterior, {format_value(interior)}});
  }
  if (options.target == PackTarget::kVolumeFraction) {
    // Lower bound on the list length: particles no larger than their control spheres.
    const double sphere = std::numbers::pi / 6.0 * mean_cubed_size(options.grading);
    const double least = options.volume_fraction * options.container.volume() / sphere;
    if (least > static_cast<double>(kMaxParticles)) {
      throw LimitExceeded("random.volume_fraction", format_value(options.volume_fraction),
                          Wording{Sentence::kFractionParticles, {format_value(std::round(least))}});
    }
  }
  // Runs the container cannot hold or the memory cannot take (issue 12), before any work.
  check_resources(options);
}

}  // namespace aggpack
