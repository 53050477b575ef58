#pragma once
// Files of the mesomodel's phase image (mesh/voxels.h, issue 16 item 6):
// - VTK XML image data (.vti): cell data "phase" (UInt8: 0 mortar, 1 ITZ, 2 aggregate,
//   3 outside) and "particle" (UInt32, 1-based, 0 = none), raw appended binary (ParaView, vtk).
// - raw + JSON header for FFT solvers: BASE.phase.raw (uint8), BASE.particle.raw (uint32
//   little-endian), x fastest then y then z, and BASE.json (dims, spacing, origin, order, phase
//   codes, voxel counts and fractions, the exact aggregate and ITZ volumes).

#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/mesh/voxels.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// Writes the image as .vti. \throw IoError
void write_vti(const std::string& path, const VoxelImage& image, Overwrite overwrite);

/// Writes BASE.phase.raw, BASE.particle.raw and BASE.json (`base` without extension); all or
/// nothing. The header's exact volumes come from `packing` and `itz_thickness`. \throw IoError
void write_voxel_raw(const std::string& base, const VoxelImage& image, const Packing& packing,
                     double itz_thickness, Overwrite overwrite);

}  // namespace aggpack
