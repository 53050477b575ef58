// -o corner cases of the outputs the earlier tests left out (issue 35, item 3): merge's -o,
// export --per-particle, calibrate --table / --plot and densify --trace. Each refuses "" and a
// path of the wrong kind in one line (exit 2 for "", 3 for the path), leaves a FIFO or folder in
// place and leaves no temporary file behind.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/cli_test.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;
using test::CliRun;

class OutputCornersCliTest : public test::CliTest {
 protected:
  OutputCornersCliTest() : CliTest("aggpack_out_corners_") {}

  // Exit code, exactly one line on stderr starting with "aggpack: error: " and holding `words`,
  // nothing in the folder besides `kept` (no temporary).
  void expect_refused(const CliRun& result, int exit_code, const std::string& words,
                      const std::vector<std::string>& kept) {
    EXPECT_EQ(result.exit_code, exit_code) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_EQ(result.err.rfind("aggpack: error: ", 0), 0U) << result.err;
    EXPECT_NE(result.err.find(words), std::string::npos) << result.err;
    EXPECT_EQ(files(), kept);
  }
};

TEST_F(OutputCornersCliTest, MergeExportPerParticleCalibrateAndDensifyTrace) {
  ASSERT_EQ(run("pack --progress none -o small.h5 --set container.length=0.6 --set "
                "container.width=0.4 --set container.depth=0.4")
                .exit_code,
            0);
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  fs::create_directory(path("dir"));
  const std::vector<std::string> kept = {"dir", "fifo", "small.h5"};

  // export --per-particle takes a folder: "" and a FIFO are refused.
  expect_refused(run("export small.h5 --per-particle -o ''"), 2, "-o/--output", kept);
  expect_refused(run("export small.h5 --per-particle --format stl -o fifo"), 3,
                 "cannot write fifo: not a folder; -o/--output takes a folder path", kept);
  EXPECT_EQ(fs::status(path("fifo")).type(), fs::file_type::fifo);

  // calibrate --table / --plot take files: "", a folder, a FIFO (even with --force).
  expect_refused(run("calibrate --alpha 0.8 --samples 4 --table ''"), 2, "--table", kept);
  expect_refused(run("calibrate --alpha 0.8 --samples 4 --plot ''"), 2, "--plot", kept);
  expect_refused(run("calibrate --alpha 0.8 --samples 4 --table dir"), 3,
                 "refusing to replace dir: not a regular file (directory)", kept);
  expect_refused(run("calibrate --alpha 0.8 --samples 4 --plot fifo --force"), 3,
                 "refusing to replace fifo: not a regular file (FIFO)", kept);
  EXPECT_EQ(fs::status(path("fifo")).type(), fs::file_type::fifo);

  // densify --trace '' was taken as "no trace": now refused like every output flag.
  expect_refused(run("densify small.h5 -o out.h5 --sweeps 2 --progress none --trace ''"), 2,
                 "--trace", kept);
  expect_refused(run("densify small.h5 -o out.h5 --sweeps 2 --progress none --trace dir"), 3,
                 "refusing to replace dir: not a regular file (directory)", kept);
  expect_refused(run("densify small.h5 -o out.h5 --sweeps 2 --progress none --trace fifo"), 3,
                 "fifo", kept);
  EXPECT_EQ(fs::status(path("fifo")).type(), fs::file_type::fifo);

  // merge -o takes a folder.
  if (!test::has_subcommand("merge")) GTEST_SKIP() << "built without Bullet";
  expect_refused(run("merge dir -o ''"), 2, "-o/--output", kept);
  expect_refused(run("merge dir -o fifo"), 3,
                 "cannot write fifo: not a folder; -o/--output takes a folder path", kept);
  expect_refused(run("merge dir -o small.h5"), 3, "not a folder", kept);
  EXPECT_EQ(fs::status(path("fifo")).type(), fs::file_type::fifo);
}

}  // namespace
}  // namespace aggpack
