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

struct MesoOptions {
  /// ITZ thickness t (m), >= 0; 0 = no ITZ (aggregates bonded directly to mortar). Typical
  /// 20-50 um; the layers of two particles must not meet (checked, see build_mesomodel).
  double itz_thickness = 0.0;
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

/// A conforming tetrahedral mesh of the specimen. Node numbers 0-based; tetrahedra positively
/// oriented (tetrahedra.h conventions).
struct MesoMesh {
  std::vector<Vec3> nodes;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<MesoPhase> phase;         ///< per tetrahedron
  std::vector<std::uint32_t> particle;  ///< per tetrahedron: 1-based particle (aggregate, ITZ), 0
  std::uint32_t particle_count = 0;     ///< particles of the packing (ids 1..particle_count)
  Aabb bounds;                          ///< the container's bounding box (for face node sets)
  bool is_cylinder = false;             ///< the container is a cylinder (prism), axis z
  Vec3 axis_point = Vec3::Zero();       ///< cylinder: a point on its axis (x, y used)
  double cylinder_radius = 0.0;         ///< cylinder: radius of the circle the prism circumscribes
  int cylinder_segments = 0;            ///< cylinder: sides of the prism (the first at angle 0)
  double itz_thickness = 0.0;           ///< m, as meshed
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
};

/// Meshes the packing's container into phases. \throw InvalidInput (options; particles closer
/// than the ITZ needs, naming the two particles, their gap and the packer.gap to pack with; a
/// particle crossing a wall), LimitExceeded (TetGen failed, aborted or timed out, naming the
/// reason and the particles TetGen reported; quality below the bounds), IoError (no worker
/// process).
MesoMesh build_mesomodel(const Packing& packing, const MesoOptions& options,
                         MesoReport* report = nullptr);

/// Per-phase volumes, node counts and quality of a mesh (`expected_volume` left 0).
MesoReport measure_mesomodel(const MesoMesh& mesh);

/// Faces of the specimen for node sets: bottom (z min), top (z max), sides (the rest).
enum class SpecimenFace : std::uint8_t { kBottom = 0, kTop = 1, kSide = 2 };

/// Nodes on one face of the specimen's boundary (sorted, 0-based), found geometrically within
/// 1e-9 of the container's size.
std::vector<std::uint32_t> face_nodes(const MesoMesh& mesh, SpecimenFace face);

}  // namespace aggpack
