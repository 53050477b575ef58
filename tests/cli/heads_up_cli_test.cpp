// The one-line heads-up before a heavy run (estimated particles, memory, time; even with
// --progress none) in the commands besides `pack` (runaway_cli_test.cpp): densify, settle,
// repose (one run, a seed ensemble, a sweep), mesomodel, export, shapes -n and render. A heavy
// configuration must print it as its first line of stderr (the run is stopped once it is there); a
// light one must not.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::has_subcommand;

constexpr const char* kLead = "aggpack: a large run: ~";

// The tiny trough of the golden repose case (120 particles, a 0.35 m trough, rest.max_time 0.02).
const std::string kTrough = test::source_dir() + "/tests/cli/cases/repose/trough.toml";

class HeadsUpCliTest : public test::CliTest {
 protected:
  HeadsUpCliTest() : CliTest("aggpack_heads_up_") {}

  // A packing of 12 particles (the `pack` small run of runaway_cli_test.cpp) as small.h5.
  void make_small_packing() {
    const CliRun pack =
        run("pack --progress none -o small.h5 --set container.length=0.6 --set "
            "container.width=0.4 --set container.depth=0.4");
    ASSERT_EQ(pack.exit_code, 0) << pack.err;
    ASSERT_NE(pack.out.find("particles       12\n"), std::string::npos) << pack.out;
  }

  // Runs `aggpack ARGS` in folder_ until its stderr holds the heads-up or it ends (at most
  // 120 s), then stops it (SIGTERM: a background job of a shell ignores SIGINT); its stderr.
  std::string stderr_until_heads_up(const std::string& args) {
    const std::string err = folder_.string() + ".heads-up.err";
    const std::string command = "cd '" + folder_.string() + "' && ('" + test::aggpack_binary() +
                                "' " + args + " >/dev/null 2>'" + err +
                                "' & pid=$!; for i in $(seq 1200); do grep -q 'large run' '" + err +
                                "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; " +
                                "kill -TERM $pid 2>/dev/null; wait $pid)";
    EXPECT_NE(std::system(command.c_str()), -1);
    std::string text = test::file_text(err);
    fs::remove(err);
    return text;
  }

  // The heads-up is the first line, with the particles, memory and time it states.
  static void expect_heads_up(const std::string& err, const std::string& particles,
                              const std::string& time_word) {
    ASSERT_EQ(err.rfind(kLead, 0), 0U) << err;
    const std::string first = err.substr(0, err.find('\n'));
    EXPECT_EQ(first.rfind(std::string(kLead) + particles + " particles, ~", 0), 0U) << first;
    EXPECT_NE(first.find(" of memory, " + time_word), std::string::npos) << first;
    EXPECT_NE(first.find("(rough estimate; Ctrl-C stops it)"), std::string::npos) << first;
  }
};

TEST_F(HeadsUpCliTest, Densify) {
  make_small_packing();
  // 10^9 sweeps of 12 particles: the budget's time, hours ("up to": it stops at its target).
  expect_heads_up(stderr_until_heads_up("densify small.h5 -o heavy.h5 --sweeps 1000000000 "
                                        "--progress none"),
                  "12", "up to ~");
  const CliRun light = run("densify small.h5 -o light.h5 --sweeps 20 --progress none");
  EXPECT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err.find("large run"), std::string::npos) << light.err;
}

TEST_F(HeadsUpCliTest, Settle) {
  if (!has_subcommand("settle")) GTEST_SKIP() << "built without Bullet";
  make_small_packing();
  // A time step of 10 microseconds: ~2 x 10^5 steps to rest for 12 bodies.
  expect_heads_up(stderr_until_heads_up("settle small.h5 -o heavy.h5 --dt 1e-5 --progress none"),
                  "12", "~");
  const CliRun light = run("settle small.h5 -o light.h5 --max-time 0.05 --progress none");
  EXPECT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err.find("large run"), std::string::npos) << light.err;
}

TEST_F(HeadsUpCliTest, ReposeEnsembleAndSweep) {
  if (!has_subcommand("repose") || !has_subcommand("sweep")) GTEST_SKIP() << "built without Bullet";
  // The paper's trough with R = 0.02 m: 75 x 25 x 70 lattice sites.
  expect_heads_up(stderr_until_heads_up("repose --set particle.radius=0.02 --set "
                                        "particle.edge_length=0.02 -o paper --progress none"),
                  "131250", "~");
  // The tiny trough (a few seconds a run): 500 seeds, and a sweep of 10 x 10 cases.
  const std::string trough = "'" + kTrough + "'";
  expect_heads_up(
      stderr_until_heads_up("repose " + trough + " --seeds 1-500 -o seeds --progress none"), "120",
      "~");
  expect_heads_up(
      stderr_until_heads_up("sweep " + trough +
                            " --set 'sweep.alphas=[0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9]' --set "
                            "'sweep.frictions=[0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0]' -o grid "
                            "--no-plot --progress none"),
      "120", "~");
  // One run of the tiny trough: light.
  const CliRun light = run("repose " + trough + " -o one --width 64 --progress none");
  EXPECT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err.find("large run"), std::string::npos) << light.err;
}

TEST_F(HeadsUpCliTest, Mesomodel) {
  make_small_packing();
  // 2048^3 voxels: 43 GB at 5 bytes each (then refused by the voxel limit: nothing written).
  const CliRun heavy = run("mesomodel small.h5 --voxels 2048 -o heavy.raw");
  expect_heads_up(heavy.err, "12", "~");
  EXPECT_EQ(heavy.exit_code, 2) << heavy.err;
  const CliRun light = run("mesomodel small.h5 --voxels 32 -o light.vti");
  EXPECT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err.find("large run"), std::string::npos) << light.err;
}

TEST_F(HeadsUpCliTest, ExportShapesAndRender) {
  make_small_packing();
  // TetGen under a volume bound of 1e-12 m^3 (of the stored shape): ~10^9 C3D10 elements of
  // ~275 bytes, terabytes written (the run is stopped once the line is there).
  const std::string heavy_export = stderr_until_heads_up(
      "export small.h5 --format inp --quadratic --tet-method tetgen --max-volume 1e-12 -o "
      "heavy.inp --progress none");
  expect_heads_up(heavy_export, "12", "~");
  EXPECT_NE(heavy_export.find(" TB written, ~"), std::string::npos) << heavy_export;
  const CliRun light_export = run("export small.h5 --format inp --quadratic -o light.inp");
  EXPECT_EQ(light_export.exit_code, 0) << light_export.err;
  EXPECT_EQ(light_export.err.find("large run"), std::string::npos) << light_export.err;
  // 10^8 particles grown and described: tens of minutes on any machine.
  expect_heads_up(stderr_until_heads_up("shapes -n 100000000"), "1e+08", "~");
  const CliRun light_shapes = run("shapes -n 100");
  EXPECT_EQ(light_shapes.exit_code, 0) << light_shapes.err;
  EXPECT_EQ(light_shapes.err.find("large run"), std::string::npos) << light_shapes.err;
  if (!has_subcommand("render")) GTEST_SKIP() << "built without rendering";
  // 8192 x 8192 pixels x 16 samples x 4 bytes: 4.3 GB of image.
  expect_heads_up(
      stderr_until_heads_up("render small.h5 --size 8192x8192 --samples 16 -o heavy.png"), "12",
      "~");
  const CliRun light_render = run("render small.h5 --size 64x64 -o light.png");
  EXPECT_EQ(light_render.exit_code, 0) << light_render.err;
  EXPECT_EQ(light_render.err.find("large run"), std::string::npos) << light_render.err;
}

}  // namespace
}  // namespace aggpack
