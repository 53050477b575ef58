// Structural checks of an imported particle mesh (closed, 2-manifold, non-degenerate, one piece).

#include "aggpack/geom/triangle_mesh.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "aggpack/core/error_words.h"

namespace aggpack {

namespace {

// A fault in one sentence, which names the file first ("{}: mesh is open: ..."): the message is
// the rest after "mesh " ("is open: ...").
MeshCheck fail(Sentence sentence, std::vector<std::string> values) {
  std::vector<std::string> with_file = values;
  with_file.insert(with_file.begin(), "");
  std::string message = fill_words(english_words(sentence), with_file);
  message.erase(0, 7);  // ": mesh "
  return {.is_ok = false, .message = message, .wording = {sentence, std::move(values)}};
}

std::string mesh_number(std::size_t number) { return std::to_string(number); }

// Union-find over vertices (path halving), for the vertex fans and the pieces.
class Pieces {
 public:
  explicit Pieces(std::size_t count) : parent_(count) {
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace

MeshCheck check_particle_mesh(const TriangleMesh& mesh) {
  const auto& vertices = mesh.vertices;
  const auto& triangles = mesh.triangles;
  if (triangles.size() < 4) {
    return fail(Sentence::kMeshTriangleCount, {mesh_number(triangles.size())});
  }
  Aabb bounds;
  for (const Vec3& v : vertices) {
    if (!v.allFinite()) return fail(Sentence::kMeshNonFinite, {});
    bounds.expand(v);
  }
  const double diagonal_squared = bounds.extent().squaredNorm();
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (const std::uint32_t v : t) {
      if (v >= vertices.size()) {
        return fail(Sentence::kMeshTriangleVertex,
                    {mesh_number(f), mesh_number(v), mesh_number(vertices.size())});
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      return fail(Sentence::kMeshRepeatedVertex, {mesh_number(f)});
    }
    const Vec3 n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
    if (!(n.norm() > 1e-12 * diagonal_squared)) {
      return fail(Sentence::kMeshZeroArea, {mesh_number(f)});
    }
  }
  // Directed half-edges (from, to, face), sorted by their undirected key.
  struct Half {
    std::uint32_t low, high, from, face;
  };
  std::vector<Half> halves;
  halves.reserve(triangles.size() * 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[f][static_cast<std::size_t>(k)];
      const std::uint32_t b = triangles[f][static_cast<std::size_t>((k + 1) % 3)];
      halves.push_back({std::min(a, b), std::max(a, b), a, static_cast<std::uint32_t>(f)});
    }
  }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return std::tie(x.low, x.high, x.face) < std::tie(y.low, y.high, y.face);
  });
  for (std::size_t i = 0; i < halves.size();) {
    std::size_t j = i;
    while (j < halves.size() && halves[j].low == halves[i].low &&
           halves[j].high == halves[i].high) {
      ++j;
    }
    const std::size_t uses = j - i;
    const std::string low = mesh_number(halves[i].low);
    const std::string high = mesh_number(halves[i].high);
    if (uses == 1) return fail(Sentence::kMeshOpen, {low, high, mesh_number(halves[i].face)});
    if (uses > 2) return fail(Sentence::kMeshEdgeShared, {low, high, mesh_number(uses)});
    if (halves[i].from == halves[i + 1].from) {
      return fail(Sentence::kMeshOrientation,
                  {mesh_number(halves[i].face), mesh_number(halves[i + 1].face), low, high});
    }
    i = j;
  }
  // Each vertex's triangles must form a single fan: join a vertex's corners across the edges
  // at that vertex; more than one group at a vertex means two surfaces touch there.
  std::vector<std::uint32_t> corner_count(vertices.size(), 0);
  for (const Triangle& t : triangles) {
    for (const std::uint32_t v : t) ++corner_count[v];
  }
  Pieces corners(triangles.size() * 3);  // corner = face * 3 + k
  auto corner_of = [&](std::uint32_t face, std::uint32_t vertex) {
    const Triangle& t = triangles[face];
    const std::uint32_t k = t[0] == vertex ? 0u : (t[1] == vertex ? 1u : 2u);
    return face * 3 + k;
  };
  for (std::size_t i = 0; i < halves.size(); i += 2) {
    const Half& a = halves[i];
    const Half& b = halves[i + 1];
    corners.join(corner_of(a.face, a.low), corner_of(b.face, a.low));
    corners.join(corner_of(a.face, a.high), corner_of(b.face, a.high));
  }
  std::vector<std::int64_t> fan_of(vertices.size(), -1);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles[f][k];
      const auto root =
          static_cast<std::int64_t>(corners.find(static_cast<std::uint32_t>(f * 3 + k)));
      if (fan_of[v] < 0) {
        fan_of[v] = root;
      } else if (fan_of[v] != root) {
        return fail(Sentence::kMeshVertexSurfaces, {mesh_number(v)});
      }
    }
  }
  Pieces pieces(vertices.size());
  for (const Triangle& t : triangles) {
    pieces.join(t[0], t[1]);
    pieces.join(t[1], t[2]);
  }
  std::size_t piece_count = 0;
  for (std::uint32_t v = 0; v < vertices.size(); ++v) {
    if (corner_count[v] > 0 && pieces.find(v) == v) ++piece_count;
  }
  if (piece_count > 1) {
    return fail(Sentence::kMeshPieces, {mesh_number(piece_count)});
  }
  return {};
}

double mesh_volume(const TriangleMesh& mesh) {
  // Tetrahedra from the first vertex, not the origin: less cancellation far from the origin.
  if (mesh.vertices.empty()) return 0.0;
  const Vec3& apex = mesh.vertices.front();
  double volume = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - apex;
    const Vec3 b = mesh.vertices[t[1]] - apex;
    const Vec3 c = mesh.vertices[t[2]] - apex;
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

}  // namespace aggpack
