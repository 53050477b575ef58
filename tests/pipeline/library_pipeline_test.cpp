// Packing library shapes from mesh files (particle.library) with every packer kind: overlap-free
// and contained (verify, brute force), each particle a library shape scaled to its sieve size
// (enclosing diameter), the library stored once, use-once, reproducible, provenance, and the
// config keys.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include "../support/mesh_files.h"
#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/geom/enclosing_sphere.h"
#include "aggpack/io/mesh_read.h"
#include "aggpack/pack/verify.h"
#include "aggpack/pipeline/pipeline.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

// A library folder of 4 shapes in mm: two dented cubes, two bumpy rocks, in 3 formats.
class Library {
 public:
  Library() {
    std::string pattern = (fs::temp_directory_path() / "aggpack-libpack-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
    test::write_file(file("cube.stl"), test::stl_binary(test::dented_cube(10, 3)));
    test::write_file(file("flat.obj"), test::obj_text(test::dented_cube(4, 1)));
    test::write_file(file("rock.ply"),
                     test::ply_bytes(test::dented_icosahedron(5, 0.7, Vec3(1, 2, 3)),
                                     test::PlyEncoding::kLittle));
    test::write_file(file("rock2.stl"),
                     test::stl_ascii(test::dented_icosahedron(8, 0.5, Vec3::Zero())));
  }
  Library(const Library&) = delete;
  Library& operator=(const Library&) = delete;
  ~Library() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  [[nodiscard]] std::string path() const { return path_.string(); }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

std::string config_text(const Library& library, const std::string& packer,
                        const std::string& sizes = "radius_min = 0.02\nradius_max = 0.035",
                        const std::string& tables = "") {
  return "[container]\nkind = \"box\"\nlength = 0.3\nwidth = 0.3\ndepth = 0.3\n"
         "[particle]\nlibrary = \"" +
         library.path() + "\"\n" + sizes + "\n[packer]\n" + packer + "\nseed = 5\n" + tables;
}

void expect_library_packing(const Packing& packing, std::size_t library_size) {
  ASSERT_GT(packing.particles.size(), 10u);
  EXPECT_EQ(packing.shapes.size(), library_size);  // the library once, not a shape per particle
  const VerifyResult check = verify(packing, {.is_brute_force = true});
  EXPECT_TRUE(check.is_ok) << check.message;
  std::set<std::uint32_t> used;
  for (const Particle& particle : packing.particles) {
    used.insert(particle.shape);
    // Unit library shape (enclosing radius 1) x scale: the enclosing diameter is the size.
    EXPECT_NEAR(minimal_enclosing_sphere(packing.shapes[particle.shape].vertices()).radius, 1.0,
                1e-9);
  }
  EXPECT_GE(used.size(), 3u);
  // Only used shapes are stored, one provenance line each after the header.
  EXPECT_EQ(used.size(), packing.shapes.size());
  const std::string& provenance = packing.provenance.shape_library;
  EXPECT_EQ(static_cast<std::size_t>(std::count(provenance.begin(), provenance.end(), '\n')),
            packing.shapes.size() + 1)
      << provenance;
  EXPECT_NE(provenance.find("cube.stl\tfnv1a64:"), std::string::npos);
}

TEST(LibraryPipeline, RandomPackerPlacesLibraryShapesAtTheirSieveSizes) {
  const Library library;
  const PackConfig config =
      parse_pack_config(config_text(library, "kind = \"random\"\ntarget_fraction = 0.2"));
  const PipelineResult result = pack(config);
  expect_library_packing(result.packing, 4);
  for (const Particle& particle : result.packing.particles) {
    EXPECT_GE(particle.scale, 0.02 - 1e-12);  // scale = size / 2 = control radius
    EXPECT_LE(particle.scale, 0.035 + 1e-12);
    EXPECT_EQ(particle.scale, particle.control_radius);
  }
  EXPECT_GE(result.report.solid_fraction, 0.2);
  // Same config and seed: identical packing.
  const PipelineResult again = pack(config);
  ASSERT_EQ(again.packing.particles.size(), result.packing.particles.size());
  for (std::size_t i = 0; i < again.packing.particles.size(); ++i) {
    EXPECT_EQ(again.packing.particles[i].pose.position, result.packing.particles[i].pose.position);
    EXPECT_EQ(again.packing.particles[i].shape, result.packing.particles[i].shape);
  }
}

TEST(LibraryPipeline, LatticeAndDensePackersUseTheLibrary) {
  const Library library;
  const PipelineResult lattice =
      pack(parse_pack_config(config_text(library, "kind = \"lattice\"", "radius = 0.03")));
  expect_library_packing(lattice.packing, 4);
  const PipelineResult dense = pack(parse_pack_config(
      config_text(library, "kind = \"dense\"\ntarget_fraction = 0.15",
                  "radius_min = 0.02\nradius_max = 0.035", "[densify]\nmax_sweeps = 20\n")));
  expect_library_packing(dense.packing, 4);
}

// A lattice of fewer sites than library shapes stores the shapes placed, not the whole library
// (issue 35: a large library made a file of every shape).
TEST(LibraryPipeline, LatticeStoresOnlyTheShapesItPlaced) {
  const Library library;
  const std::string text =
      "[container]\nkind = \"box\"\nlength = 0.07\nwidth = 0.07\n"
      "depth = 0.07\n[particle]\nlibrary = \"" +
      library.path() + "\"\nradius = 0.03\n[packer]\nkind = \"lattice\"\nseed = 5\n";
  const PipelineResult result = pack(parse_pack_config(text));
  const Packing& packing = result.packing;
  ASSERT_EQ(packing.particles.size(), 1u);
  ASSERT_EQ(packing.shapes.size(), 1u);  // was 4: every library shape
  EXPECT_EQ(packing.particles[0].shape, 0u);
  ASSERT_EQ(result.library_shapes.size(), 1u);
  const std::string& provenance = packing.provenance.shape_library;
  EXPECT_NE(provenance.find("4 shapes, 0 skipped, 1 stored)\n"), std::string::npos) << provenance;
  EXPECT_EQ(std::count(provenance.begin(), provenance.end(), '\n'), 2) << provenance;
  // The stored shape is the library's shape library_shapes[0], unscaled (enclosing radius 1).
  EXPECT_NEAR(minimal_enclosing_sphere(packing.shapes[0].vertices()).radius, 1.0, 1e-9);
}

TEST(LibraryPipeline, UseOnceNeedsEnoughShapesAndErrorsAreOneLine) {
  const Library library;
  const PackConfig config =
      parse_pack_config(config_text(library, "kind = \"random\"\ntarget_count = 4"), "config",
                        {"particle.library_use_once=true"});
  const PipelineResult once = pack(config);
  std::set<std::uint32_t> used;
  for (const Particle& particle : once.packing.particles) used.insert(particle.shape);
  EXPECT_EQ(used.size(), once.packing.particles.size());
  const PackConfig five =
      parse_pack_config(config_text(library, "kind = \"random\"\ntarget_count = 5"), "config",
                        {"particle.library_use_once=true"});
  try {
    (void)pack(five);
    FAIL() << "5 particles from 4 shapes used once";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "limit exceeded for random.count = 5 (allowed: at most the library's 4 shapes when "
              "particle.library_use_once = true)");
  }
  test::write_file(library.file("open.obj"),
                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\n"
                   "f 1 2 4\nf 1 4 3\nf 1 2 3\n");
  try {
    (void)pack(parse_pack_config(config_text(library, "kind = \"random\"\ntarget_count = 4")));
    FAIL() << "an open mesh was packed";
  } catch (const Error& error) {
    EXPECT_EQ(error.kind(), ErrorKind::kFormatError);
    EXPECT_EQ(
        std::string(error.what()),
        library.file("open.obj") + ": mesh is non-manifold: edge (0, 1) is shared by 3 triangles");
  }
  const PipelineResult skipped =
      pack(parse_pack_config(config_text(library, "kind = \"random\"\ntarget_count = 4"), "config",
                             {"particle.library_skip_bad=true"}));
  EXPECT_NE(skipped.packing.provenance.shape_library.find("4 shapes, 1 skipped"),
            std::string::npos);
}

}  // namespace
}  // namespace aggpack
