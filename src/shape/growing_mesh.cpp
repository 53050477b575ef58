#include "growing_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "aggpack/core/error.h"

namespace aggpack::detail {

namespace {

constexpr std::uint32_t kNone = 0xFFFFFFFFU;

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

// Distances below this fraction of the particle's size count as zero in the hull rule's
// visibility test (rounding of a plane through three vertices).
constexpr double kRelativeTolerance = 1e-12;

// Insertions are stamped 2 s and 2 s + 1 on faces: s starts again below 2^31.
constexpr std::uint32_t kLastStamp = 0x7FFFFFF0U;

}  // namespace

void GrowingMesh::reset(const std::array<Vec3, 6>& base, double edge_length, double min_edge_length,
                        std::size_t expected_vertices) {
  limit_squared_ = edge_length * edge_length;
  min_edge_squared_ = min_edge_length * min_edge_length;
  const std::size_t expected_faces = 2 * expected_vertices;
  vertices_.reserve(expected_vertices);
  triangles_.reserve(expected_faces);
  queue_.reset(limit_squared_);
  free_faces_.clear();
  live_vertices_ = 6;
  top_half_ = kNone;
  may_be_stale_ = false;
  if (stamp_ > kLastStamp) {  // the stamps start again (stale ones must not match)
    std::fill(face_stamps_.begin(), face_stamps_.end(), 0);
    std::fill(vertex_stamps_.begin(), vertex_stamps_.end(), 0);
    stamp_ = 0;
  }
  vertices_.assign(base.begin(), base.end());
  triangles_.assign(kBase.triangles.begin(), kBase.triangles.end());
  grow_vertex_arrays(std::max(expected_vertices, vertices_.size()));
  grow_face_arrays(std::max(expected_faces, triangles_.size()));
  std::copy(kBase.twins.begin(), kBase.twins.end(), twins_.begin());
  std::copy(kBase.corner_faces.begin(), kBase.corner_faces.end(), corner_faces_.begin());
  std::fill_n(is_dead_vertex_.begin(), vertices_.size(), 0);
  std::fill_n(is_free_face_.begin(), triangles_.size(), 0);
  for (std::size_t f = 0; f < triangles_.size(); ++f) planes_[f].norm_squared = -1.0;
  for (const auto& t : kBase.triangles) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t from = t[k];
      const std::uint32_t to = t[kNext[k]];
      if (from > to) continue;  // each edge once
      const double length_squared = (vertices_[from] - vertices_[to]).squaredNorm();
      if (length_squared > limit_squared_) queue_.push(key_of({length_squared, from, to}));
    }
  }
}

// The private members called per insertion are defined `inline`: the library is compiled with
// -fPIC, and GCC does not inline a function with external linkage there (another definition could
// interpose it), so each call, even set_twin's one store, cost a call (-8 to -11 % instructions
// in the hull growth, bench/RESULTS.md). The arithmetic is the same: the bits do not change.
inline GrowingMesh::Key GrowingMesh::key_of(const EdgeEntry& entry) {
  const auto pair = (static_cast<std::uint64_t>(~entry.from) << 32U) | (~entry.to);
  return (static_cast<Key>(std::bit_cast<std::uint64_t>(entry.length_squared)) << 64U) | pair;
}

inline EdgeEntry GrowingMesh::entry_of(Key key) {
  const auto pair = static_cast<std::uint64_t>(key);
  return {std::bit_cast<double>(static_cast<std::uint64_t>(key >> 64U)),
          ~static_cast<std::uint32_t>(pair >> 32U), ~static_cast<std::uint32_t>(pair)};
}

bool GrowingMesh::longest_edge(EdgeEntry& entry) {
  while (!queue_.empty()) {
    entry = entry_of(queue_.top());
    // Only the hull rule removes edges; a removed edge's entry is dropped here.
    if (!may_be_stale_) {
      top_half_ = kNone;
      return true;
    }
    if (is_dead_vertex_[entry.from] == 0 && is_dead_vertex_[entry.to] == 0) {
      top_half_ = find_outgoing(entry.from, entry.to);
      if (top_half_ != kNone) return true;
    }
    queue_.pop();
  }
  return false;
}

inline std::uint32_t GrowingMesh::top_half(const EdgeEntry& entry) {
  const std::uint32_t half = top_half_ != kNone ? top_half_ : find_outgoing(entry.from, entry.to);
  if (half == kNone) broken();
  top_half_ = kNone;
  return half;
}

void GrowingMesh::split_midpoint(const EdgeEntry& entry, const DrawDistance& draw,
                                 const GrowthLimit& limit) {
  const std::uint32_t ab = top_half(entry);
  const std::uint32_t f1 = face_of(ab);
  const std::uint32_t k1 = local_of(ab);
  const std::uint32_t f2 = face_of(twins_[f1][k1]);
  const std::uint32_t k2 = local_of(twins_[f1][k1]);
  // The faces across the border of the patch {f1, f2}.
  const std::array<std::uint32_t, 4> across = {twins_[f1][kNext[k1]], twins_[f1][kPrev[k1]],
                                               twins_[f2][kNext[k2]], twins_[f2][kPrev[k2]]};
  const Vec3 midpoint = 0.5 * (vertices_[entry.from] + vertices_[entry.to]);
  const double midpoint_distance = midpoint.norm();
  const Vec3 direction = midpoint / midpoint_distance;
  // The new vertex must see exactly faces f1 and f2 (then the result is the convex hull of the
  // old body and the vertex: two faces replaced by four, no other face cut). It is in front of
  // f1 and f2 for any s >= |midpoint|; the faces it sees form a connected patch, so it sees no
  // other face as long as it stays behind the four faces across the patch's border.
  double distance = std::max(draw(direction), midpoint_distance);
  for (const std::uint32_t half : across) {
    const auto& t = triangles_[face_of(half)];
    const Vec3 normal =
        (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]);
    const double approach = normal.dot(direction);
    if (approach > 0.0) distance = std::min(distance, normal.dot(vertices_[t[0]]) / approach);
  }
  if (limit) distance = std::min(distance, limit(direction, midpoint_distance, distance));
  distance = std::max(distance, midpoint_distance);
  queue_.pop();
  split_at(ab, distance * direction);
}

inline void GrowingMesh::split_at(std::uint32_t ab, const Vec3& point) {
  // f1 holds a -> b, f2 holds b -> a; c and d are their third vertices.
  const std::uint32_t f1 = face_of(ab);
  const std::uint32_t k1 = local_of(ab);
  const std::uint32_t a = triangles_[f1][k1];
  const std::uint32_t b = triangles_[f1][kNext[k1]];
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

  const std::uint32_t p = add_vertex(point);
  const auto f3 = new_face();
  const auto f4 = new_face();
  triangles_[f1] = {a, p, c};
  triangles_[f3] = {p, b, c};
  triangles_[f2] = {b, p, d};
  triangles_[f4] = {p, a, d};
  for (const std::uint32_t face : {f1, f2, f3, f4}) planes_[face].norm_squared = -1.0;
  twins_[f1] = {half_edge(f4, 0), half_edge(f3, 2), across_ca};
  twins_[f3] = {half_edge(f2, 0), across_bc, half_edge(f1, 1)};
  twins_[f2] = {half_edge(f3, 0), half_edge(f4, 2), across_db};
  twins_[f4] = {half_edge(f1, 0), across_ad, half_edge(f2, 1)};
  set_twin(across_bc, half_edge(f3, 1));
  set_twin(across_ca, half_edge(f1, 2));
  set_twin(across_ad, half_edge(f4, 1));
  set_twin(across_db, half_edge(f2, 2));
  // f1 lost b and f2 lost a; every vertex of the split keeps a face it lies on.
  corner_faces_[a] = f1;
  corner_faces_[c] = f1;
  corner_faces_[b] = f2;
  corner_faces_[d] = f2;
  corner_faces_[p] = f1;
  // The four new edges (p is the largest index). The outer edges bc, ca, ad, db are unchanged.
  const std::array<std::uint32_t, 4> neighbours = {a, b, c, d};
  push_edges_of(p, neighbours.data(), neighbours.size());
}

void GrowingMesh::insert_hull(const EdgeEntry& entry, double t, const DrawDistance& draw,
                              const GrowthLimit& limit) {
  const std::uint32_t ab = top_half(entry);
  queue_.pop();
  const Vec3 on_edge = vertices_[entry.from] + t * (vertices_[entry.to] - vertices_[entry.from]);
  const double on_edge_distance = on_edge.norm();
  const Vec3 direction = on_edge / on_edge_distance;
  double distance = std::max(draw(direction), on_edge_distance);
  if (limit) {
    distance = std::max(std::min(distance, limit(direction, on_edge_distance, distance)),
                        on_edge_distance);
  }
  const Vec3 point = distance * direction;
  // Never inward of the edge: at (or numerically at) the edge the vertex only splits it.
  if (!(distance > on_edge_distance * (1.0 + kRelativeTolerance))) {
    split_at(ab, on_edge);
    return;
  }
  // In front of a face's plane by more than the tolerance (compared squared: no square root).
  const double tolerance_squared = kRelativeTolerance * kRelativeTolerance * distance * distance;
  // Rounding can make the patch other than a disk (or the vertex lie in the plane of one of the
  // edge's faces); then, too, the vertex splits the edge.
  if (!find_visible(ab, point, tolerance_squared) || !chain_border()) {
    split_at(ab, on_edge);
    return;
  }
  // The minimum edge length: a new vertex that would come closer than it to a vertex it joins
  // (a short edge, thin triangles around it) splits the edge instead.
  // The squared lengths are kept for the new edges' heap entries.
  for (std::size_t i = 0; i < border_count_; ++i) {
    Side& side = sides_[i];
    side.length_squared = (vertices_[side.from] - point).squaredNorm();
    if (side.length_squared < min_edge_squared_) {
      split_at(ab, on_edge);
      return;
    }
  }
  replace_patch(point);
}

inline bool GrowingMesh::find_visible(std::uint32_t ab, const Vec3& point,
                                      double tolerance_squared) {
  // The faces the new vertex sees: a connected patch (the body is convex) that holds the edge's
  // two faces; found by a walk from them across edges, each face tested once.
  stamp_ += 1;
  const std::uint32_t seen = 2 * stamp_ + 1;
  const std::uint32_t unseen = 2 * stamp_;
  const std::size_t faces = triangles_.size();
  if (visible_.size() < faces) {
    visible_.resize(faces);
    border_.resize(3 * faces);
  }
  const Triangle* triangles = triangles_.data();
  const Twins* twins = twins_.data();
  const Vec3* vertices = vertices_.data();
  Plane* planes = planes_.data();
  std::uint32_t* stamps = face_stamps_.data();
  std::uint32_t* visible = visible_.data();
  std::uint32_t* border = border_.data();
  const auto sees = [&](std::uint32_t face) {
    const Triangle& tri = triangles[face];
    Plane& plane = planes[face];
    if (plane.norm_squared < 0.0) {
      plane.normal =
          (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]);
      plane.norm_squared = plane.normal.squaredNorm();
    }
    const double height = plane.normal.dot(point - vertices[tri[0]]);
    return height > 0.0 && height * height > tolerance_squared * plane.norm_squared;
  };
  std::size_t visible_count = 0;
  for (const std::uint32_t face : {face_of(ab), face_of(twins[face_of(ab)][local_of(ab)])}) {
    if (!sees(face)) return false;  // the vertex lies in the face's plane after rounding
    stamps[face] = seen;
    visible[visible_count++] = face;
  }
  // The patch's border: half-edges of visible faces whose twin is not visible, in the order of
  // the walk.
  std::size_t border_count = 0;
  for (std::size_t i = 0; i < visible_count; ++i) {
    const std::uint32_t face = visible[i];
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t next = face_of(twins[face][k]);
      const std::uint32_t stamp = stamps[next];
      if (stamp == seen) continue;
      if (stamp != unseen) {
        if (sees(next)) {
          stamps[next] = seen;
          visible[visible_count++] = next;
          continue;
        }
        stamps[next] = unseen;
      }
      border[border_count++] = half_edge(face, k);
    }
  }
  visible_count_ = visible_count;
  border_count_ = border_count;
  return true;
}

inline bool GrowingMesh::chain_border() {
  // The border as one loop from its first half-edge: each border vertex must have exactly one
  // border half-edge leaving it (else the patch is pinched there), and the loop must use them all
  // (else there is more than one). The loop goes to sides_ (ends and outer twin of each step).
  const Triangle* triangles = triangles_.data();
  const Twins* twins = twins_.data();
  const std::uint32_t* border = border_.data();
  std::uint32_t* stamps = vertex_stamps_.data();
  std::uint32_t* next = border_next_.data();
  const std::size_t count = border_count_;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t half = border[i];
    const std::uint32_t from = triangles[face_of(half)][local_of(half)];
    if (stamps[from] == stamp_) return false;
    stamps[from] = stamp_;
    next[from] = half;
  }
  if (sides_.size() < count) sides_.resize(count);
  Side* sides = sides_.data();
  const std::uint32_t first = border[0];
  std::uint32_t half = first;
  std::size_t length = 0;
  do {
    const Triangle& tri = triangles[face_of(half)];
    const std::uint32_t to = tri[kNext[local_of(half)]];
    sides[length++] = {tri[local_of(half)], to, twins[face_of(half)][local_of(half)], 0.0};
    half = next[to];
  } while (half != first && length < count);
  return half == first && length == count;
}

inline void GrowingMesh::replace_patch(const Vec3& point) {
  // The patch's inner vertices are dropped (the border's are stamped), its faces freed, and a fan
  // of new faces joins the new vertex to the loop. Freed faces are taken back last in, first out:
  // the fan takes the patch's faces from its last, then older free faces, then new ones.
  const std::uint32_t* visible = visible_.data();
  const std::size_t m = visible_count_;
  {
    const Triangle* triangles = triangles_.data();
    std::uint32_t* stamps = vertex_stamps_.data();
    for (std::size_t i = 0; i < m; ++i) {
      for (const std::uint32_t v : triangles[visible[i]]) {
        if (stamps[v] != stamp_) {
          stamps[v] = stamp_;
          is_dead_vertex_[v] = 1;
          --live_vertices_;
        }
      }
    }
  }
  may_be_stale_ = true;
  const std::size_t n = border_count_;
  const std::uint32_t p = add_vertex(point);
  if (fan_.size() < n) fan_.resize(n);
  std::uint32_t* fan = fan_.data();
  const std::size_t reused = std::min(m, n);
  for (std::size_t i = 0; i < reused; ++i) fan[i] = visible[m - 1 - i];
  for (std::size_t i = 0; i + reused < m; ++i) {
    is_free_face_[visible[i]] = 1;
    free_faces_.push_back(visible[i]);
  }
  for (std::size_t i = reused; i < n; ++i) fan[i] = new_face();
  const Side* sides = sides_.data();
  Triangle* triangles = triangles_.data();
  Twins* twins = twins_.data();
  Plane* planes = planes_.data();
  std::uint32_t* corners = corner_faces_.data();
  for (std::size_t i = 0; i < n; ++i) {
    const Side& side = sides[i];
    const std::uint32_t face = fan[i];
    triangles[face] = {side.from, side.to, p};
    planes[face].norm_squared = -1.0;
    // Edge 1 (to -> p) meets the next fan face's edge 2 (p -> its from = this to).
    twins[face] = {side.across, half_edge(fan[i + 1 == n ? 0 : i + 1], 2),
                   half_edge(fan[i == 0 ? n - 1 : i - 1], 1)};
    twins[face_of(side.across)][local_of(side.across)] = half_edge(face, 0);
    corners[side.from] = face;
  }
  corners[p] = fan[0];
  // The new vertex's edges to the loop.
  for (std::size_t i = 0; i < n; ++i) {
    const double length_squared = sides[i].length_squared;
    if (length_squared > limit_squared_) queue_.push(key_of({length_squared, sides[i].from, p}));
  }
}

ConvexPolyhedron GrowingMesh::release() {
  if (!may_be_stale_ && free_faces_.empty()) {
    // Exactly sized copies: the working vectors were reserved from an estimate.
    return {std::vector<Vec3>(vertices_.begin(), vertices_.end()),
            std::vector<Triangle>(triangles_.begin(), triangles_.end())};
  }
  std::uint32_t* index = border_next_.data();  // scratch: the kept vertices' new indices
  std::vector<Vec3> vertices;
  vertices.reserve(live_vertices_);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (is_dead_vertex_[v] != 0) continue;
    index[v] = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(vertices_[v]);
  }
  std::vector<Triangle> triangles;
  triangles.reserve(triangles_.size() - free_faces_.size());
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    if (is_free_face_[f] != 0) continue;
    const Triangle& t = triangles_[f];
    triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  }
  return {std::move(vertices), std::move(triangles)};
}

void GrowingMesh::broken() {
  throw Error(ErrorKind::kInvalidInput, Wording{Sentence::kBrokenAdjacency, {}});
}

inline void GrowingMesh::set_twin(std::uint32_t half, std::uint32_t twin) {
  twins_[face_of(half)][local_of(half)] = twin;
}

inline std::uint32_t GrowingMesh::find_outgoing(std::uint32_t from, std::uint32_t to) const {
  // The twin of the edge that enters `from` is the next edge that leaves it.
  std::uint32_t face = corner_faces_[from];
  std::uint32_t k = find_corner(triangles_[face], from);
  if (k == 3) broken();
  const std::uint32_t first = face;
  for (std::size_t step = 0; step < triangles_.size(); ++step) {
    if (triangles_[face][kNext[k]] == to) return half_edge(face, k);
    const std::uint32_t next = twins_[face][kPrev[k]];
    face = face_of(next);
    k = local_of(next);
    if (face == first) return kNone;
  }
  broken();
}

inline std::uint32_t GrowingMesh::add_vertex(const Vec3& point) {
  const auto p = static_cast<std::uint32_t>(vertices_.size());
  vertices_.push_back(point);
  if (p >= corner_faces_.size()) grow_vertex_arrays(2 * static_cast<std::size_t>(p));
  corner_faces_[p] = 0;
  is_dead_vertex_[p] = 0;
  ++live_vertices_;
  return p;
}

inline std::uint32_t GrowingMesh::new_face() {
  if (!free_faces_.empty()) {
    const std::uint32_t face = free_faces_.back();
    free_faces_.pop_back();
    is_free_face_[face] = 0;
    return face;
  }
  const auto face = static_cast<std::uint32_t>(triangles_.size());
  triangles_.emplace_back();
  if (face >= twins_.size()) grow_face_arrays(2 * static_cast<std::size_t>(face));
  planes_[face].norm_squared = -1.0;
  is_free_face_[face] = 0;
  return face;
}

void GrowingMesh::grow_vertex_arrays(std::size_t count) {
  if (corner_faces_.size() >= count) return;
  corner_faces_.resize(count);
  is_dead_vertex_.resize(count);
  vertex_stamps_.resize(count, 0);
  border_next_.resize(count);
}

void GrowingMesh::grow_face_arrays(std::size_t count) {
  if (twins_.size() >= count) return;
  twins_.resize(count);
  planes_.resize(count, Plane{Vec3::Zero(), -1.0});
  face_stamps_.resize(count, 0);
  is_free_face_.resize(count);
}

inline void GrowingMesh::push_edges_of(std::uint32_t vertex, const std::uint32_t* neighbours,
                                       std::size_t count) {
  const Vec3& point = vertices_[vertex];
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t v = neighbours[i];
    const double length_squared = (vertices_[v] - point).squaredNorm();
    if (length_squared > limit_squared_) queue_.push(key_of({length_squared, v, vertex}));
  }
}

}  // namespace aggpack::detail
