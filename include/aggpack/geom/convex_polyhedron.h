#pragma once
// ConvexPolyhedron: a closed convex triangle mesh with outward, counter-clockwise triangles.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/geom/vec.h"

namespace aggpack {

/// Vertex indices of one triangle, counter-clockwise seen from outside (0-based).
using Triangle = std::array<std::uint32_t, 3>;

/// An undirected edge with the two triangles that share it.
/// `faces[0]` traverses the edge as vertices[0] -> vertices[1], `faces[1]` the other way.
struct Edge {
  std::array<std::uint32_t, 2> vertices;
  std::array<std::uint32_t, 2> faces;
};

/// A convex polyhedron as vertices + outward CCW triangles. A value type: operations are const and
/// return new values. The constructor checks only the cheap invariants (indices in range, at least
/// a tetrahedron); use `check_closed_manifold` and `check_convex` for the full ones.
class ConvexPolyhedron {
 public:
  ConvexPolyhedron() = default;
  /// \throw InvalidInput if fewer than 4 vertices / 4 triangles or an index is out of range.
  ConvexPolyhedron(std::vector<Vec3> vertices, std::vector<Triangle> triangles);

  [[nodiscard]] const std::vector<Vec3>& vertices() const { return vertices_; }
  [[nodiscard]] const std::vector<Triangle>& triangles() const { return triangles_; }
  [[nodiscard]] std::size_t vertex_count() const { return vertices_.size(); }
  [[nodiscard]] std::size_t triangle_count() const { return triangles_.size(); }
  [[nodiscard]] bool is_empty() const { return vertices_.empty(); }

  /// Unique edges with their adjacent faces. \throw InvalidInput if the mesh is not a closed
  /// 2-manifold (an edge used by other than exactly two oppositely oriented triangles).
  [[nodiscard]] std::vector<Edge> edges() const;
  /// For each vertex, the indices of its neighbouring vertices (sorted).
  [[nodiscard]] std::vector<std::vector<std::uint32_t>> vertex_neighbours() const;

  /// Non-normalised outward normal of triangle `face` (twice its area in length).
  [[nodiscard]] Vec3 face_normal_scaled(std::size_t face) const;
  /// Unit outward normal of triangle `face`.
  [[nodiscard]] Vec3 face_normal(std::size_t face) const;
  /// Length of the longest edge.
  [[nodiscard]] double longest_edge() const;
  /// Axis-aligned bounding box of the vertices.
  [[nodiscard]] Aabb bounds() const;

  /// The body moved by `pose` (vertices transformed, topology shared).
  [[nodiscard]] ConvexPolyhedron transformed(const Pose& pose) const;
  /// The body translated by `offset`.
  [[nodiscard]] ConvexPolyhedron translated(const Vec3& offset) const;
  /// The body scaled about the origin by `factor` (> 0).
  [[nodiscard]] ConvexPolyhedron scaled(double factor) const;

 private:
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
};

/// Axis-aligned box between two corners (12 triangles). \throw InvalidInput unless lower < upper.
ConvexPolyhedron make_box(const Vec3& lower, const Vec3& upper);
/// Octahedron with one vertex on each half-axis at the given distances from the origin, in the
/// order +x, -x, +y, -y, +z, -z. Regular when all six are equal. \throw InvalidInput if any <= 0.
ConvexPolyhedron make_octahedron(const std::array<double, 6>& distances);
/// Regular tetrahedron with circumradius `radius` centred at the origin.
ConvexPolyhedron make_regular_tetrahedron(double radius);

/// Result of a structural check; `message` says what failed.
struct CheckResult {
  bool is_ok = true;
  std::string message;
};

/// Closed, oriented 2-manifold: every edge in exactly two triangles with opposite directions,
/// no degenerate triangle, every vertex used, V - E + F = 2.
CheckResult check_closed_manifold(const ConvexPolyhedron& body);
/// Convex with outward normals: every vertex lies on or behind every face plane, within
/// `tolerance` (absolute, metres), and the volume is positive.
CheckResult check_convex(const ConvexPolyhedron& body, double tolerance);

}  // namespace aggpack
