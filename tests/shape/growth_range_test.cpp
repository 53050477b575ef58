// The range of shapes the generator reaches with its inputs (alpha, L / r, the control
// ellipsoid's axis ratios) under the hull rule: means over 120 particles at the corners of the
// range real aggregate spans, from rounded gravel to flaky, elongated crushed stone.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"

namespace aggpack {
namespace {

struct Means {
  SummaryStatistics volume_ratio, sphericity, elongation, flatness, measured_alpha;
};

Means measure(double alpha, double edge_ratio, double elongation, double flatness) {
  const GeneratorOptions options{.alpha = alpha,
                                 .radius_min = 0.01,
                                 .radius_max = 0.01,
                                 .edge_length = edge_ratio * 0.01,
                                 .seed = 7,
                                 .form = {.elongation = elongation, .flatness = flatness}};
  std::vector<double> v, s, e, f, a;
  for (std::uint64_t i = 0; i < 120; ++i) {
    const ShapeDescriptors d = describe(generate_particle(options, i).body);
    v.push_back(enclosed_volume_ratio(d));
    s.push_back(d.sphericity);
    e.push_back(d.elongation);
    f.push_back(d.flatness);
    a.push_back(d.measured_alpha);
  }
  return {summarize(v), summarize(s), summarize(e), summarize(f), summarize(a)};
}

void expect_varied(const Means& m) {
  for (const SummaryStatistics* stats :
       {&m.volume_ratio, &m.sphericity, &m.elongation, &m.flatness, &m.measured_alpha}) {
    EXPECT_GT(stats->standard_deviation, 0.0);
    EXPECT_LT(stats->minimum, stats->maximum);
  }
}

TEST(GrowthRange, AngularCoarseParticlesAreLean) {
  const Means m = measure(0.0, 1.0, 1.0, 1.0);
  EXPECT_LE(m.volume_ratio.mean, 0.30);
  expect_varied(m);
}

TEST(GrowthRange, FullFineParticlesAreNearlySpheres) {
  const Means m = measure(1.0, 0.5, 1.0, 1.0);
  EXPECT_GE(m.volume_ratio.mean, 0.90);
  EXPECT_GE(m.sphericity.mean, 0.95);
  EXPECT_GE(m.elongation.mean, 0.95);
  EXPECT_GE(m.flatness.mean, 0.95);
  expect_varied(m);
}

TEST(GrowthRange, FlakyElongatedParticles) {
  const Means m = measure(0.5, 0.6, 0.35, 0.35);
  EXPECT_LE(m.sphericity.mean, 0.70);
  EXPECT_LE(m.elongation.mean, 0.45);
  EXPECT_LE(m.flatness.mean, 0.45);
  expect_varied(m);
}

// Each axis ratio moves its own descriptor: elongation alone leaves the particles about as flat
// as spheres, flatness alone about as elongated.
TEST(GrowthRange, AxisRatiosActOnTheirOwnDescriptor) {
  const Means elongated = measure(1.0, 0.5, 0.35, 1.0);
  EXPECT_LE(elongated.elongation.mean, 0.45);
  EXPECT_GE(elongated.flatness.mean, 0.90);
  const Means flaky = measure(1.0, 0.5, 1.0, 0.35);
  EXPECT_GE(flaky.elongation.mean, 0.90);
  EXPECT_LE(flaky.flatness.mean, 0.45);
}

// Fuller inputs give fuller particles: the measured (Eq. 2) alpha and V / V_circ rise with the
// input alpha at the paper's L = r.
TEST(GrowthRange, MeasuredDescriptorsRiseWithInputAlpha) {
  double previous_alpha = 0.0;
  double previous_ratio = 0.0;
  for (const double alpha : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const Means m = measure(alpha, 1.0, 1.0, 1.0);
    EXPECT_GT(m.measured_alpha.mean, previous_alpha) << "alpha " << alpha;
    EXPECT_GT(m.volume_ratio.mean, previous_ratio) << "alpha " << alpha;
    previous_alpha = m.measured_alpha.mean;
    previous_ratio = m.volume_ratio.mean;
  }
}

}  // namespace
}  // namespace aggpack
