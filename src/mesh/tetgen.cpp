// TetGen quality meshing (Debian libtet1.5-dev). Built only when cmake/tetgen.cmake finds TetGen;
// otherwise tetgen_mesh() reports that this build cannot do it.
//
// TetGen runs only in worker processes (run_isolated): Debian's TetGen 1.5 fails assertions
// (abort) on ~0.3 % of generated shapes, e.g. `Assertion 'nonconvex' failed` in finddirection,
// and its exact predicates keep process-wide state that concurrent calls would race on; one
// single-threaded TetGen per process avoids both.

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <unordered_map>

#include "aggpack/core/error.h"
#include "aggpack/core/isolated.h"
#include "aggpack/mesh/tetrahedra.h"
#include "tetgen_worker.h"

#ifdef AGGPACK_HAS_TETGEN
#define TETLIBRARY
#include <tetgen.h>
#undef REAL
#endif

namespace aggpack {

#ifdef AGGPACK_HAS_TETGEN

namespace {

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

using Failure = detail::TetGenFailure;

// TetGen in this process: only ever called in a worker process. \throw Failure.
TetMesh mesh_here(const ConvexPolyhedron& body, const TetOptions& options) {
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
  // p: the input is a surface (PLC); Y: keep the surface triangles; q: radius-edge bound and
  // /10: smallest dihedral angle TetGen aims at; O7: optimisation level 7 (flips, smoothing,
  // vertex insertion); o/130: largest dihedral angle the optimisation accepts; a: volume bound;
  // z: number from 0; Q: quiet. The angle switches matter most: slivers have a dihedral angle
  // near 180 degrees, which TetGen's default target (165) tolerates. Measured on the paper's
  // packing (docs/formats.md): tetrahedra below 10 degrees 1.9 % -> 0.024 %, fewer tetrahedra.
  std::string switches = options.is_surface_kept ? "pYzQ" : "pzQ";
  char number[64];
  std::snprintf(number, sizeof number, "q%.6g/10O7o/130", options.radius_edge_ratio);
  switches += number;
  if (options.max_volume > 0.0) {
    std::snprintf(number, sizeof number, "a%.17g", options.max_volume);
    switches += number;
  }
  try {
    tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw detail::tetgen_failure({Sentence::kTetGenErrorCode, {std::to_string(code)}});
  }
  if (out.numberofcorners != 4 || out.numberoftetrahedra <= 0 ||
      out.numberofpoints < in.numberofpoints) {
    throw detail::tetgen_failure({Sentence::kTetGenNoTetrahedra, {}});
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
      throw Failure{"TetGen moved input vertex " + std::to_string(i), {}};
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

// A mesh as the worker sends it: node and tetrahedron counts, then the arrays.
using detail::append_array;

std::string serialize(const TetMesh& mesh) {
  const std::uint64_t counts[2] = {mesh.nodes.size(), mesh.tetrahedra.size()};
  std::string out(reinterpret_cast<const char*>(counts), sizeof counts);
  std::vector<double> coordinates;
  coordinates.reserve(3 * mesh.nodes.size());
  for (const Vec3& node : mesh.nodes)
    coordinates.insert(coordinates.end(), {node.x(), node.y(), node.z()});
  append_array(out, coordinates);
  append_array(out, mesh.tetrahedra);
  append_array(out, mesh.boundary_faces);
  return out;
}

template <class T>
const char* read_array(const char* in, std::vector<T>& values, std::size_t count) {
  values.resize(count);
  std::memcpy(values.data(), in, count * sizeof(T));
  return in + count * sizeof(T);
}

bool deserialize(const std::string& bytes, TetMesh& mesh) {
  std::uint64_t counts[2] = {0, 0};
  if (bytes.size() < sizeof counts) return false;
  std::memcpy(counts, bytes.data(), sizeof counts);
  const std::uint64_t expected = sizeof counts + counts[0] * 3 * sizeof(double) +
                                 counts[1] * (sizeof(Tetrahedron) + sizeof(std::uint8_t));
  if (bytes.size() != expected) return false;
  const char* in = bytes.data() + sizeof counts;
  std::vector<double> coordinates;
  in = read_array(in, coordinates, 3 * counts[0]);
  mesh.nodes.resize(counts[0]);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    mesh.nodes[i] = Vec3(coordinates[3 * i], coordinates[3 * i + 1], coordinates[3 * i + 2]);
  }
  in = read_array(in, mesh.tetrahedra, counts[1]);
  read_array(in, mesh.boundary_faces, counts[1]);
  for (const Tetrahedron& tet : mesh.tetrahedra) {
    for (const std::uint32_t node : tet) {
      if (node >= mesh.nodes.size()) return false;
    }
  }
  return true;
}

}  // namespace

std::vector<TetGenOutcome> tetgen_meshes(std::span<const ConvexPolyhedron* const> bodies,
                                         const TetOptions& options) {
  validate(options);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i] == nullptr || bodies[i]->is_empty()) {
      throw InvalidInput("body " + std::to_string(i), "empty", "a convex polyhedron");
    }
  }
  const auto work = [&](std::size_t i) {
    return detail::worker_answer([&] { return serialize(mesh_here(*bodies[i], options)); });
  };
  const std::vector<IsolatedOutcome> results =
      run_isolated(bodies.size(), work,
                   {.time_limit = options.time_limit,
                    .on_settled = options.on_progress != nullptr
                                      ? *options.on_progress
                                      : std::function<void(std::size_t, std::size_t)>()});
  std::vector<TetGenOutcome> outcomes(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    TetGenOutcome& outcome = outcomes[i];
    std::string bytes;
    if (!detail::worker_result(results[i], bytes, outcome.failure)) continue;
    if (deserialize(bytes, outcome.mesh)) {
      outcome.is_meshed = true;
    } else {
      outcome.mesh = {};
      outcome.failure = "malformed result from the worker process";
    }
  }
  return outcomes;
}

TetMesh tetgen_mesh(const ConvexPolyhedron& body, const TetOptions& options) {
  const ConvexPolyhedron* const bodies[1] = {&body};
  std::vector<TetGenOutcome> outcomes = tetgen_meshes(bodies, options);
  if (!outcomes[0].is_meshed) {
    throw LimitExceeded("tetgen", outcomes[0].failure,
                        "a shape TetGen can mesh (the centroid fan meshes every shape)");
  }
  return std::move(outcomes[0].mesh);
}

#else

std::vector<TetGenOutcome> tetgen_meshes(std::span<const ConvexPolyhedron* const> /*bodies*/,
                                         const TetOptions& options) {
  validate(options);
  throw InvalidInput("tetrahedra method", "tetgen",
                     "centroid-fan (this build has no TetGen: install libtet1.5-dev)");
}

TetMesh tetgen_mesh(const ConvexPolyhedron& /*body*/, const TetOptions& options) {
  validate(options);
  throw InvalidInput("tetrahedra method", "tetgen",
                     "centroid-fan (this build has no TetGen: install libtet1.5-dev)");
}

#endif

}  // namespace aggpack
