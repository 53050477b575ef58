#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/pack/grading.h"
#include "pack/pack_test_util.h"

namespace aggpack {
namespace {

using testing::invalid_field;

Grading fuller_curve(double lo, double hi, double q) {
  return {.kind = GradingKind::kFuller, .size_min = lo, .size_max = hi, .exponent = q};
}

Grading sieve_table() {
  // A concrete-like coarse aggregate table (sizes in m, volume % passing).
  return {.kind = GradingKind::kSieve,
          .sieve = {{0.00475, 5.0}, {0.0095, 30.0}, {0.0125, 55.0}, {0.019, 90.0}, {0.025, 100.0}}};
}

// Volume-weighted passing fraction of `n` sizes drawn from the grading with independent streams.
std::vector<double> sampled_passing(const Grading& grading, const std::vector<double>& sizes, int n,
                                    std::uint64_t seed) {
  std::vector<double> passing(sizes.size(), 0.0);
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    Rng rng(seed, static_cast<std::uint64_t>(i));
    const double d = sample_size(grading, rng.uniform());
    const double v = d * d * d;
    total += v;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      if (d <= sizes[k]) passing[k] += v;
    }
  }
  for (double& p : passing) p /= total;
  return passing;
}

TEST(Grading, FullerCurveKnownValues) {
  const Grading g = fuller_curve(0.005, 0.02, 0.5);
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.005), 0.0);
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.02), 1.0);
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.03), 1.0);
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.001), 0.0);
  // (sqrt(0.01) - sqrt(0.005)) / (sqrt(0.02) - sqrt(0.005))
  EXPECT_NEAR(passing_fraction(g, 0.01),
              (0.1 - std::sqrt(0.005)) / (std::sqrt(0.02) - std::sqrt(0.005)), 1e-15);
  EXPECT_DOUBLE_EQ(smallest_size(g), 0.005);
  EXPECT_DOUBLE_EQ(largest_size(g), 0.02);
}

TEST(Grading, UniformRadiusIsUniformByNumber) {
  const Grading g{.kind = GradingKind::kUniform, .radius_min = 0.1, .radius_max = 0.3};
  EXPECT_DOUBLE_EQ(sample_size(g, 0.0), 0.2);
  EXPECT_DOUBLE_EQ(sample_size(g, 0.5), 0.4);
  EXPECT_NEAR(sample_size(g, 1.0), 0.6, 1e-15);
  // Volume curve (r^4 - r0^4) / (r1^4 - r0^4) at r = 0.2.
  EXPECT_NEAR(passing_fraction(g, 0.4), (0.0016 - 0.0001) / (0.0081 - 0.0001), 1e-14);
  // E[d^3] = 8 E[r^3] = 8 (r1^4 - r0^4) / (4 (r1 - r0)).
  EXPECT_NEAR(mean_cubed_size(g), 8.0 * (0.0081 - 0.0001) / 0.8, 1e-15);
  const Grading single{.kind = GradingKind::kUniform, .radius_min = 0.1, .radius_max = 0.1};
  EXPECT_DOUBLE_EQ(sample_size(single, 0.7), 0.2);
  EXPECT_DOUBLE_EQ(passing_fraction(single, 0.2), 1.0);
  EXPECT_DOUBLE_EQ(passing_fraction(single, 0.1999), 0.0);
  EXPECT_EQ(report_sizes(single), std::vector<double>{0.2});
}

TEST(Grading, SieveTableIsRenormalisedAboveTheSmallestSieve) {
  const Grading g = sieve_table();
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.00475), 0.0);
  EXPECT_NEAR(passing_fraction(g, 0.0095), 25.0 / 95.0, 1e-15);
  EXPECT_NEAR(passing_fraction(g, 0.019), 85.0 / 95.0, 1e-15);
  EXPECT_DOUBLE_EQ(passing_fraction(g, 0.025), 1.0);
  // Linear between sieves.
  EXPECT_NEAR(passing_fraction(g, (0.0125 + 0.019) / 2), (50.0 + 85.0) / 2 / 95.0, 1e-14);
  EXPECT_EQ(size_class(g, 0.005), 0u);
  EXPECT_EQ(size_class(g, 0.0095), 0u);
  EXPECT_EQ(size_class(g, 0.01), 1u);
  EXPECT_EQ(size_class(g, 0.025), 3u);
  EXPECT_EQ(report_sizes(g).size(), 5u);
}

TEST(Grading, SamplesAreMonotoneAndInRange) {
  for (const Grading& g :
       {fuller_curve(0.005, 0.02, 0.5), fuller_curve(0.01, 0.04, 3.0), sieve_table(),
        Grading{.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.02}}) {
    double previous = 0.0;
    for (int k = 0; k <= 1000; ++k) {
      const double d = sample_size(g, k / 1000.0);
      EXPECT_GE(d, smallest_size(g) * (1 - 1e-12));
      EXPECT_LE(d, largest_size(g) * (1 + 1e-12));
      EXPECT_GE(d, previous);
      previous = d;
    }
  }
}

// The number-density sampling reproduces the VOLUME grading: with 200,000 draws the volume
// percent passing is within 1.0 percentage point of the target at every report sieve, for every
// kind and several seeds (the statistical error is ~0.2 points).
TEST(Grading, SampledSizesReproduceTheTargetByVolume) {
  const std::vector<Grading> gradings = {
      fuller_curve(0.005, 0.02, 0.5), fuller_curve(0.0025, 0.02, 0.45),
      fuller_curve(0.01, 0.04, 3.0), sieve_table(),
      Grading{.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.03}};
  for (const Grading& g : gradings) {
    const auto sizes = report_sizes(g);
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const auto passing = sampled_passing(g, sizes, 200000, seed);
      for (std::size_t k = 0; k < sizes.size(); ++k) {
        EXPECT_NEAR(100.0 * passing[k], 100.0 * passing_fraction(g, sizes[k]), 1.0)
            << to_string(g.kind) << " size " << sizes[k] << " seed " << seed;
      }
    }
  }
}

TEST(Grading, MeanCubedSizeMatchesTheNumberDensity) {
  for (const Grading& g :
       {fuller_curve(0.005, 0.02, 0.5), fuller_curve(0.01, 0.04, 3.0), sieve_table()}) {
    // Midpoint rule over u: E[d^3] = integral of sample_size(u)^3 du.
    const int n = 400000;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const double d = sample_size(g, (k + 0.5) / n);
      sum += d * d * d;
    }
    EXPECT_NEAR(sum / n / mean_cubed_size(g), 1.0, 1e-4) << to_string(g.kind);
  }
}

TEST(Grading, EachBadFieldIsNamed) {
  EXPECT_EQ(invalid_field([] { validate(Grading{.radius_min = 0.0}); }), "grading.radius_min");
  EXPECT_EQ(invalid_field([] { validate(Grading{.radius_min = 0.2, .radius_max = 0.1}); }),
            "grading.radius_max");
  EXPECT_EQ(invalid_field([] { validate(fuller_curve(-1, 0.02, 0.5)); }), "grading.size_min");
  EXPECT_EQ(invalid_field([] { validate(fuller_curve(0.02, 0.02, 0.5)); }), "grading.size_max");
  EXPECT_EQ(invalid_field([] { validate(fuller_curve(0.01, 0.02, 0.0)); }), "grading.exponent");
  EXPECT_EQ(invalid_field([] { validate(fuller_curve(0.01, 0.02, 11.0)); }), "grading.exponent");
  Grading g = sieve_table();
  g.sieve.resize(1);
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve");
  g = sieve_table();
  g.sieve[2].size = 0.009;
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve[2].size");
  g = sieve_table();
  g.sieve[3].percent_passing = 50.0;
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve[3].percent_passing");
  g = sieve_table();
  g.sieve[4].percent_passing = 99.0;
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve[4].percent_passing");
  g = sieve_table();
  g.sieve[1].percent_passing = 130.0;
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve[1].percent_passing");
  g = sieve_table();
  g.sieve[0].size = -0.001;
  EXPECT_EQ(invalid_field([&] { validate(g); }), "grading.sieve[0].size");
}

}  // namespace
}  // namespace aggpack
