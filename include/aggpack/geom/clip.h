#pragma once
// A convex body clipped by an axis-aligned plane: the exact part on one side.

#include <optional>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// The part of `body` where coordinate `axis` is <= `level` (`is_below`) or >= `level`: the
/// convex hull (Qhull) of its vertices on that side and of its edges' crossings of the plane
/// (placed exactly onto the plane, so no vertex is beyond it). `body` itself when it lies on that
/// side; nothing when the part is thinner than 1e-12 x the body's extent along `axis` (no volume
/// to speak of).
/// \throw InvalidInput if `axis` is not 0, 1 or 2.
std::optional<ConvexPolyhedron> clip_at_plane(const ConvexPolyhedron& body, int axis, double level,
                                              bool is_below);

}  // namespace aggpack
