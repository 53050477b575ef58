// The words of the exporters' enumerated options (`aggpack export --cells / --tet-method /
// --inp-layout`, the Python module's keywords): one parser each, the message naming the caller's
// option.

#include <string>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"

namespace aggpack {

MeshCells parse_mesh_cells(const std::string& word, const std::string& field) {
  if (word == "default") return MeshCells::kDefault;
  if (word == "surface") return MeshCells::kSurface;
  if (word == "tetrahedra") return MeshCells::kTetrahedra;
  throw InvalidInput(field, "'" + word + "'", "surface | tetrahedra");
}

TetMethod parse_tet_method(const std::string& word, const std::string& field) {
  if (word == "fan") return TetMethod::kCentroidFan;
  if (word == "tetgen") return TetMethod::kTetGen;
  throw InvalidInput(field, "'" + word + "'", "fan | tetgen");
}

AbaqusLayout parse_abaqus_layout(const std::string& word, const std::string& field) {
  if (word == "sets") return AbaqusLayout::kElementSets;
  if (word == "parts") return AbaqusLayout::kPartsInstances;
  throw InvalidInput(field, "'" + word + "'", "sets | parts");
}

}  // namespace aggpack
