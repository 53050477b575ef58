// Messages name what the user typed (fixtures: tests/io/fixtures/bad-inputs/, README "Found on
// 2026-12-03"): a flag typed is named as the flag, a key typed (--set, a config file) as the key,
// one test per command whose flags set library fields or config keys. And every command treats
// `-o ""` and an output that is a folder (or, for a folder output, a file) alike: one line, exit
// 2 for the empty value, 3 for the path, nothing written.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;
using test::CliRun;

const std::string kBase = "'" + test::bad_inputs_dir() + "base_s.h5'";
const std::string kExamples = test::source_dir() + "/examples/";

class FlagNamesCliTest : public test::CliTest {
 protected:
  FlagNamesCliTest() : CliTest("aggpack_flagnames_") {}

  // `arguments` fails with exit `code` and exactly the one line `message`, and writes nothing.
  void expect_refused(const std::string& arguments, int code, const std::string& message) {
    SCOPED_TRACE(arguments);
    const CliRun result = run(arguments);
    EXPECT_EQ(result.exit_code, code) << result.err;
    EXPECT_EQ(result.err, "aggpack: error: " + message + "\n");
    EXPECT_EQ(files(), std::vector<std::string>{}) << "nothing written";
  }

  [[nodiscard]] bool has(const std::string& command) const {
    return run("--help").out.find("\n  " + command + " ") != std::string::npos;
  }
};

TEST_F(FlagNamesCliTest, Densify) {
  const std::string densify = "densify " + kBase + " -o out.h5";
  expect_refused(densify + " --sweeps 0", 2,
                 "invalid --sweeps = 0 (allowed: an integer in [1, 1e9])");
  expect_refused(densify + " --target-fraction 0.99", 2,
                 "invalid --target-fraction = 0.99 (allowed: [0, 0.95); 0 = no fraction target)");
  expect_refused(densify + " --gap -1", 2, "invalid --gap = -1 (allowed: >= 0 (m))");
  expect_refused(densify + " --max-time -1", 2,
                 "invalid --max-time = -1 (allowed: >= 0 (s); 0 = no time budget)");
  expect_refused(densify + " --mode bed --bed-cooling 2", 2,
                 "invalid --bed-cooling = 2 (allowed: (0, 1])");
  expect_refused(densify + " --target-container 0.7,0.4,0.4", 2,
                 "invalid --target-container (length) = 0.7 (allowed: (0, 0.6], no larger than "
                 "the start container)");
}

TEST_F(FlagNamesCliTest, Pack) {
  // -j/--threads stands for packer.threads; typed as the flag, it is named as the flag.
  expect_refused("pack -j -1 -o out.h5", 2, "invalid -j/--threads = -1 (allowed: [0, 4096])");
  // The key typed is named as the key, with where it was given.
  expect_refused("pack --set packer.threads=-1 -o out.h5", 2,
                 "--set packer.threads=-1: invalid packer.threads = -1 (allowed: [0, 4096])");
  expect_refused("pack --compression 11 -o out.h5", 2,
                 "invalid --compression = 11 (allowed: [0, 9])");
  // --seed is typed as a flag: named as the flag, not as the --set packer.seed it stands for
  // (-1 used to be wrapped to 2^64 - 1 on the way).
  expect_refused("pack --seed -1 -o out.h5", 2,
                 "invalid --seed = -1 (allowed: an integer in [0, 2^63 - 1])");
  expect_refused("pack --seed 9223372036854775808 -o out.h5", 2,
                 "invalid --seed = 9223372036854775808 (allowed: an integer in [0, 2^63 - 1])");
  // A value the run refuses (not the configuration's checks) is named as the --set typed too;
  // the last --set of a key is the one used and named.
  expect_refused(
      "pack --set particle.library=elsewhere/ --set 'particle.library = nope/' -o out.h5", 2,
      "--set particle.library = nope/: invalid particle.library = \"nope/\" (allowed: "
      "an existing folder, or a .stl, .obj or .ply file)");
}

TEST_F(FlagNamesCliTest, Calibrate) {
  // 16 particles per evaluation: the wording is under test, not the search (236 s under the
  // sanitizers at the default 200).
  const std::string calibrate = "calibrate --samples 16 --diameter 0.01";
  // Below the range: the flag, its unit and the range at this diameter.
  expect_refused(calibrate + " --volume 1e-20", 2,
                 "invalid --volume = 1e-20 m^3 (allowed: 5.235987756e-16 to 5.235987756e-07 m^3 "
                 "(up to the volume of the sphere of --diameter 0.01 m))");
  // More than the sphere: its volume, and the closest reachable value with the inputs giving it.
  const CliRun above = run(calibrate + " --volume 6e-7");
  EXPECT_EQ(above.exit_code, 2) << above.err;
  EXPECT_EQ(above.err.rfind("aggpack: error: invalid --volume = 6e-07 m^3 (allowed: at most "
                            "5.235987756e-07 m^3 (the sphere of --diameter 0.01 m); closest "
                            "reachable: --volume ",
                            0),
            0U)
      << above.err;
  EXPECT_NE(above.err.find(", given by alpha "), std::string::npos) << above.err;
  EXPECT_EQ(above.err.find("enclosed_volume_ratio"), std::string::npos) << above.err;
  const CliRun ratio = run("calibrate --samples 16 --volume-ratio 1.5");
  EXPECT_EQ(ratio.exit_code, 2) << ratio.err;
  EXPECT_NE(ratio.err.find("invalid --volume-ratio = 1.5 (allowed: "), std::string::npos)
      << ratio.err;
  EXPECT_NE(ratio.err.find("closest reachable: --volume-ratio 0.9"), std::string::npos)
      << ratio.err;
  // Unreached inside the range: the reachable span, in the flag's words (one name for L / R).
  const CliRun below = run(calibrate + " --volume 1e-9");
  EXPECT_EQ(below.exit_code, 2) << below.err;
  EXPECT_NE(below.err.find("closest reachable: --volume "), std::string::npos) << below.err;
  EXPECT_NE(below.err.find(", L/R "), std::string::npos) << below.err;
  EXPECT_EQ(below.err.find("L/r"), std::string::npos) << below.err;
  expect_refused("calibrate --sphericity 0", 2, "invalid --sphericity = 0 (allowed: [1e-09, 1])");
  expect_refused("calibrate --alpha 0.5 --edge-ratio 2", 2,
                 "invalid --edge-ratio = 2 (allowed: [0.05, 1.5])");
  expect_refused("calibrate --alpha 0.5 --samples 1", 2,
                 "invalid --samples = 1 (allowed: [2, 100000])");
}

TEST_F(FlagNamesCliTest, ParticleAndShapes) {
  for (const std::string command : {"particle -o p.stl", "shapes -n 10"}) {
    expect_refused(command + " --max-vertices 3", 2,
                   "invalid --max-vertices = 3 (allowed: [6, 1000000])");
    expect_refused(command + " --alpha 3", 2, "invalid --alpha = 3 (allowed: [0, 1])");
  }
}

TEST_F(FlagNamesCliTest, Export) {
  const std::string export_base = "export " + kBase;
  expect_refused(export_base + " -o out.inp --poisson-ratio 0.7", 2,
                 "invalid --poisson-ratio = 0.7 (allowed: (-1, 0.5))");
  expect_refused(export_base + " -o out.stl --scale -1", 2,
                 "invalid --scale = -1 (allowed: finite and > 0)");
  expect_refused(export_base + " -o out.inp --density 0", 2,
                 "invalid --density = 0 (allowed: finite and > 0)");
  expect_refused(export_base + " -o out.inp --deck calculix --friction 20", 2,
                 "invalid --friction = 20 (allowed: [0, 10])");
  expect_refused(export_base + " -o out.inp --deck calculix --baffle-speed 0", 2,
                 "invalid --baffle-speed = 0 (allowed: finite and > 0)");
  expect_refused(export_base +
                     " -o out.vtu --cells tetrahedra --tet-method tetgen "
                     "--radius-edge 0.5",
                 2, "invalid --radius-edge = 0.5 (allowed: [1.2, 10])");
  // Checked when the deck is written (it needs the particles): still the flag.
  const CliRun baffle = run(export_base + " -o out.inp --deck calculix --baffle-position 0.1");
  EXPECT_EQ(baffle.exit_code, 2) << baffle.err;
  EXPECT_EQ(baffle.err.rfind("aggpack: error: invalid --baffle-position = 0.1 (allowed: >= ", 0),
            0U)
      << baffle.err;
  EXPECT_EQ(files(), std::vector<std::string>{});
}

TEST_F(FlagNamesCliTest, Mesomodel) {
  const std::string meso = "mesomodel " + kBase + " -o out.inp";
  expect_refused(meso + " --strain 0.5", 2,
                 "invalid --strain = 0.5 (allowed: [0, 0.1]; 0 = no step)");
  expect_refused(meso + " --material mortar=-1,0.2,2000", 2,
                 "invalid --material mortar E = -1 (allowed: (0, 1e13] Pa)");
  expect_refused(meso + " --material itz=15e9,0.7,2000", 2,
                 "invalid --material itz NU = 0.7 (allowed: (-1, 0.5))");
  // --voxels given is a voxel run whatever its value: 0 is refused, not ignored.
  expect_refused(meso + " --voxels 0", 2, "invalid --voxels = 0 (allowed: [2, 4096])");
  expect_refused(meso + " --voxels 5000", 2, "invalid --voxels = 5000 (allowed: [2, 4096])");
  // A wrong extension names the flag typed.
  expect_refused("mesomodel " + kBase + " -o m.vti", 2,
                 "invalid -o/--output = \"m.vti\" (allowed: a name ending in .inp, .msh or "
                 ".vtu; .vti or .raw with --voxels)");
  expect_refused(meso + " --voxels 32", 2,
                 "invalid -o/--output = \"out.inp\" (allowed: a name ending in .vti or .raw "
                 "with --voxels)");
}

TEST_F(FlagNamesCliTest, Render) {
  if (!has("render")) GTEST_SKIP() << "aggpack built without the drawing module";
  const std::string render = "render " + kBase + " -o out.png";
  expect_refused(render + " --samples 20", 2, "invalid --samples = 20 (allowed: [0, 16])");
  expect_refused(render + " --coarse-below -1", 2,
                 "invalid --coarse-below = -1 (allowed: [0, 1000000])");
}

TEST_F(FlagNamesCliTest, ReposeAndSweep) {
  if (!has("repose")) GTEST_SKIP() << "aggpack built without the simulation module";
  const std::string config = " '" + kExamples + "repose-acrylic-048.toml' -o out";
  for (const std::string command : {"repose", "sweep"}) {
    expect_refused(command + config + " --mu 20", 2, "invalid --mu = 20 (allowed: [0, 10])");
    expect_refused(command + config + " --alpha 3", 2, "invalid --alpha = 3 (allowed: [0, 1])");
    expect_refused(command + config + " --seed -1", 2,
                   "invalid --seed = -1 (allowed: an integer in [0, 2^63 - 1])");
    expect_refused(command + config + " --set physics.friction=20", 2,
                   "--set physics.friction=20: invalid physics.friction = 20 (allowed: [0, 10])");
  }
}

TEST_F(FlagNamesCliTest, Settle) {
  if (!has("settle")) GTEST_SKIP() << "aggpack built without the simulation module";
  // Each flag sets a field of the settling options: refused under the flag's name.
  const std::string settle = "settle " + kBase + " -o out.h5";
  expect_refused(settle + " --mu 11", 2, "invalid --mu = 11 (allowed: [0, 10])");
  expect_refused(settle + " --mu-wall 11", 2, "invalid --mu-wall = 11 (allowed: [0, 10])");
  expect_refused(settle + " --restitution 2", 2, "invalid --restitution = 2 (allowed: [0, 1])");
  expect_refused(settle + " --density -1", 2, "invalid --density = -1 (allowed: finite and > 0)");
  expect_refused(settle + " --dt-factor 0", 2, "invalid --dt-factor = 0 (allowed: [1e-06, 1])");
  expect_refused(settle + " --iterations 0", 2, "invalid --iterations = 0 (allowed: [1, 1000])");
  expect_refused(settle + " --max-time 0", 2, "invalid --max-time = 0 (allowed: finite and > 0)");
}

// -o "" is one error in every command: not "the default name", not "write nothing".
TEST_F(FlagNamesCliTest, EmptyOutputIsOneErrorEverywhere) {
  const std::string file = "invalid -o/--output = \"\" (allowed: a file path)";
  const std::string folder = "invalid -o/--output = \"\" (allowed: a folder path)";
  expect_refused("pack -o ''", 2, file);
  expect_refused("particle -o ''", 2, file);
  expect_refused("shapes -n 10 -o ''", 2, file);
  expect_refused("export " + kBase + " -o ''", 2, file);
  expect_refused("export " + kBase + " --per-particle -o ''", 2, folder);
  expect_refused("densify " + kBase + " -o ''", 2, file);
  expect_refused("mesomodel " + kBase + " -o ''", 2, file);
  expect_refused("calibrate --alpha 0.5 --table ''", 2,
                 "invalid --table = \"\" (allowed: a file path)");
  expect_refused("config-keys --update-doc ''", 2,
                 "invalid --update-doc = \"\" (allowed: a file path)");
  const std::string tables =
      " (allowed: container, particle, grading, packer, densify, output, repose.trough, "
      "repose.particle, repose.physics, repose.rest, repose.measure, repose.sweep, "
      "repose.ensemble, repose.yade)";
  expect_refused("config-keys --markdown ''", 2, "invalid --markdown = \"\"" + tables);
  expect_refused("config-keys --markdown foo", 2, "invalid --markdown = foo" + tables);
  if (has("render")) expect_refused("render " + kBase + " -o ''", 2, file);
  if (has("settle")) {
    expect_refused("settle " + kBase + " -o ''", 2, file);
    expect_refused("repose -o ''", 2, folder);
    expect_refused("sweep -o ''", 2, folder);
  }
}

// An output file that is a folder, or a folder output that is a file: exit 3, one line.
TEST_F(FlagNamesCliTest, OutputThatIsAFolderIsOneErrorEverywhere) {
  // A name ending in '/' can only be a folder.
  expect_refused("particle -o new/", 3,
                 "cannot write new/: a folder name (ends in '/'); -o/--output takes a file path");
  const std::string sub = (folder_ / "sub").string();
  fs::create_directory(sub);
  const auto expect_folder_refused = [&](const std::string& arguments) {
    SCOPED_TRACE(arguments);
    const CliRun result = run(arguments + " -o '" + sub + "'");
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_EQ(result.err,
              "aggpack: error: refusing to replace " + sub + ": not a regular file (directory)\n");
    EXPECT_EQ(files(), std::vector<std::string>{"sub"});
    EXPECT_TRUE(fs::is_empty(sub));
  };
  expect_folder_refused("pack");
  expect_folder_refused("particle");
  expect_folder_refused("shapes -n 10");
  expect_folder_refused("export " + kBase);
  expect_folder_refused("densify " + kBase);
  expect_folder_refused("mesomodel " + kBase);
  {
    SCOPED_TRACE("config-keys --update-doc");
    const CliRun result = run("config-keys --update-doc '" + sub + "'");
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_EQ(result.err,
              "aggpack: error: refusing to replace " + sub + ": not a regular file (directory)\n");
  }
  if (has("render")) expect_folder_refused("render " + kBase);
  if (has("settle")) expect_folder_refused("settle " + kBase);
  if (has("repose")) {
    fs::remove(sub);
    std::ofstream(folder_ / "file.txt") << "x";
    const CliRun result = run("repose -o file.txt");
    EXPECT_EQ(result.exit_code, 3) << result.err;
    EXPECT_EQ(result.err,
              "aggpack: error: cannot write file.txt: not a folder; -o/--output takes "
              "a folder path\n");
  }
}

// output_path_name_too_long.toml: an [output] path with a 300-byte file name is the clean exit 3
// that -o gives, naming the key, one short line; nothing is written.
TEST_F(FlagNamesCliTest, OutputNameTooLongNamesTheKey) {
  const std::string small =
      " --set container.length=0.6 --set container.width=0.4 --set container.depth=0.4";
  const CliRun result =
      run("pack '" + test::bad_inputs_dir() + "output_path_name_too_long.toml' -o out.h5" + small);
  EXPECT_EQ(result.exit_code, 3) << result.err;
  EXPECT_EQ(result.err.rfind("aggpack: error: output.stl: cannot write xxx", 0), 0U) << result.err;
  EXPECT_NE(result.err.find(".stl: file name too long (a name of 304 bytes, at most 255)\n"),
            std::string::npos)
      << result.err;
  EXPECT_LT(result.err.size(), 200U) << result.err;
  EXPECT_EQ(files(), std::vector<std::string>{});
  // -o with that name: the same reason, naming the path.
  const std::string name(300, 'x');
  const CliRun flag = run("pack -o " + name + ".h5" + small);
  EXPECT_EQ(flag.exit_code, 3) << flag.err;
  EXPECT_NE(flag.err.find(": file name too long (a name of 303 bytes, at most 255)\n"),
            std::string::npos)
      << flag.err;
  EXPECT_EQ(files(), std::vector<std::string>{});
}

}  // namespace
}  // namespace aggpack
