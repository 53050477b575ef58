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

// The squared radius within which a point counts as inside `s` (the slack absorbs rounding).
double reach_squared(const Sphere& s) {
  const double reach = s.radius * (1.0 + kSlack) + 1e-300;
  return reach * reach;
}

bool contains(const Sphere& s, const Vec3& p) {
  return (p - s.centre).squaredNorm() <= reach_squared(s);
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

// The smallest sphere with a, b, c and d on its surface (their circumsphere, in closed form);
// for nearly coplanar points, the smallest of the three-point spheres that contains all four.
Sphere sphere_of(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 w = d - a;
  const Vec3 vw = v.cross(w);
  const double det = u.dot(vw);
  const double uu = u.squaredNorm();
  const double vv = v.squaredNorm();
  const double ww = w.squaredNorm();
  if (std::abs(det) <= 1e-12 * std::sqrt(uu * vv * ww)) {
    Sphere best{Vec3::Zero(), std::numeric_limits<double>::infinity()};
    const std::array<std::array<const Vec3*, 4>, 4> sets = {
        {{&a, &b, &c, &d}, {&a, &b, &d, &c}, {&a, &c, &d, &b}, {&b, &c, &d, &a}}};
    for (const auto& set : sets) {
      const Sphere s = sphere_of(*set[0], *set[1], *set[2]);
      if (s.radius < best.radius && contains(s, *set[3])) best = s;
    }
    return best;
  }
  // Cramer's rule for 2 x . u = |u|^2 (and v, w): x = sum |u|^2 (v x w) / (2 u . (v x w)).
  const Vec3 offset = (uu * vw + vv * w.cross(u) + ww * u.cross(v)) / (2.0 * det);
  return {a + offset, offset.norm()};
}

// Points on a ball's surface (at most four: a sphere is fixed by four points in general
// position).
struct Boundary {
  std::array<Vec3, 4> points;
  int count = 0;
};

Sphere sphere_of(const Boundary& r) {
  switch (r.count) {
    case 1:
      return {r.points[0], 0.0};
    case 2:
      return sphere_of(r.points[0], r.points[1]);
    case 3:
      return sphere_of(r.points[0], r.points[1], r.points[2]);
    default:
      return sphere_of(r.points[0], r.points[1], r.points[2], r.points[3]);
  }
}

// Welzl's recursion on a few points: the smallest ball containing free[0..count) with the points
// of `boundary` on its surface.
Sphere ball_of(const Vec3* free, int count, const Boundary& boundary) {
  if (count == 0 || boundary.count == 4) return sphere_of(boundary);
  const Sphere s = ball_of(free, count - 1, boundary);
  if (contains(s, free[count - 1])) return s;
  Boundary more = boundary;
  more.points[more.count++] = free[count - 1];
  return ball_of(free, count - 1, more);
}

// Welzl's algorithm on all points in a fixed pseudo-random order (expected linear time): the
// fallback when the pivoting below does not settle (rounding on nearly cospherical points).
Sphere welzl(std::span<const Vec3> input) {
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
  return s;
}

// The point of `input` farthest from `from` (the first of equals) and its squared distance.
struct Farthest {
  const Vec3* point;
  double distance_squared;
};

Farthest farthest_from(std::span<const Vec3> input, const Vec3& from) {
  const double x = from.x();
  const double y = from.y();
  const double z = from.z();
  Farthest best{input.data(), -1.0};
  for (const Vec3& q : input) {
    const double dx = q.x() - x;
    const double dy = q.y() - y;
    const double dz = q.z() - z;
    const double d = dx * dx + dy * dy + dz * dz;
    if (d > best.distance_squared) best = {&q, d};
  }
  return best;
}

// Pivoting rounds before falling back to welzl(); a particle's sphere settles in a handful.
constexpr int kMaxPivots = 64;
// The most points a pivoting round carries over (more only on many nearly cospherical points).
constexpr int kMaxSupport = 8;
// A point within this fraction of the radius of the surface counts as on it (carried over).
constexpr double kOnSurface = 1e-9;

}  // namespace

Sphere minimal_enclosing_sphere(std::span<const Vec3> input) {
  if (input.empty()) return {};
  // Pivoting (after Gaertner, "Fast and robust smallest enclosing balls", 1999): keep the points
  // on the current ball's surface (its support); put the point farthest outside it on the surface
  // of the smallest ball containing the support and that point, and keep that ball's surface
  // points. The ball grows every round, and the first one that contains every point is the
  // smallest of all (it is the smallest ball of some of the points). A round costs one pass over
  // the points and a Welzl recursion over a handful.
  // The start: the sphere over a long chord (the point farthest from the first point, and the
  // point farthest from that one), the smallest ball of its two ends.
  const Vec3& end = *farthest_from(input, input[0]).point;
  const Vec3& other = *farthest_from(input, end).point;
  std::array<Vec3, kMaxSupport + 1> support;
  support[0] = end;
  support[1] = other;
  int count = 2;
  Sphere s = sphere_of(end, other);
  for (int round = 0; round < kMaxPivots; ++round) {
    const Farthest far = farthest_from(input, s.centre);
    if (far.distance_squared <= reach_squared(s)) {
      // Every point is inside; rounding in the spheres' formulas can leave one a hair outside
      // the radius: grow to cover it.
      s.radius = std::max(s.radius, std::sqrt(far.distance_squared));
      return s;
    }
    Boundary boundary;
    boundary.points[0] = *far.point;
    boundary.count = 1;
    const double radius = s.radius;
    s = ball_of(support.data(), count, boundary);
    if (!(s.radius > radius)) break;  // no progress after rounding: let Welzl decide
    // The new support: the pivot and the old support's points on the new surface.
    const double inner = s.radius * (1.0 - kOnSurface);
    const double inner_squared = inner * inner;
    int kept = 0;
    for (int i = 0; i < count; ++i) {
      if ((support[i] - s.centre).squaredNorm() >= inner_squared) support[kept++] = support[i];
    }
    if (kept >= kMaxSupport) break;
    support[kept++] = *far.point;
    count = kept;
  }
  s = welzl(input);
  s.radius = std::max(s.radius, std::sqrt(farthest_from(input, s.centre).distance_squared));
  return s;
}

}  // namespace aggpack
