// GJK proximity: exact answers for cubes, then agreement with an independent brute force
// (vertex strictly inside via the paper's locate_point + edge strictly through a triangle; distance
// as the minimum over vertex-triangle and edge-edge distances) on random generated particles,
// including constructed touching pairs and pairs separated / overlapping by a small epsilon.

#include "aggpack/geom/overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"
#include "support/ellipsoid.h"
#include "support/random_rotation.h"

namespace aggpack {
namespace {

// Under the sanitizers the brute force is ~10x slower; the random sweeps shrink there.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kSweepDivisor = 10;
#else
constexpr int kSweepDivisor = 1;
#endif

const ConvexPolyhedron& unit_cube() {
  static const ConvexPolyhedron cube = make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  return cube;
}

Quat axis_angle(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Vec3 random_unit(Rng& rng) {
  Vec3 v(rng.normal(), rng.normal(), rng.normal());
  return v.normalized();
}

struct CubePair {
  Pose a;
  Pose b;
};

// Face-face: B shifted along +x by 1 + s, off-centre in y and z (partial face overlap).
CubePair face_face(double s) { return {{}, {Vec3(1.0 + s, 0.3, -0.2), Quat::Identity()}}; }
// Edge-edge, crossed at right angles: A's edge along y at x = sqrt2/2, B's edge along z at
// x = sqrt2/2 + s; closest points (sqrt2/2, 0, 0) and (sqrt2/2 + s, 0, 0).
CubePair edge_edge(double s) {
  return {{Vec3::Zero(), axis_angle(Vec3::UnitY(), std::numbers::pi / 4)},
          {Vec3(std::numbers::sqrt2 + s, 0, 0), axis_angle(Vec3::UnitZ(), std::numbers::pi / 4)}};
}
// Vertex-face: B's body diagonal points along -x, so its vertex sits at (0.5 + s, 0, 0).
CubePair vertex_face(double s) {
  return {{},
          {Vec3(0.5 + std::sqrt(3.0) / 2 + s, 0, 0),
           Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3(-1, 0, 0))}};
}

// For face-face contact the closest points are not unique: then only their offset and the
// contact plane are checked.
enum class Closest { kUnique, kOffsetOnly };

void expect_distance(const CubePair& pair, double expected, const Vec3& expected_a,
                     const Vec3& expected_b, Closest closest = Closest::kUnique) {
  const SupportShape shape(unit_cube());
  for (int api = 0; api < 2; ++api) {
    const DistanceResult r = api == 0 ? gjk_distance(unit_cube(), pair.a, unit_cube(), pair.b)
                                      : gjk_distance(shape, pair.a, shape, pair.b);
    SCOPED_TRACE(api == 0 ? "ConvexPolyhedron" : "SupportShape");
    ASSERT_FALSE(r.is_intersecting) << "expected distance " << expected;
    EXPECT_NEAR(r.distance, expected, 1e-14 + 1e-12 * expected);
    if (closest == Closest::kUnique) {
      EXPECT_NEAR((r.point_a - expected_a).norm(), 0.0, 1e-12);
      EXPECT_NEAR((r.point_b - expected_b).norm(), 0.0, 1e-12);
    } else {
      EXPECT_NEAR(r.point_a.x(), expected_a.x(), 1e-14);
      EXPECT_NEAR(((r.point_b - r.point_a) - (expected_b - expected_a)).norm(), 0.0, 1e-14);
      EXPECT_LE(r.point_a.cwiseAbs().maxCoeff(), 0.5 + 1e-14);  // on A's face
    }
    EXPECT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-14);
  }
}

void expect_intersecting(const CubePair& pair) {
  const SupportShape shape(unit_cube());
  const double radius = bounding_radius(unit_cube());
  EXPECT_TRUE(gjk_distance(unit_cube(), pair.a, unit_cube(), pair.b).is_intersecting);
  EXPECT_TRUE(gjk_distance(shape, pair.a, shape, pair.b).is_intersecting);
  EXPECT_EQ(gjk_distance(shape, pair.a, shape, pair.b).distance, 0.0);
  EXPECT_FALSE(is_separated(unit_cube(), pair.a, radius, unit_cube(), pair.b, radius, 0.0));
  EXPECT_FALSE(is_separated(shape, pair.a, shape, pair.b, 0.0));
}

TEST(Overlap, CubesFaceFaceKnownDistances) {
  for (double s : {1.0, 0.1, 1e-3, 1e-6, 1e-9}) {
    expect_distance(face_face(s), s, Vec3(0.5, 0.3, -0.2), Vec3(0.5 + s, 0.3, -0.2),
                    Closest::kOffsetOnly);
  }
}

TEST(Overlap, CubesEdgeEdgeKnownDistances) {
  const double x = std::numbers::sqrt2 / 2;
  for (double s : {1.0, 0.1, 1e-3, 1e-6, 1e-9}) {
    expect_distance(edge_edge(s), s, Vec3(x, 0, 0), Vec3(x + s, 0, 0));
  }
}

TEST(Overlap, CubesVertexFaceKnownDistances) {
  for (double s : {1.0, 0.1, 1e-3, 1e-6, 1e-9}) {
    expect_distance(vertex_face(s), s, Vec3(0.5, 0, 0), Vec3(0.5 + s, 0, 0));
  }
}

TEST(Overlap, CubesTouchingAndOverlappingIntersect) {
  for (double s : {0.0, -1e-9, -0.01, -0.5}) {
    SCOPED_TRACE(s);
    expect_intersecting(face_face(s));
    expect_intersecting(edge_edge(s));
    expect_intersecting(vertex_face(s));
  }
  expect_intersecting({{}, {}});                                 // identical placement
  expect_intersecting({{}, {Vec3(1, 1, 1), Quat::Identity()}});  // corner to corner
  expect_intersecting({{}, {Vec3(1, 1, 0), Quat::Identity()}});  // edge to edge, parallel
}

TEST(Overlap, NearlyCoplanarFacesKnownDistance) {
  // B turned by theta about z: its nearest feature is a vertical edge at
  // x = 1 + s - (cos theta + sin theta) / 2, inside A's face x = 0.5.
  for (double theta : {1e-9, 1e-6, 1e-3}) {
    const double gap = 0.5 * (std::cos(theta) + std::sin(theta)) - 0.5;  // ~ theta / 2
    const SupportShape shape(unit_cube());
    for (double s : {gap + 1e-6, gap + 1e-9, gap, gap - 1e-9}) {
      const Pose b{Vec3(1.0 + s, 0.0, 0.1), axis_angle(Vec3::UnitZ(), theta)};
      const DistanceResult r = gjk_distance(shape, Pose{}, shape, b);
      const double expected = s - gap;
      SCOPED_TRACE(testing::Message() << "theta " << theta << " distance " << expected);
      if (expected > 1e-12) {
        ASSERT_FALSE(r.is_intersecting);
        EXPECT_NEAR(r.distance, expected, 1e-14);
      } else {
        EXPECT_TRUE(r.is_intersecting);
      }
      EXPECT_TRUE(std::isfinite(r.distance));
    }
  }
}

TEST(Overlap, RigidMotionOfBothBodiesKeepsDistance) {
  Rng rng(11, 0);
  for (int trial = 0; trial < 100; ++trial) {
    const CubePair base = trial % 3 == 0   ? face_face(0.25)
                          : trial % 3 == 1 ? edge_edge(0.25)
                                           : vertex_face(0.25);
    const Quat motion = test::random_rotation(rng);
    const Vec3 shift = Vec3(rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3), rng.uniform(-1e3, 1e3));
    const Pose a{motion * base.a.position + shift, motion * base.a.rotation};
    const Pose b{motion * base.b.position + shift, motion * base.b.rotation};
    const DistanceResult r = gjk_distance(unit_cube(), a, unit_cube(), b);
    ASSERT_FALSE(r.is_intersecting);
    EXPECT_NEAR(r.distance, 0.25, 1e-11);  // positions ~1e3: rounding ~1e-13
  }
}

TEST(Overlap, IsSeparatedHonoursGap) {
  const SupportShape shape(unit_cube());
  const double radius = bounding_radius(unit_cube());
  for (const CubePair& pair : {face_face(0.1), edge_edge(0.1), vertex_face(0.1)}) {
    EXPECT_TRUE(is_separated(shape, pair.a, shape, pair.b, 0.0));
    EXPECT_TRUE(is_separated(shape, pair.a, shape, pair.b, 0.099));
    EXPECT_FALSE(is_separated(shape, pair.a, shape, pair.b, 0.101));
    EXPECT_TRUE(is_separated(unit_cube(), pair.a, radius, unit_cube(), pair.b, radius, 0.099));
    EXPECT_FALSE(is_separated(unit_cube(), pair.a, radius, unit_cube(), pair.b, radius, 0.101));
  }
  // Far apart: answered by the bounding spheres.
  EXPECT_TRUE(is_separated(shape, Pose{}, shape, Pose{Vec3(10, 0, 0), Quat::Identity()}, 1.0));
  EXPECT_FALSE(is_separated(shape, Pose{}, shape, Pose{Vec3(10, 0, 0), Quat::Identity()}, 9.5));
}

TEST(Overlap, ScaledBodyWithoutCopyMatchesTheScaledCopy) {
  // Known answers: a unit cube scaled by 2 spans [-1, 1]; one at x = 1.5 + s is s away.
  const double radius = bounding_radius(unit_cube());
  const Pose origin{};
  for (const double s : {0.05, 0.3}) {
    const Pose b{Vec3(1.5 + s, 0.1, 0.0), Quat::Identity()};
    EXPECT_TRUE(
        is_separated(unit_cube(), b, radius, unit_cube(), 2.0, origin, 2.0 * radius, s * 0.99));
    EXPECT_FALSE(
        is_separated(unit_cube(), b, radius, unit_cube(), 2.0, origin, 2.0 * radius, s * 1.01));
  }
  // Generated particles at random scales, poses and gaps: the same answer as an explicit copy.
  Rng rng(41, 0);
  int separated = 0;
  for (int i = 0; i < 2000; ++i) {
    const GeneratedParticle a = generate_particle(
        {.alpha = 0.5, .radius_min = 0.5, .radius_max = 1.0, .edge_length = 0.5, .seed = 3},
        static_cast<std::uint64_t>(i));
    const GeneratedParticle b = generate_particle(
        {.alpha = 0.3, .radius_min = 0.5, .radius_max = 1.0, .edge_length = 0.5, .seed = 4},
        static_cast<std::uint64_t>(i));
    const double scale = 0.3 + 2.0 * rng.uniform();
    const ConvexPolyhedron copy = b.body.scaled(scale);
    const Pose pose_a{Vec3::Zero(), test::random_rotation(rng)};
    const Pose pose_b{random_unit(rng) * (0.5 + 2.5 * rng.uniform()), test::random_rotation(rng)};
    const double gap = 0.1 * rng.uniform();
    const double radius_a = bounding_radius(a.body);
    const double radius_b = bounding_radius(copy);
    const bool expected = is_separated(a.body, pose_a, radius_a, copy, pose_b, radius_b, gap);
    EXPECT_EQ(is_separated(a.body, pose_a, radius_a, b.body, scale, pose_b, radius_b, gap),
              expected)
        << "pair " << i;
    separated += expected ? 1 : 0;
  }
  EXPECT_GT(separated, 200);  // both answers occur
  EXPECT_LT(separated, 1800);
  EXPECT_THROW(
      (void)is_separated(unit_cube(), origin, radius, unit_cube(), 0.0, origin, radius, 0.0),
      InvalidInput);
}

TEST(Overlap, BadInputThrowsInvalidInput) {
  const SupportShape shape(unit_cube());
  const double radius = bounding_radius(unit_cube());
  const Pose far{Vec3(5, 0, 0), Quat::Identity()};
  EXPECT_THROW((void)is_separated(shape, Pose{}, shape, far, -1.0), InvalidInput);
  EXPECT_THROW((void)is_separated(shape, Pose{}, shape, far, std::nan("")), InvalidInput);
  EXPECT_THROW((void)is_separated(unit_cube(), Pose{}, radius, unit_cube(), far, radius, -1e-3),
               InvalidInput);
  const Pose scaled{Vec3::Zero(), Quat(2, 0, 0, 0)};
  EXPECT_THROW((void)gjk_distance(unit_cube(), scaled, unit_cube(), far), InvalidInput);
  const Pose not_finite{Vec3(std::nan(""), 0, 0), Quat::Identity()};
  EXPECT_THROW((void)gjk_distance(shape, Pose{}, shape, not_finite), InvalidInput);
  EXPECT_THROW((void)gjk_distance(ConvexPolyhedron{}, Pose{}, unit_cube(), far), InvalidInput);
  EXPECT_THROW(SupportShape{ConvexPolyhedron{}}, InvalidInput);
}

// --- independent brute force -----------------------------------------------------------------

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

// Squared distance between segments p1q1 and p2q2 (Ericson 5.1.9).
double segment_distance_squared(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2);
  const double denominator = a * e - b * b;
  double s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p1 + d1 * s) - (p2 + d2 * t)).squaredNorm();
}

struct Particle {
  ConvexPolyhedron body;
  std::vector<Edge> edges;
  SupportShape shape;
  double radius = 0;
};

const std::vector<Particle>& particle_pool() {
  static const std::vector<Particle> pool = [] {
    std::vector<Particle> particles;
    // L / r from 0.5 to 1 (radius 0.5..1 m, L = 0.5 m), alpha across the range.
    for (double alpha : {0.2, 0.5, 0.9}) {
      const GeneratorOptions options{
          .alpha = alpha, .radius_min = 0.5, .radius_max = 1.0, .edge_length = 0.5, .seed = 42};
      for (std::uint64_t i = 0; i < 24; ++i) {
        Particle p;
        p.body = generate_particle(options, i).body;
        p.edges = p.body.edges();
        p.shape = SupportShape(p.body);
        p.radius = bounding_radius(p.body);
        particles.push_back(std::move(p));
      }
    }
    return particles;
  }();
  return pool;
}

// Brute-force overlap of two bodies given in world coordinates: a vertex strictly inside the
// other (locate_point), or an edge crossing a triangle of the other strictly (both endpoints
// strictly on opposite sides of its plane, the line strictly inside its three edges).
// `volume_tolerance` (m^3) is what "strictly" means.
bool brute_overlap_one_way(const ConvexPolyhedron& a, const std::vector<Edge>& a_edges,
                           const ConvexPolyhedron& b, double volume_tolerance) {
  for (const auto& v : a.vertices()) {
    if (locate_point(b, v, volume_tolerance) == PointLocation::kInside) return true;
  }
  const auto& av = a.vertices();
  const auto& bv = b.vertices();
  const std::size_t faces = b.triangle_count();
  // side[v * faces + f] = 6 * signed volume of (triangle f, vertex v), from each triangle's
  // plane (normal = (b - a) x (c - a), so the value equals orient(a, b, c, v)).
  std::vector<Vec3> normals(faces);
  std::vector<double> offsets(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    const auto& t = b.triangles()[f];
    normals[f] = (bv[t[1]] - bv[t[0]]).cross(bv[t[2]] - bv[t[0]]);
    offsets[f] = normals[f].dot(bv[t[0]]);
  }
  std::vector<double> side(av.size() * faces);
  for (std::size_t v = 0; v < av.size(); ++v) {
    for (std::size_t f = 0; f < faces; ++f)
      side[v * faces + f] = normals[f].dot(av[v]) - offsets[f];
  }
  const double tolerance = 6.0 * volume_tolerance;
  for (const auto& edge : a_edges) {
    const Vec3& p = av[edge.vertices[0]];
    const Vec3& q = av[edge.vertices[1]];
    for (std::size_t f = 0; f < faces; ++f) {
      const double sp = side[edge.vertices[0] * faces + f];
      const double sq = side[edge.vertices[1] * faces + f];
      if (sp > tolerance && sq > tolerance) break;  // edge strictly outside a face plane of B
      if (!((sp > tolerance && sq < -tolerance) || (sp < -tolerance && sq > tolerance))) continue;
      const auto& t = b.triangles()[f];
      const double o1 = orient(p, q, bv[t[0]], bv[t[1]]);
      const double o2 = orient(p, q, bv[t[1]], bv[t[2]]);
      const double o3 = orient(p, q, bv[t[2]], bv[t[0]]);
      if ((o1 > tolerance && o2 > tolerance && o3 > tolerance) ||
          (o1 < -tolerance && o2 < -tolerance && o3 < -tolerance)) {
        return true;
      }
    }
  }
  return false;
}

bool brute_overlap(const ConvexPolyhedron& a, const std::vector<Edge>& a_edges,
                   const ConvexPolyhedron& b, const std::vector<Edge>& b_edges,
                   double volume_tolerance) {
  return brute_overlap_one_way(a, a_edges, b, volume_tolerance) ||
         brute_overlap_one_way(b, b_edges, a, volume_tolerance);
}

// Distance between two disjoint convex bodies (world coordinates): the minimum over vertex-
// triangle and edge-edge pairs.
double brute_distance(const ConvexPolyhedron& a, const std::vector<Edge>& a_edges,
                      const ConvexPolyhedron& b, const std::vector<Edge>& b_edges) {
  double best = std::numeric_limits<double>::infinity();
  const auto vertex_triangle = [&best](const ConvexPolyhedron& points,
                                       const ConvexPolyhedron& body) {
    const auto& bv = body.vertices();
    for (const auto& p : points.vertices()) {
      for (const auto& t : body.triangles()) {
        best = std::min(best,
                        (p - closest_on_triangle(p, bv[t[0]], bv[t[1]], bv[t[2]])).squaredNorm());
      }
    }
  };
  vertex_triangle(a, b);
  vertex_triangle(b, a);
  for (const auto& ea : a_edges) {
    for (const auto& eb : b_edges) {
      best = std::min(best, segment_distance_squared(
                                a.vertices()[ea.vertices[0]], a.vertices()[ea.vertices[1]],
                                b.vertices()[eb.vertices[0]], b.vertices()[eb.vertices[1]]));
    }
  }
  return std::sqrt(best);
}

// A point on a random feature (vertex, edge or face) of `body` and a unit direction in that
// feature's normal cone, so the point maximises direction . x over the body.
struct Feature {
  Vec3 point;
  Vec3 direction;
};

Feature random_feature(const Particle& particle, Rng& rng) {
  const ConvexPolyhedron& body = particle.body;
  const int kind = static_cast<int>(rng.uniform() * 3.0);
  if (kind == 0) {  // face
    const auto f = static_cast<std::size_t>(rng.uniform() * body.triangle_count());
    const auto& t = body.triangles()[f];
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) {
      u = 1 - u;
      v = 1 - v;
    }
    const auto& vs = body.vertices();
    return {vs[t[0]] + u * (vs[t[1]] - vs[t[0]]) + v * (vs[t[2]] - vs[t[0]]), body.face_normal(f)};
  }
  if (kind == 1) {  // edge
    const auto& e = particle.edges[static_cast<std::size_t>(rng.uniform() * particle.edges.size())];
    const double u = rng.uniform();
    const Vec3 point =
        (1 - u) * body.vertices()[e.vertices[0]] + u * body.vertices()[e.vertices[1]];
    return {point, (body.face_normal(e.faces[0]) + body.face_normal(e.faces[1])).normalized()};
  }
  const auto v = static_cast<std::uint32_t>(rng.uniform() * body.vertex_count());
  Vec3 direction = Vec3::Zero();
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const auto& t = body.triangles()[f];
    if (t[0] == v || t[1] == v || t[2] == v) direction += body.face_normal(f);
  }
  return {body.vertices()[v], direction.normalized()};
}

// Places B so that it touches A at one point with the plane through it normal to `normal`
// separating them (distance exactly 0); `normal` points from A to B.
struct Contact {
  Pose pose_a;
  Pose pose_b;
  Vec3 normal;
};

Contact touching_pair(const Particle& a, const Particle& b, Rng& rng) {
  const Feature fa = random_feature(a, rng);
  const Feature fb = random_feature(b, rng);
  Contact contact;
  contact.pose_a = {Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)),
                    test::random_rotation(rng)};
  contact.normal = contact.pose_a.rotation * fa.direction;
  const Vec3 touch = contact.pose_a.apply(fa.point);
  const Quat spin = axis_angle(contact.normal, rng.uniform(0, 2 * std::numbers::pi));
  contact.pose_b.rotation =
      (spin * Quat::FromTwoVectors(fb.direction, -contact.normal)).normalized();
  contact.pose_b.position = touch - contact.pose_b.rotation * fb.point;
  return contact;
}

struct SweepCounts {
  int random_overlap = 0, random_separate = 0, touching = 0, separated = 0, pushed_in = 0,
      pushed_in_overlap = 0, ambiguous = 0;
};

TEST(Overlap, AgreesWithBruteForceOnRandomPairs) {
  const auto& pool = particle_pool();
  const int pairs = 100000 / kSweepDivisor;
  Rng rng(2024, 7);
  SweepCounts counts;
  for (int trial = 0; trial < pairs; ++trial) {
    const Particle& a = pool[static_cast<std::size_t>(rng.uniform() * pool.size())];
    const Particle& b = pool[static_cast<std::size_t>(rng.uniform() * pool.size())];
    const double scale = a.radius + b.radius;
    const double volume_tolerance = 1e-14 * scale * scale * scale;
    const int category = trial % 5;  // 0, 1: random; 2: touching; 3: +eps; 4: -eps
    Pose pose_a, pose_b;
    Vec3 normal = Vec3::Zero();
    double eps = 0;
    if (category <= 1) {
      pose_a = {Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)),
                test::random_rotation(rng)};
      pose_b = {pose_a.position + rng.uniform(0, 1.6 * scale) * random_unit(rng),
                test::random_rotation(rng)};
    } else {
      const Contact contact = touching_pair(a, b, rng);
      pose_a = contact.pose_a;
      pose_b = contact.pose_b;
      normal = contact.normal;
      eps = std::pow(10.0, -3.0 - 6.0 * rng.uniform()) * scale;  // 1e-9 .. 1e-3 of the size
      if (category == 3) pose_b.position += eps * normal;
      if (category == 4) pose_b.position -= eps * normal;
    }
    const DistanceResult by_polyhedron = gjk_distance(a.body, pose_a, b.body, pose_b);
    const DistanceResult by_shape = gjk_distance(a.shape, pose_a, b.shape, pose_b);
    const bool separated_0 = is_separated(a.shape, pose_a, b.shape, pose_b, 0.0);
    const bool separated_0_polyhedron =
        is_separated(a.body, pose_a, a.radius, b.body, pose_b, b.radius, 0.0);
    const ConvexPolyhedron world_a = a.body.transformed(pose_a);
    const ConvexPolyhedron world_b = b.body.transformed(pose_b);
    const bool brute = brute_overlap(world_a, a.edges, world_b, b.edges, volume_tolerance);
    SCOPED_TRACE(testing::Message()
                 << "trial " << trial << " category " << category << " eps " << eps << " brute "
                 << brute << " gjk distance " << by_shape.distance);
    ASSERT_TRUE(std::isfinite(by_polyhedron.distance) && std::isfinite(by_shape.distance));
    // Both APIs and both query kinds agree with each other.
    ASSERT_EQ(by_polyhedron.is_intersecting, by_shape.is_intersecting);
    ASSERT_NEAR(by_polyhedron.distance, by_shape.distance, 1e-12 * scale);
    ASSERT_EQ(separated_0, !by_shape.is_intersecting);
    ASSERT_EQ(separated_0_polyhedron, !by_shape.is_intersecting);
    // Warm-started queries answer the same whatever the hint (none, random, the contact normal
    // and its opposite); an axis the query hands back separates the two bodies' vertices.
    Rng hint_rng(77, static_cast<std::uint64_t>(trial));
    for (const Vec3& hint : {Vec3(Vec3::Zero()), random_unit(hint_rng), normal, Vec3(-normal)}) {
      Vec3 axis = hint;
      ASSERT_EQ(is_separated(a.shape, pose_a, b.shape, pose_b, 0.0, axis), separated_0);
      if (separated_0 && axis != hint) {
        double top_a = -1e300;
        double bottom_b = 1e300;
        for (const Vec3& v : world_a.vertices()) top_a = std::max(top_a, axis.dot(v));
        for (const Vec3& v : world_b.vertices()) bottom_b = std::min(bottom_b, axis.dot(v));
        ASSERT_LT(top_a, bottom_b);
      }
    }
    switch (category) {
      case 2:  // touching: distance 0, and the brute force sees no strict overlap
        ASSERT_TRUE(by_shape.is_intersecting);
        ASSERT_FALSE(brute);
        ++counts.touching;
        break;
      case 3:  // separated by exactly eps
        ASSERT_FALSE(by_shape.is_intersecting);
        ASSERT_NEAR(by_shape.distance, eps, 1e-12 * scale + 1e-9 * eps);
        ASSERT_FALSE(brute);
        ASSERT_TRUE(is_separated(a.shape, pose_a, b.shape, pose_b, 0.5 * eps));
        ASSERT_FALSE(is_separated(a.shape, pose_a, b.shape, pose_b, 1.5 * eps));
        ++counts.separated;
        break;
      default:  // random or pushed in by eps: classified by the brute force
        if (brute) {
          ASSERT_TRUE(by_shape.is_intersecting);  // never "separated" when they overlap
        } else if (by_shape.is_intersecting) {
          // No strict crossing found but GJK says contact: must be touching within tolerance.
          ASSERT_LE(brute_distance(world_a, a.edges, world_b, b.edges), 1e-11 * scale);
          ++counts.ambiguous;
        }
        if (category == 4) {
          ++counts.pushed_in;
          counts.pushed_in_overlap += brute ? 1 : 0;
        } else {
          ++(brute ? counts.random_overlap : counts.random_separate);
        }
        break;
    }
  }
  // The sweep must exercise both outcomes in every class.
  EXPECT_GT(counts.random_overlap, pairs / 10);
  EXPECT_GT(counts.random_separate, pairs / 10);
  EXPECT_GT(counts.pushed_in_overlap, counts.pushed_in / 2);
  RecordProperty("random_overlap", counts.random_overlap);
  RecordProperty("ambiguous", counts.ambiguous);
  std::printf(
      "random: %d overlapping, %d separate; touching %d; +eps %d; -eps %d (%d overlap); "
      "contact without strict crossing %d\n",
      counts.random_overlap, counts.random_separate, counts.touching, counts.separated,
      counts.pushed_in, counts.pushed_in_overlap, counts.ambiguous);
}

TEST(Overlap, DistanceMatchesBruteForceDistance) {
  const auto& pool = particle_pool();
  const int pairs = 2000 / kSweepDivisor;
  Rng rng(77, 3);
  for (int trial = 0; trial < pairs; ++trial) {
    const Particle& a = pool[static_cast<std::size_t>(rng.uniform() * pool.size())];
    const Particle& b = pool[static_cast<std::size_t>(rng.uniform() * pool.size())];
    const double scale = a.radius + b.radius;
    Contact contact = touching_pair(a, b, rng);
    // Separated along the contact normal by 1e-6..0.3 of the size, half also slid sideways
    // (then the distance is only bounded below by the shift and found by the brute force).
    const double shift = std::pow(10.0, -6.0 + 5.5 * rng.uniform()) * scale;
    contact.pose_b.position += shift * contact.normal;
    if (trial % 2 == 1) {
      const Vec3 side = contact.normal.cross(random_unit(rng)).normalized();
      contact.pose_b.position += rng.uniform(0, 0.5) * scale * side;
    }
    const ConvexPolyhedron world_a = a.body.transformed(contact.pose_a);
    const ConvexPolyhedron world_b = b.body.transformed(contact.pose_b);
    const double expected = brute_distance(world_a, a.edges, world_b, b.edges);
    ASSERT_GE(expected, shift * (1 - 1e-9));
    for (int api = 0; api < 2; ++api) {
      const DistanceResult r = api == 0
                                   ? gjk_distance(a.body, contact.pose_a, b.body, contact.pose_b)
                                   : gjk_distance(a.shape, contact.pose_a, b.shape, contact.pose_b);
      SCOPED_TRACE(testing::Message() << "trial " << trial << " api " << api);
      ASSERT_FALSE(r.is_intersecting);
      ASSERT_NEAR(r.distance, expected, 1e-9 * expected);
      ASSERT_NEAR((r.point_a - r.point_b).norm(), r.distance, 1e-9 * expected);
      const double volume_tolerance = 1e-13 * scale * scale * scale;
      ASSERT_NE(locate_point(world_a, r.point_a, volume_tolerance), PointLocation::kOutside);
      ASSERT_NE(locate_point(world_b, r.point_b, volume_tolerance), PointLocation::kOutside);
    }
  }
}

TEST(Overlap, EllipsoidsHillClimbAndAgreeWithScan) {
  Rng rng(8, 8);
  const ConvexPolyhedron small = test::make_ellipsoid(4, 6, Vec3(1.0, 0.7, 0.5));
  const ConvexPolyhedron large = test::make_ellipsoid(24, 48, Vec3(1.0, 0.6, 0.3));
  const SupportShape small_shape(small);
  const SupportShape large_shape(large);
  ASSERT_TRUE(check_convex(large, 1e-12).is_ok);
  EXPECT_EQ(large_shape.vertex_count(), large.vertex_count());
  EXPECT_TRUE(large_shape.uses_hill_climbing());
  EXPECT_FALSE(small_shape.uses_hill_climbing());
  const double radius_small = bounding_radius(small);
  const double radius_large = bounding_radius(large);
  for (int trial = 0; trial < 3000; ++trial) {
    const Pose pose_a{Vec3::Zero(), test::random_rotation(rng)};
    const Pose pose_b{rng.uniform(0.0, 2.2) * random_unit(rng), test::random_rotation(rng)};
    const bool is_large_a = trial % 2 == 0;
    const ConvexPolyhedron& a = is_large_a ? large : small;
    const SupportShape& shape_a = is_large_a ? large_shape : small_shape;
    const DistanceResult exact = gjk_distance(a, pose_a, large, pose_b);
    const DistanceResult fast = gjk_distance(shape_a, pose_a, large_shape, pose_b);
    ASSERT_EQ(exact.is_intersecting, fast.is_intersecting) << trial;
    ASSERT_NEAR(exact.distance, fast.distance, 1e-12) << trial;
    ASSERT_EQ(is_separated(a, pose_a, is_large_a ? radius_large : radius_small, large, pose_b,
                           radius_large, 0.05),
              is_separated(shape_a, pose_a, large_shape, pose_b, 0.05))
        << trial;
  }
}

TEST(Overlap, SupportShapeKeepsEverySupportValue) {
  // Dropping non-hull vertices and hill-climbing must not change any support value: compare with
  // a scan over every original vertex, for generated particles (most of whose vertices lie on
  // hull faces, so their climbing graph runs through dropped vertices) and polyhedral
  // ellipsoids, with each search method.
  Rng rng(5, 5);
  std::vector<ConvexPolyhedron> bodies;
  for (double edge : {1.0, 0.5, 0.25, 0.15}) {
    for (std::uint64_t i = 0; i < 6; ++i) {
      bodies.push_back(generate_particle({.alpha = 0.1 + 0.15 * static_cast<double>(i),
                                          .radius_min = 1,
                                          .radius_max = 1,
                                          .edge_length = edge,
                                          .seed = 9},
                                         i)
                           .body);
    }
  }
  bodies.push_back(test::make_ellipsoid(12, 24, Vec3(1.0, 0.8, 0.6)));
  bodies.push_back(test::make_ellipsoid(30, 60, Vec3(1.0, 1.0, 0.2)));
  for (const SupportSearch search :
       {SupportSearch::kAuto, SupportSearch::kScan, SupportSearch::kHillClimb}) {
    for (const ConvexPolyhedron& body : bodies) {
      const SupportShape shape(body, search);
      ASSERT_EQ(shape.uses_hill_climbing(),
                search == SupportSearch::kHillClimb ||
                    (search == SupportSearch::kAuto &&
                     shape.vertex_count() > SupportShape::kHillClimbMinVertices));
      ASSERT_LE(shape.vertex_count(), body.vertex_count());
      ASSERT_GE(shape.vertex_count(), 4u);
      std::uint32_t hint = SupportShape::kNoHint;
      for (int k = 0; k < 1000; ++k) {
        const Vec3 direction = random_unit(rng);
        double best = -1e300;
        for (const auto& v : body.vertices()) best = std::max(best, direction.dot(v));
        // Alternate cold starts and warm starts from the previous answer.
        hint = shape.support(direction, k % 2 == 0 ? SupportShape::kNoHint : hint);
        ASSERT_NEAR(direction.dot(shape.vertex(hint)), best, 1e-13);
      }
    }
  }
  // A cube keeps all 8 corners; its inner radius is the half side.
  const SupportShape cube(unit_cube());
  EXPECT_EQ(cube.vertex_count(), 8u);
  EXPECT_NEAR(cube.inner_radius(), 0.5, 1e-15);
  EXPECT_NEAR(cube.bounding_radius(), std::sqrt(0.75), 1e-15);
}

}  // namespace
}  // namespace aggpack
