#pragma once
// Convex bodies as half-spaces: a body's face planes, the largest excess of a point over them (a
// fast inside test and lower bound of the distance), and the exact distance from a point.

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// The half-space normal . x <= offset (normal of unit length, pointing out of the half-space).
struct HalfSpace {
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;
};

/// The outward face planes of a convex body, one per triangle with positive area (coplanar
/// triangles repeat a plane).
std::vector<HalfSpace> face_half_spaces(const ConvexPolyhedron& body);

/// Largest normal . p - offset over the planes: <= 0 inside their intersection, and for a
/// convex body's face planes a lower bound of the distance outside (-infinity for no plane).
inline double plane_excess(std::span<const HalfSpace> planes, const Vec3& p) {
  double excess = -std::numeric_limits<double>::infinity();
  for (const HalfSpace& plane : planes)
    excess = std::max(excess, plane.normal.dot(p) - plane.offset);
  return excess;
}

/// Distance from `point` to the convex body (0 inside): the closest point of any surface
/// triangle. O(triangles).
double distance_to_body(const ConvexPolyhedron& body, const Vec3& point);

}  // namespace aggpack
