#pragma once
// Internal helpers shared by the packers and statistics.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "aggpack/core/rng.h"
#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack::detail {

/// Uniformly distributed rotation (Shoemake 1992, "Uniform random rotations").
inline Quat random_rotation(Rng& rng) {
  const double u1 = rng.uniform();
  const double u2 = 2.0 * std::numbers::pi * rng.uniform();
  const double u3 = 2.0 * std::numbers::pi * rng.uniform();
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  Quat rotation(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  rotation.normalize();
  return rotation;
}

/// The body moved so that its centroid is at the origin; `centroid` receives the old centroid.
inline ConvexPolyhedron centred_on_centroid(const ConvexPolyhedron& body, Vec3& centroid,
                                            double& volume) {
  const MassProperties mass = mass_properties(body);
  centroid = mass.centroid;
  volume = mass.volume;
  return body.translated(-mass.centroid);
}

}  // namespace aggpack::detail
