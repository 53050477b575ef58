#pragma once
// The convex hull of a point set in 3D (Qhull), and its simplification to a vertex budget.

#include <cstddef>
#include <span>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// The convex hull of `points` as a ConvexPolyhedron: only the hull's vertices, each of Qhull's
/// (merged, planar) facets fanned into outward counter-clockwise triangles. Qhull's default
/// merging of coplanar facets keeps the result convex within its roundoff. Thread-safe (each call
/// has its own Qhull state).
/// \throw InvalidInput ("hull") if fewer than 4 points, a non-finite coordinate, or the points
///        span no volume (all on a plane or a line); the message quotes Qhull's reason.
ConvexPolyhedron convex_hull(std::span<const Vec3> points);

/// A hull with at most `max_vertices` vertices inscribed in `body`: the hull of the body's
/// support vertices in `max_vertices` directions spread evenly over the sphere (a Fibonacci
/// lattice), so it only ever loses volume. `body` itself when it has no more than the budget.
/// \throw InvalidInput if max_vertices < 4.
ConvexPolyhedron simplify_hull(const ConvexPolyhedron& body, std::size_t max_vertices);

}  // namespace aggpack
