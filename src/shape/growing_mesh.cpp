#include "growing_mesh.h"

#include <algorithm>
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

}  // namespace

GrowingMesh::GrowingMesh(const std::array<Vec3, 6>& base, double edge_length,
                         double min_edge_length, std::size_t expected_vertices)
    : limit_squared_(edge_length * edge_length),
      min_edge_squared_(min_edge_length * min_edge_length) {
  const std::size_t expected_faces = 2 * expected_vertices;
  vertices_.reserve(expected_vertices);
  triangles_.reserve(expected_faces);
  twins_.reserve(expected_faces);
  corner_faces_.reserve(expected_vertices);
  heap_.reserve(expected_faces);
  vertices_.assign(base.begin(), base.end());
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

bool GrowingMesh::longest_edge(EdgeEntry& entry) {
  while (!heap_.empty()) {
    entry = heap_.front();
    // Only the hull rule removes edges; a removed edge's entry is dropped here.
    if (is_dead_vertex_.empty() ||
        (is_dead_vertex_[entry.from] == 0 && is_dead_vertex_[entry.to] == 0 &&
         find_outgoing(entry.from, entry.to) != kNone)) {
      return true;
    }
    pop();
  }
  return false;
}

void GrowingMesh::split_midpoint(const EdgeEntry& entry, const DrawDistance& draw,
                                 const GrowthLimit& limit) {
  const std::uint32_t ab = find_outgoing(entry.from, entry.to);
  if (ab == kNone) broken();
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
  pop();
  split_at(ab, distance * direction);
}

void GrowingMesh::split_at(std::uint32_t ab, const Vec3& point) {
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
  const std::uint32_t ab = find_outgoing(entry.from, entry.to);
  if (ab == kNone) broken();
  pop();
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

  // The faces the new vertex sees: a connected patch (the body is convex) that holds the edge's
  // two faces; found by a walk from them across edges.
  if (is_dead_vertex_.empty()) is_dead_vertex_.assign(vertices_.size(), 0);
  is_visible_.resize(triangles_.size(), 0);
  is_free_face_.resize(triangles_.size(), 0);
  // In front of a face's plane by more than the tolerance (compared squared: no square root).
  const double tolerance_squared = kRelativeTolerance * kRelativeTolerance * distance * distance;
  const auto sees = [&](std::uint32_t face) {
    const Triangle& tri = triangles_[face];
    const Vec3 normal =
        (vertices_[tri[1]] - vertices_[tri[0]]).cross(vertices_[tri[2]] - vertices_[tri[0]]);
    const double height = normal.dot(point - vertices_[tri[0]]);
    return height > 0.0 && height * height > tolerance_squared * normal.squaredNorm();
  };
  visible_.clear();
  for (const std::uint32_t face : {face_of(ab), face_of(twins_[face_of(ab)][local_of(ab)])}) {
    if (!sees(face)) {  // the vertex lies in the face's plane after rounding: split instead
      split_at(ab, on_edge);
      return;
    }
    is_visible_[face] = 1;
    visible_.push_back(face);
  }
  for (std::size_t i = 0; i < visible_.size(); ++i) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t next = face_of(twins_[visible_[i]][k]);
      if (is_visible_[next] == 0 && sees(next)) {
        is_visible_[next] = 1;
        visible_.push_back(next);
      }
    }
  }
  // Its border (half-edges of visible faces whose twin is not visible), walked as one loop: the
  // next border half-edge leaves the current one's end, found by turning about that vertex inside
  // the patch. Border vertices are marked 2 in is_dead_vertex_ (kept; reset below).
  const auto from_of = [&](std::uint32_t half) {
    return triangles_[face_of(half)][local_of(half)];
  };
  std::size_t border_count = 0;
  std::uint32_t first = kNone;
  for (const std::uint32_t face : visible_) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      if (is_visible_[face_of(twins_[face][k])] != 0) continue;
      ++border_count;
      if (first == kNone) first = half_edge(face, k);
    }
  }
  std::vector<std::uint32_t>& loop = loop_;
  loop.clear();
  bool is_disk = true;
  std::uint32_t half = first;
  do {
    const std::uint32_t from = from_of(half);
    if (is_dead_vertex_[from] == 2 || loop.size() == border_count) {
      is_disk = false;  // a vertex met twice (a pinched patch), or more than one loop
      break;
    }
    is_dead_vertex_[from] = 2;
    loop.push_back(half);
    std::uint32_t face = face_of(half);
    std::uint32_t k = kNext[local_of(half)];
    while (is_visible_[face_of(twins_[face][k])] != 0) {
      const std::uint32_t twin = twins_[face][k];
      face = face_of(twin);
      k = kNext[local_of(twin)];
    }
    half = half_edge(face, k);
  } while (half != first);
  // The minimum edge length: a new vertex that would come closer than it to a vertex it joins
  // (a short edge, thin triangles around it) splits the edge instead.
  const bool is_too_close = std::any_of(loop.begin(), loop.end(), [&](std::uint32_t h) {
    return (vertices_[from_of(h)] - point).squaredNorm() < min_edge_squared_;
  });
  // Rounding can make the patch other than a disk; then, too, the vertex splits the edge.
  if (!is_disk || loop.size() != border_count || is_too_close) {
    for (const std::uint32_t h : loop) is_dead_vertex_[from_of(h)] = 0;
    for (const std::uint32_t face : visible_) is_visible_[face] = 0;
    split_at(ab, on_edge);
    return;
  }

  // Replace the patch: its inner vertices are dropped, its faces freed, and a fan of new faces
  // joins the new vertex to the loop.
  std::vector<Border>& border = border_;
  border.clear();
  for (const std::uint32_t h : loop) {
    const Triangle& tri = triangles_[face_of(h)];
    border.push_back({tri[local_of(h)], tri[kNext[local_of(h)]], twins_[face_of(h)][local_of(h)]});
  }
  for (const std::uint32_t face : visible_) {
    for (const std::uint32_t v : triangles_[face]) {
      if (is_dead_vertex_[v] == 0) {
        is_dead_vertex_[v] = 1;
        --live_vertices_;
      }
    }
  }
  for (const Border& side : border) is_dead_vertex_[side.from] = 0;
  for (const std::uint32_t face : visible_) {
    is_visible_[face] = 0;
    is_free_face_[face] = 1;
    free_faces_.push_back(face);
  }
  const std::uint32_t p = add_vertex(point);
  const std::size_t n = border.size();
  std::vector<std::uint32_t>& fan = fan_;
  fan.resize(n);
  for (std::size_t i = 0; i < n; ++i) fan[i] = new_face();
  for (std::size_t i = 0; i < n; ++i) {
    const Border& side = border[i];
    const std::uint32_t face = fan[i];
    triangles_[face] = {side.from, side.to, p};
    // Edge 1 (to -> p) meets the next fan face's edge 2 (p -> its from = this to).
    twins_[face] = {side.across, half_edge(fan[(i + 1) % n], 2),
                    half_edge(fan[(i + n - 1) % n], 1)};
    set_twin(side.across, half_edge(face, 0));
    corner_faces_[side.from] = face;
  }
  corner_faces_[p] = fan[0];
  for (std::size_t i = 0; i < n; ++i) loop[i] = border[i].from;  // the new vertex's neighbours
  push_edges_of(p, loop.data(), n);
}

ConvexPolyhedron GrowingMesh::release() {
  if (is_dead_vertex_.empty() && free_faces_.empty()) {
    // Exactly sized copies: the working vectors were reserved from an estimate.
    return {std::vector<Vec3>(vertices_.begin(), vertices_.end()),
            std::vector<Triangle>(triangles_.begin(), triangles_.end())};
  }
  is_dead_vertex_.resize(vertices_.size(), 0);
  std::vector<std::uint32_t> index(vertices_.size(), kNone);
  std::vector<Vec3> vertices;
  vertices.reserve(live_vertices_);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (is_dead_vertex_[v] != 0) continue;
    index[v] = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(vertices_[v]);
  }
  is_free_face_.resize(triangles_.size(), 0);
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
  throw Error(ErrorKind::kInvalidInput, "internal: broken adjacency in aggregate growth");
}

void GrowingMesh::set_twin(std::uint32_t half, std::uint32_t twin) {
  twins_[face_of(half)][local_of(half)] = twin;
}

std::uint32_t GrowingMesh::find_outgoing(std::uint32_t from, std::uint32_t to) const {
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

std::uint32_t GrowingMesh::add_vertex(const Vec3& point) {
  const auto p = static_cast<std::uint32_t>(vertices_.size());
  vertices_.push_back(point);
  corner_faces_.push_back(0);
  if (!is_dead_vertex_.empty()) is_dead_vertex_.push_back(0);
  ++live_vertices_;
  return p;
}

std::uint32_t GrowingMesh::new_face() {
  if (!free_faces_.empty()) {
    const std::uint32_t face = free_faces_.back();
    free_faces_.pop_back();
    is_free_face_[face] = 0;
    return face;
  }
  const auto face = static_cast<std::uint32_t>(triangles_.size());
  triangles_.emplace_back();
  twins_.emplace_back();
  return face;
}

void GrowingMesh::push_edges_of(std::uint32_t vertex, const std::uint32_t* neighbours,
                                std::size_t count) {
  const Vec3& point = vertices_[vertex];
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t v = neighbours[i];
    const double length_squared = (vertices_[v] - point).squaredNorm();
    if (length_squared > limit_squared_) insert({length_squared, v, vertex});
  }
}

void GrowingMesh::insert(const EdgeEntry& entry) {
  // A binary max-heap, sifted up by hand (as std::push_heap does).
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

void GrowingMesh::pop() {
  // The last entry sifts down from the root.
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

}  // namespace aggpack::detail
