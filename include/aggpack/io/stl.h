#pragma once
// STL writer/reader. STL stores facets with an outward normal and three vertices counter-clockwise
// seen from outside (the paper's Section 4). Coordinates are written in metres times `scale`.

#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

enum class StlEncoding { kBinary, kAscii };

struct StlOptions {
  StlEncoding encoding = StlEncoding::kBinary;
  double scale = 1.0;  ///< multiply coordinates by this (1000 writes millimetres), > 0
  std::string solid_name = "aggpack";
  Overwrite overwrite = Overwrite::kAllow;
};

/// Writes `bodies` (already placed in world coordinates) into one STL file, atomically.
/// \throw InvalidInput (scale), IoError.
void write_stl(const std::string& path, const std::vector<ConvexPolyhedron>& bodies,
               const StlOptions& options = {});

/// A triangle soup read from an STL file.
struct StlMesh {
  std::vector<Vec3> normals;
  std::vector<std::array<Vec3, 3>> triangles;
};

/// Reads binary or ASCII STL. \throw IoError, FormatError (truncated or malformed file).
StlMesh read_stl(const std::string& path);

}  // namespace aggpack
