#pragma once
// Reads the TetGen .poly fixtures (tests/mesh/fixtures/): a body in its local frame, one triangle
// per facet, vertices numbered from 0 as TetGen's own tools write them.

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack::test {

/// The body of a .poly file: "<vertex count> 3 0 0", "<i> <x> <y> <z>" per vertex, "<facet
/// count> 0", then "1" and "3 <a> <b> <c>" per facet. \throw FormatError for anything else.
inline ConvexPolyhedron read_poly(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw FormatError("cannot read " + path);
  std::size_t vertex_count = 0;
  int dimension = 0;
  int attributes = 0;
  int markers = 0;
  in >> vertex_count >> dimension >> attributes >> markers;
  if (!in || dimension != 3) throw FormatError(path + ": bad node header");
  std::vector<Vec3> vertices(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    std::size_t index = 0;
    in >> index >> vertices[i][0] >> vertices[i][1] >> vertices[i][2];
    if (!in || index != i) throw FormatError(path + ": bad vertex line " + std::to_string(i));
  }
  std::size_t facet_count = 0;
  in >> facet_count >> markers;
  std::vector<Triangle> triangles(facet_count);
  for (std::size_t f = 0; f < facet_count; ++f) {
    int polygons = 0;
    int corners = 0;
    in >> polygons >> corners >> triangles[f][0] >> triangles[f][1] >> triangles[f][2];
    if (!in || polygons != 1 || corners != 3) {
      throw FormatError(path + ": facet " + std::to_string(f) + " is not one triangle");
    }
  }
  return {std::move(vertices), std::move(triangles)};
}

}  // namespace aggpack::test
