#pragma once
// Exact mass properties of a closed triangle mesh (divergence theorem), and the paper's
// signed-tetrahedron point-in-convex test.

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Volume, surface, centroid and inertia of a homogeneous body of unit density.
struct MassProperties {
  double volume = 0.0;           ///< m^3
  double surface_area = 0.0;     ///< m^2
  Vec3 centroid = Vec3::Zero();  ///< m
  /// Inertia tensor about the centroid for unit density (kg m^2 per kg/m^3, i.e. m^5).
  Mat3 inertia = Mat3::Zero();
};

/// Exact volume, surface, centroid and inertia tensor (about the centroid) of a closed outward
/// mesh, by summing signed tetrahedra (origin, triangle) -- the divergence theorem.
MassProperties mass_properties(const ConvexPolyhedron& body);

/// Signed volume of the tetrahedron (p, a, b, c): positive when p lies on the outer side of the
/// counter-clockwise triangle (a, b, c). This is the paper's intrusion measure.
double signed_tetra_volume(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Where a point lies relative to a convex body.
enum class PointLocation { kInside, kOnBoundary, kOutside };

/// The paper's intrusion criterion (Section 2.3): signed tetra volume of (p, triangle) for every
/// outward triangle; > tolerance for any -> outside, all < -tolerance -> inside, else boundary.
/// `tolerance` is a volume (m^3); pass e.g. 1e-12 * scale^3.
PointLocation locate_point(const ConvexPolyhedron& body, const Vec3& point, double tolerance);

}  // namespace aggpack
