// Internal: a piecewise linear complex (points, planar facets made of polygons, region seeds) and
// its tetrahedralisation by TetGen in a worker process. Used by mesomodel.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/mesh/tetrahedra.h"

namespace aggpack::detail {

struct PlcFacet {
  /// The facet's polygons (point numbers); the first is its outline, the others lie inside it and
  /// become edges of its triangulation (e.g. an ITZ shell's footprint on a wall).
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

}  // namespace aggpack::detail
