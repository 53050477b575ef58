#pragma once
// The phase image of a concrete mesomodel (issue 16, item 6): the container cut into cubic voxels,
// each labelled by the phase at its centre - aggregate (inside a particle), ITZ (outside every
// particle but within the ITZ thickness of one), mortar (the rest), or outside (a cylinder's
// corners) - and, for aggregate and ITZ voxels, the particle (1-based; 0 for none). For FFT
// homogenisation solvers and quick looks; the tetrahedral mesomodel is the exact one.
//
// Exact reference volumes: the aggregates' are the polyhedra's; an ITZ shell of thickness t
// around a convex body K has volume S t + M t^2 + 4/3 pi t^3 (Steiner's formula: S the surface
// area, M = 1/2 sum over edges of length x exterior dihedral angle), exact while the shells
// neither overlap nor cross a wall.

#include <array>
#include <cstdint>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// Phase codes of a voxel.
enum class VoxelPhase : std::uint8_t { kMortar = 0, kItz = 1, kAggregate = 2, kOutside = 3 };

struct VoxelOptions {
  /// Voxels along the container's longest side, [2, 4096]; the voxels are cubes of that side / n.
  std::uint32_t resolution = 128;
  double itz_thickness = 0.0;  ///< m, [0, half the container's smallest side); 0 = no ITZ
  /// Largest voxel count accepted (memory: 5 bytes per voxel), checked before allocating.
  std::uint64_t max_voxels = std::uint64_t{1} << 31;
};

/// Throws InvalidInput naming "voxels" / "itz_thickness" unless usable.
void validate(const VoxelOptions& options);

struct VoxelImage {
  std::array<std::uint32_t, 3> dims{};  ///< voxels along x, y, z
  double spacing = 0;                   ///< m, voxel side
  Vec3 origin = Vec3::Zero();           ///< m, corner of voxel (0, 0, 0) (the container's lower)
  std::vector<std::uint8_t> phase;      ///< VoxelPhase per voxel, x fastest, then y, then z
  std::vector<std::uint32_t> particle;  ///< 1-based particle of aggregate / ITZ voxels, else 0

  [[nodiscard]] std::uint64_t count() const { return std::uint64_t{dims[0]} * dims[1] * dims[2]; }
  /// Voxels of each phase (index = VoxelPhase code).
  [[nodiscard]] std::array<std::uint64_t, 4> phase_counts() const;
};

/// Labels every voxel of the packing's container. Deterministic at any thread count.
/// \throw InvalidInput for bad options, LimitExceeded when the image would exceed max_voxels.
VoxelImage voxelize(const Packing& packing, const VoxelOptions& options);

/// Volume of the shell of thickness t around a convex body (Steiner's formula; m^3).
double offset_shell_volume(const ConvexPolyhedron& body, double thickness);

}  // namespace aggpack
