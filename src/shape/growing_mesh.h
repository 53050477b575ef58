#pragma once
// The triangle mesh a particle grows in (shape/generator.cpp): twin half-edges, a heap of the
// edges longer than L, and the two growth rules' insertions of a new vertex. Internal to shape/.

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/shape/generator.h"

namespace aggpack::detail {

// A candidate edge in the max-heap: the undirected edge {from, to} with from < to. The longest
// edge wins; ties go to the smaller (from, to), so the order never depends on how the heap
// stores its entries.
struct EdgeEntry {
  double length_squared;
  std::uint32_t from;
  std::uint32_t to;
  bool operator<(const EdgeEntry& other) const {
    if (length_squared != other.length_squared) return length_squared < other.length_squared;
    if (from != other.from) return from > other.from;  // deterministic tie-break
    return to > other.to;
  }
};

// Adjacency as twins: twin[f][k] is the oppositely running half-edge of triangle f's edge k, in
// the neighbouring triangle (a half-edge is packed as face * 4 + position).
using Twins = std::array<std::uint32_t, 3>;

// The Eq. 3 distance (m) drawn for a new vertex in the unit direction from the centre.
using DrawDistance = std::function<double(const Vec3& direction)>;

// Triangle mesh with twin half-edges, grown one vertex at a time.
//
// Speed (bench/RESULTS.md, "Generator"): storage is reserved from the expected vertex count
// rather than the cap; adjacency is kept as twin half-edges, so an insertion rewires its
// neighbours without searching; the heap holds only edges longer than L (shorter ones can never
// be chosen) and is keyed by vertex pair, so an insertion pushes only its new edges. Under the
// midpoint rule no entry ever goes stale (an edge leaves the mesh only by being split, which pops
// it); under the hull rule an edge can vanish inside the replaced patch, and its entry is dropped
// when it reaches the top (vertices never move, so a live entry's length is still right).
class GrowingMesh {
 public:
  // The base octahedron (make_octahedron's vertex and triangle order) with the given six
  // vertices (+x, -x, +y, -y, +z, -z directions). Growth stops when every edge is <= edge_length;
  // the hull rule makes no edge shorter than min_edge_length to the new vertex (it splits the
  // edge instead).
  GrowingMesh(const std::array<Vec3, 6>& base, double edge_length, double min_edge_length,
              std::size_t expected_vertices);

  [[nodiscard]] std::size_t vertex_count() const { return live_vertices_; }

  // The longest live edge that is longer than L; false when every edge is within L.
  bool longest_edge(EdgeEntry& entry);

  // Midpoint rule: the new vertex on the ray from the origin through the edge midpoint, at the
  // drawn distance clamped so that only the edge's two faces are replaced, then by `limit`.
  void split_midpoint(const EdgeEntry& entry, const DrawDistance& draw, const GrowthLimit& limit);

  // Hull rule: the point at fraction t of the edge from `from` to `to`, moved out along the ray
  // from the origin to the drawn distance, or as far as `limit` allows (never inward of the
  // edge); the mesh becomes the convex hull of itself and the new vertex.
  void insert_hull(const EdgeEntry& entry, double t, const DrawDistance& draw,
                   const GrowthLimit& limit);

  // The grown body (dropped vertices removed, faces compacted).
  ConvexPolyhedron release();

 private:
  [[noreturn]] static void broken();
  void set_twin(std::uint32_t half, std::uint32_t twin);
  // The half-edge from -> to, by turning around `from`, or kNone when the edge does not exist.
  [[nodiscard]] std::uint32_t find_outgoing(std::uint32_t from, std::uint32_t to) const;
  // Splits the edge's two faces at a new vertex `point` (four faces; no other face changes).
  void split_at(std::uint32_t ab, const Vec3& point);
  std::uint32_t add_vertex(const Vec3& point);
  std::uint32_t new_face();
  // Heap entries for the new vertex's edges to `neighbours` that are longer than L.
  void push_edges_of(std::uint32_t vertex, const std::uint32_t* neighbours, std::size_t count);
  void insert(const EdgeEntry& entry);
  void pop();

  double limit_squared_;
  double min_edge_squared_;
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<Twins> twins_;
  std::vector<std::uint32_t> corner_faces_;   // one face containing each vertex
  std::vector<EdgeEntry> heap_;               // edges longer than L
  std::vector<std::uint8_t> is_dead_vertex_;  // hull rule: vertices that ended up inside
  std::vector<std::uint8_t> is_free_face_;    // hull rule: slots of replaced faces
  std::vector<std::uint32_t> free_faces_;
  std::size_t live_vertices_ = 6;
  // Scratch of insert_hull, kept between calls (an insertion allocates nothing).
  struct Border {
    std::uint32_t from, to, across;  // a half-edge of the replaced patch's border and its twin
  };
  std::vector<std::uint32_t> visible_;
  std::vector<std::uint32_t> loop_;
  std::vector<Border> border_;
  std::vector<std::uint32_t> fan_;
  std::vector<std::uint8_t> is_visible_;
};

}  // namespace aggpack::detail
