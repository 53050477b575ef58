#include "aggpack/shape/generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

constexpr std::uint32_t kVertexCapLimit = 1000000;
// Safety factor of estimated_vertex_count over the sphere tiling (see there).
constexpr double kVertexCountMargin = 3.0;

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

// Position of the half-edge from -> to in triangle t (0..2), or 3 if t does not contain it.
constexpr std::uint32_t find_half_edge(const Triangle& t, std::uint32_t from, std::uint32_t to) {
  if (t[0] == from && t[1] == to) return 0;
  if (t[1] == from && t[2] == to) return 1;
  if (t[2] == from && t[0] == to) return 2;
  return 3;
}

// Position of vertex v in triangle t (0..2), or 3.
constexpr std::uint32_t find_corner(const Triangle& t, std::uint32_t v) {
  return t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : 3;
}

// A half-edge named by its face and position: triangle[face][local] -> triangle[face][local+1].
// Packed as face * 4 + local (faces stay below 2^30: the vertex cap is 10^6).
constexpr std::uint32_t half_edge(std::uint32_t face, std::uint32_t local) {
  return (face << 2) | local;
}
constexpr std::uint32_t face_of(std::uint32_t half) { return half >> 2; }
constexpr std::uint32_t local_of(std::uint32_t half) { return half & 3U; }

// Adjacency as twins: twin[f][k] is the oppositely running half-edge of triangle f's edge k, in
// the neighbouring triangle.
using Twins = std::array<std::uint32_t, 3>;

// The base octahedron's topology, the same for every particle: make_octahedron's triangles (same
// order), their twins, and one triangle at each vertex.
struct BaseTopology {
  std::array<Triangle, 8> triangles{};
  std::array<Twins, 8> twins{};
  std::array<std::uint32_t, 6> corner_faces{};
};

constexpr BaseTopology make_base_topology() {
  BaseTopology base;
  std::uint32_t f = 0;
  for (std::uint32_t sx = 0; sx < 2; ++sx) {
    for (std::uint32_t sy = 0; sy < 2; ++sy) {
      for (std::uint32_t sz = 0; sz < 2; ++sz) {
        const std::uint32_t x = sx;      // 0: +x, 1: -x
        const std::uint32_t y = 2 + sy;  // 2: +y, 3: -y
        const std::uint32_t z = 4 + sz;  // 4: +z, 5: -z
        const bool is_positive = ((sx + sy + sz) % 2) == 0;
        base.triangles[f++] = is_positive ? Triangle{x, y, z} : Triangle{x, z, y};
      }
    }
  }
  for (std::uint32_t face = 0; face < 8; ++face) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t from = base.triangles[face][k];
      const std::uint32_t to = base.triangles[face][(k + 1) % 3];
      for (std::uint32_t other = 0; other < 8; ++other) {
        const std::uint32_t j = find_half_edge(base.triangles[other], to, from);
        if (j < 3) base.twins[face][k] = half_edge(other, j);
      }
      base.corner_faces[from] = face;
    }
  }
  return base;
}

constexpr BaseTopology kBase = make_base_topology();

// Next and previous position in a triangle (cheaper than % 3 on a variable).
constexpr std::array<std::uint32_t, 3> kNext = {1, 2, 0};
constexpr std::array<std::uint32_t, 3> kPrev = {2, 0, 1};

// Triangle mesh with twin half-edges, grown one split at a time.
//
// Speed (bench/RESULTS.md, "Generator"): storage is reserved from the expected vertex count
// rather than the cap; adjacency is kept as twin half-edges, so a split rewires its neighbours
// without searching; the heap holds only edges longer than L (shorter ones can never be chosen)
// and is keyed by vertex pair, so a split pushes only its new edges and no entry ever goes
// stale (an edge leaves the mesh only by being split, which pops it, and never comes back:
// growth only adds vertices); the face of the chosen edge is found by turning around its first
// vertex. None of this changes which edge is split or where the new vertex goes: the results
// are bit-identical to the plain version (a golden-hash test in tests/shape pins them).
class GrowingMesh {
 public:
  GrowingMesh(const std::array<double, 6>& distances, double edge_length,
              std::size_t expected_vertices)
      : limit_squared_(edge_length * edge_length) {
    const std::size_t expected_faces = 2 * expected_vertices;
    vertices_.reserve(expected_vertices);
    triangles_.reserve(expected_faces);
    twins_.reserve(expected_faces);
    corner_faces_.reserve(expected_vertices);
    heap_.reserve(expected_faces);
    // The octahedron of make_octahedron, same vertex and triangle order.
    vertices_ = {{distances[0], 0, 0},  {-distances[1], 0, 0}, {0, distances[2], 0},
                 {0, -distances[3], 0}, {0, 0, distances[4]},  {0, 0, -distances[5]}};
    triangles_.assign(kBase.triangles.begin(), kBase.triangles.end());
    twins_.assign(kBase.twins.begin(), kBase.twins.end());
    corner_faces_.assign(kBase.corner_faces.begin(), kBase.corner_faces.end());
    for (const auto& t : kBase.triangles) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t from = t[k];
        const std::uint32_t to = t[kNext[k]];
        if (from > to) continue;  // each edge once
        const double length_squared = (vertices_[from] - vertices_[to]).squaredNorm();
        if (length_squared > limit_squared_) insert({length_squared, from, to});
      }
    }
  }

  [[nodiscard]] std::size_t vertex_count() const { return vertices_.size(); }

  // The longest edge that is longer than L; false when every edge is within L.
  bool longest_edge(EdgeEntry& entry) const {
    if (heap_.empty()) return false;
    entry = heap_.front();
    return true;
  }

  // Splits the edge of `entry` (the heap's top) with a new vertex on the ray from the origin
  // through the edge midpoint, at distance `drawn` clamped so that the body stays convex (and
  // within `limit`).
  void split(const EdgeEntry& entry, double drawn, const GrowthLimit& limit) {
    pop();
    // f1 holds a -> b (a < b), f2 holds b -> a; c and d are their third vertices.
    const std::uint32_t ab = find_outgoing(entry.from, entry.to);
    const std::uint32_t f1 = face_of(ab);
    const std::uint32_t k1 = local_of(ab);
    const std::uint32_t a = entry.from;
    const std::uint32_t b = entry.to;
    const std::uint32_t c = triangles_[f1][kPrev[k1]];
    const std::uint32_t ba = twins_[f1][k1];
    const std::uint32_t f2 = face_of(ba);
    const std::uint32_t k2 = local_of(ba);
    const std::uint32_t d = triangles_[f2][kPrev[k2]];
    // The half-edges across the border of the patch {f1, f2}: c -> b, a -> c, d -> a, b -> d.
    const std::uint32_t across_bc = twins_[f1][kNext[k1]];
    const std::uint32_t across_ca = twins_[f1][kPrev[k1]];
    const std::uint32_t across_ad = twins_[f2][kNext[k2]];
    const std::uint32_t across_db = twins_[f2][kPrev[k2]];

    const Vec3 midpoint = 0.5 * (vertices_[a] + vertices_[b]);
    const double midpoint_distance = midpoint.norm();
    const Vec3 direction = midpoint / midpoint_distance;
    // The new vertex must see exactly faces f1 and f2 (then the result is the convex hull of the
    // old body and the vertex: two faces replaced by four, no other face cut). It is in front of
    // f1 and f2 for any s >= |midpoint|; the faces it sees form a connected patch, so it sees no
    // other face as long as it stays behind the four faces across the patch's border.
    double distance = std::max(drawn, midpoint_distance);
    for (const std::uint32_t across : {across_bc, across_ca, across_ad, across_db}) {
      const auto& t = triangles_[face_of(across)];
      const Vec3 normal =
          (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]);
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
    twins_[f1] = {half_edge(f4, 0), half_edge(f3, 2), across_ca};
    twins_.push_back({half_edge(f2, 0), across_bc, half_edge(f1, 1)});  // f3
    twins_[f2] = {half_edge(f3, 0), half_edge(f4, 2), across_db};
    twins_.push_back({half_edge(f1, 0), across_ad, half_edge(f2, 1)});  // f4
    set_twin(across_bc, half_edge(f3, 1));
    set_twin(across_ca, half_edge(f1, 2));
    set_twin(across_ad, half_edge(f4, 1));
    set_twin(across_db, half_edge(f2, 2));
    // f1 lost b and f2 lost a; every vertex of the split keeps a face it lies on.
    corner_faces_[a] = f1;
    corner_faces_[c] = f1;
    corner_faces_[b] = f2;
    corner_faces_[d] = f2;
    corner_faces_.push_back(f1);
    // The four new edges (p is the largest index). The outer edges bc, ca, ad, db are unchanged.
    const Vec3& new_vertex = vertices_[p];
    for (const std::uint32_t v : {a, b, c, d}) {
      const double length_squared = (vertices_[v] - new_vertex).squaredNorm();
      if (length_squared > limit_squared_) insert({length_squared, v, p});
    }
  }

  ConvexPolyhedron release() {
    // Exactly sized copies: the working vectors were reserved from an estimate.
    return {std::vector<Vec3>(vertices_.begin(), vertices_.end()),
            std::vector<Triangle>(triangles_.begin(), triangles_.end())};
  }

 private:
  [[noreturn]] static void broken() {
    throw Error(ErrorKind::kInvalidInput, "internal: broken adjacency in aggregate growth");
  }
  void set_twin(std::uint32_t half, std::uint32_t twin) {
    twins_[face_of(half)][local_of(half)] = twin;
  }
  // The half-edge from -> to, by turning around `from`: the twin of the edge that enters `from`
  // is the next edge that leaves it.
  [[nodiscard]] std::uint32_t find_outgoing(std::uint32_t from, std::uint32_t to) const {
    std::uint32_t face = corner_faces_[from];
    std::uint32_t k = find_corner(triangles_[face], from);
    if (k == 3) broken();
    for (std::size_t step = 0; step < triangles_.size(); ++step) {
      if (triangles_[face][kNext[k]] == to) return half_edge(face, k);
      const std::uint32_t next = twins_[face][kPrev[k]];
      face = face_of(next);
      k = local_of(next);
    }
    broken();
  }
  // Adds an edge longer than L to the heap: a binary max-heap, sifted up by hand (as
  // std::push_heap does).
  void insert(const EdgeEntry& entry) {
    std::size_t hole = heap_.size();
    heap_.push_back(entry);
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 2;
      if (!(heap_[parent] < entry)) break;
      heap_[hole] = heap_[parent];
      hole = parent;
    }
    heap_[hole] = entry;
  }
  // Removes the top of the heap: the last entry sifts down from the root.
  void pop() {
    const EdgeEntry last = heap_.back();
    heap_.pop_back();
    const std::size_t size = heap_.size();
    if (size == 0) return;
    std::size_t hole = 0;
    for (;;) {
      std::size_t child = 2 * hole + 1;
      if (child >= size) break;
      if (child + 1 < size && heap_[child] < heap_[child + 1]) ++child;
      if (!(last < heap_[child])) break;
      heap_[hole] = heap_[child];
      hole = child;
    }
    heap_[hole] = last;
  }

  double limit_squared_;
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<Twins> twins_;
  std::vector<std::uint32_t> corner_faces_;  // one face containing each vertex
  std::vector<EdgeEntry> heap_;              // edges longer than L
};

}  // namespace

double eq3_distance(double alpha, double radius, double u) {
  return radius * (alpha + (1.0 - alpha) * (0.2 + 0.8 * u));
}

double estimated_vertex_count(double radius, double edge_length) {
  // Adjacent base vertices lie on perpendicular half-axes within r, so every base edge is at most
  // sqrt(2) r: a longer L means no growth at all.
  if (edge_length >= std::sqrt(2.0) * radius * (1.0 + 1e-12)) return 6.0;
  // Sphere area / equilateral triangle area = faces; V = F/2 + 2 for a closed triangulation.
  // Growth ends with edges between about L/2 and L, so real counts exceed this tiling: measured
  // over alpha in [0, 1] and L/r in [0.05, 1.41] they reach 2.77 times it (alpha 1, L/r 1.4; 2.0
  // to 2.5 times for L/r <= 0.5), hence the factor 3.
  const double faces =
      4.0 * std::numbers::pi * radius * radius / (std::sqrt(3.0) / 4.0 * edge_length * edge_length);
  return std::max(6.0, kVertexCountMargin * (faces / 2.0 + 2.0));
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
    // The smallest L whose estimate fits the cap (inverting estimated_vertex_count).
    const double no_growth = std::sqrt(2.0) * params.radius * (1.0 + 1e-12);
    const double half_faces = params.max_vertices / kVertexCountMargin - 2.0;
    const double smallest =
        half_faces <= 0.0 ? no_growth
                          : std::min(no_growth, params.radius * std::sqrt(4.0 * std::numbers::pi /
                                                                          (std::sqrt(3.0) / 4.0) /
                                                                          (2.0 * half_faces)));
    throw LimitExceeded("edge_length", format_value(params.edge_length),
                        ">= about " + format_value(smallest) + " m for radius " +
                            format_value(params.radius) + " m: may need up to " +
                            format_value(std::round(estimate)) + " vertices, max_vertices is " +
                            std::to_string(params.max_vertices));
  }
}

ConvexPolyhedron grow_aggregate(const GrowthParams& params, Rng& rng, const GrowthLimit& limit) {
  validate(params);
  std::array<double, 6> distances{};
  for (auto& d : distances) d = eq3_distance(params.alpha, params.radius, rng.uniform());
  // Reserve for the estimate, not for the cap: a 20,000-vertex reservation per particle costs more
  // in page faults than the growth itself.
  const auto expected = static_cast<std::size_t>(
      std::min(estimated_vertex_count(params.radius, params.edge_length) + 16.0,
               static_cast<double>(params.max_vertices) + 1.0));
  GrowingMesh mesh(distances, params.edge_length, expected);
  EdgeEntry longest{};
  while (mesh.longest_edge(longest)) {
    if (mesh.vertex_count() >= params.max_vertices) {
      throw LimitExceeded("max_vertices", std::to_string(params.max_vertices),
                          "a larger cap or a longer edge_length (growth still had edges of " +
                              format_value(std::sqrt(longest.length_squared)) +
                              " m > L = " + format_value(params.edge_length) + " m)");
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
