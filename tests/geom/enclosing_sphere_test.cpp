// Minimal enclosing sphere against exact answers and a brute-force search.

#include "aggpack/geom/enclosing_sphere.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "aggpack/core/rng.h"

namespace aggpack {
namespace {

TEST(EnclosingSphere, RegularSolidsAndDegenerateSets) {
  const std::vector<Vec3> octahedron = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                        {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  Sphere s = minimal_enclosing_sphere(octahedron);
  EXPECT_NEAR(s.radius, 1.0, 1e-12);
  EXPECT_NEAR(s.centre.norm(), 0.0, 1e-12);

  std::vector<Vec3> cube;
  for (int k = 0; k < 8; ++k)
    cube.emplace_back(k & 1 ? 3.0 : 1.0, k & 2 ? 2.0 : 0.0, k & 4 ? 4 : 2);
  s = minimal_enclosing_sphere(cube);
  EXPECT_NEAR(s.radius, std::sqrt(3.0), 1e-12);
  EXPECT_NEAR((s.centre - Vec3(2, 1, 3)).norm(), 0.0, 1e-12);

  // Regular tetrahedron of edge 2 sqrt 2: circumradius sqrt 3 at the centroid.
  const std::vector<Vec3> tetrahedron = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  s = minimal_enclosing_sphere(tetrahedron);
  EXPECT_NEAR(s.radius, std::sqrt(3.0), 1e-12);

  // Collinear points: the diameter sphere of the two ends.
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}};
  s = minimal_enclosing_sphere(line);
  EXPECT_NEAR(s.radius, 1.5 * std::sqrt(3.0), 1e-12);

  // An obtuse triangle: the sphere over its longest side, not its circumcircle.
  const std::vector<Vec3> obtuse = {{-1, 0, 0}, {1, 0, 0}, {0, 0.1, 0}};
  s = minimal_enclosing_sphere(obtuse);
  EXPECT_NEAR(s.radius, 1.0, 1e-12);

  EXPECT_EQ(minimal_enclosing_sphere({}).radius, 0.0);
  const std::vector<Vec3> one = {{4, 5, 6}};
  EXPECT_EQ(minimal_enclosing_sphere(one).radius, 0.0);
}

// Smallest sphere through 2, 3 or 4 of the points that contains them all, by exhaustion.
double brute_force_radius(const std::vector<Vec3>& p) {
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Vec3& centre, double radius) {
    for (const Vec3& q : p) {
      if ((q - centre).norm() > radius * (1 + 1e-9)) return;
    }
    best = std::min(best, radius);
  };
  const std::size_t n = p.size();
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      consider(0.5 * (p[a] + p[b]), 0.5 * (p[a] - p[b]).norm());
      for (std::size_t c = b + 1; c < n; ++c) {
        const Vec3 u = p[b] - p[a];
        const Vec3 v = p[c] - p[a];
        const Vec3 w = u.cross(v);
        const Vec3 o =
            (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u)) / (2.0 * w.squaredNorm());
        consider(p[a] + o, o.norm());
        for (std::size_t d = c + 1; d < n; ++d) {
          Mat3 m;
          m.row(0) = u;
          m.row(1) = v;
          m.row(2) = p[d] - p[a];
          const Vec3 rhs(0.5 * u.squaredNorm(), 0.5 * v.squaredNorm(),
                         0.5 * m.row(2).squaredNorm());
          const Vec3 x = m.partialPivLu().solve(rhs);
          consider(p[a] + x, x.norm());
        }
      }
    }
  }
  return best;
}

TEST(EnclosingSphere, MatchesExhaustiveSearchOnRandomSets) {
  for (std::uint64_t trial = 0; trial < 200; ++trial) {
    Rng rng(7, trial);
    std::vector<Vec3> p;
    const int n = 3 + static_cast<int>(trial % 10);
    for (int i = 0; i < n; ++i) {
      // Anisotropic clouds: different solutions touch 2, 3 or 4 points.
      p.emplace_back(rng.uniform(-1, 1), rng.uniform(-0.5, 0.5),
                     rng.uniform(-0.2, 0.2) * (trial % 3));
    }
    const Sphere s = minimal_enclosing_sphere(p);
    for (const Vec3& q : p) EXPECT_LE((q - s.centre).norm(), s.radius * (1 + 1e-12));
    EXPECT_NEAR(s.radius, brute_force_radius(p), 1e-9) << "trial " << trial;
  }
}

TEST(EnclosingSphere, CosphericalPointsGiveTheirSphere) {
  // Many points on one sphere (more than a pivoting round carries over, so the fallback runs for
  // the larger sets): the sphere itself, since the points spread over all of it.
  const Vec3 centre(1.0, -2.0, 3.0);
  for (const int n : {4, 6, 9, 12, 40, 400}) {
    Rng rng(11, static_cast<std::uint64_t>(n));
    std::vector<Vec3> p;
    // The six axis points first: every set spans the whole sphere.
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                             Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
      p.push_back(centre + 2.0 * axis);
    }
    p.resize(std::min<std::size_t>(p.size(), static_cast<std::size_t>(n)));
    while (p.size() < static_cast<std::size_t>(n)) {
      const Vec3 q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      if (q.norm() > 0.1) p.push_back(centre + 2.0 * q.normalized());
    }
    const Sphere s = minimal_enclosing_sphere(p);
    for (const Vec3& q : p) EXPECT_LE((q - s.centre).norm(), s.radius * (1 + 1e-12));
    if (n >= 6) {
      EXPECT_NEAR(s.radius, 2.0, 1e-12) << n << " points";
      EXPECT_NEAR((s.centre - centre).norm(), 0.0, 1e-12) << n << " points";
    } else {
      EXPECT_NEAR(s.radius, brute_force_radius(p), 1e-12) << n << " points";
    }
  }
}

TEST(EnclosingSphere, LargeSetIsReproducibleAndTight) {
  // 20,000 points on a unit sphere's cap and inside it: radius at most 1 and at least the
  // half-distance of the farthest pair found.
  Rng rng(3, 0);
  std::vector<Vec3> p;
  for (int i = 0; i < 20000; ++i) {
    Vec3 q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (q.norm() > 1.0) q.normalize();
    p.push_back(q);
  }
  const Sphere a = minimal_enclosing_sphere(p);
  const Sphere b = minimal_enclosing_sphere(p);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_LE(a.radius, 1.0 + 1e-12);
  EXPECT_GT(a.radius, 0.999);
}

}  // namespace
}  // namespace aggpack
