#pragma once
// The concrete mesomodel (issue 16): the container meshed into aggregate, ITZ and mortar
// tetrahedra that share nodes on every interface (one conforming mesh).
//
// Geometry, exact by construction:
//  - aggregate k is the packing's convex polyhedron k, its surface triangles kept as they are;
//  - its ITZ is a layer over those triangles: every aggregate vertex is moved out by the
//    displacement that moves each of its face planes out by the ITZ thickness t (exactly for a
//    vertex of three faces, in the least-squares sense for more), and each aggregate triangle
//    with its moved copy bounds a prism of three tetrahedra (so the layer is t thick everywhere
//    up to the least-squares residual, and its tetrahedra are as flat as t / the triangle size,
//    never slivers). Near a wall the displacement shrinks so half the aggregate's clearance
//    stays mortar;
//  - the mortar is the container (a box, or a cylinder as the prism circumscribed about it with
//    `cylinder_segments` sides) minus the aggregates and their layers.
// TetGen (run in a worker process, core/isolated.h) tetrahedralises aggregates and mortar with
// the layers as holes, keeping every input triangle (switch Y), so the layers' prisms share its
// nodes and every phase volume is a sum over exact polyhedra (checked, 1e-9). Each TetGen
// tetrahedron's phase comes from its region seed and is checked against the geometry.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/mesh/quality.h"
#include "aggpack/mesh/tetrahedra.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// Phase of a tetrahedron.
enum class MesoPhase : std::uint8_t { kMortar = 0, kItz = 1, kAggregate = 2 };

/// Names used for element sets and reports: "MORTAR", "ITZ", "AGGREGATE".
const char* phase_set_name(MesoPhase phase);

/// How the ITZ is modelled (the user's choice, `--itz-kind`).
enum class ItzKind : std::uint8_t {
  /// A solid layer of the ITZ thickness around every aggregate, meshed with tetrahedra.
  kSolid = 0,
  /// Zero-thickness cohesive elements (Abaqus COH3D6) on every aggregate-mortar interface: the
  /// aggregates and the mortar meshed bonded (no layer), then split along each aggregate's
  /// surface, the mortar side on its own copies of the surface nodes, and each surface triangle
  /// joined to its copy by a 6-node wedge. The ITZ thickness is then the elements' constitutive
  /// thickness (their stiffness is the ITZ's modulus over it), not a geometric one.
  kCohesive = 1
};

/// "solid" or "cohesive".
const char* to_string(ItzKind kind);

struct MesoOptions {
  /// ITZ thickness t (m), >= 0; 0 = no ITZ (aggregates bonded directly to mortar). Typical
  /// 20-50 um; the layers of two particles must not meet (checked, see build_mesomodel).
  double itz_thickness = 0.0;
  /// Solid layer or cohesive elements; kCohesive needs itz_thickness > 0 (its constitutive
  /// thickness) and a packing whose aggregates do not touch.
  ItzKind itz_kind = ItzKind::kSolid;
  /// Target element edge length in the aggregates and in the mortar (m); 0 = no size bound
  /// (TetGen's quality bound alone). The bound passed to TetGen is the volume of the regular
  /// tetrahedron of that edge, h^3 / (6 sqrt 2).
  double aggregate_size = 0.0;
  double mortar_size = 0.0;
  /// TetGen's radius-edge bound (-q) for aggregates and mortar: 0 = none (the default), else in
  /// [1.2, 10]. It improves the aggregates' tetrahedra; the mortar's worst ones sit in the thin
  /// gaps between the kept surfaces, which -q cannot split (docs/mesomodel.md).
  double radius_edge_ratio = 0.0;
  /// Sides of the prism that stands in for a cylinder container (circumscribed), [8, 4096].
  int cylinder_segments = 96;
  /// Quality bounds the user may set: the mesh is refused (LimitExceeded) when its smallest
  /// dihedral angle is below min_dihedral_degrees or its largest aspect ratio above
  /// max_aspect_ratio. Defaults accept every valid mesh (0 degrees, infinity).
  double min_dihedral_degrees = 0.0;
  double max_aspect_ratio = 1e300;
  /// Seconds TetGen may take before it is stopped, [0.001, 604800].
  double time_limit = 3600.0;
};

/// Throws InvalidInput naming the field unless the options are usable.
void validate(const MesoOptions& options);

/// A 6-node zero-thickness cohesive element (Abaqus COH3D6 node order): nodes 0-2 a triangle of
/// the aggregate's surface, ordered so that its right-hand normal points out of the aggregate
/// (the element's thickness direction, bottom to top), nodes 3-5 the mortar side's copies of
/// nodes 0-2 (same positions).
using CohesiveWedge = std::array<std::uint32_t, 6>;

/// A conforming tetrahedral mesh of the specimen. Node numbers 0-based; tetrahedra positively
/// oriented (tetrahedra.h conventions). With a cohesive ITZ the aggregate and mortar tetrahedra
/// share no node: the cohesive wedges join them.
struct MesoMesh {
  std::vector<Vec3> nodes;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<MesoPhase> phase;         ///< per tetrahedron
  std::vector<std::uint32_t> particle;  ///< per tetrahedron: 1-based particle (aggregate, ITZ), 0
  std::uint32_t particle_count = 0;     ///< particles of the packing (ids 1..particle_count)
  Aabb bounds;                          ///< the container's bounding box (for face node sets)
  /// Periodic axes (x, y, z) of a periodic box: the mesh is the box with every particle image
  /// that meets it clipped to it, and each node on a periodic face has a partner on the opposite
  /// face at the same in-plane coordinates (bit for bit; `periodic_pairs`).
  std::array<bool, 3> periodic{};
  /// The container meshed: the prism its kind gives for `prism_sides` (container.h,
  /// container_prism_floor) is the specimen, whose side walls face_nodes() finds.
  Container container;
  int prism_sides = 0;  ///< sides of a curved container's prism (MesoOptions::cylinder_segments)
  double itz_thickness = 0.0;           ///< m, as meshed (cohesive: the constitutive thickness)
  std::vector<CohesiveWedge> cohesive;  ///< cohesive ITZ elements (empty for a solid ITZ)
  std::vector<std::uint32_t> cohesive_particle;  ///< per cohesive element: 1-based particle
};

/// Expected (exact) and meshed volumes and the quality of one phase.
struct MesoPhaseReport {
  double expected_volume = 0.0;  ///< m^3, from the polyhedra (see the header comment)
  double meshed_volume = 0.0;    ///< m^3, sum of the phase's tetrahedron volumes
  std::uint64_t nodes = 0;       ///< nodes used by the phase's tetrahedra
  TetQuality quality;
};

struct MesoReport {
  std::array<MesoPhaseReport, 3> phases;  ///< index = MesoPhase code
  double container_volume = 0.0;          ///< m^3, the meshed container (prism for a cylinder)
  double mesh_seconds = 0.0;              ///< wall time in TetGen
  /// Tetrahedra whose phase TetGen's region flood got wrong and the geometric check mended
  /// (see build_mesomodel); 0 in nearly every mesh.
  std::uint64_t relabelled_tetrahedra = 0;
  std::string tetgen_switches;
  /// Cohesive ITZ: its elements, their area (sum of the wedges' triangles, m^2) and the exact
  /// one (the aggregates' surface areas).
  std::uint64_t cohesive_elements = 0;
  double interface_area = 0.0;
  double expected_interface_area = 0.0;
};

/// Meshes the packing's container into phases. \throw InvalidInput (options; particles closer
/// than the ITZ needs, naming the two particles, their gap and the packer.gap to pack with; a
/// particle crossing a wall), LimitExceeded (TetGen failed, aborted or timed out, naming the
/// reason and the particles TetGen reported; quality below the bounds), IoError (no worker
/// process).
MesoMesh build_mesomodel(const Packing& packing, const MesoOptions& options,
                         MesoReport* report = nullptr);

/// Per-phase volumes, node counts and quality of a mesh, and its cohesive elements and their
/// area (`expected_volume` and `expected_interface_area` left 0). The ITZ phase's node count of
/// a cohesive mesh counts the wedges' nodes.
MesoReport measure_mesomodel(const MesoMesh& mesh);

/// Turns a bonded mesh (aggregate and mortar tetrahedra sharing their interface nodes, no ITZ
/// tetrahedra) into the cohesive-ITZ form (ItzKind::kCohesive): every node used by both an
/// aggregate and a mortar tetrahedron gets a copy (appended to mesh.nodes, same position) that the
/// mortar tetrahedra use instead, and every aggregate-mortar triangle becomes a CohesiveWedge of
/// its aggregate's particle, ordered by particle, then by the aggregate tetrahedron and face it
/// lies on; mesh.itz_thickness = thickness. build_mesomodel calls it; public for meshes made
/// elsewhere. \throw InvalidInput (ITZ tetrahedra or wedges present, thickness <= 0),
/// LimitExceeded (2^32 nodes or more).
void split_cohesive_interfaces(MesoMesh& mesh, double thickness);

/// Faces of the specimen for node sets: bottom (z min), top (z max), sides (the rest).
enum class SpecimenFace : std::uint8_t { kBottom = 0, kTop = 1, kSide = 2 };

/// Nodes on one face of the specimen's boundary (sorted, 0-based), found geometrically within
/// 1e-9 of the container's size.
std::vector<std::uint32_t> face_nodes(const MesoMesh& mesh, SpecimenFace face);

/// A node on an upper face of a periodic mesh (coordinate = bounds.upper on some periodic axis)
/// and its image: the node at the same point with each such coordinate moved to the lower face.
/// `shifted` says on which axes it moved (an edge node two, a corner node three), so that
/// u(node) = u(image) + the sum over those axes of the box's macroscopic displacement over one
/// period. Every node on an upper face is `node` of exactly one pair, an image is never one.
struct PeriodicPair {
  std::uint32_t node = 0;
  std::uint32_t image = 0;
  std::array<bool, 3> shifted{};
};

/// The pairs of a periodic mesh (empty for a walled one), by node. \throw LimitExceeded when a
/// node on an upper face has no image (the mesh is not periodic).
std::vector<PeriodicPair> periodic_pairs(const MesoMesh& mesh);

}  // namespace aggpack
