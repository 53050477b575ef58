#include "aggpack/geom/convex_polyhedron.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack {

namespace {

struct HalfEdge {
  std::uint32_t low;
  std::uint32_t high;
  std::uint32_t face;
  bool is_forward;  // traversed low -> high
};

// Half-edges sorted by undirected key; a closed oriented manifold has each key exactly twice,
// once in each direction.
std::vector<HalfEdge> sorted_half_edges(const std::vector<Triangle>& triangles) {
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(triangles.size() * 3);
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = triangles[f][k];
      const std::uint32_t v = triangles[f][(k + 1) % 3];
      half_edges.push_back({std::min(u, v), std::max(u, v), f, u < v});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return std::tie(a.low, a.high, a.face) < std::tie(b.low, b.high, b.face);
  });
  return half_edges;
}

}  // namespace

ConvexPolyhedron::ConvexPolyhedron(std::vector<Vec3> vertices, std::vector<Triangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  if (vertices_.size() < 4) {
    throw InvalidInput(
        Wording{Sentence::kText, {"polyhedron.vertices"}},
        Wording{Sentence::kPolyhedronVertexCount, {std::to_string(vertices_.size())}},
        Wording{Sentence::kAtLeast, {"4"}});
  }
  if (triangles_.size() < 4) {
    throw InvalidInput(
        Wording{Sentence::kText, {"polyhedron.triangles"}},
        Wording{Sentence::kPolyhedronTriangleCount, {std::to_string(triangles_.size())}},
        Wording{Sentence::kAtLeast, {"4"}});
  }
  // Fast paths first (the generator builds a polyhedron per particle): the largest index and a
  // sum of x * 0, which is 0 exactly when every coordinate is finite (inf * 0 and NaN give NaN).
  std::uint32_t largest_index = 0;
  for (const auto& triangle : triangles_) {
    largest_index = std::max(largest_index, triangle[0]);
    largest_index = std::max(largest_index, triangle[1]);
    largest_index = std::max(largest_index, triangle[2]);
  }
  if (largest_index >= vertices_.size()) {
    for (const auto& triangle : triangles_) {
      for (auto index : triangle) {
        if (index >= vertices_.size()) {
          throw InvalidInput(Wording{Sentence::kText, {"polyhedron.triangles"}},
                             Wording{Sentence::kPolyhedronVertexIndex, {std::to_string(index)}},
                             Wording{Sentence::kBelow, {std::to_string(vertices_.size())}});
        }
      }
    }
  }
  double zero_if_finite = 0.0;
  for (const auto& vertex : vertices_) {
    zero_if_finite += vertex.x() * 0.0 + vertex.y() * 0.0 + vertex.z() * 0.0;
  }
  if (zero_if_finite != 0.0) {
    throw InvalidInput(Wording{Sentence::kText, {"polyhedron.vertices"}},
                       Wording{Sentence::kPhraseNonFiniteCoordinate, {}},
                       Wording{Sentence::kPhraseFiniteNumbers, {}});
  }
}

std::vector<Edge> ConvexPolyhedron::edges() const {
  const auto half_edges = sorted_half_edges(triangles_);
  std::vector<Edge> result;
  result.reserve(half_edges.size() / 2);
  for (std::size_t i = 0; i < half_edges.size(); i += 2) {
    const auto& a = half_edges[i];
    if (i + 1 >= half_edges.size() || half_edges[i + 1].low != a.low ||
        half_edges[i + 1].high != a.high || half_edges[i + 1].is_forward == a.is_forward ||
        (i + 2 < half_edges.size() && half_edges[i + 2].low == a.low &&
         half_edges[i + 2].high == a.high)) {
      throw InvalidInput(
          Wording{Sentence::kText, {"polyhedron.triangles"}},
          Wording{Sentence::kPolyhedronEdge, {std::to_string(a.low), std::to_string(a.high)}},
          Wording{Sentence::kPolyhedronEdgeTwice, {}});
    }
    const auto& b = half_edges[i + 1];
    const auto& forward = a.is_forward ? a : b;
    const auto& backward = a.is_forward ? b : a;
    result.push_back({{a.low, a.high}, {forward.face, backward.face}});
  }
  return result;
}

std::vector<std::vector<std::uint32_t>> ConvexPolyhedron::vertex_neighbours() const {
  std::vector<std::vector<std::uint32_t>> neighbours(vertices_.size());
  for (const auto& triangle : triangles_) {
    for (int k = 0; k < 3; ++k) {
      neighbours[triangle[k]].push_back(triangle[(k + 1) % 3]);
    }
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

Vec3 ConvexPolyhedron::face_normal_scaled(std::size_t face) const {
  const auto& t = triangles_[face];
  const Vec3& a = vertices_[t[0]];
  return (vertices_[t[1]] - a).cross(vertices_[t[2]] - a);
}

Vec3 ConvexPolyhedron::face_normal(std::size_t face) const {
  return face_normal_scaled(face).normalized();
}

double ConvexPolyhedron::longest_edge() const {
  double longest_squared = 0.0;
  for (const auto& t : triangles_) {
    for (int k = 0; k < 3; ++k) {
      longest_squared =
          std::max(longest_squared, (vertices_[t[k]] - vertices_[t[(k + 1) % 3]]).squaredNorm());
    }
  }
  return std::sqrt(longest_squared);
}

Aabb ConvexPolyhedron::bounds() const {
  Aabb box;
  for (const auto& v : vertices_) box.expand(v);
  return box;
}

ConvexPolyhedron ConvexPolyhedron::transformed(const Pose& pose) const {
  ConvexPolyhedron result = *this;
  const Mat3 rotation = pose.rotation.toRotationMatrix();
  for (auto& v : result.vertices_) v = rotation * v + pose.position;
  return result;
}

ConvexPolyhedron ConvexPolyhedron::translated(const Vec3& offset) const {
  ConvexPolyhedron result = *this;
  for (auto& v : result.vertices_) v += offset;
  return result;
}

ConvexPolyhedron ConvexPolyhedron::scaled(double factor) const {
  require_positive("scale factor", factor);
  ConvexPolyhedron result = *this;
  for (auto& v : result.vertices_) v *= factor;
  return result;
}

ConvexPolyhedron make_box(const Vec3& lower, const Vec3& upper) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!(upper[axis] > lower[axis])) {
      throw InvalidInput("box.upper[" + std::to_string(axis) + "]", format_value(upper[axis]),
                         "> lower = " + format_value(lower[axis]));
    }
  }
  std::vector<Vec3> vertices;
  for (int i = 0; i < 8; ++i) {
    vertices.emplace_back((i & 1) != 0 ? upper.x() : lower.x(),
                          (i & 2) != 0 ? upper.y() : lower.y(),
                          (i & 4) != 0 ? upper.z() : lower.z());
  }
  // Two CCW-from-outside triangles per face; vertex bit 0 = x, bit 1 = y, bit 2 = z.
  std::vector<Triangle> triangles = {
      {0, 2, 1}, {1, 2, 3},  // z = lower
      {4, 5, 6}, {5, 7, 6},  // z = upper
      {0, 1, 4}, {1, 5, 4},  // y = lower
      {2, 6, 3}, {3, 6, 7},  // y = upper
      {0, 4, 2}, {2, 4, 6},  // x = lower
      {1, 3, 5}, {3, 7, 5},  // x = upper
  };
  return {std::move(vertices), std::move(triangles)};
}

ConvexPolyhedron make_octahedron(const std::array<double, 6>& distances) {
  for (std::size_t i = 0; i < 6; ++i) require_positive("octahedron distance", distances[i]);
  std::vector<Vec3> vertices = {
      {distances[0], 0, 0},  {-distances[1], 0, 0}, {0, distances[2], 0},
      {0, -distances[3], 0}, {0, 0, distances[4]},  {0, 0, -distances[5]},
  };
  std::vector<Triangle> triangles;
  // One face per octant; (x, y, z) is CCW from outside when the octant's sign product is +.
  for (int sx = 0; sx < 2; ++sx) {
    for (int sy = 0; sy < 2; ++sy) {
      for (int sz = 0; sz < 2; ++sz) {
        const auto x = static_cast<std::uint32_t>(sx);      // 0: +x, 1: -x
        const auto y = static_cast<std::uint32_t>(2 + sy);  // 2: +y, 3: -y
        const auto z = static_cast<std::uint32_t>(4 + sz);  // 4: +z, 5: -z
        const bool is_positive = ((sx + sy + sz) % 2) == 0;
        triangles.push_back(is_positive ? Triangle{x, y, z} : Triangle{x, z, y});
      }
    }
  }
  return {std::move(vertices), std::move(triangles)};
}

ConvexPolyhedron make_regular_tetrahedron(double radius) {
  require_positive("tetrahedron radius", radius);
  const double s = radius / std::sqrt(3.0);
  std::vector<Vec3> vertices = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return {std::move(vertices), std::move(triangles)};
}

CheckResult check_closed_manifold(const ConvexPolyhedron& body) {
  std::size_t edge_count = 0;
  try {
    edge_count = body.edges().size();
  } catch (const InvalidInput& error) {
    return {false, error.what()};
  }
  std::vector<bool> is_used(body.vertex_count(), false);
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const auto& t = body.triangles()[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return {false, "triangle " + std::to_string(f) + " repeats a vertex"};
    }
    for (auto index : t) is_used[index] = true;
  }
  for (std::size_t v = 0; v < is_used.size(); ++v) {
    if (!is_used[v]) return {false, "vertex " + std::to_string(v) + " is in no triangle"};
  }
  const auto euler = static_cast<long long>(body.vertex_count()) -
                     static_cast<long long>(edge_count) +
                     static_cast<long long>(body.triangle_count());
  if (euler != 2) return {false, "V - E + F = " + std::to_string(euler) + ", expected 2"};
  return {};
}

CheckResult check_convex(const ConvexPolyhedron& body, double tolerance) {
  const auto& vertices = body.vertices();
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 scaled_normal = body.face_normal_scaled(f);
    const double twice_area = scaled_normal.norm();
    if (!(twice_area > 0.0)) return {false, "triangle " + std::to_string(f) + " has zero area"};
    const Vec3 normal = scaled_normal / twice_area;
    const double offset = normal.dot(vertices[body.triangles()[f][0]]);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const double height = normal.dot(vertices[v]) - offset;
      if (height > tolerance) {
        return {false, "vertex " + std::to_string(v) + " lies " + format_value(height) +
                           " in front of triangle " + std::to_string(f)};
      }
    }
  }
  if (!(mass_properties(body).volume > 0.0)) return {false, "volume is not positive"};
  return {};
}

}  // namespace aggpack
