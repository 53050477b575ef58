// libFuzzer target for the shape library's mesh readers: the bytes are read as an STL (binary or
// ASCII), an OBJ and a PLY file in turn, the way `aggpack shapes --library` reads each file of a
// folder -- parse_mesh, then (for a mesh that parses) check_particle_mesh and import_shape (hull,
// excess, vertex budget, centring). Every aggpack::Error is a correct answer; a crash, sanitizer
// report, leak, timeout or out-of-memory is a finding. Built by scripts/fuzz.sh (CMake option
// AGGPACK_BUILD_FUZZ); seeds: tests/fuzz/corpus/mesh_reader.

#include <cstddef>
#include <cstdint>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/triangle_mesh.h"
#include "aggpack/io/mesh_read.h"
#include "aggpack/shape/shape_library.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string content(reinterpret_cast<const char*>(data), size);
  for (const auto format : {aggpack::MeshFileFormat::kStl, aggpack::MeshFileFormat::kObj,
                            aggpack::MeshFileFormat::kPly}) {
    try {
      const aggpack::TriangleMesh mesh = aggpack::parse_mesh(content, format, "fuzz");
      if (!aggpack::check_particle_mesh(mesh).is_ok) continue;
      aggpack::ShapeImportOptions options;
      options.max_vertices = 64;  // exercises simplify_hull on larger hulls
      (void)aggpack::import_shape(mesh, options, "fuzz", aggpack::content_hash(content));
    } catch (const aggpack::Error&) {
      // A refused file is a correct answer.
    }
  }
  return 0;
}
