#pragma once
// Tetrahedral meshes of one convex particle: the paper's centroid fan (Section 4: "the centre
// joined to every surface triangle") and a quality mesh through TetGen (Debian libtet1.5-dev).
//
// Conventions shared by every exporter:
//  - Indices are 0-based here; writers add 1 for formats that count from 1.
//  - A tetrahedron (n0, n1, n2, n3) is positively oriented: det[n1-n0, n2-n0, n3-n0] > 0, i.e.
//    n0 -> n1 -> n2 is counter-clockwise seen from n3. This is the orientation Abaqus (C3D4),
//    CalculiX, VTK (VTK_TETRA), Gmsh (type 4) and LS-DYNA expect.
//  - Face k of a tetrahedron uses the local nodes kTetraFaces[k], the Abaqus/CalculiX face
//    numbering S1..S4 (S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1); in a positive
//    tetrahedron each face is counter-clockwise seen from the opposite node (its right-hand
//    normal points into the tetrahedron), so a surface triangle appears reversed in its face.
//  - The body's surface vertices come first, in the body's order, so node i < vertex_count is
//    vertex i of the ConvexPolyhedron; interior (and, for TetGen, no other) nodes follow.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Local node numbers of the four faces of a tetrahedron (Abaqus S1..S4), each inward CCW.
inline constexpr std::array<std::array<int, 3>, 4> kTetraFaces = {
    {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}}};

/// Node pairs of the six edges of a tetrahedron, in the order of the C3D10 / VTK_QUADRATIC_TETRA
/// mid-side nodes 5..10: (1,2), (2,3), (3,1), (1,4), (2,4), (3,4) (1-based).
inline constexpr std::array<std::array<int, 2>, 6> kTetraEdges = {
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

/// Four node numbers of a linear tetrahedron, positively oriented.
using Tetrahedron = std::array<std::uint32_t, 4>;

/// A tetrahedral mesh of one body. Lengths in the body's units (metres).
struct TetMesh {
  std::vector<Vec3> nodes;
  std::vector<Tetrahedron> tetrahedra;  ///< positively oriented
  /// Per tetrahedron: bit k set when face k (kTetraFaces[k]) lies on the body's surface.
  std::vector<std::uint8_t> boundary_faces;
};

/// A 10-node (quadratic) tetrahedral mesh: corner nodes as in TetMesh, then one node at the
/// middle of every edge. Element node order is the Abaqus C3D10 / VTK_QUADRATIC_TETRA order:
/// 4 corners, then the mid-side nodes of kTetraEdges.
struct QuadraticTetMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<std::uint32_t, 10>> tetrahedra;
  std::vector<std::uint8_t> boundary_faces;  ///< as in TetMesh
};

enum class TetMethod {
  kCentroidFan,  ///< the paper's: the centroid joined to every surface triangle (exact volume)
  kTetGen        ///< TetGen quality mesh, surface triangles kept (switch -Y)
};

/// How to cut a particle into tetrahedra.
struct TetOptions {
  TetMethod method = TetMethod::kCentroidFan;
  /// TetGen only: largest tetrahedron volume (m^3, in the body's units), 0 = no bound (>= 0).
  double max_volume = 0.0;
  /// TetGen only: bound on the radius-edge ratio (circumradius / shortest edge) of every
  /// tetrahedron, TetGen's -q. In [1.2, 10]; smaller = better shaped, more tetrahedra. The value
  /// is passed to TetGen as an upper bound; TetGen may leave a few slivers at the surface because
  /// the surface triangles are kept.
  double radius_edge_ratio = 2.0;
  /// TetGen only: keep the surface triangles exactly as they are (TetGen's -Y): the mesh's
  /// surface matches the STL node for node and the volume is exact, but the bounds above then
  /// hold only where TetGen can meet them without splitting a surface triangle. When false,
  /// TetGen adds nodes on the surface too and meets the bounds everywhere, but it treats nearly
  /// coplanar neighbouring faces as one, so the surface moves slightly (volume within ~1e-5
  /// relative).
  bool is_surface_kept = true;
  /// TetGen only: seconds TetGen may spend on one shape before it is stopped and the shape
  /// counts as failed, in [0.001, 604800]. A generated shape takes milliseconds; Debian's TetGen
  /// 1.5 loops forever on a few (tests/mesh/fixtures/tetgen-hang).
  double time_limit = 20.0;
  /// TetGen only (tetgen_meshes): when set, called in the calling process as each shape is
  /// meshed or fails, (shapes settled so far, shapes); for a progress display, must not throw.
  /// A pointer (owned by the caller) keeps the options a plain value.
  const std::function<void(std::size_t done, std::size_t total)>* on_progress = nullptr;
};

/// The centroid fan's tetrahedron on surface triangle (a, b, c), `centre` being the centroid's
/// node number: (a, c, b, centre). a -> c -> b is clockwise from outside, i.e. counter-clockwise
/// seen from the centroid, which makes the tetrahedron positive and its face S1 the triangle.
inline Tetrahedron fan_tetrahedron(const Triangle& triangle, std::uint32_t centre) {
  return {triangle[0], triangle[2], triangle[1], centre};
}

/// Throws InvalidInput naming the field unless the options are usable.
void validate(const TetOptions& options);

/// Signed volume of the tetrahedron (a, b, c, d): det[b-a, c-a, d-a] / 6, positive when it is
/// positively oriented (see the conventions above). m^3.
double tetra_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The paper's fan: node V (after the V surface vertices) is the body's centroid, and every
/// surface triangle (a, b, c) gives the tetrahedron (a, c, b, centroid), whose face S1 is the
/// surface triangle. F tetrahedra, V + 1 nodes; their volumes sum to the body's volume exactly
/// (up to rounding). Precondition: a convex body with positive volume (the centroid is inside).
/// \throw InvalidInput if the body is empty or has no positive volume.
TetMesh centroid_fan(const ConvexPolyhedron& body);

/// A TetGen quality mesh of the body (switches p, q, a and, with is_surface_kept, Y). The body's
/// vertices stay the first nodes in their order; TetGen adds Steiner nodes inside (and, unless
/// is_surface_kept, on the flat surface faces) to meet `max_volume` and `radius_edge_ratio`.
/// TetGen runs in a worker process (see tetgen_meshes), so its failed assertions (Debian's TetGen
/// 1.5 aborts on ~0.3 % of generated shapes) cannot end the calling process.
/// \throw InvalidInput (options), LimitExceeded (TetGen failed, aborted or timed out on this
///        input, saying which), IoError (no worker process could be started).
TetMesh tetgen_mesh(const ConvexPolyhedron& body, const TetOptions& options);

/// One shape's result from tetgen_meshes.
struct TetGenOutcome {
  bool is_meshed = false;  ///< TetGen produced `mesh`; otherwise `failure` says what happened
  TetMesh mesh;            ///< as tetgen_mesh returns it (empty when !is_meshed)
  /// e.g. "TetGen died of signal 6 (Aborted)" (a failed assertion in TetGen), "TetGen error
  /// code 3", "TetGen timed out after 20 s".
  std::string failure;
};

/// TetGen meshes of many bodies, each as tetgen_mesh would make it, computed in forked worker
/// processes (as many as TBB may use threads, each meshing batches of shapes; see run_isolated in
/// aggpack/core/isolated.h): a shape on which TetGen aborts, crashes or overruns
/// options.time_limit fails alone. Outcomes come in the order of `bodies` and do not depend on the
/// number of workers. \throw InvalidInput (options, a null or empty body), IoError (no worker
/// process could be started).
std::vector<TetGenOutcome> tetgen_meshes(std::span<const ConvexPolyhedron* const> bodies,
                                         const TetOptions& options);

/// Dispatches on options.method. \throw as centroid_fan / tetgen_mesh.
TetMesh tetrahedralize(const ConvexPolyhedron& body, const TetOptions& options = {});

/// Where the mid-side nodes of a 10-node mesh go, without coordinates: mid-side node
/// `corner_count + i` is the middle of the corner nodes `midside_edges[i]`. Edges are numbered in
/// the order they are first met, tetrahedron by tetrahedron, each in kTetraEdges order.
struct QuadraticTopology {
  std::vector<std::array<std::uint32_t, 2>> midside_edges;
  std::vector<std::array<std::uint32_t, 10>> tetrahedra;  ///< C3D10 node order
};

/// The 10-node elements over linear `tetrahedra` whose corner nodes are 0 .. corner_count - 1.
QuadraticTopology quadratic_topology(std::span<const Tetrahedron> tetrahedra,
                                     std::uint32_t corner_count);

/// Appends the mid-side nodes of `topology` to the corner nodes `nodes` (coordinates in any
/// frame: each is the exact midpoint expression 0.5 (a + b) of the given corners).
void append_midside_nodes(const QuadraticTopology& topology, std::vector<Vec3>& nodes);

/// Adds a node at the middle of every edge (shared between neighbouring tetrahedra) and returns
/// 10-node tetrahedra (quadratic_topology + append_midside_nodes). Straight-sided: mid-side nodes
/// sit on the straight edges, so the volume is unchanged.
QuadraticTetMesh make_quadratic(const TetMesh& mesh);

/// Sum of the signed tetrahedron volumes (m^3).
double mesh_volume(const TetMesh& mesh);

/// Smallest signed tetrahedron volume (m^3); > 0 when every tetrahedron is positively oriented.
double min_tetra_volume(const TetMesh& mesh);

/// Number of nodes, tetrahedra and unique edges of a mesh (used to size exports up front).
struct TetMeshCounts {
  std::size_t nodes = 0;
  std::size_t tetrahedra = 0;
  std::size_t edges = 0;
};
TetMeshCounts count(const TetMesh& mesh);

}  // namespace aggpack
