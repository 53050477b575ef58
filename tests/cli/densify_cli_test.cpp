// `aggpack densify` end to end: a random packing densified (fixed and bed), provenance, byte-
// identical output at 1 and 2 threads, bad options (non-zero exit, one-line error, no output).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "aggpack/config/config.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/verify.h"
#include "support/cli_test.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::file_text;

class DensifyCliTest : public test::CliTest {
 protected:
  DensifyCliTest() : CliTest("aggpack_densify_") {}
  void SetUp() override {
    CliTest::SetUp();
    std::ofstream(folder_ / "loose.toml") << R"([container]
kind = "box"
length = 0.4
width = 0.4
depth = 0.4
[particle]
alpha = 0.5
edge_length = 0.0
edge_length_ratio = 1.0
radius_min = 0.05
radius_max = 0.05
[packer]
kind = "random"
seed = 3
target_fraction = 0.25
)";
    const CliRun pack = run("pack loose.toml -o loose.h5 --progress none");
    ASSERT_EQ(pack.exit_code, 0) << pack.err;
  }
};

TEST_F(DensifyCliTest, FixedModeWritesAVerifiedDensePackingWithProvenance) {
  const CliRun result =
      run("densify loose.h5 -o dense.h5 --target-fraction 0.33 --sweeps 2000 --seed 4 --progress "
          "none --trace trace.txt");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("target reached"), std::string::npos) << result.out;
  const Packing loose = read_packing((folder_ / "loose.h5").string());
  const Packing dense = read_packing((folder_ / "dense.h5").string());
  EXPECT_EQ(dense.provenance.packer, "dense");
  EXPECT_EQ(dense.provenance.seed, 4u);
  EXPECT_NE(dense.provenance.config_toml.find("# densify.target_fraction = 0.33"),
            std::string::npos);
  EXPECT_EQ(dense.particles.size(), loose.particles.size());
  EXPECT_LT(dense.container.volume(), 0.8 * loose.container.volume());
  const VerifyResult check = verify(dense, {.is_brute_force = true});
  EXPECT_TRUE(check.is_ok) << check.message;
  const std::string trace = file_text(folder_ / "trace.txt");
  EXPECT_EQ(trace.rfind("# seconds sweeps solid_fraction cpu_seconds\n", 0), 0u);
  EXPECT_GT(std::count(trace.begin(), trace.end(), '\n'), 1);
  {
    // Every update: wall time, sweeps, fraction, CPU time; none of them goes backward.
    std::istringstream lines(trace.substr(trace.find('\n') + 1));
    std::string line;
    double previous[4] = {0.0, 0.0, 0.0, 0.0};
    int rows = 0;
    while (std::getline(lines, line)) {
      std::istringstream fields(line);
      double value[4] = {-1.0, -1.0, -1.0, -1.0};
      std::string rest;
      ASSERT_TRUE(fields >> value[0] >> value[1] >> value[2] >> value[3]) << line;
      EXPECT_FALSE(fields >> rest) << line;
      for (int k = 0; k < 4; ++k) EXPECT_GE(value[k], previous[k]) << line;
      std::copy(std::begin(value), std::end(value), std::begin(previous));
      ++rows;
    }
    EXPECT_GT(rows, 0);
    EXPECT_GT(previous[3], 0.0);  // the run took some CPU time
  }
  // `aggpack info` still reads the stored configuration (the densify keys are comments).
  const CliRun info = run("info dense.h5 --no-descriptors");
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(info.out.find("not readable"), std::string::npos) << info.out;
}

// The dense packer kind through the config: `aggpack pack --set packer.kind=dense`.
TEST_F(DensifyCliTest, PackWithTheDenseKindWritesAVerifiedPackingWhoseConfigRepacksIt) {
  const CliRun result =
      run("pack loose.toml --set packer.kind=dense --set packer.target_fraction=0.2 "
          "--set densify.target_fraction=0.32 --set densify.max_sweeps=2000 -o dense.h5 "
          "--progress none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("dense packer, seed 3"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("target reached"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("(asked 0.3200)"), std::string::npos) << result.out;
  EXPECT_TRUE(result.err.empty()) << result.err;  // no warning: fill and densifier reached
  // The fill ran enlarged; the output box is the given one.
  EXPECT_NE(result.out.find("fill container  box 0.4678"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("container       box 0.4 x 0.4 x 0.4 m"), std::string::npos)
      << result.out;
  const Packing dense = read_packing((folder_ / "dense.h5").string());
  const auto* box = dense.container.get_if<BoxContainer>();
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->length, 0.4);
  EXPECT_EQ(box->width, 0.4);
  EXPECT_EQ(box->depth, 0.4);
  EXPECT_EQ(dense.provenance.packer, "dense");
  EXPECT_EQ(dense.provenance.seed, 3u);
  const VerifyResult check = verify(dense, {.is_brute_force = true});
  EXPECT_TRUE(check.is_ok) << check.message;
  const auto at = result.out.find("solid fraction  ");
  ASSERT_NE(at, std::string::npos) << result.out;
  const double fraction = std::stod(result.out.substr(at + 16, 6));
  EXPECT_GE(fraction, 0.32);  // printed with 4 decimals
  // The stored (resolved) configuration is a config file that packs the same file again.
  const PackConfig stored = parse_pack_config(dense.provenance.config_toml, "stored");
  EXPECT_EQ(stored.resolved_toml, dense.provenance.config_toml);
  std::ofstream(folder_ / "resolved.toml") << dense.provenance.config_toml;
  const CliRun again = run("pack resolved.toml -o again.h5 --progress none -j 1");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(test::same_bytes(file_text(folder_ / "again.h5"), file_text(folder_ / "dense.h5")));
  // A bad densify key is named; nothing is written.
  const CliRun bad =
      run("pack loose.toml --set packer.kind=dense --set densify.max_sweeps=0 -o bad.h5");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("densify.max_sweeps"), std::string::npos) << bad.err;
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(fs::exists(folder_ / "bad.h5"));
}

TEST_F(DensifyCliTest, SameSeedIsByteIdenticalAtOneAndTwoThreads) {
  ASSERT_EQ(run("densify loose.h5 -o one.h5 --target-fraction 0.3 --sweeps 40 -j 1 "
                "--progress none")
                .exit_code,
            0);
  ASSERT_EQ(run("densify loose.h5 -o two.h5 --target-fraction 0.3 --sweeps 40 -j 2 "
                "--progress none")
                .exit_code,
            0);
  EXPECT_TRUE(test::same_bytes(file_text(folder_ / "one.h5"), file_text(folder_ / "two.h5")));
}

TEST_F(DensifyCliTest, BedModeReportsTheBulkFraction) {
  const CliRun result = run("densify loose.h5 -o bed.h5 --mode bed --sweeps 100 --progress none");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("bulk fraction"), std::string::npos) << result.out;
}

TEST_F(DensifyCliTest, BadOptionsFailWithOneLineAndNoOutput) {
  const struct {
    const char* arguments;
    const char* names;
  } cases[] = {
      {"--mode heap", "--mode"},
      {"--target-fraction 0.99", "invalid --target-fraction = 0.99"},
      {"--sweeps 0", "invalid --sweeps = 0"},
      {"--max-time -1", "invalid --max-time = -1"},
      {"--gap -0.1", "invalid --gap = -0.1"},
      {"--target-container 0.3,0.3", "--target-container"},
      {"--target-container 0.5,0.4,0.4", "invalid --target-container (length) = 0.5"},
      {"--progress loud", "--progress"},
  };
  for (const auto& bad : cases) {
    const std::string arguments = bad.arguments;
    const CliRun result = run("densify loose.h5 -o out.h5 " + arguments +
                              (arguments.find("--progress") == 0 ? "" : " --progress none"));
    EXPECT_NE(result.exit_code, 0) << bad.arguments;
    EXPECT_NE(result.err.find(bad.names), std::string::npos) << bad.arguments << ": " << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_FALSE(fs::exists(folder_ / "out.h5")) << bad.arguments;
  }
  const CliRun missing = run("densify nothing.h5 -o out.h5");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.err.find("nothing.h5"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace aggpack
