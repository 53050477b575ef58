// The random aggregate generator (paper Section 2, Eq. 3): invariants over many seeds, exact
// special cases, statistics of the shape control, determinism and input validation.

#include "aggpack/shape/generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"

namespace aggpack {
namespace {

// Relative tolerance for "every edge <= L" and "every vertex within r": both are decided on
// squared lengths, so only the final rounding of a square root separates them from the limit.
constexpr double kLengthTolerance = 1e-12;

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001B3ULL;
  }
  return hash;
}

std::uint64_t hash_body(std::uint64_t hash, const ConvexPolyhedron& body) {
  hash = fnv1a(hash, body.vertices().data(), body.vertices().size() * sizeof(Vec3));
  return fnv1a(hash, body.triangles().data(), body.triangles().size() * sizeof(Triangle));
}

TEST(Eq3Distance, EndsOfTheRangeAndLinearInU) {
  const double r = 0.25;
  for (const double alpha : {0.0, 0.3, 0.5, 0.9, 1.0}) {
    EXPECT_DOUBLE_EQ(eq3_distance(alpha, r, 0.0), r * (alpha + 0.2 * (1.0 - alpha)));
    EXPECT_NEAR(eq3_distance(alpha, r, 1.0), r, 1e-15);
    EXPECT_NEAR(eq3_distance(alpha, r, 0.5),
                0.5 * (eq3_distance(alpha, r, 0.0) + eq3_distance(alpha, r, 1.0)), 1e-15);
  }
  // At alpha = 1 every draw is r (regular octahedron); at alpha = 0 the range is [0.2 r, r].
  EXPECT_DOUBLE_EQ(eq3_distance(1.0, r, 0.123), r);
  EXPECT_DOUBLE_EQ(eq3_distance(0.0, r, 0.0), 0.2 * r);
  // At r = 1 the reading agrees with the paper's printed form alpha*r + 0.2(1-alpha) +
  // 0.8(1-alpha)rU.
  for (const double u : {0.0, 0.25, 0.77}) {
    const double alpha = 0.4;
    EXPECT_NEAR(eq3_distance(alpha, 1.0, u), alpha + 0.2 * (1 - alpha) + 0.8 * (1 - alpha) * u,
                1e-15);
  }
}

// >= 10,000 seeds spread over alpha in [0, 1] and L/r in [0.3, 2], at three length scales, both
// growth rules, control spheres and turned control ellipsoids. Every result must be a closed,
// convex, outward 2-manifold with V - E + F = 2, every edge <= L and every vertex within its
// control surface.
TEST(GrowAggregate, InvariantsOverTenThousandSeeds) {
  constexpr int kCount = 10000;
  const double scales[] = {1e-3, 0.1, 20.0};
  std::size_t total_vertices = 0;
  int grown = 0;
  for (int i = 0; i < kCount; ++i) {
    const double alpha = static_cast<double>(i % 101) / 100.0;
    const double edge_over_radius = 0.3 + 1.7 * static_cast<double>((i * 7919) % 1000) / 999.0;
    const double radius = scales[i % 3];
    GrowthParams params{.alpha = alpha, .radius = radius, .edge_length = edge_over_radius * radius};
    params.form.growth = i % 2 == 0 ? Growth::kHull : Growth::kMidpoint;
    params.form.min_edge_ratio = 0.05 * static_cast<double>(i % 11);  // 0 .. 0.5
    if (i % 4 >= 2) {                                                 // a control ellipsoid, turned
      params.form.elongation = std::min(1.0, 0.2 + 0.8 * static_cast<double>((i * 31) % 97) / 96.0);
      params.form.flatness = std::min(1.0, 0.2 + 0.8 * static_cast<double>((i * 17) % 89) / 88.0);
      params.axes = Quat(Eigen::AngleAxisd(0.1 * i, Vec3(1, 2, 3).normalized()));
    }
    Rng rng(12345, static_cast<std::uint64_t>(i));
    const ConvexPolyhedron body = grow_aggregate(params, rng);
    SCOPED_TRACE("particle " + std::to_string(i) + " alpha " + std::to_string(alpha) + " L/r " +
                 std::to_string(edge_over_radius) + " r " + std::to_string(radius));

    const CheckResult manifold = check_closed_manifold(body);
    ASSERT_TRUE(manifold.is_ok) << manifold.message;
    const CheckResult convex = check_convex(body, 1e-9 * radius);
    ASSERT_TRUE(convex.is_ok) << convex.message;
    const auto edges = body.edges();
    ASSERT_EQ(static_cast<long long>(body.vertex_count()) - static_cast<long long>(edges.size()) +
                  static_cast<long long>(body.triangle_count()),
              2);
    // Outward: every face normal points away from the growth centre (the origin is inside).
    for (std::size_t f = 0; f < body.triangle_count(); ++f) {
      ASSERT_GT(body.face_normal_scaled(f).dot(body.vertices()[body.triangles()[f][0]]), 0.0);
    }
    for (const auto& edge : edges) {
      const double length =
          (body.vertices()[edge.vertices[0]] - body.vertices()[edge.vertices[1]]).norm();
      ASSERT_LE(length, params.edge_length * (1 + kLengthTolerance));
    }
    for (const auto& vertex : body.vertices()) {
      ASSERT_LE(vertex.norm(),
                control_radius_along(params, vertex.normalized()) * (1 + kLengthTolerance));
    }
    ASSERT_EQ(locate_point(body, Vec3::Zero(), 1e-12 * radius * radius * radius),
              PointLocation::kInside);
    total_vertices += body.vertex_count();
    if (body.vertex_count() > 6) ++grown;
  }
  // The sweep must actually exercise growth, not just return octahedra.
  EXPECT_GT(grown, kCount / 2);
  EXPECT_GT(total_vertices, static_cast<std::size_t>(20 * kCount));
}

// The six base vertices stay at indices 0..5 on the half-axes +x, -x, +y, -y, +z, -z (growth
// only adds vertices), so Eq. 3 can be checked on every particle.
// (The midpoint rule keeps them; the hull rule may drop a base vertex that ends up inside.)
TEST(GrowAggregate, BaseVerticesFollowEq3Range) {
  const double r = 0.1;
  for (const double alpha : {0.0, 0.2, 0.5, 0.8}) {
    const double lower = r * (alpha + 0.2 * (1.0 - alpha));
    double smallest = r;
    double largest = 0;
    double sum = 0;
    int count = 0;
    for (std::uint64_t i = 0; i < 1000; ++i) {
      Rng rng(99, i);
      const auto body = grow_aggregate({.alpha = alpha,
                                        .radius = r,
                                        .edge_length = 0.6 * r,
                                        .form = {.growth = Growth::kMidpoint}},
                                       rng);
      for (int k = 0; k < 6; ++k) {
        const Vec3& v = body.vertices()[static_cast<std::size_t>(k)];
        const int axis = k / 2;
        const double sign = (k % 2 == 0) ? 1.0 : -1.0;
        // Exactly on its half-axis.
        for (int other = 0; other < 3; ++other) {
          if (other != axis) {
            ASSERT_EQ(v[other], 0.0);
          }
        }
        const double d = sign * v[axis];
        ASSERT_GE(d, lower * (1 - 1e-15));
        ASSERT_LE(d, r);
        smallest = std::min(smallest, d);
        largest = std::max(largest, d);
        sum += d;
        ++count;
      }
    }
    // 6,000 uniform draws: the extremes come within 0.2% of the range's ends and the mean is
    // the midpoint r (alpha + 0.6 (1 - alpha)) within a few standard errors.
    const double span = r - lower;
    EXPECT_LT(smallest - lower, 0.002 * span) << "alpha " << alpha;
    EXPECT_LT(r - largest, 0.002 * span) << "alpha " << alpha;
    const double standard_error = span / std::sqrt(12.0 * count);
    EXPECT_NEAR(sum / count, r * (alpha + 0.6 * (1 - alpha)), 5 * standard_error)
        << "alpha " << alpha;
  }
}

TEST(GrowAggregate, AlphaOneWithoutGrowthIsTheRegularOctahedron) {
  const double r = 0.3;
  // Every edge of the regular octahedron is r sqrt(2), so L >= that means no growth.
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    Rng rng(seed, 0);
    const auto body = grow_aggregate(
        {.alpha = 1.0, .radius = r, .edge_length = r * std::sqrt(2.0) * 1.0001}, rng);
    ASSERT_EQ(body.vertex_count(), 6u);
    ASSERT_EQ(body.triangle_count(), 8u);
    const ConvexPolyhedron regular = make_octahedron({r, r, r, r, r, r});
    for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(body.vertices()[k], regular.vertices()[k]);
    const auto mass = mass_properties(body);
    EXPECT_NEAR(mass.volume, 4.0 / 3.0 * r * r * r, 1e-15);
    EXPECT_NEAR(mass.surface_area, 4.0 * std::sqrt(3.0) * r * r, 1e-14);
  }
}

TEST(GrowAggregate, AlphaOneGrownKeepsRegularBase) {
  const double r = 0.1;
  Rng rng(5, 3);
  const auto body = grow_aggregate(
      {.alpha = 1.0, .radius = r, .edge_length = 0.4 * r, .form = {.growth = Growth::kMidpoint}},
      rng);
  ASSERT_GT(body.vertex_count(), 6u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(body.vertices()[k].norm(), r);
  // With alpha = 1 every draw is r; a vertex only comes in closer where the convexity clamp
  // stops it (most do: see MeasuredAlphaRisesWithInputAlpha). The first split of the regular
  // octahedron is unconstrained, so some new vertex reaches r.
  std::size_t on_sphere = 0;
  for (const auto& v : body.vertices()) {
    EXPECT_LE(v.norm(), r * (1 + kLengthTolerance));
    if (v.norm() > r * (1 - 1e-12)) ++on_sphere;
  }
  EXPECT_GT(on_sphere, 6u);
}

// Hull rule at alpha = 1: every draw is the control radius and every point of an edge lies inside
// the sphere, so every new vertex bulges out onto the sphere; the random points make every
// particle different (only the midpoint rule's alpha = 1 particles are all alike).
TEST(GrowAggregate, HullAlphaOneVerticesOnTheSphereAndParticlesDiffer) {
  const double r = 0.1;
  std::vector<double> volumes;
  for (std::uint64_t i = 0; i < 50; ++i) {
    Rng rng(5, i);
    // No minimum edge (which would make some new vertices split their edge instead).
    const auto body = grow_aggregate(
        {.alpha = 1.0, .radius = r, .edge_length = 0.5 * r, .form = {.min_edge_ratio = 0.0}}, rng);
    ASSERT_GT(body.vertex_count(), 30u);
    for (const auto& v : body.vertices()) ASSERT_NEAR(v.norm(), r, 1e-14);
    volumes.push_back(mass_properties(body).volume);
  }
  const auto stats = summarize(volumes);
  EXPECT_GT(stats.standard_deviation, 1e-3 * stats.mean);
  // A polyhedron inscribed in the sphere with edges <= r / 2: between 85 % and 100 % of it.
  EXPECT_GT(stats.minimum, 0.85 * 4.0 / 3.0 * std::numbers::pi * r * r * r);
  EXPECT_LT(stats.maximum, 4.0 / 3.0 * std::numbers::pi * r * r * r);
}

// A limit that always answers s_lo puts every new vertex on the edge it splits (the midpoint
// rule: its midpoint; the hull rule: its random point): growth then only subdivides the base
// octahedron, so the volume is exactly the base's.
TEST(GrowAggregate, GrowthLimitIsHonoured) {
  for (const Growth growth : {Growth::kMidpoint, Growth::kHull}) {
    SCOPED_TRACE(growth_name(growth));
    int calls = 0;
    const GrowthLimit flat = [&calls](const Vec3& direction, double s_lo, double s_hi) {
      ++calls;
      EXPECT_NEAR(direction.norm(), 1.0, 1e-14);
      EXPECT_LE(s_lo, s_hi * (1 + 1e-12));
      return s_lo;
    };
    const GrowthParams params{
        .alpha = 0.3, .radius = 0.1, .edge_length = 0.04, .form = {.growth = growth}};
    Rng rng(8, 1);
    const auto body = grow_aggregate(params, rng, flat);
    Rng replay(8, 1);
    std::array<double, 6> distances{};
    for (auto& d : distances) d = eq3_distance(params.alpha, params.radius, replay.uniform());
    const auto base = mass_properties(make_octahedron(distances));
    EXPECT_EQ(static_cast<std::size_t>(calls), body.vertex_count() - 6);
    EXPECT_NEAR(mass_properties(body).volume, base.volume, 1e-12 * base.volume);
    EXPECT_LE(body.longest_edge(), params.edge_length * (1 + kLengthTolerance));
    EXPECT_TRUE(check_closed_manifold(body).is_ok);
    EXPECT_TRUE(check_convex(body, 1e-12).is_ok);

    // A limit halfway into the feasible interval: a smaller body, still convex and within L.
    const GrowthParams full_params{
        .alpha = 1.0, .radius = 0.1, .edge_length = 0.05, .form = {.growth = growth}};
    const GrowthLimit halfway = [](const Vec3&, double s_lo, double s_hi) {
      return s_lo + 0.5 * (s_hi - s_lo);
    };
    Rng rng2(8, 2);
    const auto capped = grow_aggregate(full_params, rng2, halfway);
    Rng rng3(8, 2);
    const auto full = grow_aggregate(full_params, rng3);
    EXPECT_LT(mass_properties(capped).volume, 0.99 * mass_properties(full).volume);
    EXPECT_TRUE(check_convex(capped, 1e-12).is_ok);
    EXPECT_LE(capped.longest_edge(), full_params.edge_length * (1 + kLengthTolerance));
  }
}

// The measured alpha (Eq. 2) is a different number from the input alpha (Eq. 3), but fuller
// inputs must give fuller particles on average. Measured at L/r = 0.5 (means of 400 particles):
//   input   0.0   0.1   0.2   0.3   0.4   0.5   0.6   0.7   0.8   0.9   1.0
//   mean   0.698 0.731 0.757 0.779 0.800 0.820 0.838 0.850 0.855 0.858 0.835
// It rises clearly up to 0.8, is nearly flat from 0.8 to 0.9 and drops at exactly 1: the regular
// base octahedron makes the convexity clamp bind on most splits (92% of new vertices land on their
// edge's midpoint), so growth adds less than from a slightly irregular base. The test pins both
// facts.
TEST(GrowAggregate, MeasuredAlphaRisesWithInputAlpha) {
  auto mean_measured = [](double alpha) {
    std::vector<double> measured;
    for (std::uint64_t i = 0; i < 400; ++i) {
      const auto particle = generate_particle({.alpha = alpha,
                                               .radius_min = 0.1,
                                               .radius_max = 0.1,
                                               .edge_length = 0.05,
                                               .seed = 3,
                                               .form = {.growth = Growth::kMidpoint}},
                                              i);
      measured.push_back(describe(particle.body).measured_alpha);
    }
    return summarize(measured);
  };
  double previous_mean = 0;
  double previous_error = 0;
  for (const double alpha : {0.0, 0.2, 0.4, 0.6, 0.8}) {
    const auto stats = mean_measured(alpha);
    const double error = stats.standard_deviation / std::sqrt(static_cast<double>(stats.count));
    EXPECT_GT(stats.mean, previous_mean + 3 * (error + previous_error)) << "alpha " << alpha;
    EXPECT_GT(stats.minimum, 0.0);
    EXPECT_LT(stats.maximum, 1.0);  // no polyhedron reaches the sphere's alpha of 1
    previous_mean = stats.mean;
    previous_error = error;
  }
  const auto regular = mean_measured(1.0);
  const double regular_error =
      regular.standard_deviation / std::sqrt(static_cast<double>(regular.count));
  EXPECT_LT(regular.mean, previous_mean - 3 * (regular_error + previous_error));
  EXPECT_GT(regular.mean, mean_measured(0.5).mean);
}

TEST(GenerateParticle, RadiusRangeAndFixedRadius) {
  const GeneratorOptions range{
      .alpha = 0.5, .radius_min = 0.05, .radius_max = 0.2, .edge_length = 0.1, .seed = 11};
  double smallest = 1;
  double largest = 0;
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const auto particle = generate_particle(range, i);
    ASSERT_GE(particle.control_radius, 0.05);
    ASSERT_LT(particle.control_radius, 0.2);
    for (const auto& v : particle.body.vertices()) {
      ASSERT_LE(v.norm(), particle.control_radius * (1 + kLengthTolerance));
    }
    ASSERT_LE(particle.body.longest_edge(), 0.1 * (1 + kLengthTolerance));
    smallest = std::min(smallest, particle.control_radius);
    largest = std::max(largest, particle.control_radius);
  }
  EXPECT_LT(smallest, 0.051);
  EXPECT_GT(largest, 0.199);
  const GeneratorOptions fixed{
      .alpha = 0.5, .radius_min = 0.07, .radius_max = 0.07, .edge_length = 0.1};
  EXPECT_EQ(generate_particle(fixed, 4).control_radius, 0.07);
}

TEST(GenerateParticle, SameOptionsAndIndexGiveIdenticalBits) {
  const GeneratorOptions options{
      .alpha = 0.37, .radius_min = 0.05, .radius_max = 0.12, .edge_length = 0.04, .seed = 2024};
  for (std::uint64_t i = 0; i < 200; ++i) {
    const auto a = generate_particle(options, i);
    const auto b = generate_particle(options, i);
    ASSERT_EQ(a.control_radius, b.control_radius);
    ASSERT_EQ(a.body.vertex_count(), b.body.vertex_count());
    ASSERT_EQ(0, std::memcmp(a.body.vertices().data(), b.body.vertices().data(),
                             a.body.vertex_count() * sizeof(Vec3)));
    ASSERT_EQ(a.body.triangles(), b.body.triangles());
  }
  // Different index or seed: a different particle.
  const auto first = generate_particle(options, 0);
  EXPECT_NE(first.body.vertices(), generate_particle(options, 1).body.vertices());
  GeneratorOptions other_seed = options;
  other_seed.seed = 2025;
  EXPECT_NE(first.body.vertices(), generate_particle(other_seed, 0).body.vertices());
}

// Particles generated by two threads in an interleaved order equal the serial ones bit for bit.
TEST(GenerateParticle, IndependentOfThreadAndOrder) {
  const GeneratorOptions options{
      .alpha = 0.6, .radius_min = 0.08, .radius_max = 0.1, .edge_length = 0.03, .seed = 77};
  constexpr std::uint64_t kCount = 300;
  std::vector<std::uint64_t> serial(kCount);
  for (std::uint64_t i = 0; i < kCount; ++i) {
    serial[i] = hash_body(0xcbf29ce484222325ULL, generate_particle(options, i).body);
  }
  std::vector<std::uint64_t> threaded(kCount);
  auto work = [&](std::uint64_t start) {
    for (std::uint64_t i = kCount - 1 - start; i < kCount; i -= 2) {  // backwards, every other
      threaded[i] = hash_body(0xcbf29ce484222325ULL, generate_particle(options, i).body);
    }
  };
  std::thread a(work, 0);
  std::thread b(work, 1);
  a.join();
  b.join();
  EXPECT_EQ(serial, threaded);
}

// Each thread keeps its growing mesh from one particle to the next: a growth aborted midway (here
// by a throwing GrowthLimit) leaves nothing behind, and a particle grown inside another's
// GrowthLimit gets a mesh of its own, so neither changes a bit of the particles around it.
TEST(GrowAggregate, KeptMeshLeavesNoTrace) {
  for (const Growth growth : {Growth::kHull, Growth::kMidpoint}) {
    SCOPED_TRACE(growth_name(growth));
    const GrowthParams params{
        .alpha = 0.4, .radius = 0.1, .edge_length = 0.03, .form = {.growth = growth}};
    const auto grow = [&params](const GrowthLimit& limit) {
      Rng rng(5, 3);
      return hash_body(0xcbf29ce484222325ULL, grow_aggregate(params, rng, limit));
    };
    const std::uint64_t fresh = grow({});
    int calls = 0;
    const GrowthLimit abort_midway = [&calls](const Vec3&, double, double s_hi) {
      if (++calls == 20) throw std::runtime_error("aborted");
      return s_hi;
    };
    EXPECT_THROW(grow(abort_midway), std::runtime_error);
    EXPECT_EQ(calls, 20);
    EXPECT_EQ(grow({}), fresh);
    std::size_t inner_vertices = 0;
    const GrowthLimit nested = [&](const Vec3&, double, double s_hi) {
      Rng inner(9, 9);
      inner_vertices = grow_aggregate(params, inner).vertex_count();
      return s_hi;  // no clamp: the outer particle is the unlimited one
    };
    EXPECT_EQ(grow(nested), fresh);
    EXPECT_GT(inner_vertices, 6U);
    EXPECT_EQ(grow({}), fresh);
  }
}

// The hash of particles 0..count-1 (radius 0.05-0.1 m, seed 1) for alpha 0, 0.5 and 1 in turn:
// their control radii and exact bits.
[[maybe_unused]] std::uint64_t family_hash(double edge_length, const GrowthForm& form,
                                           std::uint64_t count) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const double alpha : {0.0, 0.5, 1.0}) {
    const GeneratorOptions options{.alpha = alpha,
                                   .radius_min = 0.05,
                                   .radius_max = 0.1,
                                   .edge_length = edge_length,
                                   .seed = 1,
                                   .form = form};
    for (std::uint64_t i = 0; i < count; ++i) {
      const auto particle = generate_particle(options, i);
      hash = fnv1a(hash, &particle.control_radius, sizeof(double));
      hash = hash_body(hash, particle.body);
    }
  }
  return hash;
}

// Golden value: a hash of the exact bits of 500 particles. It pins the algorithm (Eq. 3 draws,
// longest-edge order with its tie-break, the convexity clamp), so an optimisation that changes
// any result fails here. IEEE double arithmetic without FMA contraction makes it reproducible on
// x86-64; other architectures may contract a*b+c and are skipped.
TEST(GenerateParticle, GoldenHashOfFiveHundredParticles) {
#if !defined(__x86_64__)
  GTEST_SKIP() << "golden bits recorded on x86-64";
#else
  const std::uint64_t hash = family_hash(0.035, {.growth = Growth::kMidpoint}, 500);
  EXPECT_EQ(hash, 0xd59b8022d9560cc6ULL) << std::hex << "0x" << hash;
#endif
}

TEST(Validate, EveryFieldNamedWithValueAndRange) {
  auto field_of = [](const GrowthParams& params) -> std::string {
    try {
      validate(params);
    } catch (const InvalidInput& error) {
      EXPECT_NE(std::string(error.what()).find("allowed"), std::string::npos);
      return error.field();
    }
    return "";
  };
  const GrowthParams good{.alpha = 0.5, .radius = 0.1, .edge_length = 0.05};
  EXPECT_EQ(field_of(good), "");
  const double nan = std::nan("");
  const double inf = INFINITY;
  for (const double alpha : {-0.01, 1.01, nan, inf, -inf}) {
    auto p = good;
    p.alpha = alpha;
    EXPECT_EQ(field_of(p), "alpha") << alpha;
  }
  for (const double radius : {0.0, -0.1, nan, inf}) {
    auto p = good;
    p.radius = radius;
    EXPECT_EQ(field_of(p), "radius") << radius;
  }
  for (const double edge : {0.0, -1.0, nan, inf}) {
    auto p = good;
    p.edge_length = edge;
    EXPECT_EQ(field_of(p), "edge_length") << edge;
  }
  for (const std::uint32_t cap : {0u, 5u, 1000001u}) {
    auto p = good;
    p.max_vertices = cap;
    EXPECT_EQ(field_of(p), "max_vertices") << cap;
  }
  // Both ends of alpha are allowed.
  auto p = good;
  p.alpha = 0.0;
  EXPECT_NO_THROW(validate(p));
  p.alpha = 1.0;
  EXPECT_NO_THROW(validate(p));
  // Invalid input reaches grow_aggregate's own check too.
  Rng rng(1, 1);
  EXPECT_THROW(grow_aggregate({.alpha = 2.0}, rng), InvalidInput);
}

TEST(Validate, EdgeTooSmallForVertexCapIsLimitExceeded) {
  const GrowthParams tiny{.alpha = 0.5, .radius = 0.1, .edge_length = 1e-5};
  std::string message;
  try {
    validate(tiny);
    FAIL() << "expected LimitExceeded";
  } catch (const LimitExceeded& error) {
    EXPECT_EQ(error.kind(), ErrorKind::kLimitExceeded);
    message = error.what();
  }
  EXPECT_NE(message.find("edge_length"), std::string::npos) << message;
  EXPECT_NE(message.find("1e-05"), std::string::npos) << message;
  EXPECT_NE(message.find("max_vertices is 20000"), std::string::npos) << message;
  // The smallest L the message names is the boundary: accepted just above, rejected just below.
  const auto at = message.find(">= about ");
  ASSERT_NE(at, std::string::npos) << message;
  const double smallest = std::stod(message.substr(at + 9));
  GrowthParams fine = tiny;
  fine.edge_length = smallest * 1.0001;
  EXPECT_NO_THROW(validate(fine));
  fine.edge_length = smallest * 0.9999;
  EXPECT_THROW(validate(fine), LimitExceeded);
}

TEST(EstimatedVertexCount, NoGrowthAndScaling) {
  // L >= sqrt(2) r: the base octahedron is final.
  EXPECT_EQ(estimated_vertex_count(1.0, 1.5), 6.0);
  EXPECT_EQ(estimated_vertex_count(0.1, 0.15), 6.0);
  // Only L / r matters, and halving L roughly quadruples the count.
  EXPECT_NEAR(estimated_vertex_count(0.2, 0.02), estimated_vertex_count(1.0, 0.1), 1e-9);
  EXPECT_NEAR(estimated_vertex_count(1.0, 0.05) / estimated_vertex_count(1.0, 0.1), 4.0, 0.05);
  // A cap of 6 allows only the base octahedron.
  EXPECT_NO_THROW(validate(GrowthParams{.radius = 1.0, .edge_length = 1.5, .max_vertices = 6}));
  EXPECT_THROW(validate(GrowthParams{.radius = 1.0, .edge_length = 1.2, .max_vertices = 6}),
               LimitExceeded);
}

TEST(Validate, GeneratorOptions) {
  const GeneratorOptions good{
      .alpha = 0.5, .radius_min = 0.05, .radius_max = 0.1, .edge_length = 0.05};
  EXPECT_NO_THROW(validate(good));
  auto swapped = good;
  swapped.radius_min = 0.2;
  try {
    validate(swapped);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "radius_max");
    EXPECT_NE(std::string(error.what()).find("radius_min"), std::string::npos);
  }
  auto bad_min = good;
  bad_min.radius_min = -1;
  EXPECT_THROW(validate(bad_min), InvalidInput);
  auto bad_max = good;
  bad_max.radius_max = std::nan("");
  EXPECT_THROW(validate(bad_max), InvalidInput);
  // The vertex cap is checked for the largest radius, the hardest case.
  auto big = good;
  big.radius_max = 100.0;
  EXPECT_THROW(validate(big), LimitExceeded);
  EXPECT_THROW(generate_particle(big, 0), LimitExceeded);
}

// The up-front estimate is an upper range: with the cap set to it, growth never runs out of
// vertices, across alpha and L/r (including just below sqrt(2) r, the worst ratio measured).
TEST(GrowAggregate, CapAtTheEstimateIsEnough) {
  int grown = 0;
  for (const double edge_over_radius : {0.08, 0.2, 0.35, 0.5, 0.7, 1.0, 1.4}) {
    for (const double alpha : {0.0, 0.5, 0.9, 0.95, 1.0}) {
      const double radius = 0.1;
      GrowthParams params{
          .alpha = alpha, .radius = radius, .edge_length = edge_over_radius * radius};
      params.max_vertices = static_cast<std::uint32_t>(
          std::ceil(estimated_vertex_count(radius, params.edge_length, params.form.growth)));
      ASSERT_NO_THROW(validate(params));
      const int count = edge_over_radius < 0.1 ? 5 : 60;
      for (int i = 0; i < count; ++i) {
        Rng rng(31, static_cast<std::uint64_t>(i));
        ConvexPolyhedron body;
        ASSERT_NO_THROW(body = grow_aggregate(params, rng))
            << "alpha " << alpha << " L/r " << edge_over_radius << " particle " << i;
        ASSERT_LE(body.vertex_count(), params.max_vertices);
        ++grown;
      }
    }
  }
  EXPECT_EQ(grown, 5 * 5 + 6 * 5 * 60);
}

// The hull rule's bits, pinned as the midpoint rule's above (every new input below draws: the
// random point, the control ellipsoid, the minimum edge ratio).
TEST(GenerateParticle, GoldenHashOfHullGrowth) {
#if !defined(__x86_64__)
  GTEST_SKIP() << "golden bits recorded on x86-64";
#else
  const std::uint64_t hash = family_hash(0.05, {.elongation = 0.7, .flatness = 0.8}, 300);
  EXPECT_EQ(hash, 0xdd8038b068615436ULL) << std::hex << "0x" << hash;
#endif
}

TEST(Validate, GrowthFormFieldsNamed) {
  auto field_of = [](const GrowthForm& form) -> std::string {
    try {
      validate(form, "particle.");
    } catch (const InvalidInput& error) {
      return error.field();
    }
    return "";
  };
  EXPECT_EQ(field_of({}), "");
  EXPECT_EQ(field_of({.elongation = 0.05}), "particle.elongation");
  EXPECT_EQ(field_of({.elongation = 1.2}), "particle.elongation");
  EXPECT_EQ(field_of({.flatness = std::nan("")}), "particle.flatness");
  EXPECT_EQ(field_of({.min_edge_ratio = 0.6}), "particle.min_edge_ratio");
  EXPECT_EQ(field_of({.min_edge_ratio = -0.1}), "particle.min_edge_ratio");
  EXPECT_EQ(find_growth("hull"), Growth::kHull);
  EXPECT_EQ(find_growth("midpoint"), Growth::kMidpoint);
  EXPECT_FALSE(find_growth("Hull").has_value());
  EXPECT_STREQ(growth_name(Growth::kMidpoint), "midpoint");
}

// The control ellipsoid's radius: the semi-axes along its turned axes, 1 / sqrt(sum (u_i/a_i)^2)
// between them.
TEST(ControlRadius, EllipsoidSemiAxesAndBetween) {
  GrowthParams params{.radius = 2.0, .form = {.elongation = 0.5, .flatness = 0.25}};
  EXPECT_DOUBLE_EQ(control_radius_along(params, Vec3(1, 0, 0)), 2.0);
  EXPECT_DOUBLE_EQ(control_radius_along(params, Vec3(0, -1, 0)), 1.0);
  EXPECT_DOUBLE_EQ(control_radius_along(params, Vec3(0, 0, 1)), 0.25);
  const Vec3 u = Vec3(1, 1, 0).normalized();
  EXPECT_NEAR(control_radius_along(params, u), 1.0 / std::sqrt(0.5 / 4.0 + 0.5 / 1.0), 1e-15);
  params.axes = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()));  // x -> y
  EXPECT_NEAR(control_radius_along(params, Vec3(0, 1, 0)), 2.0, 1e-14);
  EXPECT_NEAR(control_radius_along(params, Vec3(1, 0, 0)), 1.0, 1e-14);
  GrowthParams sphere{.radius = 0.3};
  EXPECT_EQ(control_radius_along(sphere, u), 0.3);
}

}  // namespace
}  // namespace aggpack
