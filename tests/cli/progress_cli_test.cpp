// Progress of the long stages end to end (issue 36, item 2): `sweep` and `repose --seeds` show
// their bar at 0 of N before the first run ends; `mesomodel --voxels` shows its stage; export's
// TetGen stage shows the estimate's ETA and the per-shape time limit; export's tetrahedron
// quality gets a one-line verdict (item 4). The display's text itself: progress_test.cpp.

#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

using test::CliRun;
using test::has_subcommand;

// The tiny trough of the golden sweep case (a few seconds a run).
const std::string kStageTrough = "'" + test::source_dir() + "/tests/cli/cases/sweep/trough.toml'";

using ProgressCliTest = test::CliTest;

// `before` occurs in `text`, and before `after` when that occurs too.
void expect_before(const std::string& text, const std::string& before, const std::string& after) {
  const auto first = text.find(before);
  ASSERT_NE(first, std::string::npos) << text;
  const auto second = text.find(after);
  ASSERT_NE(second, std::string::npos) << text;
  EXPECT_LT(first, second) << text;
}

TEST_F(ProgressCliTest, SweepAndSeedEnsembleShowTheBarFromTheStart) {
  if (!has_subcommand("sweep") || !has_subcommand("repose")) GTEST_SKIP() << "built without Bullet";
  // One run at a time: "0/2" can only come from the start, "1/2" after the first run.
  const CliRun sweep = run("sweep " + kStageTrough +
                           " -o grid --set sweep.alphas=[0.5] --set sweep.frictions=[0.2,0.4] "
                           "--width 64 --no-plot --progress bar -j 1");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  expect_before(sweep.err, "0.0%  0/2 cases", "1/2 cases");
  const CliRun seeds =
      run("repose " + kStageTrough + " --seeds 1-2 -o seeds --width 64 --progress bar -j 1");
  ASSERT_EQ(seeds.exit_code, 0) << seeds.err;
  expect_before(seeds.err, "0.0%  0/2 seeds", "1/2 seeds");
}

TEST_F(ProgressCliTest, MesomodelVoxelsShowsItsStage) {
  ASSERT_EQ(run("pack --progress none -o small.h5 --set container.length=0.6 --set "
                "container.width=0.4 --set container.depth=0.4")
                .exit_code,
            0);
  // 160^3 voxels at 0.8 us each: 3.3 s by the estimate, so the stage is shown at once.
  const CliRun heavy = run("mesomodel small.h5 --voxels 160 -o heavy.vti --progress lines");
  ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
  EXPECT_EQ(heavy.err.rfind("voxelising: 0:00 elapsed, ETA ~0:03 by the estimate\n", 0), 0U)
      << heavy.err;
  EXPECT_NE(heavy.err.find("voxelising: done in "), std::string::npos) << heavy.err;
  // A light image ends before any line is due: nothing.
  const CliRun light = run("mesomodel small.h5 --voxels 32 -o light.vti --progress lines");
  ASSERT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err.find("voxelising"), std::string::npos) << light.err;
}

TEST_F(ProgressCliTest, ExportTetGenStageShowsEtaAndShapeLimitAndQualityVerdict) {
  // Particles of R = 0.07 m in the paper's box: ~3,000 shapes, ~3 s of TetGen by the estimate
  // on one thread, so the stage is shown at once.
  ASSERT_EQ(run("pack --progress none -o many.h5 --set particle.radius=0.07 --set "
                "particle.edge_length=0.07")
                .exit_code,
            0);
  const CliRun tetgen =
      run("export many.h5 --format inp --tet-method tetgen --tet-time-limit 30 -o many.inp -j 1 "
          "--progress lines");
  ASSERT_EQ(tetgen.exit_code, 0) << tetgen.err;
  // The first line: no shape done yet, the count and the estimate's ETA.
  EXPECT_EQ(tetgen.err.rfind("meshing shapes (TetGen): 0:00 elapsed, 0 of ", 0), 0U) << tetgen.err;
  const std::string first = tetgen.err.substr(0, tetgen.err.find('\n'));
  EXPECT_NE(first.find(" shapes, ETA ~0:0"), std::string::npos) << first;
  // Any later line (every 2 s while it runs) counts the shapes meshed, with a measured rate.
  std::size_t line_start = first.size() + 1;
  for (std::size_t end = tetgen.err.find('\n', line_start); end != std::string::npos;
       line_start = end + 1, end = tetgen.err.find('\n', line_start)) {
    const std::string line = tetgen.err.substr(line_start, end - line_start);
    if (line.find(" elapsed, ") == std::string::npos) continue;
    EXPECT_NE(line.find(" shapes/s, ETA "), std::string::npos) << line;
  }
  EXPECT_NE(first.find(" by the estimate (each shape stops at its time limit of 30 s)"),
            std::string::npos)
      << first;
  EXPECT_NE(tetgen.err.find("meshing shapes (TetGen): done in "), std::string::npos) << tetgen.err;
  // The quality line is followed by its verdict, one line, naming what made the flat
  // tetrahedra and what to do.
  EXPECT_NE(tetgen.out.find("\nquality verdict: as expected (TetGen keeps the surface "
                            "triangles: flat where --radius-edge would split one); solvers run "
                            "such meshes (CalculiX down to 0.017 deg"),
            std::string::npos)
      << tetgen.out;
  EXPECT_NE(tetgen.out.find("better-shaped: --split-surface\n"), std::string::npos) << tetgen.out;
  const CliRun fan = run("export many.h5 --format inp -o fan.inp --progress lines");
  ASSERT_EQ(fan.exit_code, 0) << fan.err;
  EXPECT_EQ(fan.err.find("meshing shapes"), std::string::npos) << fan.err;
  EXPECT_NE(fan.out.find("\nquality verdict: as expected (the centroid fan: flat over small or "
                         "steep surface triangles)"),
            std::string::npos)
      << fan.out;
  EXPECT_NE(fan.out.find("better-shaped: --tet-method tetgen --split-surface\n"), std::string::npos)
      << fan.out;
}

// The first capture of the last match of `pattern` in `text` ("" when it does not match).
std::string captured(const std::string& text, const std::string& pattern) {
  std::string last;
  const std::regex expression(pattern);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), expression);
       it != std::sregex_iterator(); ++it) {
    last = (*it)[1].str();
  }
  return last;
}

// A stage's time is measured once: its display's final line ("shapes: ... in T s") and the
// summary ("T s shapes") print the same number; so do densify's display and its summary.
TEST_F(ProgressCliTest, StageTimesAgreeBetweenDisplayAndSummary) {
  const CliRun pack =
      run("pack --progress lines -o small.h5 --set packer.kind=random --set container.length=0.3 "
          "--set container.width=0.3 --set container.depth=0.3 --set particle.radius_min=0.02 "
          "--set particle.radius_max=0.03 --set packer.target_fraction=0.25");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  const std::string shapes = captured(pack.err, R"((?:^|\n)shapes: [^\n]* in ([0-9.e-]+) s)");
  const std::string placing = captured(pack.err, R"((?:^|\n)placing: [^\n]* in ([0-9.e-]+) s)");
  ASSERT_FALSE(shapes.empty()) << pack.err;
  ASSERT_FALSE(placing.empty()) << pack.err;
  EXPECT_NE(pack.out.find("time            " + shapes + " s shapes + " + placing + " s placement"),
            std::string::npos)
      << pack.out << pack.err;

  const CliRun densify =
      run("densify small.h5 -o dense.h5 --sweeps 30 --target-fraction 0.3 --progress lines");
  ASSERT_EQ(densify.exit_code, 0) << densify.err;
  const std::string shown = captured(densify.err, R"(densify: [^\n]* in ([0-9.e-]+) s)");
  ASSERT_FALSE(shown.empty()) << densify.err;
  EXPECT_NE(densify.out.find(" sweeps (" + shown + " s)"), std::string::npos)
      << densify.out << densify.err;
}

// `shapes -n` shows its particles grown over its chunks, with the rate, when the run is estimated
// at or takes 2 s or more; a short run prints nothing, and --progress none nothing at all. Which
// run takes 2 s depends on the machine and its load (150,000 particles: 1.5 s idle, more when
// loaded), so the display is asked for from the start (AGGPACK_PROGRESS_DELAY=0).
TEST_F(ProgressCliTest, ShapesShowsTheParticlesGrown) {
  const CliRun heavy = run("shapes -n 20000 --progress lines", "AGGPACK_PROGRESS_DELAY=0");
  ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
  // One line per chunk of 8,192 particles (each a further 10 % or more), then the total.
  EXPECT_NE(heavy.err.find("growing:  41.0%  8192/20000 particles"), std::string::npos)
      << heavy.err;
  EXPECT_NE(heavy.err.find("growing: 100.0%  20000/20000 particles in "), std::string::npos)
      << heavy.err;
  const CliRun quiet = run("shapes -n 20000 --progress none", "AGGPACK_PROGRESS_DELAY=0");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  const CliRun bad = run("shapes -n 100 --progress lines", "AGGPACK_PROGRESS_DELAY=soon");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err,
            "aggpack: error: invalid AGGPACK_PROGRESS_DELAY = \"soon\" (allowed: seconds in "
            "[0, 3600] (unset: 2))\n");
  // Refused before the command runs (a missing file would be the error otherwise), any command.
  const CliRun before = run("info no-such-file.h5", "AGGPACK_PROGRESS_DELAY=-1");
  EXPECT_EQ(before.exit_code, 2);
  EXPECT_EQ(before.err.rfind("aggpack: error: invalid AGGPACK_PROGRESS_DELAY = \"-1\"", 0), 0U)
      << before.err;
  EXPECT_EQ(run("info --help", "AGGPACK_PROGRESS_DELAY=-1").exit_code, 0);
  EXPECT_NE(heavy.out.find("sphericity"), std::string::npos) << heavy.out;
  const CliRun light = run("shapes -n 100 --progress lines");
  ASSERT_EQ(light.exit_code, 0) << light.err;
  EXPECT_EQ(light.err, "");
  EXPECT_EQ(run("shapes -n 10 --progress sometimes").exit_code, 2);
}

}  // namespace
}  // namespace aggpack
