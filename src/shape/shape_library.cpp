// Importing a particle mesh made elsewhere: checks, convex hull, excess limit, vertex budget,
// centroid and unit size.

#include "aggpack/shape/shape_library.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/convex_hull_3d.h"
#include "aggpack/geom/enclosing_sphere.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack {

std::string_view length_unit_name(LengthUnit unit) {
  return unit == LengthUnit::kMillimetre ? "mm" : "m";
}

double metres_per_unit(LengthUnit unit) { return unit == LengthUnit::kMillimetre ? 1e-3 : 1.0; }

void validate(const ShapeImportOptions& options) {
  require_in_range("particle.library_max_hull_excess", options.max_hull_excess, 0.0, 100.0);
  if (options.max_vertices < 4 || options.max_vertices > 1000000) {
    throw InvalidInput("particle.library_max_vertices", std::to_string(options.max_vertices),
                       "[4, 1000000]");
  }
}

std::string ShapeLibraryOptions::paths_text() const {
  std::string text;
  for (const std::string& path : paths) text += (text.empty() ? "" : ", ") + path;
  return text;
}

std::string ShapeLibrary::summary() const {
  return source + " (" + std::to_string(shapes.size()) + " shapes, " +
         std::to_string(skipped.size()) + " skipped, units " +
         std::string(length_unit_name(units)) + ")";
}

std::string ShapeLibrary::hull_summary() const {
  double mesh_total = 0.0;
  double hull_total = 0.0;
  for (const LibraryShape& shape : shapes) {
    mesh_total += shape.mesh_volume;
    hull_total += shape.hull_volume;
  }
  char text[160];
  std::snprintf(text, sizeof text, "add %.6g m^3 to %.6g m^3 of meshes (%+.3f %%)",
                hull_total - mesh_total, mesh_total, 100.0 * (hull_total / mesh_total - 1.0));
  return text;
}

std::string ShapeLibrary::provenance(std::span<const std::uint32_t> stored) const {
  std::string text = "library " + source + " (units " + std::string(length_unit_name(units)) +
                     ", " + std::to_string(shapes.size()) + " shapes, " +
                     std::to_string(skipped.size()) + " skipped, " + std::to_string(stored.size()) +
                     " stored)\n";
  for (const std::uint32_t k : stored) {
    const LibraryShape& shape = shapes.at(k);
    text += shape.name + "\t" + shape.hash + "\n";
  }
  return text;
}

LibraryShape import_shape(const TriangleMesh& mesh, const ShapeImportOptions& options,
                          std::string name, std::string hash, const std::string& file) {
  // The errors' sentences name the file first.
  const std::string named = file.empty() ? name : file;
  const MeshCheck check = check_particle_mesh(mesh);
  if (!check.is_ok) {
    Wording wording = check.wording;
    wording.values.insert(wording.values.begin(), named);
    throw FormatError(wording);
  }
  const double unit = metres_per_unit(options.units);
  LibraryShape shape;
  shape.name = std::move(name);
  shape.hash = std::move(hash);
  shape.mesh_vertices = mesh.vertices.size();
  shape.mesh_triangles = mesh.triangles.size();
  // Inward-facing files (every triangle turned) are the same solid: the magnitude counts.
  shape.mesh_volume = std::abs(mesh_volume(mesh)) * unit * unit * unit;
  std::vector<Vec3> points(mesh.vertices.size());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = mesh.vertices[i] * unit;
  ConvexPolyhedron hull;
  try {
    hull = convex_hull(points);
  } catch (const InvalidInput& error) {
    const Wording& code = error.value_wording();
    if (code.sentence == Sentence::kQhullError && !error.wording().values.empty()) {
      throw FormatError(Wording{Sentence::kMeshNoHull,
                                {named, code.values.at(0), error.wording().values.front()}});
    }
    throw FormatError(Wording{Sentence::kMeshNoHullReason, {error.what()}});
  }
  shape.hull_vertices = hull.vertex_count();
  shape.hull_volume = mass_properties(hull).volume;
  if (options.max_hull_excess > 0.0 && shape.hull_excess() > options.max_hull_excess) {
    char excess[48];
    std::snprintf(excess, sizeof excess, "%.3g", 100.0 * shape.hull_excess());
    char limit[48];
    std::snprintf(limit, sizeof limit, "%.6g", options.max_hull_excess);
    throw Error(ErrorKind::kLimitExceeded,
                Wording{Sentence::kMeshHullExcess,
                        {named, excess, "particle.library_max_hull_excess", limit}});
  }
  ConvexPolyhedron body = simplify_hull(hull, options.max_vertices);
  const MassProperties mass = mass_properties(body);
  shape.volume = mass.volume;
  body = body.translated(-mass.centroid);
  const Sphere sphere = minimal_enclosing_sphere(body.vertices());
  shape.size = 2.0 * sphere.radius;
  const double to_unit = 1.0 / sphere.radius;
  shape.body = body.scaled(to_unit);
  shape.enclosing_centre = sphere.centre * to_unit;
  return shape;
}

}  // namespace aggpack
