#pragma once
// A library of particle shapes made elsewhere (scanned or drawn meshes): each mesh checked,
// replaced by its convex hull (the volume the hull adds reported), simplified to a vertex budget,
// centred at its centroid and stored at unit size, to be scaled to the grading's sizes by the
// packers (particle.library). Reading the files is io's (aggpack/io/shape_library_files.h).

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/geom/triangle_mesh.h"

namespace aggpack {

/// The length unit the mesh files are written in.
enum class LengthUnit { kMillimetre, kMetre };

/// "mm" or "m".
std::string_view length_unit_name(LengthUnit unit);
/// Metres per file unit: 1e-3 for mm, 1 for m.
double metres_per_unit(LengthUnit unit);

/// How meshes become library shapes.
struct ShapeImportOptions {
  LengthUnit units = LengthUnit::kMillimetre;  ///< unit of the files' coordinates
  /// Refuse a shape whose hull adds more than this fraction of its mesh volume ((V_hull -
  /// V_mesh) / V_mesh); 0 = no limit. [0, 100]
  double max_hull_excess = 0.0;
  /// Hulls with more vertices are simplified to at most this many (simplify_hull), [4, 10^6].
  std::uint32_t max_vertices = 1000;
};

/// Where the library comes from and how it is used (config keys particle.library*).
struct ShapeLibraryOptions {
  /// Each a folder of .stl/.obj/.ply files or one such file, read in this order; empty = none.
  std::vector<std::string> paths;
  ShapeImportOptions import{};
  bool is_skipping_bad = false;  ///< skip (and count) files that fail, instead of stopping
  bool is_use_once = false;      ///< each shape placed at most once
  /// Whether a library is asked for (a path given).
  [[nodiscard]] bool is_used() const { return !paths.empty(); }
  /// The paths for messages and the provenance: "rocks/", "a.stl, b.stl".
  [[nodiscard]] std::string paths_text() const;
};

/// One imported shape. Volumes in m^3 at the file's size (after the unit).
struct LibraryShape {
  /// File name (within its folder); with several library paths, the path as found ("rocks/a.stl").
  std::string name;
  std::string hash;  ///< content_hash of the file's bytes
  /// The hull (simplified), centroid at the origin, scaled so that its smallest enclosing sphere
  /// has radius 1: a particle of sieve size d is this body scaled by d / 2.
  ConvexPolyhedron body;
  Vec3 enclosing_centre = Vec3::Zero();  ///< centre of that sphere in the unit body's frame
  double size = 0.0;                     ///< sieve size as read: enclosing diameter (m)
  double mesh_volume = 0.0;              ///< the mesh's own volume
  double hull_volume = 0.0;              ///< its convex hull's, before simplification
  double volume = 0.0;                   ///< the stored shape's (after simplification)
  std::size_t mesh_vertices = 0;
  std::size_t mesh_triangles = 0;
  std::size_t hull_vertices = 0;  ///< before simplification
  /// (V_hull - V_mesh) / V_mesh: what making the shape convex added.
  [[nodiscard]] double hull_excess() const { return hull_volume / mesh_volume - 1.0; }
  /// (V - V_hull) / V_hull: what simplification changed (<= 0).
  [[nodiscard]] double simplification_change() const { return volume / hull_volume - 1.0; }
};

/// A loaded library: the shapes in file-name order, and what was skipped.
struct ShapeLibrary {
  std::string source;  ///< the path(s) it was loaded from, ", "-separated
  LengthUnit units = LengthUnit::kMillimetre;
  std::vector<LibraryShape> shapes;
  std::vector<std::string> skipped;  ///< one line per skipped file: "name: reason"

  /// Provenance text stored in the native file: a header line ("library SRC (units mm, 40
  /// shapes, 1 skipped, 12 stored)"), then one line per stored shape ("name<TAB>hash"): the
  /// packing's shape k, library shape stored[k], on line k + 1.
  [[nodiscard]] std::string provenance(std::span<const std::uint32_t> stored) const;
  /// "rocks/ (12 shapes, 1 skipped, units mm)": what was loaded, for the front ends.
  [[nodiscard]] std::string summary() const;
  /// "add 1.2e-06 m^3 to 3.4e-05 m^3 of meshes (+3.529 %)": the volume the convex hulls added,
  /// summed over the shapes.
  [[nodiscard]] std::string hull_summary() const;
};

/// Makes one library shape from a mesh in file units: check_particle_mesh, then the hull, the
/// excess limit, the vertex budget, the centroid and the unit size. `name` and `hash` are copied.
/// \throw FormatError when the mesh fails a check or spans no volume, Error of kind
///        kLimitExceeded above max_hull_excess; one line naming `file` first ("rocks/a.stl: mesh
///        is open: ..."; `name` when `file` is empty), its sentence's first value.
LibraryShape import_shape(const TriangleMesh& mesh, const ShapeImportOptions& options,
                          std::string name, std::string hash, const std::string& file = {});

/// \throw InvalidInput naming particle.library_max_hull_excess / particle.library_max_vertices.
void validate(const ShapeImportOptions& options);

/// A packer's view of a library: the options it was asked for and, once the pipeline loaded it,
/// the shapes (shared, read-only: one copy whatever the particle count).
struct ShapeFiles {
  ShapeLibraryOptions options{};
  std::shared_ptr<const ShapeLibrary> loaded{};
  [[nodiscard]] bool is_used() const { return options.is_used(); }
};

}  // namespace aggpack
