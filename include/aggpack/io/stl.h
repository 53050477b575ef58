#pragma once
// STL reader, and the encoding choice of the STL writer. STL stores facets with an outward normal
// and three vertices counter-clockwise seen from outside (the paper's Section 4). The one STL
// writer is the exporter's (write(packing, path, {.format = ExportFormat::kStl}), export.h;
// src/io/export_stl.cpp).

#include <array>
#include <string>
#include <vector>

#include "aggpack/geom/vec.h"

namespace aggpack {

enum class StlEncoding { kBinary, kAscii };

/// A triangle soup read from an STL file.
struct StlMesh {
  std::vector<Vec3> normals;
  std::vector<std::array<Vec3, 3>> triangles;
};

/// Reads binary or ASCII STL. \throw IoError, FormatError (truncated or malformed file).
StlMesh read_stl(const std::string& path);

/// Parses an STL file's whole content (binary when its size is 84 + 50 x the facet count, else
/// ASCII); `path` only names the file in messages. \throw FormatError.
StlMesh parse_stl(const std::string& content, const std::string& path);

}  // namespace aggpack
