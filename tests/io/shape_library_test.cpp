// Particle shape libraries from files (particle.library): the STL / OBJ / PLY readers, the mesh
// checks with their one-line errors, convex hulls against volumes known in closed form, the
// vertex budget, skipping bad files, units and the unit-size normalisation.

#include "aggpack/io/shape_library_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "../support/mesh_files.h"
#include "aggpack/core/error.h"
#include "aggpack/geom/convex_hull_3d.h"
#include "aggpack/geom/enclosing_sphere.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/mesh_read.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;
using test::PlyEncoding;

class Folder {
 public:
  Folder() {
    std::string pattern = (fs::temp_directory_path() / "aggpack-shapelib-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  Folder(const Folder&) = delete;
  Folder& operator=(const Folder&) = delete;
  ~Folder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  [[nodiscard]] std::string path() const { return path_.string(); }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  void write(const std::string& name, const std::string& bytes) const {
    test::write_file(file(name), bytes);
  }

 private:
  fs::path path_;
};

// What a load of `path` throws, as (kind, message); fails the test when it does not throw.
std::pair<ErrorKind, std::string> load_error(const ShapeLibraryOptions& options) {
  try {
    (void)load_shape_library(options);
  } catch (const Error& error) {
    return {error.kind(), error.what()};
  }
  ADD_FAILURE() << "no error for " << options.paths_text();
  return {ErrorKind::kInvalidInput, ""};
}

TEST(MeshRead, EveryFormatReadsTheSameMesh) {
  const TriangleMesh rock = test::dented_icosahedron(5.0, 0.7, Vec3(1, 2, 3));
  ASSERT_TRUE(check_particle_mesh(rock).is_ok) << check_particle_mesh(rock).message;
  const double volume = mesh_volume(rock);
  ASSERT_GT(volume, 0.0);
  const std::pair<std::string, std::string> files[] = {
      {"rock.obj", test::obj_text(rock)},
      {"rock.ply", test::ply_bytes(rock, PlyEncoding::kAscii)},
      {"rock_le.ply", test::ply_bytes(rock, PlyEncoding::kLittle)},
      {"rock_be.PLY", test::ply_bytes(rock, PlyEncoding::kBig)},
  };
  for (const auto& [name, bytes] : files) {
    MeshFileFormat format{};
    ASSERT_TRUE(mesh_file_format(name, format)) << name;
    const TriangleMesh read = parse_mesh(bytes, format, name);
    EXPECT_EQ(read.vertices, rock.vertices) << name;
    EXPECT_EQ(read.triangles, rock.triangles) << name;
  }
  // STL stores floats and repeats each corner: joined back to the 32 vertices, same triangles.
  for (const auto& bytes : {test::stl_binary(rock), test::stl_ascii(rock)}) {
    const TriangleMesh read = parse_mesh(bytes, MeshFileFormat::kStl, "rock.stl");
    EXPECT_EQ(read.vertices.size(), rock.vertices.size());
    EXPECT_EQ(read.triangles.size(), rock.triangles.size());
    EXPECT_TRUE(check_particle_mesh(read).is_ok);
    EXPECT_NEAR(mesh_volume(read), volume, 1e-6 * volume);  // float coordinates
  }
}

TEST(MeshRead, MalformedFilesAreOneLineErrorsNamingTheFile) {
  const TriangleMesh cube = test::dented_cube(1.0, 0.3);
  std::string big = test::ply_bytes(cube, PlyEncoding::kLittle);
  const auto at = big.find("element face 14");
  big.replace(at, 15, "element face 99999999");  // more faces than the bytes left
  const std::pair<std::string, std::string> cases[] = {
      {"a.obj", "v 0 0 0\nv 1 0 x\n"},
      {"b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"c.obj", "v 0 0 0\ncurv 0 1\n"},
      {"d.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n"},
      {"e.ply", big},
      {"f.ply", test::ply_bytes(cube, PlyEncoding::kBig).substr(0, 300)},
      {"g.stl", "solid x\nfacet normal 0 0 1\n outer loop\n"},
      {"h.stl", "not an stl at all"},
      // An element without properties and 6e12 entries (a fuzzer's find): read at once, no loop.
      {"i.ply", "ply\nformat binary_little_endian 1.0\nelement junk 6111111111111\nend_header\n"},
  };
  for (const auto& [name, bytes] : cases) {
    MeshFileFormat format{};
    ASSERT_TRUE(mesh_file_format(name, format));
    try {
      (void)parse_mesh(bytes, format, name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const FormatError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(name, 0), 0u) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

TEST(MeshCheck, NamesWhatIsWrong) {
  EXPECT_TRUE(check_particle_mesh(test::dented_cube(1, 0.5)).is_ok);
  TriangleMesh open = test::dented_cube(1, 0.5);
  open.triangles.pop_back();
  EXPECT_NE(check_particle_mesh(open).message.find("is open"), std::string::npos);
  EXPECT_NE(check_particle_mesh(test::finned_cube()).message.find("shared by 3 triangles"),
            std::string::npos)
      << check_particle_mesh(test::finned_cube()).message;
  EXPECT_NE(check_particle_mesh(test::bowtie()).message.find("non-manifold: vertex 0"),
            std::string::npos)
      << check_particle_mesh(test::bowtie()).message;
  TriangleMesh sliver = test::dented_cube(1, 0.5);
  sliver.vertices.emplace_back(0.5, 0.0, 0.0);  // midpoint of edge (0, 1)
  sliver.triangles.push_back({0, 1, 9});
  EXPECT_NE(check_particle_mesh(sliver).message.find("triangle 14 has zero area"),
            std::string::npos);
  TriangleMesh flipped = test::dented_cube(1, 0.5);
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_NE(check_particle_mesh(flipped).message.find("inconsistently oriented"),
            std::string::npos);
  TriangleMesh two = test::dented_icosahedron(1, 0.8, Vec3::Zero());
  const TriangleMesh other = test::dented_icosahedron(1, 0.8, Vec3(5, 0, 0));
  const auto offset = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (auto t : other.triangles)
    two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  EXPECT_NE(check_particle_mesh(two).message.find("2 separate pieces"), std::string::npos);
}

TEST(ShapeImport, HullVolumesAreExact) {
  // Dented cube of 10 mm: mesh 1000 - 100 x 4 / 3 mm^3, hull exactly the cube.
  const LibraryShape cube =
      import_shape(test::dented_cube(10.0, 4.0), {.units = LengthUnit::kMillimetre}, "c", "h");
  EXPECT_NEAR(cube.mesh_volume, (1000.0 - 400.0 / 3.0) * 1e-9, 1e-20);
  EXPECT_NEAR(cube.hull_volume, 1000.0 * 1e-9, 1e-20);
  EXPECT_NEAR(cube.hull_excess(), 1000.0 / (1000.0 - 400.0 / 3.0) - 1.0, 1e-12);
  EXPECT_EQ(cube.hull_vertices, 8u);
  EXPECT_EQ(cube.volume, cube.hull_volume);  // within the budget: not simplified
  // Stored at unit size: enclosing sphere radius 1 (the cube's half diagonal), centroid 0.
  EXPECT_NEAR(cube.size, 10e-3 * std::sqrt(3.0), 1e-15);
  const MassProperties mass = mass_properties(cube.body);
  EXPECT_NEAR(mass.centroid.norm(), 0.0, 1e-12);
  EXPECT_NEAR(mass.volume, 8.0 / (3.0 * std::sqrt(3.0)), 1e-12);  // (2 / sqrt 3)^3
  EXPECT_NEAR(minimal_enclosing_sphere(cube.body.vertices()).radius, 1.0, 1e-12);
  EXPECT_TRUE(check_convex(cube.body, 1e-12).is_ok);

  // The bumpy rock in metres: its hull is the icosahedron.
  const TriangleMesh rock = test::dented_icosahedron(0.02, 0.6, Vec3(0.5, -0.2, 0.1));
  const LibraryShape shape = import_shape(rock, {.units = LengthUnit::kMetre}, "r", "h");
  EXPECT_NEAR(shape.hull_volume, test::icosahedron_volume(0.02), 1e-15 * 1e-3);
  EXPECT_NEAR(shape.mesh_volume, mesh_volume(rock), 1e-18);
  EXPECT_GT(shape.hull_excess(), 0.0);
  EXPECT_EQ(shape.hull_vertices, 12u);
  EXPECT_NEAR(shape.size, 0.04, 1e-12);
}

TEST(ShapeImport, VertexBudgetOnlyLosesVolumeAndReportsIt) {
  // Many points on a sphere: a hull of ~2000 vertices simplified to at most 100.
  std::vector<Vec3> points;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < 2000; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / 2000.0;
    const double r = std::sqrt(1.0 - z * z);
    points.emplace_back(r * std::cos(golden * k), r * std::sin(golden * k), z);
  }
  const ConvexPolyhedron hull = convex_hull(points);
  EXPECT_EQ(hull.vertex_count(), 2000u);
  EXPECT_TRUE(check_closed_manifold(hull).is_ok) << check_closed_manifold(hull).message;
  const ConvexPolyhedron small = simplify_hull(hull, 100);
  EXPECT_LE(small.vertex_count(), 100u);
  EXPECT_GE(small.vertex_count(), 80u);
  EXPECT_TRUE(check_convex(small, 1e-12).is_ok);
  for (const Vec3& v : small.vertices()) {  // every kept vertex is a hull vertex
    EXPECT_NE(std::find(points.begin(), points.end(), v), points.end());
  }
  const double full = mass_properties(hull).volume;
  const double reduced = mass_properties(small).volume;
  EXPECT_LT(reduced, full);
  EXPECT_GT(reduced, 0.9 * full);
  EXPECT_THROW((void)convex_hull(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}),
               InvalidInput);
}

TEST(ShapeLibraryFiles, LoadsAFolderInNameOrderWithHashes) {
  Folder folder;
  const TriangleMesh cube = test::dented_cube(10.0, 4.0);
  const TriangleMesh rock = test::dented_icosahedron(6.0, 0.7, Vec3(100, 0, 0));
  folder.write("b_cube.stl", test::stl_binary(cube));
  folder.write("a_rock.OBJ", test::obj_text(rock));
  folder.write("c_rock.ply", test::ply_bytes(rock, PlyEncoding::kLittle));
  folder.write("d_cube_ascii.stl", test::stl_ascii(cube));
  folder.write("notes.txt", "ignored");
  const ShapeLibrary library = load_shape_library({.paths = {folder.path()}});
  ASSERT_EQ(library.shapes.size(), 4u);
  EXPECT_EQ(library.shapes[0].name, "a_rock.OBJ");
  EXPECT_EQ(library.shapes[3].name, "d_cube_ascii.stl");
  EXPECT_EQ(library.shapes[1].hash, content_hash(test::stl_binary(cube)));
  EXPECT_NE(library.shapes[1].hash, library.shapes[3].hash);
  EXPECT_NEAR(library.shapes[1].hull_volume, 1000e-9, 1e-18);
  EXPECT_NEAR(library.shapes[0].hull_volume, test::icosahedron_volume(6e-3), 1e-16);
  // The provenance lists the stored shapes only, in the packing's order (library 3, then 0).
  const std::vector<std::uint32_t> stored = {3, 0};
  const std::string provenance = library.provenance(stored);
  EXPECT_NE(provenance.find("4 shapes, 0 skipped, 2 stored)\nd_cube_ascii.stl\tfnv1a64:"),
            std::string::npos)
      << provenance;
  EXPECT_NE(provenance.find("\na_rock.OBJ\tfnv1a64:"), std::string::npos) << provenance;
  EXPECT_EQ(provenance.find("b_"), std::string::npos) << provenance;
}

TEST(ShapeLibraryFiles, BadFilesStopTheLoadOrAreSkippedAndCounted) {
  Folder folder;
  TriangleMesh open = test::dented_cube(1.0, 0.3);
  open.triangles.pop_back();
  folder.write("good.stl", test::stl_binary(test::dented_cube(1.0, 0.3)));
  folder.write("open.stl", test::stl_binary(open));
  folder.write("bowtie.obj", test::obj_text(test::bowtie()));
  folder.write("zero.ply",
               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty "
               "float y\nproperty float z\nelement face 4\nproperty list uchar int "
               "vertex_indices\nend_header\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n3 0 1 2\n"
               "3 0 2 3\n3 0 3 1\n3 1 3 2\n");
  const auto [kind, message] = load_error({.paths = {folder.path()}});
  EXPECT_EQ(kind, ErrorKind::kFormatError);
  EXPECT_EQ(message, folder.file("bowtie.obj") +
                         ": mesh is non-manifold: vertex 0 joins two surfaces that touch only "
                         "there");
  const ShapeLibrary library =
      load_shape_library({.paths = {folder.path()}, .is_skipping_bad = true});
  ASSERT_EQ(library.shapes.size(), 1u);
  ASSERT_EQ(library.skipped.size(), 3u);
  EXPECT_EQ(library.skipped[1].rfind("open.stl: mesh is open: edge", 0), 0u);
  EXPECT_EQ(library.skipped[2], "zero.ply: mesh triangle 0 has zero area (degenerate)");
  // The hull excess limit: the dented cube's hull adds 1 / (1 - 0.1) - 1 = 11.1 %.
  const ShapeLibraryOptions strict{.paths = {folder.file("good.stl")},
                                   .import = {.max_hull_excess = 0.1}};
  const auto [limit_kind, limit_message] = load_error(strict);
  EXPECT_EQ(limit_kind, ErrorKind::kLimitExceeded);
  EXPECT_EQ(limit_message, folder.file("good.stl") +
                               ": its convex hull adds 11.1 % to its volume, above "
                               "particle.library_max_hull_excess = 0.1");
  EXPECT_NO_THROW((void)load_shape_library(
      {.paths = {folder.file("good.stl")}, .import = {.max_hull_excess = 0.12}}));
  EXPECT_EQ(load_error({.paths = {folder.file("none")}}).second,
            "invalid particle.library = \"" + folder.file("none") +
                "\" (allowed: an existing folder, or a .stl, .obj or .ply file)");
}

}  // namespace
}  // namespace aggpack
