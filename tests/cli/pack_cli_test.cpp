// `aggpack pack` and `aggpack info` end to end: the paper's case, determinism across thread
// counts, and bad input (non-zero exit, one-line error, no output file left).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/io/native.h"
#include "aggpack/io/stl.h"
#include "aggpack/pack/verify.h"
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::file_text;

using PackCliTest = test::CliTest;

// A random packing small enough for a test: 0.3 m cube, radii 0.03-0.05 m, 20 % solid.
const char* const kSmallRandom =
    "--set packer.kind=random --set container.length=0.3 --set container.width=0.3 "
    "--set container.depth=0.3 --set particle.radius_min=0.03 --set particle.radius_max=0.05 "
    "--set packer.target_fraction=0.2 --set packer.gap=0.002";

TEST_F(PackCliTest, PapersCaseEndToEndThenInfo) {
  const CliRun pack = run("pack --progress lines");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_NE(pack.out.find("particles       1050\n"), std::string::npos) << pack.out;
  EXPECT_NE(pack.out.find("solid volume    "), std::string::npos) << pack.out;
  EXPECT_NE(pack.out.find("wrote aggpack-seed1.h5"), std::string::npos) << pack.out;
  EXPECT_NE(pack.err.find("placing: "), std::string::npos) << pack.err;  // plain progress lines
  ASSERT_EQ(files(), std::vector<std::string>{"aggpack-seed1.h5"});

  const Packing packing = read_packing(path("aggpack-seed1.h5"));
  EXPECT_EQ(packing.particles.size(), 1050U);
  EXPECT_EQ(packing.provenance.packer, "lattice");
  EXPECT_EQ(packing.provenance.seed, 1U);
  EXPECT_EQ(packing.provenance.config_toml, parse_pack_config("").resolved_toml);
  EXPECT_EQ(packing.container.get_if<BoxContainer>()->length, 3.0);
  EXPECT_TRUE(verify(packing).is_ok);

  const CliRun info = run("info aggpack-seed1.h5");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("packer          lattice, seed 1"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("1050"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("sphericity"), std::string::npos) << info.out;

  const CliRun json = run("info aggpack-seed1.h5 --json --bins 4 --no-descriptors");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"particle_count\": 1050"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"packer\": \"lattice\""), std::string::npos) << json.out;
  // A real JSON reader accepts it.
  std::ofstream(path("info.json")) << json.out;
  const std::string check = "/usr/bin/python3 -c 'import json,sys; d = json.load(open(\"" +
                            path("info.json") +
                            "\")); sys.exit(0 if len(d[\"statistics\"][\"profiles\"][\"z\"]"
                            "[\"solid_fraction\"]) == 4 else 1)'";
  EXPECT_EQ(std::system(check.c_str()), 0);
}

TEST_F(PackCliTest, SameSeedGivesByteIdenticalFilesForAnyThreadCount) {
  for (const auto& packer : std::vector<std::string>{"", kSmallRandom}) {
    SCOPED_TRACE(packer.empty() ? "lattice" : "random");
    ASSERT_EQ(run("pack --progress none --seed 5 -j 1 -o one.h5 " + packer).exit_code, 0);
    ASSERT_EQ(run("pack --progress none --seed 5 -j 2 -o two.h5 " + packer).exit_code, 0);
    ASSERT_EQ(run("pack --progress none --seed 6 -j 2 -o other.h5 " + packer).exit_code, 0);
    const std::string one = file_text(folder_ / "one.h5");
    ASSERT_GT(one.size(), 1000U);
    EXPECT_TRUE(one == file_text(folder_ / "two.h5"));
    EXPECT_FALSE(one == file_text(folder_ / "other.h5"));  // the seed matters
    for (const char* name : {"one.h5", "two.h5", "other.h5"}) fs::remove(folder_ / name);
  }
}

TEST_F(PackCliTest, RandomPackingWithXdmfAndTargetGrading) {
  const CliRun pack =
      run(std::string("pack --progress none ") + kSmallRandom + " -o r.h5 --xdmf --compression 4");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_EQ(files(), (std::vector<std::string>{"r.h5", "r.xdmf"}));
  const Packing packing = read_packing(path("r.h5"));
  EXPECT_EQ(packing.provenance.packer, "random");
  EXPECT_TRUE(verify(packing, {.gap = 0.002}).is_ok);
  const CliRun info = run("info r.h5 --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  // The stored config names a uniform grading; info compares against it.
  EXPECT_NE(info.out.find("\"target_percent\""), std::string::npos) << info.out;
}

TEST_F(PackCliTest, ExampleConfigRunsWithOverrides) {
  // The concrete example, shrunk to a 50 mm cube at 15 % so that it runs in a test.
  const CliRun pack = run("pack '" + test::source_dir() +
                          "/examples/concrete-fuller.toml' --set container.length=0.05 "
                          "--set container.width=0.05 --set container.depth=0.05 "
                          "--set packer.target_fraction=0.15 --progress none --json");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_NE(pack.out.find("\"output\": \"aggpack-seed1.h5\""), std::string::npos) << pack.out;
  EXPECT_NE(pack.out.find("\"is_target_reached\": true"), std::string::npos) << pack.out;
  const Packing packing = read_packing(path("aggpack-seed1.h5"));
  EXPECT_NE(packing.provenance.config_toml.find("kind = \"fuller\""), std::string::npos);
  EXPECT_NE(packing.provenance.config_toml.find("length = 0.05"), std::string::npos);
}

TEST_F(PackCliTest, PrintConfigWritesNothing) {
  const CliRun run_result = run("pack --print-config --set packer.gap=0.01");
  ASSERT_EQ(run_result.exit_code, 0) << run_result.err;
  EXPECT_NE(run_result.out.find("[packer]\nkind = \"lattice\"\nseed = 1\ngap = 0.01\n"),
            std::string::npos)
      << run_result.out;
  EXPECT_TRUE(files().empty());
}

// Each bad input: the given exit code, exactly one line on stderr starting "aggpack: error:"
// and containing `expected`, and no file left behind (not even a temporary one).
TEST_F(PackCliTest, BadInputFailsCleanlyWithOneLine) {
  std::ofstream(path("syntax.toml")) << "[packer]\ngap = = 1\n";
  std::ofstream(path("unknown.toml")) << "[packer]\ngapp = 0.001\n";
  std::ofstream(path("notes.h5")) << "not hdf5\n";
  struct Case {
    std::string arguments;
    int exit_code;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"pack unknown.toml", 2,
       "unknown.toml:2: unknown key 'packer.gapp'; did you mean 'packer.gap'?"},
      {"pack syntax.toml", 2, "syntax.toml:2:"},
      {"pack missing.toml", 3, "cannot read config missing.toml"},
      {"pack --set particle.alpha=2", 2, "invalid particle.alpha = 2 (allowed: [0, 1])"},
      {"pack --set packer.kind=latice", 2, "did you mean 'lattice'?"},
      {"pack --set packer.target_count=1.5 --set packer.kind=random", 2,
       "packer.target_count must be an integer"},
      {"pack -o no/such/folder/run.h5", 3, "folder no/such/folder does not exist"},
      {"pack --compression 12", 2, "--compression"},
      {"pack --progress sometimes", 2, "--progress"},
      {"pack --threads=-3", 2, "invalid -j/--threads = -3 (allowed: [0, 4096])"},
      {"info missing.h5", 3, "cannot read missing.h5: no such file"},
      {"info notes.h5", 2, "notes.h5: not an HDF5 file"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.arguments);
    const CliRun result = run(c.arguments);
    EXPECT_EQ(result.exit_code, c.exit_code) << result.err;
    EXPECT_EQ(result.err.rfind("aggpack: error: ", 0), 0U) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
    EXPECT_EQ(files(), (std::vector<std::string>{"notes.h5", "syntax.toml", "unknown.toml"}));
  }
}

TEST_F(PackCliTest, ExistingOutputIsKeptWithoutForce) {
  ASSERT_EQ(run("pack --progress none -o run.h5 --set container.depth=0.5").exit_code, 0);
  const std::string before = file_text(folder_ / "run.h5");
  const CliRun again = run("pack --progress none -o run.h5 --seed 2 --set container.depth=0.5");
  EXPECT_EQ(again.exit_code, 3);
  EXPECT_NE(again.err.find("file exists (use --force to replace it)"), std::string::npos);
  EXPECT_TRUE(before == file_text(folder_ / "run.h5"));
  const CliRun forced =
      run("pack --progress none -o run.h5 --seed 2 --force --set container.depth=0.5");
  EXPECT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_FALSE(before == file_text(folder_ / "run.h5"));
  EXPECT_EQ(files(), std::vector<std::string>{"run.h5"});
}

TEST_F(PackCliTest, WarningsForIneffectiveKeysGoToStderr) {
  const CliRun pack =
      run("pack --progress none --set container.radius=0.3 --set container.depth=0.5");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_NE(pack.err.find("aggpack: warning: --set container.radius=0.3: container.radius is "
                          "ignored (used only when container.kind = cylinder)"),
            std::string::npos)
      << pack.err;
}

// With --json, the [output] exports are listed with their counts and, for tetrahedra, the
// element quality (the same figures `aggpack export` prints).
TEST_F(PackCliTest, JsonReportListsExportsWithTheirQuality) {
  std::ofstream(path("run.toml")) << "[container]\ndepth = 0.4\n\n[output]\nnative = \"run.h5\"\n"
                                     "stl = \"run.stl\"\ninp = \"run.inp\"\n";
  const CliRun pack = run("pack run.toml --progress none --json");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  std::ofstream(path("pack.json")) << pack.out;
  const std::string check =
      "/usr/bin/python3 -c 'import json,sys; e = json.load(open(\"" + path("pack.json") +
      "\"))[\"exports\"]; i, s = e[0], e[1]; q = i[\"quality\"]; "
      "ok = i[\"format\"] == \"inp\" and s[\"format\"] == \"stl\" and \"quality\" not in s and "
      "q[\"tetrahedra\"] == i[\"elements\"] > 0 and 0 < q[\"min_dihedral_deg\"] < 70.53 and "
      "q[\"max_aspect_ratio\"] >= 1 and q[\"below_10_deg\"] >= 0; sys.exit(0 if ok else 1)'";
  EXPECT_EQ(std::system(check.c_str()), 0) << pack.out;
}

TEST_F(PackCliTest, OutputTableWritesEveryListedFormat) {
  std::ofstream(path("run.toml")) << "[container]\ndepth = 0.4\n\n[output]\nnative = \"run.h5\"\n"
                                     "stl = \"run.stl\"\ninp = \"run.inp\"\ndat = \"rock.dat\"\n";
  const CliRun pack = run("pack run.toml --progress none");
  ASSERT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_EQ(files(),
            (std::vector<std::string>{"rock.dat", "run.h5", "run.inp", "run.stl", "run.toml"}));
  EXPECT_NE(pack.out.find("wrote run.stl (stl, "), std::string::npos) << pack.out;
  const Packing packing = read_packing(path("run.h5"));
  ASSERT_GT(packing.particles.size(), 0U);
  // The STL holds every particle's surface triangles, and the .inp one element set each.
  std::size_t triangles = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    triangles += packing.placed(i).triangle_count();
  }
  EXPECT_EQ(read_stl(path("run.stl")).triangles.size(), triangles);
  const std::string inp = file_text(folder_ / "run.inp");
  EXPECT_NE(inp.find("ELSET=P" + std::to_string(packing.particles.size()) + "\n"),
            std::string::npos);
  EXPECT_EQ(inp.find("ELSET=P" + std::to_string(packing.particles.size() + 1) + "\n"),
            std::string::npos);

  // Without --force nothing is replaced and the run stops before packing.
  const std::string before = file_text(folder_ / "run.stl");
  fs::remove(folder_ / "run.h5");
  const CliRun again = run("pack run.toml --progress none --seed 3");
  EXPECT_EQ(again.exit_code, 3) << again.err;
  EXPECT_NE(again.err.find("file exists"), std::string::npos) << again.err;
  EXPECT_TRUE(before == file_text(folder_ / "run.stl"));
  EXPECT_EQ(files(), (std::vector<std::string>{"rock.dat", "run.inp", "run.stl", "run.toml"}));

  const CliRun clash = run("pack run.toml --progress none --force --set output.vtu=run.h5");
  EXPECT_EQ(clash.exit_code, 2);
  EXPECT_NE(clash.err.find("invalid output.vtu = run.h5"), std::string::npos) << clash.err;
  const CliRun twice = run("pack run.toml --progress none --force --set output.obj=./run.stl");
  EXPECT_EQ(twice.exit_code, 2);
  // Keys are taken in name order, so the later one (stl) is named as the clash.
  EXPECT_NE(twice.err.find("invalid output.stl = run.stl"), std::string::npos) << twice.err;
}

}  // namespace
}  // namespace aggpack
