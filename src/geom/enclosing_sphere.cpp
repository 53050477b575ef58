// Minimal enclosing sphere (geom/enclosing_sphere.h).

#include "aggpack/geom/enclosing_sphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "aggpack/core/rng.h"

namespace aggpack {

namespace {

constexpr double kSlack = 1e-12;

bool contains(const Sphere& s, const Vec3& p) {
  return (p - s.centre).norm() <= s.radius * (1.0 + kSlack) + 1e-300;
}

Sphere sphere_of(const Vec3& a, const Vec3& b) { return {0.5 * (a + b), 0.5 * (a - b).norm()}; }

// The smallest sphere with a, b and c on its surface: centred on their circumcircle (or, for
// nearly collinear points, the diameter sphere of the farthest pair).
Sphere sphere_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 n = u.cross(v);
  const double nn = n.squaredNorm();
  if (nn <= 1e-24 * u.squaredNorm() * v.squaredNorm()) {
    Sphere best = sphere_of(a, b);
    for (const Sphere& s : {sphere_of(a, c), sphere_of(b, c)}) {
      if (s.radius > best.radius) best = s;
    }
    return best;
  }
  const Vec3 offset = (u.squaredNorm() * v.cross(n) + v.squaredNorm() * n.cross(u)) / (2.0 * nn);
  return {a + offset, offset.norm()};
}

// The smallest sphere with a, b, c and d on its surface (their circumsphere); for nearly
// coplanar points, the smallest of the three-point spheres that contains all four.
Sphere sphere_of(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Mat3 m;
  m.row(0) = b - a;
  m.row(1) = c - a;
  m.row(2) = d - a;
  const double det = m.determinant();
  const double scale = m.row(0).norm() * m.row(1).norm() * m.row(2).norm();
  if (std::abs(det) <= 1e-12 * scale) {
    Sphere best{Vec3::Zero(), std::numeric_limits<double>::infinity()};
    const std::array<std::array<const Vec3*, 4>, 4> sets = {
        {{&a, &b, &c, &d}, {&a, &b, &d, &c}, {&a, &c, &d, &b}, {&b, &c, &d, &a}}};
    for (const auto& set : sets) {
      const Sphere s = sphere_of(*set[0], *set[1], *set[2]);
      if (s.radius < best.radius && contains(s, *set[3])) best = s;
    }
    return best;
  }
  const Vec3 rhs(0.5 * m.row(0).squaredNorm(), 0.5 * m.row(1).squaredNorm(),
                 0.5 * m.row(2).squaredNorm());
  const Vec3 offset = m.partialPivLu().solve(rhs);
  return {a + offset, offset.norm()};
}

}  // namespace

Sphere minimal_enclosing_sphere(std::span<const Vec3> input) {
  if (input.empty()) return {};
  std::vector<Vec3> p(input.begin(), input.end());
  // A fixed shuffle (Fisher-Yates on a fixed stream): expected O(n), reproducible.
  Rng rng(0x656e636cULL, p.size());
  for (std::size_t i = p.size() - 1; i > 0; --i) {
    std::swap(p[i], p[static_cast<std::size_t>(rng.next() % (i + 1))]);
  }
  Sphere s{p[0], 0.0};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (contains(s, p[i])) continue;
    s = {p[i], 0.0};
    for (std::size_t j = 0; j < i; ++j) {
      if (contains(s, p[j])) continue;
      s = sphere_of(p[i], p[j]);
      for (std::size_t k = 0; k < j; ++k) {
        if (contains(s, p[k])) continue;
        s = sphere_of(p[i], p[j], p[k]);
        for (std::size_t l = 0; l < k; ++l) {
          if (!contains(s, p[l])) s = sphere_of(p[i], p[j], p[k], p[l]);
        }
      }
    }
  }
  // Rounding in the nested updates can leave a point a hair outside: grow to cover all.
  for (const Vec3& q : p) s.radius = std::max(s.radius, (q - s.centre).norm());
  return s;
}

}  // namespace aggpack
