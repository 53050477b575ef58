#include "aggpack/mesh/tetrahedra.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
  require_in_range("TetGen time limit (s)", options.time_limit, 1e-3, 7 * 24 * 3600.0);
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
  for (const auto& t : body.triangles()) mesh.tetrahedra.push_back(fan_tetrahedron(t, centre));
  mesh.boundary_faces.assign(mesh.tetrahedra.size(), 1);
  return mesh;
}

TetMesh tetrahedralize(const ConvexPolyhedron& body, const TetOptions& options) {
  validate(options);
  if (options.method == TetMethod::kTetGen) return tetgen_mesh(body, options);
  return centroid_fan(body);
}

QuadraticTopology quadratic_topology(std::span<const Tetrahedron> tetrahedra,
                                     std::uint32_t corner_count) {
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  QuadraticTopology topology;
  topology.tetrahedra.reserve(tetrahedra.size());
  // The edges met so far, chained per lower corner (edge i is mid-side node corner_count + i):
  // a corner has a few dozen edges at most, so walking its chain beats hashing, and the exports
  // call this once or twice per particle.
  std::vector<std::uint32_t> first_edge(corner_count, kNone);
  std::vector<std::uint32_t> next_edge;
  next_edge.reserve(tetrahedra.size() * 2 + corner_count);
  topology.midside_edges.reserve(next_edge.capacity());
  for (const auto& tet : tetrahedra) {
    std::array<std::uint32_t, 10> element{};
    for (int k = 0; k < 4; ++k) element[k] = tet[k];
    for (int e = 0; e < 6; ++e) {
      const std::uint32_t a = tet[kTetraEdges[e][0]];
      const std::uint32_t b = tet[kTetraEdges[e][1]];
      const std::uint32_t low = std::min(a, b);
      const std::uint32_t high = std::max(a, b);
      std::uint32_t edge = first_edge[low];
      while (edge != kNone &&
             std::max(topology.midside_edges[edge][0], topology.midside_edges[edge][1]) != high) {
        edge = next_edge[edge];
      }
      if (edge == kNone) {
        edge = static_cast<std::uint32_t>(topology.midside_edges.size());
        topology.midside_edges.push_back({a, b});
        next_edge.push_back(first_edge[low]);
        first_edge[low] = edge;
      }
      element[4 + e] = corner_count + edge;
    }
    topology.tetrahedra.push_back(element);
  }
  return topology;
}

void append_midside_nodes(const QuadraticTopology& topology, std::vector<Vec3>& nodes) {
  nodes.reserve(nodes.size() + topology.midside_edges.size());
  for (const auto& [a, b] : topology.midside_edges) {
    const Vec3 midpoint = 0.5 * (nodes[a] + nodes[b]);
    nodes.push_back(midpoint);
  }
}

QuadraticTetMesh make_quadratic(const TetMesh& mesh) {
  QuadraticTopology topology =
      quadratic_topology(mesh.tetrahedra, static_cast<std::uint32_t>(mesh.nodes.size()));
  QuadraticTetMesh result;
  result.nodes = mesh.nodes;
  append_midside_nodes(topology, result.nodes);
  result.tetrahedra = std::move(topology.tetrahedra);
  result.boundary_faces = mesh.boundary_faces;
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
