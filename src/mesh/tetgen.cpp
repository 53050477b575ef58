// TetGen quality meshing (Debian libtet1.5-dev). Built only when cmake/tetgen.cmake finds TetGen;
// otherwise tetgen_mesh() reports that this build cannot do it.

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>
#include <unordered_map>

#include "aggpack/core/error.h"
#include "aggpack/mesh/tetrahedra.h"

#ifdef AGGPACK_HAS_TETGEN
#define TETLIBRARY
#include <tetgen.h>
#undef REAL
#endif

namespace aggpack {

#ifdef AGGPACK_HAS_TETGEN

namespace {

// TetGen's exact predicates keep their error bounds in process-wide globals that every
// tetrahedralize() call re-initialises (exactinit); concurrent calls would race on them, so
// calls are serialised. Meshing is per shape and cached by the exporters, so this costs little.
std::mutex& tetgen_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::array<std::uint32_t, 3> sorted(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  std::array<std::uint32_t, 3> key{a, b, c};
  std::sort(key.begin(), key.end());
  return key;
}

struct TriangleKeyHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& key) const {
    return (static_cast<std::size_t>(key[0]) * 73856093U) ^
           (static_cast<std::size_t>(key[1]) * 19349663U) ^
           (static_cast<std::size_t>(key[2]) * 83492791U);
  }
};

}  // namespace

TetMesh tetgen_mesh(const ConvexPolyhedron& body, const TetOptions& options) {
  validate(options);
  if (body.is_empty()) throw InvalidInput("body", "empty", "a convex polyhedron");
  tetgenio in;
  tetgenio out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(body.vertex_count());
  in.pointlist = new double[3 * body.vertex_count()];
  for (std::size_t i = 0; i < body.vertex_count(); ++i) {
    for (int axis = 0; axis < 3; ++axis) in.pointlist[3 * i + axis] = body.vertices()[i][axis];
  }
  in.numberoffacets = static_cast<int>(body.triangle_count());
  in.facetlist = new tetgenio::facet[body.triangle_count()];
  in.facetmarkerlist = nullptr;
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) {
      facet.polygonlist[0].vertexlist[k] = static_cast<int>(body.triangles()[f][k]);
    }
  }
  // p: the input is a surface (PLC); Y: keep the surface triangles; q: radius-edge bound;
  // a: volume bound; z: number from 0; Q: quiet.
  std::string switches = options.is_surface_kept ? "pYzQ" : "pzQ";
  char number[64];
  std::snprintf(number, sizeof number, "q%.6g", options.radius_edge_ratio);
  switches += number;
  if (options.max_volume > 0.0) {
    std::snprintf(number, sizeof number, "a%.17g", options.max_volume);
    switches += number;
  }
  {
    std::lock_guard lock(tetgen_mutex());
    try {
      tetrahedralize(switches.data(), &in, &out);
    } catch (int code) {
      throw LimitExceeded("tetgen", "error code " + std::to_string(code),
                          "a valid closed surface; try a larger radius-edge ratio");
    }
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra <= 0 ||
      out.numberofpoints < in.numberofpoints) {
    throw LimitExceeded("tetgen", "no tetrahedra", "a closed surface with positive volume");
  }

  TetMesh mesh;
  mesh.nodes.resize(static_cast<std::size_t>(out.numberofpoints));
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    mesh.nodes[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
  }
  // TetGen keeps the input points first and in order; the exporters rely on it (node i = body
  // vertex i), so check rather than assume.
  for (std::size_t i = 0; i < body.vertex_count(); ++i) {
    if (mesh.nodes[i] != body.vertices()[i]) {
      throw LimitExceeded("tetgen", "moved input vertex " + std::to_string(i),
                          "input vertices kept in place");
    }
  }
  mesh.tetrahedra.resize(static_cast<std::size_t>(out.numberoftetrahedra));
  mesh.boundary_faces.assign(mesh.tetrahedra.size(), 0);
  // In a mesh of one solid body a face used by exactly one tetrahedron is on the surface.
  std::unordered_map<std::array<std::uint32_t, 3>, int, TriangleKeyHash> face_uses;
  face_uses.reserve(mesh.tetrahedra.size() * 4);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    auto& tet = mesh.tetrahedra[e];
    for (int k = 0; k < 4; ++k) tet[k] = static_cast<std::uint32_t>(out.tetrahedronlist[4 * e + k]);
    // TetGen's own orientation convention is the opposite of ours; fix by sign, not by belief.
    if (tetra_volume(mesh.nodes[tet[0]], mesh.nodes[tet[1]], mesh.nodes[tet[2]],
                     mesh.nodes[tet[3]]) < 0.0) {
      std::swap(tet[0], tet[1]);
    }
    for (const auto& face : kTetraFaces) {
      ++face_uses[sorted(tet[face[0]], tet[face[1]], tet[face[2]])];
    }
  }
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const auto& tet = mesh.tetrahedra[e];
    for (int k = 0; k < 4; ++k) {
      const auto& face = kTetraFaces[k];
      if (face_uses[sorted(tet[face[0]], tet[face[1]], tet[face[2]])] == 1) {
        mesh.boundary_faces[e] |= static_cast<std::uint8_t>(1U << k);
      }
    }
  }
  return mesh;
}

#else

TetMesh tetgen_mesh(const ConvexPolyhedron& /*body*/, const TetOptions& options) {
  validate(options);
  throw InvalidInput("tetrahedra method", "tetgen",
                     "centroid-fan (this build has no TetGen: install libtet1.5-dev)");
}

#endif

}  // namespace aggpack
