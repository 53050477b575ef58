// Particles to a measured target: grid + bisection over the Eq. 3 alpha (issue 15, item 1).

#include "aggpack/shape/calibrate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/shape/generator.h"

namespace aggpack {

namespace {

constexpr int kMaxBisections = 40;
constexpr double kSmallestBracket = 1e-6;  // alpha

GeneratorOptions generator_options(const CalibrationOptions& options, double alpha) {
  const double radius = 0.5 * options.diameter;
  return {.alpha = alpha,
          .radius_min = radius,
          .radius_max = radius,
          .edge_length = options.edge_ratio * radius,
          .max_vertices = options.max_vertices,
          .seed = options.seed};
}

std::string short_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

double relative_miss(double mean, double value) { return std::abs(mean - value) / value; }

}  // namespace

const char* calibration_target_name(CalibrationTarget target) {
  switch (target) {
    case CalibrationTarget::kVolumeRatio:
      return "volume_ratio";
    case CalibrationTarget::kEnclosedVolumeRatio:
      return "enclosed_volume_ratio";
    case CalibrationTarget::kMeasuredAlpha:
      return "measured_alpha";
    case CalibrationTarget::kSphericity:
      return "sphericity";
    case CalibrationTarget::kElongation:
      return "elongation";
    case CalibrationTarget::kFlatness:
      return "flatness";
  }
  return "?";
}

double calibration_value(CalibrationTarget target, const ShapeDescriptors& descriptors,
                         double control_radius) {
  switch (target) {
    case CalibrationTarget::kVolumeRatio:
      return descriptors.volume /
             (4.0 / 3.0 * std::numbers::pi * control_radius * control_radius * control_radius);
    case CalibrationTarget::kEnclosedVolumeRatio: {
      const double r = descriptors.enclosing_radius;
      return descriptors.volume / (4.0 / 3.0 * std::numbers::pi * r * r * r);
    }
    case CalibrationTarget::kMeasuredAlpha:
      return descriptors.measured_alpha;
    case CalibrationTarget::kSphericity:
      return descriptors.sphericity;
    case CalibrationTarget::kElongation:
      return descriptors.elongation;
    case CalibrationTarget::kFlatness:
      return descriptors.flatness;
  }
  return 0.0;
}

void validate(const CalibrationOptions& options) {
  const std::string name = calibration_target_name(options.target);
  if (!(options.value > 0.0 && options.value <= 1.0)) {
    throw InvalidInput(name, format_value(options.value), "(0, 1]");
  }
  require_positive("diameter", options.diameter);
  require_in_range("edge_ratio", options.edge_ratio, 0.05, 1.5);
  if (options.samples < 2 || options.samples > 100000) {
    throw InvalidInput("samples", std::to_string(options.samples), "[2, 100000]");
  }
  if (options.grid_points < 3 || options.grid_points > 101) {
    throw InvalidInput("grid_points", std::to_string(options.grid_points), "[3, 101]");
  }
  if (!(options.tolerance > 0.0 && options.tolerance <= 0.02)) {
    throw InvalidInput("tolerance", format_value(options.tolerance), "(0, 0.02]");
  }
  validate(generator_options(options, 0.5));
}

SummaryStatistics evaluate_calibration(const CalibrationOptions& options, double alpha,
                                       SummaryStatistics* volume,
                                       std::vector<SummaryStatistics>* all,
                                       SummaryStatistics* enclosing) {
  const GeneratorOptions generator = generator_options(options, alpha);
  constexpr std::size_t kTargets = std::size(kCalibrationTargets);
  std::vector<double> values(options.samples * kTargets);  // [target][sample]
  std::vector<double> volumes(options.samples);
  std::vector<double> enclosing_radii(options.samples);
  parallel_for_index(0, options.samples, [&](std::size_t i) {
    const GeneratedParticle particle = generate_particle(generator, i);
    const ShapeDescriptors d = describe(particle.body);
    for (std::size_t t = 0; t < kTargets; ++t) {
      values[t * options.samples + i] =
          calibration_value(kCalibrationTargets[t], d, particle.control_radius);
    }
    volumes[i] = d.volume;
    enclosing_radii[i] = d.enclosing_radius;
  });
  if (volume != nullptr) *volume = summarize(volumes);
  if (enclosing != nullptr) *enclosing = summarize(enclosing_radii);
  SummaryStatistics target;
  if (all != nullptr) all->clear();
  for (std::size_t t = 0; t < kTargets; ++t) {
    const auto begin = values.begin() + static_cast<std::ptrdiff_t>(t * options.samples);
    const SummaryStatistics stats =
        summarize(std::vector<double>(begin, begin + static_cast<std::ptrdiff_t>(options.samples)));
    if (kCalibrationTargets[t] == options.target) target = stats;
    if (all != nullptr) all->push_back(stats);
  }
  return target;
}

CalibrationResult calibrate(const CalibrationOptions& options) {
  validate(options);
  CalibrationResult result;
  result.radius = 0.5 * options.diameter;
  result.edge_length = options.edge_ratio * result.radius;
  auto& evaluated = result.evaluated;
  const std::size_t n = options.grid_points;
  for (std::size_t k = 0; k < n; ++k) {
    const double alpha = static_cast<double>(k) / static_cast<double>(n - 1);
    evaluated.push_back({alpha, evaluate_calibration(options, alpha)});
  }
  result.reachable_minimum = evaluated.front().achieved.mean;
  result.reachable_maximum = evaluated.front().achieved.mean;
  for (const auto& point : evaluated) {
    result.reachable_minimum = std::min(result.reachable_minimum, point.achieved.mean);
    result.reachable_maximum = std::max(result.reachable_maximum, point.achieved.mean);
  }
  const double value = options.value;
  const std::string name = calibration_target_name(options.target);
  if (value < result.reachable_minimum || value > result.reachable_maximum) {
    const bool is_volume = options.target == CalibrationTarget::kVolumeRatio ||
                           options.target == CalibrationTarget::kEnclosedVolumeRatio;
    throw InvalidInput(name, format_value(value),
                       "[" + short_number(result.reachable_minimum) + ", " +
                           short_number(result.reachable_maximum) +
                           "], the means reachable over alpha in [0, 1] at L/r = " +
                           short_number(options.edge_ratio) + " (" +
                           std::to_string(options.samples) + " particles, seed " +
                           std::to_string(options.seed) + ")" +
                           (is_volume ? "; convex growth inside the control sphere makes no fuller "
                                        "particles"
                                      : ""));
  }

  // The first bracket from alpha = 1 down (fuller particles first).
  std::size_t upper = n - 1;
  while (upper > 0) {
    const double a = evaluated[upper - 1].achieved.mean - value;
    const double b = evaluated[upper].achieved.mean - value;
    if (a * b <= 0.0) break;
    --upper;
  }
  CalibrationPoint lo = evaluated[upper - 1];
  CalibrationPoint hi = evaluated[upper];
  CalibrationPoint best =
      relative_miss(lo.achieved.mean, value) < relative_miss(hi.achieved.mean, value) ? lo : hi;
  for (int step = 0; step < kMaxBisections; ++step) {
    if (relative_miss(best.achieved.mean, value) <= options.tolerance) break;
    if (hi.alpha - lo.alpha < kSmallestBracket) break;
    const double alpha = 0.5 * (lo.alpha + hi.alpha);
    const CalibrationPoint middle{alpha, evaluate_calibration(options, alpha)};
    evaluated.push_back(middle);
    if (relative_miss(middle.achieved.mean, value) < relative_miss(best.achieved.mean, value)) {
      best = middle;
    }
    if ((lo.achieved.mean - value) * (middle.achieved.mean - value) <= 0.0) {
      hi = middle;
    } else {
      lo = middle;
    }
  }
  std::sort(evaluated.begin(), evaluated.end(),
            [](const auto& a, const auto& b) { return a.alpha < b.alpha; });
  result.alpha = best.alpha;
  CalibrationOptions sized = options;
  if (options.target == CalibrationTarget::kEnclosedVolumeRatio) {
    // Ratios do not depend on the scale (L / r is fixed): size the control sphere so that the
    // mean enclosing diameter is D, and measure the particles at that size.
    SummaryStatistics enclosing;
    evaluate_calibration(options, best.alpha, nullptr, nullptr, &enclosing);
    sized.diameter = options.diameter * (0.5 * options.diameter) / enclosing.mean;
    result.radius = 0.5 * sized.diameter;
    result.edge_length = options.edge_ratio * result.radius;
  }
  result.achieved = evaluate_calibration(sized, best.alpha, &result.volume, &result.all_descriptors,
                                         &result.enclosing_radius);
  result.within_tolerance = relative_miss(result.achieved.mean, value) <= options.tolerance;
  return result;
}

}  // namespace aggpack
