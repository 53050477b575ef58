#pragma once
// The smallest sphere enclosing a set of points (pivoting on a support of a few points, each
// round one pass over the points plus Welzl's recursion over the support; Welzl's algorithm over
// all points in a fixed pseudo-random order as the fallback: same answer on every run). The
// circumscribed sphere of a real particle, as a caliper or a photograph measures it, is this sphere
// of its vertices; the generator's control sphere (radius R) only bounds it.
//
// Own code, not a library's: CGAL's Min_sphere_d would do it but is a large dependency for ~100
// lines, and no other Debian package the project uses has it.

#include <span>

#include "aggpack/geom/vec.h"

namespace aggpack {

struct Sphere {
  Vec3 centre = Vec3::Zero();
  double radius = 0;
};

/// The smallest sphere containing every point (to a relative tolerance of 1e-12 of its radius).
/// Empty input gives radius 0 at the origin.
Sphere minimal_enclosing_sphere(std::span<const Vec3> points);

}  // namespace aggpack
