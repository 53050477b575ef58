// The periodic box end to end: `aggpack pack` with container.periodic, the native file (written,
// read back, an older file without the attribute), `aggpack info`, an export, the same bytes at
// one and two threads, densify and the dense kind in it, and the one-line refusals (bad word,
// the lattice packer, a bed, mesomodel).

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/native.h"
#include "aggpack/io/stl.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/verify.h"
#include "support/cli_test.h"
#include "support/files.h"
#include "support/paths.h"
#include "support/readers.h"

namespace aggpack {
namespace {

class PeriodicCliTest : public test::CliTest {
 protected:
  PeriodicCliTest() : CliTest("aggpack_periodic_") {}
  void SetUp() override {
    CliTest::SetUp();
    std::ofstream(folder_ / "periodic.toml") << "[container]\n"
                                                "kind = \"box\"\n"
                                                "length = 0.1\n"
                                                "width = 0.1\n"
                                                "depth = 0.1\n"
                                                "periodic = \"xyz\"\n"
                                                "[packer]\n"
                                                "kind = \"random\"\n"
                                                "seed = 5\n"
                                                "target_fraction = 0.25\n"
                                                "[particle]\n"
                                                "radius_min = 0.006\n"
                                                "radius_max = 0.012\n";
  }
  // Expects a refusal: non-zero exit, one line on stderr containing `part`.
  void expect_one_line_refusal(const std::string& arguments, const std::string& part) const {
    const test::CliRun result = run(arguments);
    EXPECT_NE(result.exit_code, 0) << arguments;
    EXPECT_NE(result.err.find(part), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  }
};

TEST_F(PeriodicCliTest, PackInfoReadBackAndSameBytesAtOneAndTwoThreads) {
  const test::CliRun one = run("pack periodic.toml -o one.h5 -j 1 --progress none");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("box 0.1 x 0.1 x 0.1 m, periodic in xyz"), std::string::npos) << one.out;
  const test::CliRun two = run("pack periodic.toml -o two.h5 -j 2 --progress none");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_TRUE(
      test::same_bytes(test::file_text(folder_ / "one.h5"), test::file_text(folder_ / "two.h5")));

  const Packing packing = read_packing((folder_ / "one.h5").string());
  EXPECT_EQ(periodic_axes(packing.container), (std::array<bool, 3>{true, true, true}));
  EXPECT_GT(packing.particles.size(), 20u);
  EXPECT_TRUE(verify(packing, {.is_brute_force = true}).is_ok);
  // The stored configuration says it too, and packs the same file again.
  EXPECT_NE(packing.provenance.config_toml.find("periodic = \"xyz\""), std::string::npos)
      << packing.provenance.config_toml;
  std::ofstream(folder_ / "stored.toml") << packing.provenance.config_toml;
  ASSERT_EQ(run("pack stored.toml -o again.h5 --progress none").exit_code, 0);
  EXPECT_TRUE(
      test::same_bytes(test::file_text(folder_ / "again.h5"), test::file_text(folder_ / "one.h5")));

  const test::CliRun info = run("info one.h5");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("container       box 0.1 x 0.1 x 0.1 m, periodic in xyz, wall gap 0 m"),
            std::string::npos)
      << info.out;
  const test::CliRun json = run("info one.h5 --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"periodic\": \"xyz\""), std::string::npos) << json.out;

  // An export writes every particle once, whole: the STL reaches beyond the box.
  const test::CliRun stl = run("export one.h5 -o one.stl --ascii");
  ASSERT_EQ(stl.exit_code, 0) << stl.err;
  const std::string text = test::file_text(folder_ / "one.stl");
  std::size_t solids = 0;
  for (std::size_t at = text.find("endsolid"); at != std::string::npos;
       at = text.find("endsolid", at + 1)) {
    ++solids;
  }
  EXPECT_GE(solids, 1u);
  double lowest = 1e300;
  for (std::size_t at = text.find("vertex "); at != std::string::npos;
       at = text.find("vertex ", at + 1)) {
    lowest = std::min(lowest, std::stod(text.substr(at + 7, 30)));
  }
  EXPECT_LT(lowest, 0.0);
}

TEST_F(PeriodicCliTest, WalledBoxFilesHaveNoPeriodicAttributeAndReadAsBefore) {
  ASSERT_EQ(run("pack periodic.toml --set container.periodic=none -o walled.h5 --progress none")
                .exit_code,
            0);
  const std::string bytes = test::file_text(folder_ / "walled.h5");
  EXPECT_EQ(bytes.find("periodic"), std::string::npos);
  EXPECT_FALSE(is_periodic(read_packing((folder_ / "walled.h5").string()).container));
  const test::CliRun info = run("info walled.h5");
  EXPECT_EQ(info.out.find("periodic"), std::string::npos) << info.out;
  // A file written by an earlier version (the golden export case's) reads as a walled box.
  const Packing old = read_packing(test::source_dir() + "/tests/cli/cases/export/expected/tiny.h5");
  EXPECT_FALSE(is_periodic(old.container));
  EXPECT_GT(old.particles.size(), 0u);
}

TEST_F(PeriodicCliTest, RefusalsAreOneLineNamingTheKey) {
  expect_one_line_refusal(
      "pack periodic.toml --set container.periodic=xzy -o bad.h5 --progress none",
      "invalid container.periodic = \"xzy\" (allowed: none | x | y | z | xy | "
      "xz | yz | xyz)");
  expect_one_line_refusal("pack periodic.toml --set packer.kind=lattice -o bad.h5 --progress none",
                          "packer.kind = lattice does not take periodic containers yet");
  expect_one_line_refusal(
      "pack periodic.toml --set packer.kind=dense --set densify.mode=bed -o bad.h5 --progress none",
      "densify.mode = bed does not take periodic containers yet");
  expect_one_line_refusal(
      "pack periodic.toml --set container.length=0.02 -o bad.h5 --progress none",
      "container.length = 0.02 m");
  EXPECT_FALSE(std::filesystem::exists(folder_ / "bad.h5"));
  ASSERT_EQ(run("pack periodic.toml -o one.h5 --progress none").exit_code, 0);
  expect_one_line_refusal("mesomodel one.h5 --itz 0.0001 -o rve.inp",
                          "invalid --itz = 0.0001 (allowed: 0 with container.periodic");
  expect_one_line_refusal("mesomodel one.h5 --quadratic -o rve.inp",
                          "invalid --quadratic = true with container.periodic (allowed: linear "
                          "elements");
  EXPECT_FALSE(std::filesystem::exists(folder_ / "rve.inp"));
  expect_one_line_refusal("densify one.h5 -o dense.h5 --target-container 0.02,0.1,0.1",
                          "container.length = 0.02 m");
}

TEST_F(PeriodicCliTest, DensifyAndTheDenseKindKeepThePeriodicBox) {
  ASSERT_EQ(run("pack periodic.toml -o loose.h5 --progress none").exit_code, 0);
  const std::string densify = "densify loose.h5 --target-fraction 0.4 --sweeps 400 --progress none";
  const test::CliRun one = run(densify + " -o one.h5 -j 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const test::CliRun two = run(densify + " -o two.h5 -j 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_TRUE(
      test::same_bytes(test::file_text(folder_ / "one.h5"), test::file_text(folder_ / "two.h5")));
  const Packing loose = read_packing((folder_ / "loose.h5").string());
  const Packing dense = read_packing((folder_ / "one.h5").string());
  EXPECT_EQ(periodic_axes(dense.container), (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(dense.particles.size(), loose.particles.size());
  EXPECT_LT(dense.container.volume(), 0.9 * loose.container.volume());
  EXPECT_TRUE(verify(dense, {.gap = 0.0, .is_brute_force = true}).is_ok);
  const test::CliRun info = run("info one.h5");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("periodic in xyz"), std::string::npos) << info.out;

  // The dense kind: the fill in the enlarged periodic box, compressed into the given one.
  const test::CliRun kind =
      run("pack periodic.toml --set packer.kind=dense --set densify.target_fraction=0.35 "
          "--set densify.max_sweeps=600 -o kind.h5 --progress none");
  ASSERT_EQ(kind.exit_code, 0) << kind.err;
  const Packing packed = read_packing((folder_ / "kind.h5").string());
  EXPECT_EQ(periodic_axes(packed.container), (std::array<bool, 3>{true, true, true}));
  EXPECT_NEAR(packed.container.volume(), 0.001, 1e-12);
  EXPECT_TRUE(verify(packed, {.is_brute_force = true}).is_ok);
  EXPECT_NE(kind.out.find("periodic in xyz"), std::string::npos) << kind.out;
}

TEST_F(PeriodicCliTest, StlCutToTheBoxTilesAndIsRefusedElsewhere) {
  ASSERT_EQ(run("pack periodic.toml -o one.h5 --progress none").exit_code, 0);
  const test::CliRun cut = run("export one.h5 -o cut.stl --cut-to-box");
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  const Packing packing = read_packing((folder_ / "one.h5").string());
  double solid = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    solid += mass_properties(packing.placed(i)).volume;
  }
  // The enclosed volume of the file (divergence theorem over its float coordinates) is the
  // particles' (each once: the images' pieces fill what the particles' own pieces leave out),
  // and every vertex lies in the box, up to float rounding.
  const StlMesh mesh = read_stl((folder_ / "cut.stl").string());
  double six_volume = 0.0;
  for (const auto& t : mesh.triangles) {
    six_volume += t[0].dot(t[1].cross(t[2]));
    for (const Vec3& vertex : t) {
      EXPECT_TRUE((vertex.array() >= -1e-7).all() && (vertex.array() <= 0.1 + 1e-7).all())
          << vertex.transpose();
    }
  }
  EXPECT_NEAR(six_volume / 6.0, solid, 1e-5 * solid);
  // Without the flag the file reaches beyond the box.
  ASSERT_EQ(run("export one.h5 -o whole.stl").exit_code, 0);
  const StlMesh whole = read_stl((folder_ / "whole.stl").string());
  EXPECT_LT(whole.triangles.size(), mesh.triangles.size());

  expect_one_line_refusal("export one.h5 -o cut.obj --cut-to-box", "--cut-to-box");
  expect_one_line_refusal("export one.h5 -o cut.vtu --cut-to-box", "only for .stl");
  ASSERT_EQ(run("pack periodic.toml --set container.periodic=none -o walled.h5 --progress none")
                .exit_code,
            0);
  expect_one_line_refusal("export walled.h5 -o walled.stl --cut-to-box",
                          "--cut-to-box = true for a packing without periodic faces");
  EXPECT_FALSE(std::filesystem::exists(folder_ / "walled.stl"));
}

TEST_F(PeriodicCliTest, MesomodelWritesTiesAndSixLoadCasesAndATilingImage) {
  ASSERT_EQ(run("pack periodic.toml --set container.length=0.04 --set container.width=0.04 "
                "--set container.depth=0.04 -o small.h5 --progress none")
                .exit_code,
            0);
  const test::CliRun mesh = run("mesomodel small.h5 -o rve.inp --progress none");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  EXPECT_NE(mesh.out.find("periodic ties and six load cases of strain 0.001"), std::string::npos)
      << mesh.out;
  std::ifstream in(folder_ / "rve.inp");
  std::string line;
  std::size_t steps = 0;
  std::size_t equations = 0;
  std::set<std::string> sets;
  while (std::getline(in, line)) {
    steps += line == "*STEP";
    equations += line == "*EQUATION";
    if (line.rfind("*NSET, NSET=", 0) == 0) sets.insert(line.substr(12));
  }
  EXPECT_EQ(steps, 6U);
  EXPECT_EQ(equations, 1U);
  for (const char* name :
       {"XMIN", "XMAX", "YMIN", "YMAX", "ZMIN", "ZMAX", "REF_X", "REF_Y", "REF_Z"}) {
    EXPECT_EQ(sets.count(name), 1U) << name;
  }
  const test::CliRun image = run("mesomodel small.h5 --voxels 16 -o rve.vti");
  EXPECT_EQ(image.exit_code, 0) << image.err;
}

TEST_F(PeriodicCliTest, HomogenizeRunsCalculixAndWritesTheStiffness) {
  AGGPACK_REQUIRE_READER("ccx");
  ASSERT_EQ(run("pack periodic.toml --set container.length=0.04 --set container.width=0.04 "
                "--set container.depth=0.04 -o small.h5 --progress none")
                .exit_code,
            0);
  const test::CliRun result =
      run("mesomodel small.h5 -o rve.inp --homogenize --solver iterative -j 1 --progress none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("wrote rve-stiffness.json"), std::string::npos) << result.out;
  const auto json = nlohmann::json::parse(test::file_text(folder_ / "rve-stiffness.json"));
  const double e = json["isotropic_projection"]["youngs_modulus_pa"].get<double>();
  EXPECT_GT(e, json["bounds"]["reuss_youngs_modulus_pa"].get<double>());
  EXPECT_LT(e, json["bounds"]["voigt_youngs_modulus_pa"].get<double>());
  EXPECT_LT(json["asymmetry"].get<double>(), 0.01);
  EXPECT_EQ(json["stiffness_pa"].size(), 6U);
  EXPECT_EQ(json["solver"]["threads"].get<int>(), 1);
  EXPECT_EQ(json["solver"]["method"].get<std::string>(), "iterative (ITERATIVE CHOLESKY)");
  EXPECT_GT(json["solver"]["cpu_seconds"].get<double>(), 0.0);
  std::ifstream in(folder_ / "rve.inp");
  std::string line;
  std::size_t iterative_steps = 0;
  while (std::getline(in, line)) iterative_steps += line == "*STATIC, SOLVER=ITERATIVE CHOLESKY";
  EXPECT_EQ(iterative_steps, 6U);
  // Asked again without --force: refused before meshing, nothing replaced.
  expect_one_line_refusal("mesomodel small.h5 -o rve.inp --homogenize", "rve.inp");
}

TEST_F(PeriodicCliTest, HomogenizeRefusalsComeBeforeTheWork) {
  ASSERT_EQ(run("pack periodic.toml --set container.periodic=xy --set container.length=0.04 "
                "--set container.width=0.04 --set container.depth=0.04 -o xy.h5 --progress none")
                .exit_code,
            0);
  expect_one_line_refusal("mesomodel xy.h5 -o xy.inp --homogenize",
                          "invalid --homogenize = with container.periodic = xy (allowed: a "
                          "packing periodic in x, y and z");
  expect_one_line_refusal("mesomodel xy.h5 -o xy.vti --voxels 8 --homogenize",
                          "invalid --homogenize = with --voxels");
  // Without CalculiX: the package is named, and no mesh is made or written.
  const test::CliRun missing = run("mesomodel xy.h5 -o xy.inp --homogenize", "PATH=/nonexistent");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("calculix-ccx"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(folder_ / "xy.inp"));
}

}  // namespace
}  // namespace aggpack
