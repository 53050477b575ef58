// Particles to measured targets: a grid over the searched inputs, then Nelder-Mead.

#include "aggpack/shape/calibrate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

namespace aggpack {

namespace {

constexpr std::size_t kTargets = std::size(kCalibrationTargets);

std::string short_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

double relative_miss(double mean, double value) { return std::abs(mean - value) / value; }

bool has_goal(const CalibrationOptions& options, CalibrationTarget target) {
  return std::any_of(options.goals.begin(), options.goals.end(),
                     [&](const CalibrationGoal& goal) { return goal.target == target; });
}

// The searched inputs as coordinates in [0, 1]: alpha always, L / r unless fixed (on a log
// scale: the shapes change fastest at small L), each axis ratio when its descriptor is a goal.
class SearchSpace {
 public:
  explicit SearchSpace(const CalibrationOptions& options) : options_(options) {
    dims_.push_back(kAlpha);
    if (!options.edge_ratio) dims_.push_back(kEdge);
    if (has_goal(options, CalibrationTarget::kElongation)) dims_.push_back(kElongation);
    if (has_goal(options, CalibrationTarget::kFlatness)) dims_.push_back(kFlatness);
  }
  [[nodiscard]] std::size_t size() const { return dims_.size(); }

  [[nodiscard]] CalibrationInputs inputs(const std::vector<double>& u) const {
    CalibrationInputs in{.alpha = 0.5,
                         .edge_ratio = options_.edge_ratio.value_or(1.0),
                         .elongation = options_.form.elongation,
                         .flatness = options_.form.flatness};
    for (std::size_t d = 0; d < dims_.size(); ++d) {
      const double x = std::clamp(u[d], 0.0, 1.0);
      switch (dims_[d]) {
        case kAlpha:
          in.alpha = x;
          break;
        case kEdge:
          in.edge_ratio =
              kMinSearchedEdgeRatio * std::pow(kMaxSearchedEdgeRatio / kMinSearchedEdgeRatio, x);
          break;
        case kElongation:
          in.elongation = kMinSearchedAxisRatio + (1.0 - kMinSearchedAxisRatio) * x;
          break;
        case kFlatness:
          in.flatness = kMinSearchedAxisRatio + (1.0 - kMinSearchedAxisRatio) * x;
          break;
      }
    }
    return in;
  }

  // "alpha [0, 1], L/R [0.25, 1.4], elongation [0.15, 1]": the searched ranges, for messages.
  [[nodiscard]] std::string ranges() const {
    std::string text;
    for (const Dim d : dims_) {
      if (!text.empty()) text += ", ";
      text += d == kAlpha  ? "alpha [0, 1]"
              : d == kEdge ? "L/R [" + short_number(kMinSearchedEdgeRatio) + ", " +
                                 short_number(kMaxSearchedEdgeRatio) + "]"
              : d == kElongation ? "elongation [" + short_number(kMinSearchedAxisRatio) + ", 1]"
                                 : "flatness [" + short_number(kMinSearchedAxisRatio) + ", 1]";
    }
    if (options_.edge_ratio) text += " at L/R " + short_number(*options_.edge_ratio);
    return text;
  }

 private:
  enum Dim { kAlpha, kEdge, kElongation, kFlatness };
  const CalibrationOptions& options_;
  std::vector<Dim> dims_;
};

std::string describe_inputs(const CalibrationInputs& in) {
  return "alpha " + short_number(in.alpha) + ", L/R " + short_number(in.edge_ratio) +
         ", elongation " + short_number(in.elongation) + ", flatness " + short_number(in.flatness);
}

// Evaluates points and keeps them all; the objective is the sum of squared relative misses.
class Search {
 public:
  Search(const CalibrationOptions& options, const SearchSpace& space)
      : options_(options), space_(space) {}

  double objective(const std::vector<double>& u) {
    coordinates.push_back(u);
    CalibrationPoint point = evaluate_calibration(options_, space_.inputs(u));
    double sum = 0.0;
    double worst = 0.0;
    for (const CalibrationGoal& goal : options_.goals) {
      const double miss = relative_miss(mean_of(point, goal.target), goal.value);
      sum += miss * miss;
      worst = std::max(worst, miss);
    }
    if (evaluated.empty() || sum < best_sum_) {
      best_sum_ = sum;
      best_worst_ = worst;
      best = evaluated.size();
    }
    evaluated.push_back(std::move(point));
    return sum;
  }
  [[nodiscard]] bool is_done() const {
    // Well inside the tolerance, so that the full evaluation stays inside it too.
    return (!evaluated.empty() && best_worst_ <= 0.5 * options_.tolerance) ||
           evaluated.size() >= options_.max_evaluations;
  }

  std::vector<CalibrationPoint> evaluated;
  std::vector<std::vector<double>> coordinates;  // of each evaluated point, in [0, 1]^k
  std::size_t best = 0;

 private:
  const CalibrationOptions& options_;
  const SearchSpace& space_;
  double best_sum_ = 0.0;
  double best_worst_ = 0.0;
};

// Nelder-Mead (reflection 1, expansion 2, contraction 1/2, shrink 1/2) in the unit cube, the
// coordinates clamped when evaluated; starts from `start` with steps of `step`.
void nelder_mead(Search& search, std::vector<double> start, double step) {
  const std::size_t n = start.size();
  std::vector<std::vector<double>> simplex(n + 1, start);
  std::vector<double> value(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    simplex[i + 1][i] += start[i] + step <= 1.0 ? step : -step;
  }
  for (std::size_t i = 0; i <= n; ++i) {
    if (search.is_done()) return;
    value[i] = search.objective(simplex[i]);
  }
  const auto along = [&](const std::vector<double>& centre, const std::vector<double>& worst,
                         double t) {
    std::vector<double> p(n);
    for (std::size_t d = 0; d < n; ++d) p[d] = centre[d] + t * (worst[d] - centre[d]);
    return p;
  };
  while (!search.is_done()) {
    std::vector<std::size_t> order(n + 1);
    for (std::size_t i = 0; i <= n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return value[a] < value[b]; });
    const std::size_t worst = order[n];
    double size = 0.0;
    for (std::size_t i = 1; i <= n; ++i) {
      for (std::size_t d = 0; d < n; ++d) {
        size = std::max(size, std::abs(simplex[order[i]][d] - simplex[order[0]][d]));
      }
    }
    if (size < 1e-3) return;
    std::vector<double> centre(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t d = 0; d < n; ++d)
        centre[d] += simplex[order[i]][d] / static_cast<double>(n);
    }
    const std::vector<double> reflected = along(centre, simplex[worst], -1.0);
    const double r = search.objective(reflected);
    if (r < value[order[0]]) {
      if (search.is_done()) return;
      const std::vector<double> expanded = along(centre, simplex[worst], -2.0);
      const double e = search.objective(expanded);
      simplex[worst] = e < r ? expanded : reflected;
      value[worst] = std::min(e, r);
    } else if (r < value[order[n - 1]]) {
      simplex[worst] = reflected;
      value[worst] = r;
    } else {
      if (search.is_done()) return;
      const std::vector<double> contracted = along(centre, simplex[worst], 0.5);
      const double c = search.objective(contracted);
      if (c < value[worst]) {
        simplex[worst] = contracted;
        value[worst] = c;
      } else {
        for (std::size_t i = 1; i <= n && !search.is_done(); ++i) {
          for (std::size_t d = 0; d < n; ++d) {
            simplex[order[i]][d] = 0.5 * (simplex[order[i]][d] + simplex[order[0]][d]);
          }
          value[order[i]] = search.objective(simplex[order[i]]);
        }
      }
    }
  }
}

}  // namespace

const char* calibration_target_name(CalibrationTarget target) {
  switch (target) {
    case CalibrationTarget::kVolumeRatio:
      return "control_volume_ratio";
    case CalibrationTarget::kEnclosedVolumeRatio:
      return "volume_ratio";
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
    case CalibrationTarget::kEnclosedVolumeRatio:
      return enclosed_volume_ratio(descriptors);
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

double mean_of(const CalibrationPoint& point, CalibrationTarget target) {
  for (std::size_t t = 0; t < kTargets; ++t) {
    if (kCalibrationTargets[t] == target) return point.descriptors[t].mean;
  }
  return 0.0;
}

void validate(const CalibrationOptions& options) {
  if (options.goals.empty() || options.goals.size() > 3) {
    throw InvalidInput("goals", std::to_string(options.goals.size()) + " targets", "1 to 3");
  }
  for (std::size_t i = 0; i < options.goals.size(); ++i) {
    const CalibrationGoal& goal = options.goals[i];
    const std::string name = calibration_target_name(goal.target);
    if (!(goal.value > 0.0 && goal.value <= 1.0)) {
      throw InvalidInput(name, format_value(goal.value), "(0, 1]");
    }
    for (std::size_t j = 0; j < i; ++j) {
      const CalibrationTarget other = options.goals[j].target;
      const auto is_volume = [](CalibrationTarget t) {
        return t == CalibrationTarget::kVolumeRatio || t == CalibrationTarget::kEnclosedVolumeRatio;
      };
      if (other == goal.target || (is_volume(other) && is_volume(goal.target))) {
        throw InvalidInput(name, format_value(goal.value), "one target per descriptor");
      }
    }
  }
  require_positive("diameter", options.diameter);
  if (options.volume) require_positive("volume", *options.volume);
  if (options.edge_ratio) require_in_range("edge_ratio", *options.edge_ratio, 0.05, 1.5);
  if (options.samples < 2 || options.samples > 100000) {
    throw InvalidInput("samples", std::to_string(options.samples), "[2, 100000]");
  }
  if (!(options.tolerance > 0.0 && options.tolerance <= 0.2)) {
    throw InvalidInput("tolerance", format_value(options.tolerance), "(0, 0.2]");
  }
  if (options.max_evaluations < 10 || options.max_evaluations > 10000) {
    throw InvalidInput("max_evaluations", std::to_string(options.max_evaluations), "[10, 10000]");
  }
  validate(options.form);
  const double radius = 0.5 * options.diameter;
  validate(GrowthParams{.radius = radius,
                        .edge_length = options.edge_ratio.value_or(kMinSearchedEdgeRatio) * radius,
                        .max_vertices = options.max_vertices,
                        .form = options.form});
}

CalibrationPoint evaluate_calibration(const CalibrationOptions& options,
                                      const CalibrationInputs& inputs, double radius,
                                      SummaryStatistics* volume, SummaryStatistics* enclosing) {
  const double r = radius > 0.0 ? radius : 0.5 * options.diameter;
  GeneratorOptions generator{.alpha = inputs.alpha,
                             .radius_min = r,
                             .radius_max = r,
                             .edge_length = inputs.edge_ratio * r,
                             .max_vertices = options.max_vertices,
                             .seed = options.seed,
                             .form = options.form};
  generator.form.elongation = inputs.elongation;
  generator.form.flatness = inputs.flatness;
  const std::size_t n = options.samples;
  std::vector<double> values(n * kTargets);  // [target][sample]
  std::vector<double> volumes(n);
  std::vector<double> enclosing_radii(n);
  parallel_for_index(0, n, [&](std::size_t i) {
    const GeneratedParticle particle = generate_particle(generator, i);
    const ShapeDescriptors d = describe(particle.body);
    for (std::size_t t = 0; t < kTargets; ++t) {
      values[t * n + i] = calibration_value(kCalibrationTargets[t], d, particle.control_radius);
    }
    volumes[i] = d.volume;
    enclosing_radii[i] = d.enclosing_radius;
  });
  if (volume != nullptr) *volume = summarize(volumes);
  if (enclosing != nullptr) *enclosing = summarize(enclosing_radii);
  CalibrationPoint point{.inputs = inputs, .descriptors = {}};
  for (std::size_t t = 0; t < kTargets; ++t) {
    const auto begin = values.begin() + static_cast<std::ptrdiff_t>(t * n);
    point.descriptors.push_back(
        summarize(std::vector<double>(begin, begin + static_cast<std::ptrdiff_t>(n))));
  }
  return point;
}

CalibrationResult calibrate(const CalibrationOptions& options) {
  validate(options);
  const SearchSpace space(options);
  Search search(options, space);
  // The grid: 3 values per searched input, in a fixed order; the descent starts at its best.
  const std::size_t k = space.size();
  std::size_t corners = 1;
  for (std::size_t d = 0; d < k; ++d) corners *= 3;
  std::vector<double> start(k, 0.5);
  for (std::size_t index = 0; index < corners && !search.is_done(); ++index) {
    std::vector<double> u(k);
    for (std::size_t d = 0, rest = index; d < k; ++d, rest /= 3) {
      u[d] = 0.5 * static_cast<double>(rest % 3);
    }
    const std::size_t before = search.best;
    search.objective(u);
    if (search.best != before || index == 0) start = u;
  }
  // Restarts from the best point with a smaller simplex while the goals are not met: a descent
  // on a noisy (finite-sample) objective can stall on a face of the cube.
  for (double step = 0.25; step > 0.01 && !search.is_done(); step *= 0.5) {
    nelder_mead(search, search.evaluated.empty() ? start : search.coordinates[search.best], step);
  }

  CalibrationResult result;
  const CalibrationPoint& best = search.evaluated[search.best];
  result.inputs = best.inputs;
  result.radius = 0.5 * options.diameter;
  if (options.volume) {
    // The measured volume itself: scale so that the mean volume is met (volume ~ r^3).
    SummaryStatistics volume;
    evaluate_calibration(options, best.inputs, 0.0, &volume);
    result.radius = 0.5 * options.diameter * std::cbrt(*options.volume / volume.mean);
  } else if (has_goal(options, CalibrationTarget::kEnclosedVolumeRatio)) {
    // Ratios do not depend on the scale: size the control sphere so that the mean enclosing
    // diameter is D.
    SummaryStatistics enclosing;
    evaluate_calibration(options, best.inputs, 0.0, nullptr, &enclosing);
    result.radius = 0.5 * options.diameter * (0.5 * options.diameter) / enclosing.mean;
  }
  result.edge_length = result.inputs.edge_ratio * result.radius;
  const CalibrationPoint final_point = evaluate_calibration(
      options, result.inputs, result.radius, &result.volume, &result.enclosing_radius);
  result.all_descriptors = final_point.descriptors;
  result.within_tolerance = true;
  const CalibrationGoal* worst = nullptr;
  double worst_miss = -1.0;
  for (const CalibrationGoal& goal : options.goals) {
    const double mean = mean_of(final_point, goal.target);
    for (std::size_t t = 0; t < kTargets; ++t) {
      if (kCalibrationTargets[t] == goal.target)
        result.achieved.push_back(final_point.descriptors[t]);
    }
    const double miss = relative_miss(mean, goal.value);
    if (miss > options.tolerance) result.within_tolerance = false;
    if (miss > worst_miss) {
      worst_miss = miss;
      worst = &goal;
    }
  }
  result.evaluated = std::move(search.evaluated);
  if (!result.within_tolerance) {
    double lo = 1e300;
    double hi = -1e300;
    for (const CalibrationPoint& point : result.evaluated) {
      lo = std::min(lo, mean_of(point, worst->target));
      hi = std::max(hi, mean_of(point, worst->target));
    }
    const std::string name = calibration_target_name(worst->target);
    throw CalibrationUnreached(
        name, format_value(worst->value),
        "a mean the generator reaches" +
            std::string(options.goals.size() > 1 ? " together with the other targets" : "") +
            ": over " + space.ranges() + " the means of " + name + " span [" + short_number(lo) +
            ", " + short_number(hi) + "]; the closest inputs (" + describe_inputs(result.inputs) +
            ") give " + short_number(mean_of(final_point, worst->target)) + " (" +
            short_number(100.0 * worst_miss) + " % off)",
        lo, hi, mean_of(final_point, worst->target), describe_inputs(result.inputs));
  }
  return result;
}

}  // namespace aggpack
