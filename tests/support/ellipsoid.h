#pragma once
// A polyhedral ellipsoid, the test body of the support-search tests and benchmarks
// (tests/geom/overlap_test.cpp, bench/overlap_bench.cpp): every vertex is a hull vertex, so large
// ones exercise hill-climbing.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack::test {

/// Latitude/longitude grid centred at the origin with semi-axes `axes` (x, y, z): the two poles
/// (+z, -z) and `rings` - 1 rings of `segments` vertices, 2 + (rings - 1) segments vertices in
/// all, triangles outward. Preconditions: rings >= 2, segments >= 3.
inline ConvexPolyhedron make_ellipsoid(int rings, int segments, const Vec3& axes) {
  std::vector<Vec3> vertices = {Vec3(0, 0, axes.z()), Vec3(0, 0, -axes.z())};
  for (int i = 1; i < rings; ++i) {
    const double polar = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double azimuth = 2 * std::numbers::pi * j / segments;
      vertices.emplace_back(axes.x() * std::sin(polar) * std::cos(azimuth),
                            axes.y() * std::sin(polar) * std::sin(azimuth),
                            axes.z() * std::cos(polar));
    }
  }
  const auto ring = [segments](int i, int j) {
    return static_cast<std::uint32_t>(2 + (i - 1) * segments + (j % segments));
  };
  std::vector<Triangle> triangles;
  for (int j = 0; j < segments; ++j) {
    triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    triangles.push_back({1, ring(rings - 1, j + 1), ring(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  }
  for (auto& t : triangles) {  // orient outward (the origin is inside)
    const Vec3 normal = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
    if (normal.dot(vertices[t[0]]) < 0) std::swap(t[1], t[2]);
  }
  return {std::move(vertices), std::move(triangles)};
}

}  // namespace aggpack::test
