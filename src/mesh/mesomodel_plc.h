// Internal: a piecewise linear complex (points, planar facets made of polygons, region seeds) and
// its tetrahedralisation by TetGen in a worker process. Used by mesomodel.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "aggpack/geom/halfspace.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/mesh/tetrahedra.h"

namespace aggpack::detail {

struct PlcFacet {
  /// The facet's polygons (point numbers); the first is its outline, the others lie inside it and
  /// become edges of its triangulation; a one-point polygon is a point it must use (the walls'
  /// grid).
  std::vector<std::vector<std::uint32_t>> polygons;
  int marker = 0;  ///< reported back when TetGen finds the facet intersecting another
};

struct PlcRegion {
  Vec3 seed = Vec3::Zero();  ///< a point strictly inside the region
  int attribute = 0;         ///< given to every tetrahedron of the region
  double max_volume = 0.0;   ///< m^3, > 0 bounds the region's tetrahedra, 0 = none
};

struct Plc {
  std::vector<Vec3> points;
  std::vector<PlcFacet> facets;
  std::vector<PlcRegion> regions;
  std::vector<Vec3> holes;  ///< a point in each region TetGen leaves empty (the ITZ layers)
};

struct PlcMesh {
  std::vector<Vec3> nodes;  ///< the PLC's points first, in order, then TetGen's Steiner points
  std::vector<Tetrahedron> tetrahedra;  ///< positively oriented
  std::vector<int> attributes;          ///< region attribute per tetrahedron
};

/// TetGen's tetrahedralisation of the PLC with `switches` (TetGen's command-line letters; A and
/// the region list give the attributes) in a worker process stopped after `time_limit` s.
/// \throw LimitExceeded naming what TetGen reported and, for intersecting facets, their markers
///        (TetGen's -d run, also in a worker); IoError when no worker could start.
PlcMesh tetrahedralize_plc(const Plc& plc, const std::string& switches, double time_limit);

/// An aggregate's ITZ layer: the outer surface is the aggregate's triangle mesh with vertex i
/// moved to outer[i], by the displacement that moves each face plane at the vertex out by the
/// thickness in the least-squares sense (exactly for a vertex of three faces). Near a wall the
/// displacement shrinks so that half the aggregate's clearance stays outside the layer.
struct ItzLayer {
  std::vector<Vec3> outer;
  double max_offset = 0.0;  ///< m, the largest vertex displacement
};
ItzLayer itz_layer(const ConvexPolyhedron& aggregate, double thickness,
                   std::span<const HalfSpace> walls);

/// Three tetrahedra per prism between inner triangle (a, b, c) (node inner_base + a, ...) and
/// outer triangle (outer_base + a, ...), cut consistently between neighbouring prisms. Node
/// order as found; the caller orients them.
void append_prism_tetrahedra(std::span<const Triangle> triangles, std::uint32_t inner_base,
                             std::uint32_t outer_base, std::vector<Tetrahedron>& out);

/// One aggregate as face planes (convex, exact), with its bounding box.
struct PhaseBody {
  std::span<const HalfSpace> planes;
  Aabb bounds;
  std::uint32_t particle = 0;  ///< 1-based particle; 0 = the body's index + 1
};

/// Checks the phase and particle of every tetrahedron TetGen made (aggregates and mortar; the ITZ
/// layers are holes there) against the geometry: its centroid clearly (`margin`, m) inside
/// aggregate k, or clearly outside every aggregate. TetGen's regions are the phases only if its
/// flood from each seed reached every tetrahedron of the region (with an earlier ITZ geometry it
/// once did not). A tetrahedron whose centroid is too close to an aggregate's surface to decide
/// keeps TetGen's label. Returns the number of tetrahedra relabelled.
std::size_t relabel_by_geometry(const std::vector<PhaseBody>& bodies, double margin,
                                MesoMesh& mesh);

/// A periodic box's complex without its regions: every image of every particle that meets the
/// box, clipped to it (its faces in the box's planes, the caps, are parts of the box's facets, not
/// facets of their own), and the six box facets: outline through every point on the box's edges,
/// the caps, and a point grid of `wall_spacing`. Every point on an upper periodic face is the exact
/// translation of one on the lower face (the grid is copied, cap points are moved onto their
/// partners, which differ in the last bits only). Point numbers 0-7 are the box's corners.
/// \throw InvalidInput when a vertex of an image lies within `min_gap` of a box face (or a
/// particle crosses a walled face); LimitExceeded when a point has no partner.
struct PeriodicComplex {
  Plc plc;
  std::vector<ConvexPolyhedron> pieces;              ///< the clipped images
  std::vector<std::vector<HalfSpace>> piece_planes;  ///< each piece's face planes
  std::vector<std::uint32_t> piece_particle;         ///< 1-based particle of each piece
};
PeriodicComplex periodic_complex(const Packing& packing, double wall_spacing, double min_gap);

/// Replaces the periodic faces' facets of a periodic complex (its facets 0-5) by the triangles
/// TetGen made of each lower face in `first` (a mesh of `plc`, with Y) and their translations onto
/// the upper face, so that a second mesh has the same triangles on both faces of a pair (a
/// homogeneous box then takes an affine displacement exactly under periodic ties).
void copy_lower_face_triangles(const PlcMesh& first, const std::array<bool, 3>& periodic,
                               const Vec3& extent, Plc& plc);

/// Throws InvalidInput naming itz_thickness unless it can be a cohesive ITZ's constitutive
/// thickness (finite, > 0): the one check of validate(MesoOptions) and split_cohesive_interfaces.
void check_cohesive_thickness(double thickness);

}  // namespace aggpack::detail
