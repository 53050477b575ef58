#include "aggpack/shape/generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>
#include <string>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

constexpr std::uint32_t kVertexCapLimit = 1000000;

// A candidate edge in the max-heap, identified by the half-edge (face, local) that ran u -> v when
// it was pushed. Entries go stale when faces are rewritten; they are checked when popped.
struct EdgeEntry {
  double length_squared;
  std::uint32_t face;
  std::uint32_t local;
  std::uint32_t from;
  std::uint32_t to;
  bool operator<(const EdgeEntry& other) const {
    if (length_squared != other.length_squared) return length_squared < other.length_squared;
    if (from != other.from) return from > other.from;  // deterministic tie-break
    return to > other.to;
  }
};

// Triangle mesh with face adjacency: neighbour[f][k] is the face across the edge
// triangle[f][k] -> triangle[f][(k+1)%3].
class GrowingMesh {
 public:
  GrowingMesh(const ConvexPolyhedron& base, std::uint32_t vertex_capacity) {
    vertices_ = base.vertices();
    triangles_ = base.triangles();
    vertices_.reserve(vertex_capacity);
    triangles_.reserve(2 * static_cast<std::size_t>(vertex_capacity));
    neighbours_.assign(triangles_.size(), {0, 0, 0});
    for (const auto& edge : base.edges()) {
      set_neighbour(edge.faces[0], edge.vertices[0], edge.vertices[1], edge.faces[1]);
      set_neighbour(edge.faces[1], edge.vertices[1], edge.vertices[0], edge.faces[0]);
    }
    for (std::uint32_t f = 0; f < triangles_.size(); ++f) {
      for (std::uint32_t k = 0; k < 3; ++k) push(f, k);
    }
  }

  [[nodiscard]] std::size_t vertex_count() const { return vertices_.size(); }

  // Pops stale entries; returns false when no edge is left (never happens for a closed mesh).
  bool longest_edge(EdgeEntry& entry) {
    while (!heap_.empty()) {
      entry = heap_.top();
      const auto& t = triangles_[entry.face];
      if (t[entry.local] == entry.from && t[(entry.local + 1) % 3] == entry.to) return true;
      heap_.pop();
    }
    return false;
  }

  // Splits the edge of `entry` with a new vertex on the ray from the origin through the edge
  // midpoint, at distance `drawn` clamped so that the body stays convex (and within `limit`).
  void split(const EdgeEntry& entry, double drawn, const GrowthLimit& limit) {
    heap_.pop();
    const std::uint32_t f1 = entry.face;
    const std::uint32_t k1 = entry.local;
    const std::uint32_t a = triangles_[f1][k1];
    const std::uint32_t b = triangles_[f1][(k1 + 1) % 3];
    const std::uint32_t c = triangles_[f1][(k1 + 2) % 3];
    const std::uint32_t f2 = neighbours_[f1][k1];
    const std::uint32_t k2 = local_index(f2, b, a);
    const std::uint32_t d = triangles_[f2][(k2 + 2) % 3];
    const std::uint32_t across_bc = neighbours_[f1][(k1 + 1) % 3];
    const std::uint32_t across_ca = neighbours_[f1][(k1 + 2) % 3];
    const std::uint32_t across_ad = neighbours_[f2][(k2 + 1) % 3];
    const std::uint32_t across_db = neighbours_[f2][(k2 + 2) % 3];

    const Vec3 midpoint = 0.5 * (vertices_[a] + vertices_[b]);
    const double midpoint_distance = midpoint.norm();
    const Vec3 direction = midpoint / midpoint_distance;
    // The new vertex must see exactly faces f1 and f2 (then the result is the convex hull of the
    // old body and the vertex: two faces replaced by four, no other face cut). It is in front of
    // f1 and f2 for any s >= |midpoint|; the faces it sees form a connected patch, so it sees no
    // other face as long as it stays behind the four faces across the patch's border.
    double distance = std::max(drawn, midpoint_distance);
    for (const std::uint32_t face : {across_bc, across_ca, across_ad, across_db}) {
      const auto& t = triangles_[face];
      const Vec3 normal = (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]);
      const double approach = normal.dot(direction);
      if (approach > 0.0) distance = std::min(distance, normal.dot(vertices_[t[0]]) / approach);
    }
    if (limit) distance = std::min(distance, limit(direction, midpoint_distance, distance));
    distance = std::max(distance, midpoint_distance);

    const auto p = static_cast<std::uint32_t>(vertices_.size());
    vertices_.push_back(distance * direction);
    const auto f3 = static_cast<std::uint32_t>(triangles_.size());
    const std::uint32_t f4 = f3 + 1;
    triangles_[f1] = {a, p, c};
    triangles_.push_back({p, b, c});  // f3
    triangles_[f2] = {b, p, d};
    triangles_.push_back({p, a, d});  // f4
    neighbours_[f1] = {f4, f3, across_ca};
    neighbours_.push_back({f2, across_bc, f1});
    neighbours_[f2] = {f3, f4, across_db};
    neighbours_.push_back({f1, across_ad, f2});
    set_neighbour(across_bc, c, b, f3);
    set_neighbour(across_ad, d, a, f4);
    set_neighbour(across_ca, a, c, f1);
    set_neighbour(across_db, b, d, f2);
    for (const std::uint32_t face : {f1, f2, f3, f4}) {
      for (std::uint32_t k = 0; k < 3; ++k) push(face, k);
    }
  }

  ConvexPolyhedron release() { return {std::move(vertices_), std::move(triangles_)}; }

 private:
  [[nodiscard]] std::uint32_t local_index(std::uint32_t face, std::uint32_t from,
                                          std::uint32_t to) const {
    const auto& t = triangles_[face];
    for (std::uint32_t k = 0; k < 3; ++k) {
      if (t[k] == from && t[(k + 1) % 3] == to) return k;
    }
    throw Error(ErrorKind::kInvalidInput, "internal: broken adjacency in aggregate growth");
  }
  void set_neighbour(std::uint32_t face, std::uint32_t from, std::uint32_t to,
                     std::uint32_t neighbour) {
    neighbours_[face][local_index(face, from, to)] = neighbour;
  }
  void push(std::uint32_t face, std::uint32_t k) {
    const std::uint32_t from = triangles_[face][k];
    const std::uint32_t to = triangles_[face][(k + 1) % 3];
    // Each undirected edge is pushed from the face where it runs low -> high, so once.
    if (from > to) return;
    heap_.push({(vertices_[from] - vertices_[to]).squaredNorm(), face, k, from, to});
  }

  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<std::array<std::uint32_t, 3>> neighbours_;
  std::priority_queue<EdgeEntry> heap_;
};

}  // namespace

double eq3_distance(double alpha, double radius, double u) {
  return radius * (alpha + (1.0 - alpha) * (0.2 + 0.8 * u));
}

double estimated_vertex_count(double radius, double edge_length) {
  // Sphere area / equilateral triangle area = faces; V = F/2 + 2 for a closed triangulation.
  const double faces = 4.0 * std::numbers::pi * radius * radius /
                       (std::sqrt(3.0) / 4.0 * edge_length * edge_length);
  return std::max(6.0, faces / 2.0 + 2.0);
}

void validate(const GrowthParams& params) {
  require_in_range("alpha", params.alpha, 0.0, 1.0);
  require_positive("radius", params.radius);
  require_positive("edge_length", params.edge_length);
  if (params.max_vertices < 6 || params.max_vertices > kVertexCapLimit) {
    throw InvalidInput("max_vertices", std::to_string(params.max_vertices),
                       "[6, " + std::to_string(kVertexCapLimit) + "]");
  }
  const double estimate = estimated_vertex_count(params.radius, params.edge_length);
  if (estimate > params.max_vertices) {
    throw LimitExceeded("edge_length", format_value(params.edge_length),
                        ">= about " +
                            format_value(params.radius * std::sqrt(4.0 * std::numbers::pi /
                                                                   (std::sqrt(3.0) / 4.0) /
                                                                   (2.0 * params.max_vertices))) +
                            " m for radius " + format_value(params.radius) + " m: needs about " +
                            format_value(std::round(estimate)) + " vertices, max_vertices is " +
                            std::to_string(params.max_vertices));
  }
}

ConvexPolyhedron grow_aggregate(const GrowthParams& params, Rng& rng, const GrowthLimit& limit) {
  validate(params);
  std::array<double, 6> distances{};
  for (auto& d : distances) d = eq3_distance(params.alpha, params.radius, rng.uniform());
  GrowingMesh mesh(make_octahedron(distances), params.max_vertices);
  const double limit_squared = params.edge_length * params.edge_length;
  EdgeEntry longest{};
  while (mesh.longest_edge(longest) && longest.length_squared > limit_squared) {
    if (mesh.vertex_count() >= params.max_vertices) {
      throw LimitExceeded("max_vertices", std::to_string(params.max_vertices),
                          "a larger cap or a longer edge_length (growth still had edges of " +
                              format_value(std::sqrt(longest.length_squared)) + " m > L = " +
                              format_value(params.edge_length) + " m)");
    }
    mesh.split(longest, eq3_distance(params.alpha, params.radius, rng.uniform()), limit);
  }
  return mesh.release();
}

void validate(const GeneratorOptions& options) {
  require_in_range("alpha", options.alpha, 0.0, 1.0);
  require_positive("radius_min", options.radius_min);
  require_positive("radius_max", options.radius_max);
  if (options.radius_max < options.radius_min) {
    throw InvalidInput("radius_max", format_value(options.radius_max),
                       ">= radius_min = " + format_value(options.radius_min));
  }
  // The smallest edge-to-radius ratio is the hardest case for the vertex cap.
  validate(GrowthParams{.alpha = options.alpha,
                        .radius = options.radius_max,
                        .edge_length = options.edge_length,
                        .max_vertices = options.max_vertices});
}

GeneratedParticle generate_particle(const GeneratorOptions& options, std::uint64_t index) {
  Rng rng(options.seed, index);
  const double radius = options.radius_min == options.radius_max
                            ? options.radius_min
                            : rng.uniform(options.radius_min, options.radius_max);
  GrowthParams params{.alpha = options.alpha,
                      .radius = radius,
                      .edge_length = options.edge_length,
                      .max_vertices = options.max_vertices};
  return {grow_aggregate(params, rng), radius};
}

}  // namespace aggpack
