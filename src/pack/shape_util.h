#pragma once
// Internal helpers shared by the packers and statistics.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>

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

/// The order in which a use-once file library hands out its `count` shapes: a permutation drawn
/// from its own stream of `seed` (Fisher-Yates), the same for any thread count.
inline std::vector<std::uint32_t> use_once_order(std::size_t count, std::uint64_t seed) {
  constexpr std::uint64_t kUseOnceSalt = 0x0CE5A1F17E5ULL;
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), std::uint32_t{0});
  Rng rng(seed ^ kUseOnceSalt, 0);
  for (std::size_t i = count; i > 1; --i) {
    const auto j = static_cast<std::size_t>(std::min<double>(
        std::floor(rng.uniform() * static_cast<double>(i)), static_cast<double>(i - 1)));
    std::swap(order[i - 1], order[j]);
  }
  return order;
}

/// A library slot drawn uniformly from `rng` among `count` (> 0).
inline std::uint32_t library_slot(Rng& rng, std::size_t count) {
  return static_cast<std::uint32_t>(std::min<double>(
      std::floor(rng.uniform() * static_cast<double>(count)), static_cast<double>(count - 1)));
}

}  // namespace aggpack::detail
