// `aggpack shapes --library` and `aggpack pack` / `info` with particle.library, end to end: the
// rows and summary printed, the exact hull numbers of a dented cube, the provenance in the
// native file, and one-line errors with exit 2.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_test.h"
#include "support/mesh_files.h"

namespace aggpack {
namespace {

using test::CliRun;

class LibraryCli : public test::CliTest {
 protected:
  void write_library() const {
    std::filesystem::create_directories(path("rocks"));
    test::write_file(path("rocks/cube.stl"), test::stl_binary(test::dented_cube(10, 3)));
    test::write_file(path("rocks/rock.obj"),
                     test::obj_text(test::dented_icosahedron(6, 0.7, Vec3(1, 1, 1))));
    test::write_file(
        path("rocks/rock.ply"),
        test::ply_bytes(test::dented_icosahedron(8, 0.5, Vec3::Zero()), test::PlyEncoding::kBig));
  }
};

TEST_F(LibraryCli, ShapesPrintsEachShapeAndTheSummary) {
  write_library();
  const CliRun run = this->run("shapes --library rocks --units mm");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("index,control_radius,volume,"), std::string::npos);
  // The dented cube (file order: cube.stl first): hull = 1000 mm^3, mesh 1000 - 100 mm^3.
  EXPECT_NE(run.out.find(",cube.stl,fnv1a64:"), std::string::npos);
  const auto at = run.out.find(",cube.stl,");
  ASSERT_NE(at, std::string::npos) << run.out;
  const auto begin = run.out.rfind('\n', at) + 1;
  std::vector<std::string> fields;
  std::stringstream row(run.out.substr(begin, run.out.find('\n', at) - begin));
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  ASSERT_GE(fields.size(), 6u);
  const std::size_t n = fields.size();
  EXPECT_NEAR(std::stod(fields[n - 4]), 900e-9, 1e-18);   // mesh: 1000 - 10^2 x 3 / 3 mm^3
  EXPECT_NEAR(std::stod(fields[n - 3]), 1000e-9, 1e-18);  // hull: the cube
  EXPECT_NEAR(std::stod(fields[n - 2]), 1.0 / 9.0, 1e-12);
  EXPECT_EQ(std::stod(fields[n - 1]), 0.0);  // 8 vertices: within the budget
  EXPECT_NE(run.out.find("library         rocks (3 shapes, 0 skipped, units mm)"),
            std::string::npos);
  EXPECT_NE(run.out.find("descriptor                      mean"), std::string::npos);
  EXPECT_NE(run.out.find("sphericity"), std::string::npos);
}

TEST_F(LibraryCli, PackStoresTheLibraryOnceAndInfoShowsIt) {
  write_library();
  test::write_file(path("rocks.toml"),
                   "[container]\nkind = \"box\"\nlength = 0.2\nwidth = 0.2\ndepth = 0.2\n"
                   "[particle]\nlibrary = \"rocks\"\nradius_min = 0.015\nradius_max = 0.025\n"
                   "[packer]\nkind = \"random\"\ntarget_fraction = 0.15\nseed = 2\n");
  const CliRun pack = run("pack rocks.toml -o rocks.h5");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  // The run names its library: where from, shapes, skipped, and the volume the hulls added (the
  // dented cube's 100 mm^3 and the two dented icosahedra's).
  EXPECT_NE(pack.out.find("\nshape library   rocks (3 shapes, 0 skipped, units mm)\n"),
            std::string::npos)
      << pack.out;
  EXPECT_NE(pack.out.find("\nconvex hulls    add "), std::string::npos) << pack.out;
  const CliRun json = run("pack rocks.toml -o rocks-json.h5 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"library\": {\"source\": \"rocks\", \"shapes\": 3, \"skipped\": 0, "
                          "\"units\": \"mm\", \"mesh_volume_m3\": "),
            std::string::npos)
      << json.out;
  const CliRun info = run("info rocks.h5");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("shape library   library rocks (units mm, 3 shapes, 0 skipped, 3 "
                          "stored)"),
            std::string::npos)
      << info.out;
  // The stored shapes in order of first use (seed 2: rock.obj first), one provenance line each:
  // shape k's line names the file the packing's shape k came from (it used to list the library
  // in folder order, which named the wrong file for shape 0).
  EXPECT_NE(info.out.find("  shape 0      rock.obj fnv1a64:"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("  shape 1      cube.stl fnv1a64:"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("(3 distinct shapes)"), std::string::npos) << info.out;
  // Exports take the packing unchanged.
  const CliRun exported = run("export rocks.h5 -o rocks.stl");
  EXPECT_EQ(exported.exit_code, 0) << exported.err;
}

TEST_F(LibraryCli, BadMeshesAreOneLineErrorsOrSkipped) {
  write_library();
  TriangleMesh open = test::dented_cube(10, 3);
  open.triangles.pop_back();
  test::write_file(path("rocks/open.stl"), test::stl_ascii(open));
  const CliRun run = this->run("shapes --library rocks");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err.rfind("aggpack: error: rocks/open.stl: mesh is open: edge (", 0), 0u)
      << run.err;
  EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
  const CliRun skipped = this->run("shapes --library rocks --skip-bad");
  ASSERT_EQ(skipped.exit_code, 0) << skipped.err;
  EXPECT_NE(skipped.out.find("(3 shapes, 1 skipped, units mm)"), std::string::npos);
  EXPECT_NE(skipped.out.find("skipped         open.stl: mesh is open"), std::string::npos);
  const CliRun limit = this->run("shapes --library rocks/cube.stl --max-hull-excess 0.05");
  EXPECT_EQ(limit.exit_code, 2);
  EXPECT_NE(limit.err.find("its convex hull adds 11.1 % to its volume"), std::string::npos)
      << limit.err;
  EXPECT_NE(limit.err.find("above --max-hull-excess = 0.05"), std::string::npos) << limit.err;
  const CliRun empty = this->run("shapes --library ''");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_EQ(empty.err.rfind("aggpack: error: invalid --library = \"\"", 0), 0u) << empty.err;
  const CliRun none = this->run("pack --set particle.library=nowhere --set packer.kind=random");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("particle.library = \"nowhere\""), std::string::npos) << none.err;
}

// A list of folders and files: --library repeated or comma-separated, particle.library an array.
TEST_F(LibraryCli, ListsOfFilesAndFolders) {
  write_library();
  std::filesystem::create_directories(path("more"));
  test::write_file(path("more/cube.stl"), test::stl_ascii(test::dented_cube(20, 5)));
  const CliRun shapes = run("shapes --library rocks/rock.ply,rocks/cube.stl --library more");
  ASSERT_EQ(shapes.exit_code, 0) << shapes.err;
  // In the list's order, each named by its path (two files are called cube.stl).
  const auto ply = shapes.out.find(",rocks/rock.ply,fnv1a64:");
  const auto cube = shapes.out.find(",rocks/cube.stl,fnv1a64:");
  const auto more = shapes.out.find(",more/cube.stl,fnv1a64:");
  ASSERT_NE(more, std::string::npos) << shapes.out;
  EXPECT_LT(ply, cube);
  EXPECT_LT(cube, more);
  EXPECT_EQ(shapes.out.find("rock.obj"), std::string::npos) << "a file not listed was read";
  EXPECT_NE(shapes.out.find("library         rocks/rock.ply, rocks/cube.stl, more (3 shapes, "),
            std::string::npos)
      << shapes.out;
  // A file named twice (directly and through its folder) is refused, naming it.
  const CliRun twice = run("shapes --library rocks --library rocks/cube.stl");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("invalid --library = \"rocks/cube.stl\""), std::string::npos)
      << twice.err;
  EXPECT_NE(twice.err.find("is named twice"), std::string::npos) << twice.err;
  // The config key as an array; the resolved configuration writes it back as one.
  const CliRun pack =
      run("pack --set 'particle.library=[\"rocks/cube.stl\", \"more\"]' --set packer.kind=random "
          "--set container.length=0.2 --set container.width=0.2 --set container.depth=0.2 --set "
          "particle.radius_min=0.015 --set particle.radius_max=0.025 --set "
          "packer.target_fraction=0.1 -o two.h5");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_NE(pack.out.find("shape library   rocks/cube.stl, more (2 shapes, 0 skipped"),
            std::string::npos)
      << pack.out;
  const CliRun config =
      run("pack --set 'particle.library=[\"rocks/cube.stl\", \"more\"]' --print-config");
  EXPECT_NE(config.out.find("library = [\"rocks/cube.stl\", \"more\"]"), std::string::npos)
      << config.out;
  const CliRun bad = run("pack --set 'particle.library=[\"rocks\", 3]' --print-config");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("particle.library[1] must be a non-empty string (a file path)"),
            std::string::npos)
      << bad.err;
}

// A file in a folder the user may not enter is "permission denied", not "no such file" (stat fails
// with EACCES there). Root ignores permission bits, so as root the commands run as nobody
// (setpriv); the test fails, not skips, when that is impossible.
TEST_F(LibraryCli, FileInAnUnreadableFolderIsPermissionDeniedNotMissing) {
  write_library();
  std::filesystem::create_directories(path("locked"));
  std::filesystem::copy_file(path("rocks/cube.stl"), path("locked/cube.stl"));
  ASSERT_EQ(run("pack --progress none --set packer.kind=random --set container.length=0.3 "
                "--set container.width=0.3 --set container.depth=0.3 "
                "--set particle.radius_min=0.03 --set particle.radius_max=0.05 "
                "--set packer.target_fraction=0.1 -o locked/p.h5")
                .exit_code,
            0);
  std::filesystem::permissions(path("locked"), std::filesystem::perms::none);
  const std::string as_user =
      ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups" : "";
  // The other user can run aggpack but cannot enter the folder.
  ASSERT_EQ(run("--version", as_user).exit_code, 0) << "cannot run aggpack as another user";
  const std::string probe = "cd '" + folder_.string() + "' && " + as_user + " test -e locked/p.h5";
  ASSERT_NE(std::system(probe.c_str()), 0) << "the locked folder is readable";

  const CliRun info = run("info locked/p.h5", as_user);
  EXPECT_EQ(info.exit_code, 3);
  EXPECT_EQ(info.err, "aggpack: error: cannot read locked/p.h5: permission denied\n");
  const CliRun shapes = run("shapes --library locked/cube.stl", as_user);
  EXPECT_NE(shapes.exit_code, 0);
  EXPECT_NE(shapes.err.find("locked/cube.stl: permission denied"), std::string::npos) << shapes.err;
  EXPECT_EQ(shapes.err.find("no such file"), std::string::npos) << shapes.err;
  // A file of its own that may not be read, in a folder that may: the same words.
  std::filesystem::copy_file(path("rocks/cube.stl"), path("closed.stl"));
  std::filesystem::permissions(path("closed.stl"), std::filesystem::perms::none);
  const CliRun closed = run("shapes --library closed.stl", as_user);
  EXPECT_NE(closed.exit_code, 0);
  EXPECT_NE(closed.err.find("closed.stl: permission denied"), std::string::npos) << closed.err;
  // A file that is really missing is still "no such file".
  const CliRun missing = run("info rocks/none.h5", as_user);
  EXPECT_EQ(missing.err, "aggpack: error: cannot read rocks/none.h5: no such file\n");
  std::filesystem::permissions(path("locked"), std::filesystem::perms::owner_all);
}

}  // namespace
}  // namespace aggpack
