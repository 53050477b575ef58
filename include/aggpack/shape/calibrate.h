#pragma once
// Particles to a measured target (issue 15, item 1): find the generator's Eq. 3 alpha whose
// particles match a measured mean descriptor (V / V_circumscribed-sphere as the paper's Table 1,
// the Eq. 2 measured alpha, or the Eq. 1 sphericity) at a fixed edge-length ratio L / R.
//
// Search: a grid of alpha in [0, 1] (every point generates `samples` particles, seed `seed`,
// indices 0..samples-1, so the same particles up to alpha: common random numbers), then
// bisection inside the first bracket (from alpha = 1 down) whose ends straddle the target. The
// descriptor need not be monotone in alpha (the Eq. 2 alpha is not); the grid's smallest and
// largest means are the reachable range reported when a target lies outside it.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/shape/descriptors.h"

namespace aggpack {

/// The descriptor a calibration matches.
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

/// "volume_ratio", "measured_alpha", "sphericity", "elongation", "flatness",
/// "enclosed_volume_ratio".
const char* calibration_target_name(CalibrationTarget target);

/// The target descriptor of a particle grown with control radius `control_radius` (m).
double calibration_value(CalibrationTarget target, const ShapeDescriptors& descriptors,
                         double control_radius);

struct CalibrationOptions {
  CalibrationTarget target = CalibrationTarget::kVolumeRatio;
  double value = 0.5;  ///< target mean, in (0, 1]
  /// Circumscribed diameter D (m), > 0: of the control sphere (D = 2 r), or, for
  /// kEnclosedVolumeRatio, the mean diameter of the particles' smallest enclosing spheres (the
  /// control radius is then scaled to give it).
  double diameter = 0.01;
  double edge_ratio = 1.0;             ///< L / r, in [0.05, 1.5] (fixed, not searched)
  std::size_t samples = 200;           ///< particles per evaluation, [2, 100000]
  std::uint64_t seed = 1;              ///< particle i of every evaluation uses stream (seed, i)
  std::size_t grid_points = 11;        ///< alpha grid 0, 1/(n-1), ..., 1; [3, 101]
  double tolerance = 0.005;            ///< relative |mean - value| / value to stop at, (0, 0.02]
  std::uint32_t max_vertices = 20000;  ///< vertex cap per particle
};

/// Throws InvalidInput naming the field unless the options are usable.
void validate(const CalibrationOptions& options);

/// One evaluated generator input.
struct CalibrationPoint {
  double alpha = 0;
  SummaryStatistics achieved;  ///< of the target descriptor over the samples
};

struct CalibrationResult {
  double alpha = 0;            ///< the Eq. 3 input found
  double radius = 0;           ///< control radius r = D / 2 (m)
  double edge_length = 0;      ///< L = edge_ratio * r (m)
  SummaryStatistics achieved;  ///< target descriptor at `alpha`
  SummaryStatistics volume;    ///< particle volume at `alpha` and `radius` (m^3)
  /// Radius of each particle's smallest enclosing sphere at `alpha` and `radius` (m).
  SummaryStatistics enclosing_radius;
  /// Every target descriptor at `alpha`, in kCalibrationTargets order (the other measures of
  /// the particles found: e.g. the Eq. 2 alpha of a volume-ratio match).
  std::vector<SummaryStatistics> all_descriptors;
  double reachable_minimum = 0;             ///< smallest grid mean
  double reachable_maximum = 0;             ///< largest grid mean
  bool within_tolerance = false;            ///< |achieved.mean - value| <= tolerance * value
  std::vector<CalibrationPoint> evaluated;  ///< every point evaluated, sorted by alpha
};

/// Mean and spread of the target descriptor over `options.samples` particles grown with Eq. 3
/// input `alpha` and control radius diameter / 2; when given, `volume` gets the volume's,
/// `enclosing` the smallest enclosing sphere radius' and `all` every target descriptor's (in
/// kCalibrationTargets order). Deterministic at any thread count.
SummaryStatistics evaluate_calibration(const CalibrationOptions& options, double alpha,
                                       SummaryStatistics* volume = nullptr,
                                       std::vector<SummaryStatistics>* all = nullptr,
                                       SummaryStatistics* enclosing = nullptr);

/// Finds the alpha whose particles' mean descriptor is `options.value`.
/// \throw InvalidInput naming the descriptor, the value and the reachable range when the target
/// lies outside what alpha in [0, 1] reaches at this L / r.
CalibrationResult calibrate(const CalibrationOptions& options);

}  // namespace aggpack
