// Particle colours (no OpenGL).

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "aggpack/core/error.h"
#include "aggpack/render/colors.h"
#include "test_packings.h"

namespace aggpack {
namespace {

int distance(const Rgb& a, const Rgb& b) {
  return std::abs(a.r - b.r) + std::abs(a.g - b.g) + std::abs(a.b - b.b);
}

TEST(Colors, ParsesModeNamesAndRejectsOthers) {
  EXPECT_EQ(parse_color_mode("id"), ColorMode::kParticle);
  EXPECT_EQ(parse_color_mode("particle"), ColorMode::kParticle);
  EXPECT_EQ(parse_color_mode("size"), ColorMode::kSize);
  EXPECT_EQ(parse_color_mode("alpha"), ColorMode::kAlpha);
  for (ColorMode mode : {ColorMode::kParticle, ColorMode::kSize, ColorMode::kAlpha}) {
    EXPECT_EQ(parse_color_mode(color_mode_name(mode)), mode);
  }
  EXPECT_THROW(parse_color_mode("red"), InvalidInput);
}

TEST(Colors, ParticleModeGivesNeighboursClearlyDifferentColours) {
  const Packing packing = test::grid_packing(10, 10, 1);
  const auto colors = particle_colors(packing, measure_shapes(packing), ColorMode::kParticle);
  ASSERT_EQ(colors.colors.size(), 100u);
  std::set<std::tuple<int, int, int>> distinct;
  for (std::size_t i = 0; i < colors.colors.size(); ++i) {
    const Rgb& c = colors.colors[i];
    distinct.insert({c.r, c.g, c.b});
    if (i + 1 < colors.colors.size()) {
      EXPECT_GT(distance(c, colors.colors[i + 1]), 60) << i;  // grid neighbours along x
    }
    if (i + 10 < colors.colors.size()) {
      EXPECT_GT(distance(c, colors.colors[i + 10]), 30) << i;  // grid neighbours along y
    }
  }
  EXPECT_EQ(distinct.size(), 100u);
}

TEST(Colors, SizeScaleFollowsTheScaledDiameter) {
  Packing packing = test::grid_packing(4, 1, 1, 0.1, 1);  // one shape, four particles
  for (std::size_t i = 0; i < 4; ++i) packing.particles[i].scale = 1.0 + 0.5 * i;
  const ShapeMeasures measures = measure_shapes(packing);
  const auto colors = particle_colors(packing, measures, ColorMode::kSize);
  EXPECT_NEAR(colors.minimum, measures.equivalent_diameter[0], 1e-15);
  EXPECT_NEAR(colors.maximum, 2.5 * measures.equivalent_diameter[0], 1e-15);
  EXPECT_EQ(colors.colors.front(), scale_color(0.0));
  EXPECT_EQ(colors.colors.back(), scale_color(1.0));
  EXPECT_EQ(colors.colors[2], scale_color(2.0 / 3.0));
  // Alpha does not change with scale: all four alike, mid-scale.
  const auto alpha = particle_colors(packing, measures, ColorMode::kAlpha);
  for (const Rgb& c : alpha.colors) EXPECT_EQ(c, scale_color(0.5));
  EXPECT_DOUBLE_EQ(alpha.minimum, alpha.maximum);
}

TEST(Colors, MeasuredAlphaOfARegularOctahedronIsExact) {
  Packing packing;
  packing.shapes.push_back(make_octahedron({1, 1, 1, 1, 1, 1}));
  packing.shapes.push_back(make_box(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  const ShapeMeasures measures = measure_shapes(packing);
  // Octahedron of circumradius 1: V = 4/3, S = 4 sqrt(3); cube of side 2: V = 8, S = 24.
  auto alpha = [](double volume, double surface) {
    return volume / (std::pow(surface, 1.5) / (6.0 * std::sqrt(M_PI)));
  };
  EXPECT_NEAR(measures.measured_alpha[0], alpha(4.0 / 3.0, 4.0 * std::sqrt(3.0)), 1e-12);
  EXPECT_NEAR(measures.measured_alpha[1], alpha(8.0, 24.0), 1e-12);
  EXPECT_NEAR(measures.measured_alpha[1], M_PI / 6.0 * std::sqrt(6.0 / M_PI) * 1.0, 1e-12);
  EXPECT_NEAR(measures.equivalent_diameter[1], std::cbrt(48.0 / M_PI), 1e-12);
}

TEST(Colors, ScaleRunsFromDarkToBright) {
  auto luminance = [](const Rgb& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  double previous = -1.0;
  for (int k = 0; k <= 20; ++k) {
    const double value = luminance(scale_color(k / 20.0));
    EXPECT_GT(value, previous) << k;
    previous = value;
  }
  EXPECT_EQ(scale_color(-3.0), scale_color(0.0));
  EXPECT_EQ(scale_color(7.0), scale_color(1.0));
  EXPECT_EQ(scale_color(std::nan("")), scale_color(0.0));
}

}  // namespace
}  // namespace aggpack
