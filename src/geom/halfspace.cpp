// Convex bodies as half-spaces (geom/halfspace.h).

#include "aggpack/geom/halfspace.h"

#include <algorithm>
#include <limits>

namespace aggpack {

namespace {

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

}  // namespace

std::vector<HalfSpace> face_half_spaces(const ConvexPolyhedron& body) {
  std::vector<HalfSpace> planes;
  planes.reserve(body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 n = body.face_normal(f);
    if (!n.allFinite()) continue;  // a zero-area triangle bounds nothing
    planes.push_back({n, n.dot(body.vertices()[body.triangles()[f][0]])});
  }
  return planes;
}

double distance_to_body(const ConvexPolyhedron& body, const Vec3& point) {
  const auto& v = body.vertices();
  bool is_inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Triangle& t = body.triangles()[f];
    const Vec3 n = body.face_normal_scaled(f);
    if (n.dot(point - v[t[0]]) > 0.0) is_inside = false;
    best = std::min(best, (point - closest_on_triangle(point, v[t[0]], v[t[1]], v[t[2]])).norm());
  }
  return is_inside ? 0.0 : best;
}

}  // namespace aggpack
