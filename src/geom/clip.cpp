// clip_at_plane (include/aggpack/geom/clip.h): one plane, exact crossings, the hull of the rest.

#include "aggpack/geom/clip.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/convex_hull_3d.h"

namespace aggpack {

std::optional<ConvexPolyhedron> clip_at_plane(const ConvexPolyhedron& body, int axis, double level,
                                              bool is_below) {
  if (axis < 0 || axis > 2) throw InvalidInput("axis", std::to_string(axis), "0, 1 or 2");
  const std::vector<Vec3>& vertices = body.vertices();
  // >= 0 on the kept side.
  auto side = [&](const Vec3& p) { return is_below ? level - p[axis] : p[axis] - level; };
  double depth = -std::numeric_limits<double>::infinity();
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -std::numeric_limits<double>::infinity();
  bool is_whole = true;
  for (const Vec3& p : vertices) {
    const double s = side(p);
    depth = std::max(depth, s);
    is_whole = is_whole && s >= 0.0;
    lowest = std::min(lowest, p[axis]);
    highest = std::max(highest, p[axis]);
  }
  if (is_whole) return body;
  const double thinnest = 1e-12 * (highest - lowest);
  if (!(depth > thinnest)) return std::nullopt;
  std::vector<Vec3> points;
  for (const Vec3& p : vertices) {
    if (side(p) >= 0.0) points.push_back(p);
  }
  // Each edge's crossing from its lower-numbered end, so the two triangles sharing it give the
  // same point (Qhull merges the duplicate).
  for (const Triangle& triangle : body.triangles()) {
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t a = triangle[k];
      std::uint32_t b = triangle[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      const double side_a = side(vertices[a]);
      const double side_b = side(vertices[b]);
      if ((side_a < 0.0) == (side_b < 0.0)) continue;
      const double t = side_a / (side_a - side_b);
      Vec3 crossing = vertices[a] + t * (vertices[b] - vertices[a]);
      crossing[axis] = level;
      points.push_back(crossing);
    }
  }
  try {
    return convex_hull(points);
  } catch (const InvalidInput&) {
    // A sliver too thin for Qhull's precision holds no volume worth writing; anything thicker
    // that fails is a real error.
    if (depth < 1e-6 * (highest - lowest)) return std::nullopt;
    throw;
  }
}

}  // namespace aggpack
