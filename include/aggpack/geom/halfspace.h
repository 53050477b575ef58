#pragma once
// Convex polyhedra cut by half-spaces: clipping by planes, and the mitred offset (every face plane
// moved outwards by a thickness t; the mesomodel's first ITZ, now a prism layer, see
// docs/mesomodel.md), and the distance from a point to a convex body.
//
// Clipping works on face polygons sharing one vertex array: a plane cut computes the point on a
// crossed edge once, for both faces that share the edge, so the result stays a closed manifold;
// vertices within `tolerance` of the plane count as on it (no sliver faces). The result is
// triangulated (a fan per face) into a ConvexPolyhedron.

#include <span>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// The half-space normal . x <= offset (normal of unit length, pointing out of the half-space).
struct HalfSpace {
  Vec3 normal = Vec3::UnitZ();
  double offset = 0.0;
};

/// The body cut by every half-space (the part with normal . x <= offset for each). Vertices within
/// `tolerance` (m, >= 0) of a plane are treated as on it. Returns an empty polyhedron when nothing
/// with positive volume is left. \throw InvalidInput if the body is empty, a normal is not unit or
/// not finite, or the tolerance is negative.
ConvexPolyhedron clip(const ConvexPolyhedron& body, std::span<const HalfSpace> half_spaces,
                      double tolerance);

/// The outward face planes of a convex body, one per triangle (coplanar triangles repeat a
/// plane; harmless for clipping).
std::vector<HalfSpace> face_half_spaces(const ConvexPolyhedron& body);

/// The mitred offset of a convex body: the intersection of its face half-spaces each moved out by
/// `thickness` (m, > 0), further cut by `bounds` (e.g. a container's walls; may be empty). Every
/// point of the body's surface is at least `thickness` inside it (exactly `thickness` below a
/// face); corners reach further (see mitre_factor). `tolerance` as for clip; 1e-6 x thickness is
/// a good choice. \throw InvalidInput (thickness <= 0 or not finite, as clip).
ConvexPolyhedron mitred_offset(const ConvexPolyhedron& body, double thickness,
                               std::span<const HalfSpace> bounds, double tolerance);

/// Largest distance from a vertex of `offset` to `body`, divided by `thickness`: 1 for a smooth
/// offset, > 1 at the mitred corners. Two bodies whose offsets of thickness t must not meet need
/// a gap of at least t x (factor_a + factor_b) (a sufficient bound).
double mitre_factor(const ConvexPolyhedron& body, const ConvexPolyhedron& offset, double thickness);

/// Distance from `point` to the convex body (0 inside): the closest point of any surface
/// triangle. O(triangles).
double distance_to_body(const ConvexPolyhedron& body, const Vec3& point);

}  // namespace aggpack
