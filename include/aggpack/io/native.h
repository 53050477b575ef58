#pragma once
// The native packing file: a Packing saved to HDF5 so every later step (export, mesh, view, stats)
// can run again without re-packing. Exact round trip: doubles are stored as IEEE float64 and read
// back bit-identically.
//
// Layout (format_name "aggpack-packing", format_version 1; all datasets little-endian):
//   /                     attributes format_name (string), format_version (int32)
//   /container            attributes kind ("box" | "cylinder"), length, width, depth, radius,
//                         height, wall_gap (float64, metres); periodic (string "x" ... "xyz",
//                         only in a periodic box's file; absent = no periodic axis)
//   /shapes/vertices          float64 [V, 3]   local-frame vertices of all shapes, concatenated (m)
//   /shapes/triangles         uint32  [T, 3]   vertex indices, 0-based, local to their shape,
//                                              counter-clockwise seen from outside
//   /shapes/vertex_offsets    uint64  [S + 1]  shape s owns vertices [off[s], off[s+1])
//   /shapes/triangle_offsets  uint64  [S + 1]  shape s owns triangles [off[s], off[s+1])
//   /particles/shape          uint32  [P]      index into the shapes
//   /particles/position       float64 [P, 3]   world position of the shape's origin (m)
//   /particles/scale          float64 [P]      uniform scale of the stored shape, > 0
//   /particles/rotation       float64 [P, 4]   unit quaternion, scalar first (w, x, y, z)
//   /particles/control_radius float64 [P]      radius r the shape was grown with (m)
//   /particles/size_class     uint32  [P]      grading class index
//   /provenance           attributes aggpack_version, config_toml, packer (strings), seed (uint64)
//   /world (optional)     vertices float64 [V', 3], triangles int64 [T', 3], particle int32 [T']:
//                         every particle's surface in world coordinates, for ParaView via XDMF.
// Non-empty datasets are chunked with the Fletcher-32 checksum filter, and the file uses the
// HDF5 1.8+ object format whose metadata also carries checksums, so corruption is detected on read.
// Object timestamps are off, so the same Packing always gives a byte-identical file.

#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// Value of the root attribute `format_name` of a native packing file.
inline constexpr const char* kNativeFormatName = "aggpack-packing";
/// Version written by this build; read_packing accepts exactly this version.
inline constexpr int kNativeFormatVersion = 1;

/// Options of write_packing.
struct NativeWriteOptions {
  Overwrite overwrite = Overwrite::kAllow;  ///< whether an existing file may be replaced
  int compression = 0;                      ///< deflate level, 0 (none, fastest) .. 9
  /// Also store every particle's surface in world coordinates under /world and write an XDMF
  /// file beside the .h5 (same name, extension .xdmf) that ParaView opens. Roughly doubles the
  /// file size.
  bool write_xdmf = false;
};

/// Writes `packing` to `path` (HDF5) atomically: a temporary file in the same folder is renamed
/// onto `path` only when complete. With write_xdmf, `path` with extension .xdmf is written too.
/// The native row of the format table: write(packing, path, options) (export.h) calls this.
/// \throw InvalidInput (compression outside [0, 9]; a particle's shape index out of range),
///        IoError (folder missing or not writable, file exists with Overwrite::kForbid, HDF5 write
///        failure).
void write_packing(const Packing& packing, const std::string& path,
                   const NativeWriteOptions& options = {});

/// Reads a packing written by write_packing and validates it: element types exact, every
/// dataset's declared size checked against what the file stores before anything is allocated, then
/// validate_packing. Every command that opens a native file goes through here.
/// \throw IoError (missing or unreadable file), FormatError (not HDF5, not an aggpack packing,
///        another format version, truncated, corrupted or invalid content), one line
///        "<path>: <dataset or attribute>: <reason>".
Packing read_packing(const std::string& path);

/// Ranges of a native file's content (docs/formats.md, "Native packing file"). Lengths in metres.
struct NativeLimits {
  static constexpr double kMaxLength = 1e6;   ///< |coordinate|, container sizes, radii, gaps
  static constexpr double kMinLength = 1e-9;  ///< container sizes in use, every particle's extent
  static constexpr double kMinScale = 1e-9;   ///< /particles/scale
  static constexpr double kMaxScale = 1e6;
  /// | |q|^2 - 1 | of /particles/rotation.
  static constexpr double kRotationTolerance = 1e-6;
  /// A vertex may lie this far in front of a face plane, relative to the shape's bounding-box
  /// diagonal, and the shape still counts as convex.
  static constexpr double kConvexTolerance = 1e-6;
  /// Largest expansion of a compressed dataset over its stored bytes (deflate's limit is 1032:1).
  static constexpr double kMaxCompressionRatio = 1032.0;
};

/// The content checks of read_packing, for a Packing from anywhere: container sizes in range, each
/// shape a closed, consistently oriented, convex 2-manifold with positive volume and coordinates in
/// range, each particle's shape index, position, unit rotation, scale and radius in range.
/// `source` names the file in messages.
/// \throw FormatError "<source>: <field>: <reason>", the field named as in the native file
///        (e.g. "/particles/scale[3]", "/shapes/triangles (shape 2, rows 40-59)").
void validate_packing(const Packing& packing, const std::string& source);

/// The XDMF side-file path for a native file path: "run.h5" -> "run.xdmf".
std::string xdmf_path_for(const std::string& path);

}  // namespace aggpack
