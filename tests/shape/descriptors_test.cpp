// Shape descriptors (paper Eq. 1 and Eq. 2, principal dimensions) and summary statistics.

#include "aggpack/shape/descriptors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/shape/generator.h"

namespace aggpack {
namespace {

constexpr double kPi = std::numbers::pi;

// Eq. 1 and Eq. 2 written out independently of the library.
double eq1_sphericity(double volume, double surface) {
  return (4 * kPi / surface) * std::pow(3 * volume / (4 * kPi), 2.0 / 3.0);
}
double eq2_alpha(double volume, double surface) {
  const double radius = std::sqrt(surface / (4 * kPi));  // sphere with the same surface
  return volume / (4.0 / 3.0 * kPi * radius * radius * radius);
}

TEST(Describe, UnitCube) {
  const auto d = describe(make_box(Vec3::Zero(), Vec3::Ones()));
  EXPECT_NEAR(d.volume, 1.0, 1e-15);
  EXPECT_NEAR(d.surface_area, 6.0, 1e-14);
  // SI of a cube = pi^(1/3) 6^(2/3) / 6.
  EXPECT_NEAR(d.sphericity, std::cbrt(kPi) * std::pow(6.0, 2.0 / 3.0) / 6.0, 1e-14);
  EXPECT_NEAR(d.measured_alpha, std::pow(d.sphericity, 1.5), 1e-14);
  EXPECT_NEAR(d.measured_alpha, eq2_alpha(1.0, 6.0), 1e-14);
  EXPECT_EQ(d.vertex_count, 8u);
  EXPECT_EQ(d.face_count, 12u);
  EXPECT_EQ(d.edge_count, 18u);
  EXPECT_NEAR(d.circumscribed_radius, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(d.equivalent_diameter, std::cbrt(6 / kPi), 1e-15);
  EXPECT_NEAR(d.longest_edge, std::sqrt(2.0), 1e-15);  // the face diagonals are mesh edges
}

TEST(Describe, RegularOctahedronMatchesEq1AndEq2) {
  for (const double r : {0.01, 1.0, 7.5}) {
    const auto d = describe(make_octahedron({r, r, r, r, r, r}));
    const double volume = 4.0 / 3.0 * r * r * r;
    const double surface = 4 * std::sqrt(3.0) * r * r;
    EXPECT_NEAR(d.volume, volume, 1e-14 * volume);
    EXPECT_NEAR(d.surface_area, surface, 1e-14 * surface);
    EXPECT_NEAR(d.sphericity, eq1_sphericity(volume, surface), 1e-14);
    EXPECT_NEAR(d.measured_alpha, eq2_alpha(volume, surface), 1e-14);
    // Closed forms: SI = pi^(1/3) / sqrt(3), alpha = SI^(3/2).
    EXPECT_NEAR(d.sphericity, std::cbrt(kPi) / std::sqrt(3.0), 1e-14);
    EXPECT_NEAR(d.measured_alpha, std::pow(std::cbrt(kPi) / std::sqrt(3.0), 1.5), 1e-14);
    EXPECT_NEAR(d.circumscribed_radius, r, 1e-15 * r);
    EXPECT_NEAR(d.longest_edge, r * std::sqrt(2.0), 1e-15 * r);
    EXPECT_NEAR(d.equivalent_diameter, std::cbrt(6 * volume / kPi), 1e-15 * r);
  }
}

TEST(Describe, BoxPrincipalDimensionsInAnyPose) {
  const ConvexPolyhedron box = make_box(Vec3(-2, -1, -0.5), Vec3(2, 1, 0.5));  // 4 x 2 x 1
  const Quat turns[] = {Quat::Identity(), Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())),
                        Quat(Eigen::AngleAxisd(2.9, Vec3(-3, 1, 0.2).normalized()))};
  for (const auto& rotation : turns) {
    const auto d = describe(box.transformed({.position = Vec3(5, -3, 8), .rotation = rotation}));
    EXPECT_NEAR(d.long_dimension, 4.0, 1e-12);
    EXPECT_NEAR(d.intermediate_dimension, 2.0, 1e-12);
    EXPECT_NEAR(d.short_dimension, 1.0, 1e-12);
    EXPECT_NEAR(d.elongation, 0.5, 1e-12);
    EXPECT_NEAR(d.flatness, 0.5, 1e-12);
    EXPECT_NEAR(d.volume, 8.0, 1e-12);
    EXPECT_NEAR(d.surface_area, 2 * (8.0 + 4.0 + 2.0), 1e-12);
    EXPECT_NEAR(d.circumscribed_radius, std::sqrt(4 + 1 + 0.25), 1e-12);
  }
}

TEST(Describe, RegularTetrahedron) {
  const double radius = 2.0;
  const double a = radius * std::sqrt(8.0 / 3.0);
  const auto d = describe(make_regular_tetrahedron(radius));
  const double volume = a * a * a / (6 * std::sqrt(2.0));
  const double surface = std::sqrt(3.0) * a * a;
  EXPECT_NEAR(d.volume, volume, 1e-14 * volume);
  EXPECT_NEAR(d.surface_area, surface, 1e-14 * surface);
  EXPECT_NEAR(d.sphericity, eq1_sphericity(volume, surface), 1e-14);
  // Closed form: SI = 4 pi^(1/3) / (sqrt(3) 2^(7/3)) = 0.6711...
  EXPECT_NEAR(d.sphericity, 4 * std::cbrt(kPi) / (std::sqrt(3.0) * std::pow(2.0, 7.0 / 3.0)),
              1e-14);
  EXPECT_NEAR(d.measured_alpha, eq2_alpha(volume, surface), 1e-14);
  EXPECT_NEAR(d.circumscribed_radius, radius, 1e-14);
  EXPECT_EQ(d.edge_count, 6u);
}

// Over generated particles: SI = alpha^(2/3) (Eq. 1 vs Eq. 2), elongation and flatness in (0, 1],
// Euler's edge count matches the mesh, and the size measures are ordered sensibly.
TEST(Describe, RelationsOverGeneratedParticles) {
  for (std::uint64_t i = 0; i < 600; ++i) {
    const double alpha = static_cast<double>(i % 11) / 10.0;
    const auto particle = generate_particle(
        {.alpha = alpha, .radius_min = 0.02, .radius_max = 0.2, .edge_length = 0.06, .seed = 5}, i);
    const auto d = describe(particle.body);
    SCOPED_TRACE(i);
    ASSERT_NEAR(d.sphericity, std::pow(d.measured_alpha, 2.0 / 3.0), 1e-12);
    ASSERT_NEAR(d.sphericity, eq1_sphericity(d.volume, d.surface_area), 1e-12);
    ASSERT_GT(d.sphericity, 0.0);
    ASSERT_LT(d.sphericity, 1.0);
    ASSERT_GT(d.elongation, 0.0);
    ASSERT_LE(d.elongation, 1.0);
    ASSERT_GT(d.flatness, 0.0);
    ASSERT_LE(d.flatness, 1.0);
    ASSERT_GE(d.long_dimension, d.intermediate_dimension);
    ASSERT_GE(d.intermediate_dimension, d.short_dimension);
    ASSERT_EQ(d.edge_count, particle.body.edges().size());
    ASSERT_EQ(d.vertex_count, particle.body.vertex_count());
    ASSERT_EQ(d.face_count, particle.body.triangle_count());
    // The equal-volume sphere fits inside the circumscribed one; every vertex within 2r of the
    // centroid (the centroid is inside the r-ball).
    ASSERT_LT(d.equivalent_diameter / 2, d.circumscribed_radius);
    ASSERT_LE(d.circumscribed_radius, 2 * particle.control_radius);
    ASSERT_LE(d.longest_edge, 0.06 * (1 + 1e-12));
    ASSERT_LE(d.long_dimension, 2 * particle.control_radius * (1 + 1e-12));
  }
}

TEST(Describe, ScaleInvariance) {
  const auto body = generate_particle({.edge_length = 0.04}, 3).body;
  const auto a = describe(body);
  const auto b = describe(body.scaled(1000.0));
  EXPECT_NEAR(b.volume, a.volume * 1e9, 1e-12 * b.volume);
  EXPECT_NEAR(b.sphericity, a.sphericity, 1e-13);
  EXPECT_NEAR(b.measured_alpha, a.measured_alpha, 1e-13);
  EXPECT_NEAR(b.elongation, a.elongation, 1e-9);
  EXPECT_NEAR(b.flatness, a.flatness, 1e-9);
  EXPECT_NEAR(b.long_dimension, a.long_dimension * 1000, 1e-9);
}

TEST(Describe, InsideOutBodyIsRejected) {
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  std::vector<Triangle> flipped = cube.triangles();
  for (auto& t : flipped) std::swap(t[1], t[2]);
  try {
    describe(ConvexPolyhedron(cube.vertices(), flipped));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "particle volume");
  }
}

TEST(Summarize, KnownValues) {
  const auto s = summarize({4.0, 1.0, 3.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.standard_deviation, std::sqrt(5.0 / 3.0));  // sample (n - 1)
  EXPECT_EQ(s.minimum, 1.0);
  EXPECT_EQ(s.maximum, 4.0);
  const auto one = summarize({7.0});
  EXPECT_EQ(one.mean, 7.0);
  EXPECT_EQ(one.standard_deviation, 0.0);
  const auto none = summarize({});
  EXPECT_EQ(none.count, 0u);
  EXPECT_EQ(none.mean, 0.0);
  // Two-pass variance stays exact for a large offset where the one-pass formula cancels.
  const auto offset = summarize({1e9 + 1, 1e9 + 2, 1e9 + 3});
  EXPECT_DOUBLE_EQ(offset.standard_deviation, 1.0);
}

TEST(DescriptorColumns, NamedUniquelyWithUnitsAndReadTheRightField) {
  const auto& columns = descriptor_columns();
  std::set<std::string> names;
  for (const auto& column : columns) {
    EXPECT_TRUE(names.insert(column.name).second) << column.name;
    EXPECT_NE(std::string(column.unit), "");
  }
  for (const char* required :
       {"volume", "surface_area", "sphericity", "measured_alpha", "vertices", "faces", "elongation",
        "flatness", "circumscribed_radius", "long", "intermediate", "short"}) {
    EXPECT_EQ(names.count(required), 1u) << required;
  }
  // Every column reads the right field: known values of a 4 x 2 x 1 box.
  const auto d = describe(make_box(Vec3(-2, -1, -0.5), Vec3(2, 1, 0.5)));
  const std::map<std::string, double> expected = {
      {"volume", 8.0},
      {"surface_area", 28.0},
      {"sphericity", eq1_sphericity(8.0, 28.0)},
      {"measured_alpha", eq2_alpha(8.0, 28.0)},
      {"vertices", 8.0},
      {"edges", 18.0},
      {"faces", 12.0},
      {"long", 4.0},
      {"intermediate", 2.0},
      {"short", 1.0},
      {"elongation", 0.5},
      {"flatness", 0.5},
      {"circumscribed_radius", std::sqrt(5.25)},
      {"enclosing_radius", std::sqrt(5.25)},  // a box: the centred sphere is the smallest
      {"equivalent_diameter", std::cbrt(48.0 / kPi)},
      {"longest_edge", std::sqrt(20.0)},
      // V over the enclosing sphere's volume, 4/3 pi 5.25^(3/2)
      {"volume_ratio", 8.0 / (4.0 / 3.0 * kPi * std::pow(5.25, 1.5))},
  };
  for (const auto& column : columns) {
    const auto known = expected.find(column.name);
    ASSERT_NE(known, expected.end()) << "no known value for new column " << column.name;
    EXPECT_NEAR(column.get(d), known->second, 1e-12) << column.name;
  }
  EXPECT_EQ(columns.size(), expected.size());
}

TEST(Summarize, RunningSummaryMatchesTheTwoPassOne) {
  std::vector<double> values;
  RunningSummary running;
  for (int i = 0; i < 1000; ++i) {
    const double value = 1e3 + std::sin(0.37 * i) * (i % 7);  // large mean, small spread
    values.push_back(value);
    running.add(value);
  }
  const SummaryStatistics expected = summarize(values);
  const SummaryStatistics got = running.result();
  EXPECT_EQ(got.count, expected.count);
  EXPECT_EQ(got.minimum, expected.minimum);
  EXPECT_EQ(got.maximum, expected.maximum);
  EXPECT_NEAR(got.mean, expected.mean, 1e-12 * std::abs(expected.mean));
  EXPECT_NEAR(got.standard_deviation, expected.standard_deviation,
              1e-9 * expected.standard_deviation);
  EXPECT_EQ(RunningSummary().result().count, 0u);
}

}  // namespace
}  // namespace aggpack
