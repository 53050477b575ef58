#pragma once
// Exact convex-convex proximity: GJK distance between two placed convex polyhedra, with a
// bounding-sphere early out. Decides non-overlap in the packers (DESIGN.md: "geometry is exact
// where it decides validity"). The paper's vertex-in-body test (locate_point) misses
// edge-through-edge crossings; this does not.

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Result of a distance query between two placed bodies.
struct DistanceResult {
  double distance = 0.0;        ///< Euclidean distance (m); 0 when the bodies intersect
  bool is_intersecting = false; ///< true when they share a point (touching counts)
  Vec3 point_a = Vec3::Zero();  ///< closest point on A (world), valid when not intersecting
  Vec3 point_b = Vec3::Zero();  ///< closest point on B (world), valid when not intersecting
  int iterations = 0;           ///< GJK iterations used
};

/// Largest distance from the local origin to a vertex (bounding-sphere radius about the origin).
double bounding_radius(const ConvexPolyhedron& body);

/// GJK distance between body `a` placed by `pose_a` and body `b` placed by `pose_b`.
/// Robust to touching and nearly coplanar configurations: the relative tolerance is ~1e-12 of the
/// bodies' size.
DistanceResult gjk_distance(const ConvexPolyhedron& a, const Pose& pose_a,
                            const ConvexPolyhedron& b, const Pose& pose_b);

/// True when the two placed bodies are at least `gap` (m, >= 0) apart; bodies that touch or
/// overlap are never separated. Uses bounding spheres (radius_a/radius_b from bounding_radius)
/// to answer most calls without GJK.
bool is_separated(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                  const ConvexPolyhedron& b, const Pose& pose_b, double radius_b, double gap);

}  // namespace aggpack
