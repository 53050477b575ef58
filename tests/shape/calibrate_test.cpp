// Particles to measured targets: calibrate() finds the generator inputs whose particles match up
// to three mean descriptors at once; checked by regenerating the particles independently.

#include "aggpack/shape/calibrate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"

namespace aggpack {
namespace {

CalibrationOptions small_options(std::vector<CalibrationGoal> goals, double diameter = 0.01) {
  CalibrationOptions options;
  options.goals = std::move(goals);
  options.diameter = diameter;
  options.samples = 60;
  options.seed = 7;
  return options;
}

// Mean descriptors of the particles of `result`, computed here from the generator and the
// descriptors, not through calibrate.cpp.
struct Regenerated {
  double enclosed_volume_ratio = 0;
  double enclosing_diameter = 0;
  double elongation = 0;
  double flatness = 0;
};
Regenerated regenerate(const CalibrationOptions& options, const CalibrationResult& result) {
  GeneratorOptions generator{.alpha = result.inputs.alpha,
                             .radius_min = result.radius,
                             .radius_max = result.radius,
                             .edge_length = result.inputs.edge_ratio * result.radius,
                             .seed = options.seed,
                             .form = options.form};
  generator.form.elongation = result.inputs.elongation;
  generator.form.flatness = result.inputs.flatness;
  Regenerated means;
  const auto n = static_cast<double>(options.samples);
  for (std::size_t i = 0; i < options.samples; ++i) {
    const auto d = describe(generate_particle(generator, i).body);
    const double r = d.enclosing_radius;
    means.enclosed_volume_ratio += d.volume / (4.0 / 3.0 * std::numbers::pi * r * r * r) / n;
    means.enclosing_diameter += 2.0 * r / n;
    means.elongation += d.elongation / n;
    means.flatness += d.flatness / n;
  }
  return means;
}

// The paper's acrylic particles (Table 1): V = 390.3 mm^3 at a circumscribed diameter of 10 mm
// and 467.2 mm^3 at 12.5 mm, i.e. V / V_circ = 0.7454 and 0.4568.
TEST(Calibrate, BothAcrylicParticlesWithinTwoPercent) {
  for (const auto& [volume, diameter] : {std::pair{390.3e-9, 0.010}, std::pair{467.2e-9, 0.0125}}) {
    const double sphere = std::numbers::pi / 6.0 * diameter * diameter * diameter;
    auto options = small_options(
        {{.target = CalibrationTarget::kEnclosedVolumeRatio, .value = volume / sphere}}, diameter);
    options.volume = volume;
    const auto result = calibrate(options);
    SCOPED_TRACE("volume " + std::to_string(volume));
    EXPECT_TRUE(result.within_tolerance);
    const Regenerated means = regenerate(options, result);
    ASSERT_EQ(result.achieved.size(), 1u);
    EXPECT_NEAR(means.enclosed_volume_ratio, result.achieved[0].mean, 1e-12);
    EXPECT_LE(std::abs(means.enclosed_volume_ratio - volume / sphere) / (volume / sphere), 0.02);
    // Sized so that the mean volume is V; the mean enclosing diameter is then D within the
    // spread of the particles' shapes.
    EXPECT_NEAR(result.volume.mean, volume, 1e-9 * volume);
    EXPECT_NEAR(means.enclosing_diameter, diameter, 0.05 * diameter);
    EXPECT_NEAR(result.enclosing_radius.mean * 2.0, means.enclosing_diameter, 1e-12);
    EXPECT_EQ(result.achieved[0].count, options.samples);
    EXPECT_GT(result.achieved[0].standard_deviation, 0.0);
    EXPECT_GE(result.inputs.edge_ratio, kMinSearchedEdgeRatio);
    EXPECT_LE(result.inputs.edge_ratio, kMaxSearchedEdgeRatio);
  }
}

// Three targets at once: a lean, elongated, flat particle (the control ellipsoid of semi-axes
// 1 : 0.7 : 0.42 alone has V / V_circ = 0.29). The axis ratios are searched because
// elongation and flatness are goals.
TEST(Calibrate, ThreeTargetsAtOnce) {
  const auto options =
      small_options({{.target = CalibrationTarget::kEnclosedVolumeRatio, .value = 0.2},
                     {.target = CalibrationTarget::kElongation, .value = 0.7},
                     {.target = CalibrationTarget::kFlatness, .value = 0.6}});
  const auto result = calibrate(options);
  EXPECT_TRUE(result.within_tolerance);
  const Regenerated means = regenerate(options, result);
  EXPECT_LE(std::abs(means.enclosed_volume_ratio - 0.2) / 0.2, 0.02);
  EXPECT_LE(std::abs(means.elongation - 0.7) / 0.7, 0.02);
  EXPECT_LE(std::abs(means.flatness - 0.6) / 0.6, 0.02);
  EXPECT_LT(result.inputs.elongation, 1.0);
  EXPECT_LT(result.inputs.flatness, 1.0);
}

// A target out of reach: one line naming the descriptor, the value, the span of means reached and
// the closest inputs.
TEST(Calibrate, UnreachableTargetNamesTheRangeAndClosestInputs) {
  auto options =
      small_options({{.target = CalibrationTarget::kEnclosedVolumeRatio, .value = 0.01}});
  options.max_evaluations = 40;
  try {
    calibrate(options);
    FAIL() << "expected CalibrationUnreached";
  } catch (const CalibrationUnreached& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.field(), "volume_ratio");
    // The target lies below every reached mean: the closest inputs give the span's low end.
    EXPECT_GT(error.lowest(), 0.01);
    EXPECT_LE(error.lowest(), error.highest());
    EXPECT_NEAR(error.closest(), error.lowest(), 0.1 * error.lowest());
    EXPECT_EQ(error.closest_inputs().rfind("alpha ", 0), 0U) << error.closest_inputs();
    EXPECT_NE(message.find("span ["), std::string::npos) << message;
    EXPECT_NE(message.find("closest inputs (alpha"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

// Same options, same result bit for bit, at one thread or all.
TEST(Calibrate, DeterministicAtAnyThreadCount) {
  const auto options = small_options({{.target = CalibrationTarget::kSphericity, .value = 0.93}});
  const auto all = calibrate(options);
  limit_threads(1);
  const auto one = calibrate(options);
  limit_threads(0);
  EXPECT_EQ(all.inputs.alpha, one.inputs.alpha);
  EXPECT_EQ(all.inputs.edge_ratio, one.inputs.edge_ratio);
  EXPECT_EQ(all.achieved[0].mean, one.achieved[0].mean);
  EXPECT_EQ(all.evaluated.size(), one.evaluated.size());
}

TEST(Calibrate, FixedEdgeRatioIsKept) {
  auto options = small_options({{.target = CalibrationTarget::kMeasuredAlpha, .value = 0.85}});
  options.edge_ratio = 1.0;
  const auto result = calibrate(options);
  EXPECT_EQ(result.inputs.edge_ratio, 1.0);
  EXPECT_TRUE(result.within_tolerance);
}

TEST(Calibrate, InvalidOptionsNameTheField) {
  auto field_of = [](const CalibrationOptions& options) -> std::string {
    try {
      validate(options);
    } catch (const InvalidInput& error) {
      return error.field();
    }
    return "";
  };
  const CalibrationGoal ratio{.target = CalibrationTarget::kVolumeRatio, .value = 0.5};
  const CalibrationGoal enclosed{.target = CalibrationTarget::kEnclosedVolumeRatio, .value = 0.5};
  const CalibrationGoal sphericity{.target = CalibrationTarget::kSphericity, .value = 0.9};
  const CalibrationGoal elongation{.target = CalibrationTarget::kElongation, .value = 0.9};
  const CalibrationGoal flatness{.target = CalibrationTarget::kFlatness, .value = 0.9};
  EXPECT_EQ(field_of(small_options({ratio})), "");
  EXPECT_EQ(field_of(small_options({})), "goals");
  EXPECT_EQ(field_of(small_options({ratio, sphericity, elongation, flatness})), "goals");
  EXPECT_EQ(field_of(small_options({ratio, enclosed})), "volume_ratio");
  EXPECT_EQ(field_of(small_options({sphericity, sphericity})), "sphericity");
  EXPECT_EQ(field_of(small_options({{.target = CalibrationTarget::kFlatness, .value = 1.5}})),
            "flatness");
  auto bad = small_options({ratio});
  bad.samples = 1;
  EXPECT_EQ(field_of(bad), "samples");
  bad = small_options({ratio});
  bad.edge_ratio = 2.0;
  EXPECT_EQ(field_of(bad), "edge_ratio");
  bad = small_options({ratio});
  bad.diameter = -1;
  EXPECT_EQ(field_of(bad), "diameter");
}

}  // namespace
}  // namespace aggpack
