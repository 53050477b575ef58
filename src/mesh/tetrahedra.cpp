#include "aggpack/mesh/tetrahedra.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack {

namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

}  // namespace

void validate(const TetOptions& options) {
  if (!(options.max_volume >= 0.0) || !std::isfinite(options.max_volume)) {
    throw InvalidInput("max tetrahedron volume", format_value(options.max_volume),
                       ">= 0 m^3 (0 = no bound)");
  }
  require_in_range("radius-edge ratio", options.radius_edge_ratio, 1.2, 10.0);
}

double tetra_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

TetMesh centroid_fan(const ConvexPolyhedron& body) {
  if (body.is_empty()) throw InvalidInput("body", "empty", "a convex polyhedron");
  const MassProperties properties = mass_properties(body);
  if (!(properties.volume > 0.0)) {
    throw InvalidInput("body volume", format_value(properties.volume), "> 0");
  }
  TetMesh mesh;
  mesh.nodes.reserve(body.vertex_count() + 1);
  mesh.nodes = body.vertices();
  mesh.nodes.push_back(properties.centroid);
  const auto centre = static_cast<std::uint32_t>(body.vertex_count());
  mesh.tetrahedra.reserve(body.triangle_count());
  for (const auto& t : body.triangles()) {
    // (a, c, b, centroid): a->c->b is clockwise from outside, i.e. counter-clockwise seen from the
    // centroid, which makes the tetrahedron positive and its face S1 the surface triangle.
    mesh.tetrahedra.push_back({t[0], t[2], t[1], centre});
  }
  mesh.boundary_faces.assign(mesh.tetrahedra.size(), 1);
  return mesh;
}

TetMesh tetrahedralize(const ConvexPolyhedron& body, const TetOptions& options) {
  validate(options);
  if (options.method == TetMethod::kTetGen) return tetgen_mesh(body, options);
  return centroid_fan(body);
}

QuadraticTetMesh make_quadratic(const TetMesh& mesh) {
  QuadraticTetMesh result;
  result.nodes = mesh.nodes;
  result.boundary_faces = mesh.boundary_faces;
  result.tetrahedra.reserve(mesh.tetrahedra.size());
  std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
  midpoints.reserve(mesh.tetrahedra.size() * 2);
  for (const auto& tet : mesh.tetrahedra) {
    std::array<std::uint32_t, 10> element{};
    for (int k = 0; k < 4; ++k) element[k] = tet[k];
    for (int e = 0; e < 6; ++e) {
      const std::uint32_t a = tet[kTetraEdges[e][0]];
      const std::uint32_t b = tet[kTetraEdges[e][1]];
      const auto [it, is_new] =
          midpoints.try_emplace(edge_key(a, b), static_cast<std::uint32_t>(result.nodes.size()));
      if (is_new) result.nodes.push_back(0.5 * (mesh.nodes[a] + mesh.nodes[b]));
      element[4 + e] = it->second;
    }
    result.tetrahedra.push_back(element);
  }
  return result;
}

double mesh_volume(const TetMesh& mesh) {
  double volume = 0.0;
  for (const auto& t : mesh.tetrahedra) {
    volume += tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
  }
  return volume;
}

double min_tetra_volume(const TetMesh& mesh) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.tetrahedra) {
    smallest = std::min(smallest, tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]],
                                               mesh.nodes[t[3]]));
  }
  return smallest;
}

TetMeshCounts count(const TetMesh& mesh) {
  std::vector<std::uint64_t> edges;
  edges.reserve(mesh.tetrahedra.size() * 6);
  for (const auto& tet : mesh.tetrahedra) {
    for (const auto& e : kTetraEdges) edges.push_back(edge_key(tet[e[0]], tet[e[1]]));
  }
  std::sort(edges.begin(), edges.end());
  const auto unique_end = std::unique(edges.begin(), edges.end());
  return {.nodes = mesh.nodes.size(),
          .tetrahedra = mesh.tetrahedra.size(),
          .edges = static_cast<std::size_t>(unique_end - edges.begin())};
}

}  // namespace aggpack
