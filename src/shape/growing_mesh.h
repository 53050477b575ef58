#pragma once
// The triangle mesh a particle grows in (shape/generator.cpp): twin half-edges, a queue of the
// edges longer than L (edge_queue.h), and the two growth rules' insertions of a new vertex.
// Internal to shape/.

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/shape/generator.h"
#include "edge_queue.h"

namespace aggpack::detail {

// A candidate edge: the undirected edge {from, to} with from < to and its squared length.
struct EdgeEntry {
  double length_squared;
  std::uint32_t from;
  std::uint32_t to;
};

// Adjacency as twins: twin[f][k] is the oppositely running half-edge of triangle f's edge k, in
// the neighbouring triangle (a half-edge is packed as face * 4 + position).
using Twins = std::array<std::uint32_t, 3>;

// The Eq. 3 distance (m) drawn for a new vertex in the unit direction from the centre.
using DrawDistance = std::function<double(const Vec3& direction)>;

// Triangle mesh with twin half-edges, grown one vertex at a time.
//
// Speed (bench/RESULTS.md, "Generator" and "Hull growth vs the midpoint rule"): storage is
// reserved from the expected vertex count rather than the cap; adjacency is kept as twin
// half-edges, so an insertion rewires its neighbours without searching; the queue holds only
// edges longer than L (shorter ones can never be chosen), as 128-bit keys (squared length, then
// the vertex pair: one integer comparison) binned by length over a small heap (EdgeQueue), so an
// insertion pushes only its new edges. Under the midpoint rule no entry ever goes stale (an edge
// leaves the mesh only by being split, which pops it); under the hull rule an edge can vanish
// inside the replaced patch, and its entry is dropped when it reaches the top (vertices never move,
// so a live entry's length is still right; keys are distinct, so the order of the live edges never
// depends on stale ones). The hull rule's visibility walk tests each face once per insertion (faces
// are stamped with the insertion's number instead of flags that need resetting), keeps each face's
// normal once computed (the same arithmetic as before: the bits do not change), collects the
// patch's border during the walk and chains it into a loop through a per-vertex link.
class GrowingMesh {
 public:
  // Starts a particle: the base octahedron (make_octahedron's vertex and triangle order) with
  // the given six vertices (+x, -x, +y, -y, +z, -z directions). Growth stops when every edge is
  // <= edge_length; the hull rule makes no edge shorter than min_edge_length to the new vertex (it
  // splits the edge instead). Storage is kept from the previous particle (a mesh kept per thread
  // allocates nothing once warm).
  void reset(const std::array<Vec3, 6>& base, double edge_length, double min_edge_length,
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
  // A heap key: the squared length's bits (positive doubles order as their bits) above the
  // complemented vertex pair, so the larger key is the longer edge, ties to the smaller pair.
  using Key = EdgeQueue::Key;
  static Key key_of(const EdgeEntry& entry);
  static EdgeEntry entry_of(Key key);
  // A face's plane as the hull rule tests it: the normal (v1 - v0) x (v2 - v0) and its squared
  // norm (negative: not computed since the face was last written).
  struct Plane {
    Vec3 normal;
    double norm_squared;
  };

  [[noreturn]] static void broken();
  void set_twin(std::uint32_t half, std::uint32_t twin);
  // The half-edge from -> to, by turning around `from`, or kNone when the edge does not exist.
  [[nodiscard]] std::uint32_t find_outgoing(std::uint32_t from, std::uint32_t to) const;
  // The half-edge of the heap's top entry (found by longest_edge, or searched now).
  std::uint32_t top_half(const EdgeEntry& entry);
  // Splits the edge's two faces at a new vertex `point` (four faces; no other face changes).
  void split_at(std::uint32_t ab, const Vec3& point);
  // The faces `point` sees, from the edge's two faces (visible_) and the patch's border
  // (border_, in walk order); false when one of the edge's faces does not see it.
  bool find_visible(std::uint32_t ab, const Vec3& point, double tolerance_squared);
  // Chains border_ into sides_ from its first half-edge; false unless the patch is a disk.
  bool chain_border();
  // Replaces the visible patch by a fan from the new vertex `point` to its border loop (sides_,
  // with the squared lengths from `point` set).
  void replace_patch(const Vec3& point);
  std::uint32_t add_vertex(const Vec3& point);
  std::uint32_t new_face();
  // The per-vertex and per-face arrays other than vertices_ and triangles_ are kept at least as
  // long as those (grown by doubling, never shrunk: a slot is set when its vertex or face is made).
  void grow_vertex_arrays(std::size_t count);
  void grow_face_arrays(std::size_t count);
  // Heap entries for the new vertex's edges to `neighbours` that are longer than L.
  void push_edges_of(std::uint32_t vertex, const std::uint32_t* neighbours, std::size_t count);

  double limit_squared_ = 0.0;
  double min_edge_squared_ = 0.0;
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<Twins> twins_;
  std::vector<Plane> planes_;
  std::vector<std::uint32_t> corner_faces_;   // one face containing each vertex
  EdgeQueue queue_;                           // edges longer than L
  std::vector<std::uint8_t> is_dead_vertex_;  // hull rule: vertices that ended up inside
  std::vector<std::uint8_t> is_free_face_;    // hull rule: slots of replaced faces
  std::vector<std::uint32_t> free_faces_;
  std::size_t live_vertices_ = 6;
  std::uint32_t top_half_ = 0xFFFFFFFFU;  // the half-edge of the heap's top, when known
  bool may_be_stale_ = false;             // a patch was replaced: heap entries may be stale
  // Scratch of insert_hull, kept between calls (an insertion allocates nothing). Faces and
  // vertices are stamped with the insertion's number: a face stamped 2 s + 1 sees the new vertex,
  // 2 s was tested and does not; a vertex stamped s is on the border or inside the patch.
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> face_stamps_;
  std::vector<std::uint32_t> vertex_stamps_;
  std::vector<std::uint32_t> border_next_;  // per vertex (as many as vertex_stamps_): the border
                                            // half-edge leaving it
  std::vector<std::uint32_t> visible_;      // the patch's faces (the first visible_count_)
  std::vector<std::uint32_t> border_;       // its border half-edges (the first border_count_)
  std::size_t visible_count_ = 0;
  std::size_t border_count_ = 0;
  struct Side {
    std::uint32_t from, to, across;  // a border half-edge's ends and its twin (outside the patch)
    double length_squared;           // from the new vertex to `from` (set by insert_hull)
  };
  std::vector<Side> sides_;  // the border as a loop (the first border_count_)
  std::vector<std::uint32_t> fan_;
};

}  // namespace aggpack::detail
