#pragma once
// Loading a particle shape library from files (particle.library): every .stl, .obj and .ply file
// of a folder (or one file), read, hashed and imported (aggpack/shape/shape_library.h).

#include "aggpack/shape/shape_library.h"

namespace aggpack {

/// Largest mesh file read (bytes): 1 GiB.
inline constexpr std::uint64_t kMaxMeshFileBytes = 1ULL << 30;

/// Loads the library `options.paths` name, each a folder's .stl/.obj/.ply files (any case; not its
/// sub-folders; other files ignored) in file-name order, or one mesh file; several paths in their
/// order (shapes then named by path, each file at most once). Files are imported in
/// parallel; the result is the same at any thread count. A file that fails stops the load with
/// a one-line error "PATH: what is wrong" of the failure's kind, unless
/// options.is_skipping_bad, which records it in ShapeLibrary::skipped instead.
/// \throw InvalidInput (particle.library: no such folder or file, no mesh files, every file
///        skipped), IoError, FormatError, LimitExceeded.
ShapeLibrary load_shape_library(const ShapeLibraryOptions& options);

/// Lists the files `options.paths` name without reading them: the same refusals as
/// load_shape_library's for paths (no such folder or file, no mesh files, too many, a file named
/// twice), for a command to give before it starts heavy work.
void check_library_paths(const ShapeLibraryOptions& options);

}  // namespace aggpack
