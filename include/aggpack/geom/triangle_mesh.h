#pragma once
// TriangleMesh: an indexed triangle mesh as read from a file (any shape, not necessarily convex),
// and the checks an imported particle must pass: closed, 2-manifold, non-degenerate, one piece.

#include <string>
#include <vector>

#include "aggpack/core/error_words.h"
#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Vertices + triangles (0-based indices into `vertices`), in the file's units.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

/// Why a mesh cannot be a particle, or is_ok. Checks, in this order: at least 4 triangles and
/// every index in range; no triangle with a repeated vertex or an area below 1e-12 of the
/// squared bounding-box diagonal ("zero-area"); every edge in exactly two triangles ("open" when
/// one, "non-manifold" when more) that run it in opposite directions ("inconsistently
/// oriented"); every vertex's triangles form one fan ("non-manifold vertex"); one connected piece.
/// The message names the first fault found, with a triangle / vertex index (0-based).
struct MeshCheck {
  bool is_ok = true;
  std::string message;  ///< "is open: edge (3, 7) belongs to triangle 5 only (a hole)"
  Wording wording;      ///< its sentence, whose first value (the file) the caller puts first
};
MeshCheck check_particle_mesh(const TriangleMesh& mesh);

/// Enclosed volume of a closed, consistently oriented mesh (divergence theorem): positive when
/// the triangles face outward, negative when all face inward.
double mesh_volume(const TriangleMesh& mesh);

}  // namespace aggpack
