#pragma once
// Particles to measured targets: find the generator inputs (the Eq. 3 alpha, L / r and, when an
// elongation or flatness is asked for, the control ellipsoid's axis ratios) whose particles match
// up to three measured mean descriptors at once (V / V_circumscribed-sphere as the paper's
// Table 1, the Eq. 2 alpha, the Eq. 1 sphericity, elongation, flatness).
//
// Search: every evaluation grows `samples` particles with seed `seed`, indices 0..samples-1, so
// the same particles up to the inputs (common random numbers: the means are smooth in the
// inputs). A grid of three values per searched input (ends and middle of its range) picks the
// start of a Nelder-Mead descent on the sum of squared relative misses; every evaluated point
// is kept, and their smallest and largest means are the reachable range reported for a target
// that cannot be met. Deterministic at any thread count.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"

namespace aggpack {

/// A descriptor a calibration matches.
enum class CalibrationTarget {
  kVolumeRatio,  ///< V / (pi/6 D^3), D = 2 r the control sphere's diameter
  /// V / volume of the particle's smallest enclosing sphere: Table 1's V / V_circumscribed as a
  /// measurement of a real particle gives it (its circumscribed diameter is the enclosing one).
  kEnclosedVolumeRatio,
  kMeasuredAlpha,  ///< Eq. 2 alpha = SI^(3/2)
  kSphericity,     ///< Eq. 1 SI
  kElongation,     ///< intermediate / long principal dimension
  kFlatness,       ///< short / intermediate principal dimension
};

constexpr CalibrationTarget kCalibrationTargets[] = {
    CalibrationTarget::kVolumeRatio, CalibrationTarget::kMeasuredAlpha,
    CalibrationTarget::kSphericity,  CalibrationTarget::kElongation,
    CalibrationTarget::kFlatness,    CalibrationTarget::kEnclosedVolumeRatio};

/// One name per quantity, as the other outputs use it: "control_volume_ratio" (V over the
/// control sphere), "measured_alpha", "sphericity", "elongation", "flatness", "volume_ratio" (V
/// over the smallest enclosing sphere: the `volume_ratio` column of `aggpack shapes`).
const char* calibration_target_name(CalibrationTarget target);

/// The target descriptor of a particle grown with control radius `control_radius` (m).
double calibration_value(CalibrationTarget target, const ShapeDescriptors& descriptors,
                         double control_radius);

/// One mean descriptor to match.
struct CalibrationGoal {
  CalibrationTarget target = CalibrationTarget::kEnclosedVolumeRatio;
  double value = 0.5;  ///< target mean, in (0, 1]
};

/// The generator inputs a calibration sets.
struct CalibrationInputs {
  double alpha = 0.5;       ///< Eq. 3 input
  double edge_ratio = 1.0;  ///< L / r
  double elongation = 1.0;  ///< control ellipsoid's intermediate / long semi-axis
  double flatness = 1.0;    ///< control ellipsoid's short / intermediate semi-axis
};

/// The ranges searched: alpha [0, 1], L / r [kMinSearchedEdgeRatio, kMaxSearchedEdgeRatio],
/// axis ratios [kMinSearchedAxisRatio, 1].
constexpr double kMinSearchedEdgeRatio = 0.25;
constexpr double kMaxSearchedEdgeRatio = 1.4;
constexpr double kMinSearchedAxisRatio = 0.15;

struct CalibrationOptions {
  /// 1 to 3 goals, each descriptor at most once.
  std::vector<CalibrationGoal> goals = std::vector<CalibrationGoal>(1);
  /// Circumscribed diameter D (m), > 0: of the control sphere (D = 2 r), or, with a
  /// kEnclosedVolumeRatio goal, the mean diameter of the particles' smallest enclosing spheres
  /// (the control radius is then scaled to give it).
  double diameter = 0.01;
  /// Growth rule and minimum edge ratio. Its axis ratios are searched when an elongation or
  /// flatness goal is given (each with its own goal), else kept as given.
  GrowthForm form{};
  /// L / r kept fixed, in [0.05, 1.5]; unset = searched.
  std::optional<double> edge_ratio;
  /// Mean particle volume (m^3) to size the particles to, > 0: the control radius is scaled so
  /// that the particles' mean volume is this (the ratios do not depend on the scale). Unset =
  /// sized by `diameter`.
  std::optional<double> volume;
  std::size_t samples = 200;           ///< particles per evaluation, [2, 100000]
  std::uint64_t seed = 1;              ///< particle i of every evaluation uses stream (seed, i)
  double tolerance = 0.02;             ///< relative miss accepted per goal, (0, 0.2]
  std::size_t max_evaluations = 250;   ///< grid + descent, [10, 10000]
  std::uint32_t max_vertices = 20000;  ///< vertex cap per particle
};

/// Throws InvalidInput naming the field unless the options are usable.
void validate(const CalibrationOptions& options);

/// calibrate()'s refusal of a target the generator does not reach (field: the target's name):
/// the span of means over every evaluated input and what the closest inputs achieve, for a
/// front end that words it in the user's terms (the CLI gives the closest reachable --volume).
class CalibrationUnreached : public InvalidInput {
 public:
  CalibrationUnreached(const std::string& field, const std::string& value,
                       const std::string& allowed, double lowest, double highest, double closest,
                       std::string closest_inputs)
      : InvalidInput(field, value, allowed),
        lowest_(lowest),
        highest_(highest),
        closest_(closest),
        closest_inputs_(std::move(closest_inputs)) {}
  /// Smallest and largest mean of the target over the evaluated inputs.
  [[nodiscard]] double lowest() const { return lowest_; }
  [[nodiscard]] double highest() const { return highest_; }
  /// The mean the closest inputs give, and those inputs ("alpha 0, L/R 1.4, ...").
  [[nodiscard]] double closest() const { return closest_; }
  [[nodiscard]] const std::string& closest_inputs() const { return closest_inputs_; }

 private:
  double lowest_;
  double highest_;
  double closest_;
  std::string closest_inputs_;
};

/// One evaluated set of inputs: the mean and spread of every target descriptor, in
/// kCalibrationTargets order.
struct CalibrationPoint {
  CalibrationInputs inputs;
  std::vector<SummaryStatistics> descriptors;
};

struct CalibrationResult {
  CalibrationInputs inputs;                        ///< found
  double radius = 0;                               ///< control radius r (m)
  double edge_length = 0;                          ///< L = edge_ratio * r (m)
  std::vector<SummaryStatistics> achieved;         ///< per goal, at `inputs` and `radius`
  std::vector<SummaryStatistics> all_descriptors;  ///< kCalibrationTargets order
  SummaryStatistics volume;                        ///< particle volume (m^3)
  SummaryStatistics enclosing_radius;  ///< radius of each particle's smallest enclosing sphere (m)
  bool within_tolerance = false;       ///< every goal's relative miss <= tolerance
  std::vector<CalibrationPoint> evaluated;  ///< every point, in the order evaluated
};

/// The particles of `inputs` at control radius diameter / 2 (or `radius` when > 0), measured:
/// every target descriptor, and when given the volume's and the enclosing radius' statistics.
CalibrationPoint evaluate_calibration(const CalibrationOptions& options,
                                      const CalibrationInputs& inputs, double radius = 0,
                                      SummaryStatistics* volume = nullptr,
                                      SummaryStatistics* enclosing = nullptr);

/// The mean of `target` in a point.
double mean_of(const CalibrationPoint& point, CalibrationTarget target);

/// Finds the inputs whose particles' mean descriptors meet every goal.
/// \throw InvalidInput naming the goal missed by most, its value, the range of means reached and
/// the closest inputs, when the goals cannot be met together within the tolerance.
CalibrationResult calibrate(const CalibrationOptions& options);

}  // namespace aggpack
