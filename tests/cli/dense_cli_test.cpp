// `aggpack pack` with the dense kind and `aggpack densify` report what was asked against what was
// reached (issue 14): the final container is the given one, the fraction against the asked one,
// a fill that jams is a warning, and the grading is printed per sieve size against the target
// (text and --json).

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/grading.h"
#include "aggpack/pack/statistics.h"
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack::test {
namespace {

// Fuller 10-20 mm in a 80 mm cube: fill 20 % in the enlarged cube, 30 % in the given one.
const char* const kFuller = R"([container]
kind = "box"
length = 0.08
width = 0.08
depth = 0.08
[particle]
alpha = 0.5
edge_length = 0.0
[grading]
kind = "fuller"
size_min = 0.01
size_max = 0.02
exponent = 0.5
[packer]
kind = "dense"
seed = 5
target_fraction = 0.2
[densify]
target_fraction = 0.3
max_sweeps = 2000
)";

class DenseCliTest : public CliTest {
 protected:
  DenseCliTest() : CliTest("aggpack_dense_") {}
  void SetUp() override {
    CliTest::SetUp();
    std::ofstream(path("fuller.toml")) << kFuller;
  }

  // The rows "size target achieved diff" the final packing must show, as printed.
  [[nodiscard]] std::vector<std::string> expected_rows(const std::string& file) const {
    const Packing packing = read_packing(path(file));
    const PackConfig config = parse_pack_config(kFuller, "fuller.toml");
    const std::vector<GradingPoint> points = achieved_grading(packing, *config.target_grading());
    const std::string table = format_grading(points);
    std::vector<std::string> rows;
    std::size_t begin = 0;
    for (std::size_t end = table.find('\n'); end != std::string::npos;
         begin = end + 1, end = table.find('\n', begin)) {
      rows.push_back(table.substr(begin, end - begin));
    }
    EXPECT_GE(points.size(), 3u);
    EXPECT_EQ(rows.size(), points.size() + 2);  // title, header, one row per sieve size
    // The table is about this packing: its last row is 100 % passing, the rows differ.
    EXPECT_EQ(points.back().achieved_percent, 100.0);
    EXPECT_GT(points[1].achieved_percent, 0.0);
    return rows;
  }

  [[nodiscard]] bool python_ok(const std::string& json_file, const std::string& check) const {
    const std::string command = "/usr/bin/python3 -c 'import json; d = json.load(open(\"" +
                                path(json_file) + "\")); " + check + "'";
    return std::system(command.c_str()) == 0;
  }
};

TEST_F(DenseCliTest, PackPrintsTheGivenContainerTheAskedFractionAndTheGradingPerSieve) {
  const CliRun result = run("pack fuller.toml -o dense.h5 --progress none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  EXPECT_NE(result.out.find("container       box 0.08 x 0.08 x 0.08 m"), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("(asked 0.3000)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("fill container  box 0.0915"), std::string::npos) << result.out;
  for (const std::string& row : expected_rows("dense.h5")) {
    EXPECT_NE(result.out.find(row + "\n"), std::string::npos) << row << "\n" << result.out;
  }
  // `aggpack densify` on the file prints the same table (the densifier never changes sizes).
  const CliRun more = run("densify dense.h5 -o denser.h5 --target-fraction 0.32 --progress none");
  ASSERT_EQ(more.exit_code, 0) << more.err;
  for (const std::string& row : expected_rows("denser.h5")) {
    EXPECT_NE(more.out.find(row + "\n"), std::string::npos) << row << "\n" << more.out;
  }
}

TEST_F(DenseCliTest, JsonHasTheContainerTheFillTheDensifierAndTheGrading) {
  const CliRun result = run("pack fuller.toml -o dense.h5 --progress none --json");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::ofstream(path("report.json")) << result.out;
  EXPECT_TRUE(python_ok("report.json",
                        "assert d[\"container\"][\"length_m\"] == 0.08; "
                        "assert abs(d[\"fill\"][\"scale\"] - 1.5 ** (1 / 3)) < 1e-12; "
                        "assert d[\"fill\"][\"asked_fraction\"] == 0.3; "
                        "assert d[\"fill\"][\"report\"][\"target_solid_fraction\"] == 0.2; "
                        "assert d[\"densify\"][\"stop\"] == \"target reached\"; "
                        "assert d[\"report\"][\"solid_fraction\"] >= 0.3 * (1 - 1e-9); "
                        "assert d[\"report\"][\"is_target_reached\"]; "
                        "g = d[\"grading\"]; assert len(g) >= 3; "
                        "assert g[-1][\"target_percent\"] == 100 and "
                        "g[-1][\"achieved_percent\"] == 100; "
                        "assert all(abs(p[\"achieved_percent\"] - p[\"target_percent\"]) < 15 "
                        "for p in g)"))
      << result.out;
}

TEST_F(DenseCliTest, AJammedFillIsAWarningNamingBothFractions) {
  const CliRun result =
      run("pack fuller.toml -o dense.h5 --progress none --set packer.attempts=1 "
          "--set packer.max_consecutive_failures=1");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.err.find("warning: the random fill stopped at"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("below densify.target_fraction 0.3000"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("packer.target_fraction 0.2000"), std::string::npos) << result.err;
  EXPECT_NE(result.out.find("container       box 0.08 x 0.08 x 0.08 m"), std::string::npos)
      << result.out;
  // A bad combination: one line naming both keys, no file.
  const CliRun bad =
      run("pack fuller.toml -o bad.h5 --progress none --set packer.target_fraction=0.3");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("invalid packer.target_fraction = 0.3"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("densify.target_fraction"), std::string::npos) << bad.err;
  EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(path("bad.h5")));
}

// Every examples/dense-*.toml runs (small budgets), and so do the continue-from-file commands of
// examples/dense-bed.toml's header.
TEST_F(DenseCliTest, DenseExamplesAndTheContinueCommandsRun) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_dir() + "/examples")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("dense-", 0) != 0 || entry.path().extension() != ".toml") continue;
    ++count;
    const PackConfig config = load_pack_config(entry.path().string());
    const CliRun result = run("pack '" + entry.path().string() + "' -o " + name +
                              ".h5 --progress none --set densify.max_sweeps=10");
    ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
    EXPECT_NE(result.out.find("densify         "), std::string::npos) << name << result.out;
    const Packing packing = read_packing(path(name + ".h5"));
    EXPECT_EQ(packing.provenance.packer, "dense") << name;
    EXPECT_GT(packing.particles.size(), 100u) << name;
    // Bed: the given container; fixed after 10 sweeps: not compressed yet, never smaller.
    EXPECT_GE(packing.container.volume(), config.container().volume() * (1 - 1e-12)) << name;
  }
  EXPECT_GE(count, 3);
  const std::string paper = test::source_dir() + "/examples/paper.toml";
  const CliRun lattice = run("pack '" + paper + "' -o lattice.h5 --progress none");
  ASSERT_EQ(lattice.exit_code, 0) << lattice.err;
  const CliRun bed =
      run("densify lattice.h5 -o lattice-bed.h5 --mode bed --sweeps 5 --progress none");
  ASSERT_EQ(bed.exit_code, 0) << bed.err;
  EXPECT_NE(bed.out.find("bulk fraction"), std::string::npos) << bed.out;
}

}  // namespace
}  // namespace aggpack::test
