// `aggpack repose` with particle.library: the trough's lattice fill takes its shapes from mesh
// files (each particle one of them, its convex hull at enclosing radius particle.radius), the run
// records the files in repose.json and final.h5, and the library's keys are named as typed.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_test.h"
#include "support/mesh_files.h"
#include "support/paths.h"
#include "support/troughs.h"

namespace aggpack {
namespace {

using test::CliRun;

// 2 x 2 x 2 = 8 lattice sites behind the baffle, R = 5 mm; short stages.
const std::string kLibraryTrough = test::small_trough("library = \"rocks\"\n");

class ReposeLibraryCli : public test::CliTest {
 protected:
  ReposeLibraryCli() : CliTest("aggpack_repose_library_") {}
  // Two non-convex rocks (mm): a dented cube (hull: the cube) and a dented icosahedron (hull:
  // the icosahedron), so every particle's volume is one of two exact values.
  void write_inputs() const {
    std::filesystem::create_directories(path("rocks"));
    test::write_file(path("rocks/cube.stl"), test::stl_binary(test::dented_cube(10, 3)));
    test::write_file(path("rocks/rock.obj"),
                     test::obj_text(test::dented_icosahedron(6, 0.7, Vec3(1, 1, 1))));
    std::ofstream(path("small.toml")) << kLibraryTrough;
  }
};

TEST_F(ReposeLibraryCli, FillTakesItsShapesFromTheFilesAndTheRunRecordsThem) {
  write_inputs();
  const CliRun run = this->run("repose small.toml -o out --progress none");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(path("out/repose.json"));
  const nlohmann::json json = nlohmann::json::parse(in);
  const auto& particles = json.at("particles");
  ASSERT_EQ(particles.at("count").get<int>(), 8);
  // Enclosing radius R: the cube's hull has side 2 R / sqrt 3, the icosahedron circumradius R.
  const double r = 0.005;
  const double cube = std::pow(2.0 * r / std::sqrt(3.0), 3);
  const double icosahedron = test::icosahedron_volume(r);
  const double solid = particles.at("solid_volume_m3").get<double>();
  // solid = k cubes + (8 - k) icosahedra for one whole k (grown particles would not be).
  const double k = (solid - 8.0 * icosahedron) / (cube - icosahedron);
  EXPECT_NEAR(k, std::round(k), 1e-6) << solid;
  EXPECT_GE(std::round(k), 0.0);
  EXPECT_LE(std::round(k), 8.0);
  // The files the shapes came from, with their content hashes.
  const std::string library = json.at("shape_library").get<std::string>();
  EXPECT_NE(library.find("fnv1a64:"), std::string::npos) << library;
  EXPECT_TRUE(library.find("cube.stl") != std::string::npos ||
              library.find("rock.obj") != std::string::npos)
      << library;
  const CliRun info = this->run("info out/final.h5");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("shape library   library rocks (units mm, 2 shapes"), std::string::npos)
      << info.out;
}

TEST_F(ReposeLibraryCli, LibraryKeysAreNamedAsTyped) {
  write_inputs();
  const CliRun missing = run("repose small.toml --set particle.library=nope/ -o out");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("invalid particle.library = \"nope/\""), std::string::npos)
      << missing.err;
  EXPECT_FALSE(std::filesystem::exists(path("out")));
  // The table's former name still works, with a note before the same error.
  const CliRun former = run("repose small.toml --set particles.library=nope/ -o out");
  EXPECT_EQ(former.exit_code, 2);
  EXPECT_NE(former.err.find("aggpack: note: --set particles.library=nope/: [particles] is now "
                            "[particle]"),
            std::string::npos)
      << former.err;
  EXPECT_NE(former.err.find("invalid particle.library = \"nope/\""), std::string::npos)
      << former.err;
  EXPECT_FALSE(std::filesystem::exists(path("out")));
  const CliRun units = run("repose small.toml --set particle.library_units=km -o out");
  EXPECT_EQ(units.exit_code, 2);
  EXPECT_NE(units.err.find("particle.library_units"), std::string::npos) << units.err;
  // Every hull adds volume here (both rocks are dented): a limit of 0 % refuses the first.
  const CliRun excess = run("repose small.toml --set particle.library_max_hull_excess=1e-9 -o out");
  EXPECT_EQ(excess.exit_code, 2);
  EXPECT_NE(excess.err.find("particle.library_max_hull_excess"), std::string::npos) << excess.err;
  // A heavy run (the paper's 10-layer acrylic fill) with a missing library: the one line is the
  // refusal, before the heavy-run note; and so for a seed ensemble.
  for (const std::string seeds : {"", " --seeds 1-2"}) {
    const CliRun heavy = run("repose '" + test::source_dir() +
                             "/examples/repose-acrylic-075.toml' --set particle.library=nope/ -o "
                             "heavy" +
                             seeds);
    EXPECT_EQ(heavy.exit_code, 2);
    EXPECT_EQ(heavy.err.rfind("aggpack: error: invalid particle.library = \"nope/\"", 0), 0U)
        << heavy.err;
    EXPECT_EQ(heavy.err.find('\n'), heavy.err.size() - 1) << heavy.err;
    EXPECT_FALSE(std::filesystem::exists(path("heavy")));
  }
  // Without a library the library's options are not in effect: the resolved config omits them.
  const CliRun config = run("repose --print-config");
  ASSERT_EQ(config.exit_code, 0) << config.err;
  EXPECT_EQ(config.out.find("library ="), std::string::npos) << config.out;
}

}  // namespace
}  // namespace aggpack
