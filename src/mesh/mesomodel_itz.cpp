// The ITZ layer of a mesomodel aggregate (mesomodel_plc.h): its outer surface is the aggregate's
// own triangle mesh with every vertex moved out, and the layer between the two surfaces is cut
// into prisms, three tetrahedra each, by aggpack itself.

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "mesomodel_plc.h"

namespace aggpack::detail {

ItzLayer itz_layer(const ConvexPolyhedron& aggregate, double thickness,
                   std::span<const HalfSpace> walls) {
  const auto& vertices = aggregate.vertices();
  std::vector<Mat3> normal_sum(vertices.size(), Mat3::Zero());
  std::vector<Vec3> normal_total(vertices.size(), Vec3::Zero());
  for (std::size_t f = 0; f < aggregate.triangle_count(); ++f) {
    const Vec3 n = aggregate.face_normal(f);
    if (!n.allFinite()) continue;
    for (const std::uint32_t v : aggregate.triangles()[f]) {
      normal_sum[v] += n * n.transpose();
      normal_total[v] += n;
    }
  }
  ItzLayer layer;
  layer.outer.resize(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    // The displacement d that moves every face plane at v out by t as nearly as possible:
    // least squares of n_i . d = t, on the directions the normals span (an eigenvalue below
    // 1e-3 of the largest is a direction the faces do not constrain; d gets no part of it).
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(normal_sum[v]);
    const Vec3 rhs = thickness * normal_total[v];
    const double largest = solver.eigenvalues().maxCoeff();
    Vec3 d = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      const double lambda = solver.eigenvalues()[k];
      if (lambda <= 1e-3 * largest) continue;
      const Vec3 u = solver.eigenvectors().col(k);
      d += (u.dot(rhs) / lambda) * u;
    }
    // Near a wall the layer thins so that half the aggregate's clearance stays mortar.
    double scale = 1.0;
    for (const HalfSpace& wall : walls) {
      const double towards = wall.normal.dot(d);
      if (towards <= 0.0) continue;
      const double clearance = wall.offset - wall.normal.dot(vertices[v]);
      scale = std::min(scale, 0.5 * clearance / towards);
    }
    d *= std::max(scale, 0.0);
    layer.outer[v] = vertices[v] + d;
    layer.max_offset = std::max(layer.max_offset, d.norm());
  }
  return layer;
}

void append_prism_tetrahedra(std::span<const Triangle> triangles, std::uint32_t inner_base,
                             std::uint32_t outer_base, std::vector<Tetrahedron>& out) {
  for (const Triangle& tri : triangles) {
    // Bottom (inner) corners rotated so the lowest node number comes first; the quadrilateral
    // sides are cut along the diagonal through their lowest node (inner nodes are numbered below
    // outer ones), the rule that makes neighbouring prisms agree on their shared side.
    int first = 0;
    for (int k = 1; k < 3; ++k) {
      if (tri[k] < tri[first]) first = k;
    }
    const std::uint32_t v0 = inner_base + tri[first];
    const std::uint32_t v1 = inner_base + tri[(first + 1) % 3];
    const std::uint32_t v2 = inner_base + tri[(first + 2) % 3];
    const std::uint32_t w0 = outer_base + tri[first];
    const std::uint32_t w1 = outer_base + tri[(first + 1) % 3];
    const std::uint32_t w2 = outer_base + tri[(first + 2) % 3];
    out.push_back({v0, w0, w1, w2});
    if (std::min(v1, w2) < std::min(v2, w1)) {
      out.push_back({v0, v1, v2, w2});
      out.push_back({v0, v1, w2, w1});
    } else {
      out.push_back({v0, v1, v2, w1});
      out.push_back({v0, w1, v2, w2});
    }
  }
}

}  // namespace aggpack::detail
