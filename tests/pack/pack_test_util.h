#pragma once
// Brute-force checks shared by the pack tests: every pair by the exact GJK distance, every
// particle by the exact vertex containment test. Independent of the packers' broad phase.

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/packing.h"

namespace aggpack::testing {

/// Asserts that no two particles are closer than `gap` (touching counts as overlap) and that
/// every particle lies in the container shrunk by its wall_gap. O(N^2): keep N modest.
inline void expect_valid_packing(const Packing& packing, double gap) {
  const std::size_t n = packing.particles.size();
  std::vector<ConvexPolyhedron> bodies;
  bodies.reserve(n);
  for (std::size_t i = 0; i < n; ++i) bodies.push_back(packing.local_body(i));
  std::size_t outside = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!contains(packing.container, bodies[i], packing.particles[i].pose)) ++outside;
  }
  EXPECT_EQ(outside, 0u) << "particles outside the container minus wall_gap";
  std::size_t too_close = 0;
  double closest = 1e300;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const DistanceResult result =
          gjk_distance(bodies[i], packing.particles[i].pose, bodies[j], packing.particles[j].pose);
      closest = std::min(closest, result.distance);
      if (result.is_intersecting || result.distance < gap) ++too_close;
    }
  }
  EXPECT_EQ(too_close, 0u) << "pairs closer than gap " << gap << " (closest " << closest << ")";
}

/// Asserts that two packings are identical: same shapes (vertex coordinates bit for bit), same
/// poses, radii, classes and scales.
inline void expect_identical(const Packing& a, const Packing& b) {
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (std::size_t s = 0; s < a.shapes.size(); ++s) {
    ASSERT_EQ(a.shapes[s].vertices().size(), b.shapes[s].vertices().size()) << "shape " << s;
    for (std::size_t v = 0; v < a.shapes[s].vertices().size(); ++v) {
      ASSERT_EQ(a.shapes[s].vertices()[v], b.shapes[s].vertices()[v]) << "shape " << s;
    }
    ASSERT_EQ(a.shapes[s].triangles(), b.shapes[s].triangles()) << "shape " << s;
  }
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    const Particle& p = a.particles[i];
    const Particle& q = b.particles[i];
    ASSERT_EQ(p.shape, q.shape) << i;
    ASSERT_EQ(p.pose.position, q.pose.position) << i;
    ASSERT_EQ(p.pose.rotation.coeffs(), q.pose.rotation.coeffs()) << i;
    ASSERT_EQ(p.control_radius, q.control_radius) << i;
    ASSERT_EQ(p.size_class, q.size_class) << i;
    ASSERT_EQ(p.scale, q.scale) << i;
  }
}

/// Runs `function`, expects InvalidInput, and returns its field name ("" if something else).
template <class Function>
std::string invalid_field(Function&& function) {
  try {
    function();
  } catch (const InvalidInput& error) {
    return error.field();
  } catch (const std::exception& error) {
    return std::string("other exception: ") + error.what();
  }
  return "no exception";
}

}  // namespace aggpack::testing
