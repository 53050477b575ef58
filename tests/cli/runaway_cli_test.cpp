// Runaway jobs are refused before any work (issue 12): `pack` configs whose size list the
// container cannot hold or the memory cannot take, or whose shape library is far larger than the
// target needs; a heavy run that passes says so before it starts; `shapes -n` streams its rows.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

class RunawayCliTest : public test::CliTest {
 protected:
  RunawayCliTest() : CliTest("aggpack_runaway_") {}
};

TEST_F(RunawayCliTest, CountTheBoxCannotHoldIsRefusedUpFront) {
  const CliRun pack =
      run("pack '" + test::bad_inputs_dir() + "count_1e8_default_box.toml' -o out.h5");
  EXPECT_EQ(pack.exit_code, 2) << pack.err;
  EXPECT_EQ(pack.err.rfind("aggpack: error: limit exceeded for packer.target_count = 100000000 "
                           "(allowed: at most ~",
                           0),
            0u)
      << pack.err;
  EXPECT_NE(pack.err.find("8.4 m^3"), std::string::npos) << pack.err;
  EXPECT_EQ(std::count(pack.err.begin(), pack.err.end(), '\n'), 1) << pack.err;
  EXPECT_TRUE(fs::is_empty(folder_)) << "no output or temporary file";
}

TEST_F(RunawayCliTest, SizeListBeyondTheMemoryLimitIsRefusedUpFront) {
  // ~5 x 10^7 particles of 5-20 mm at 35 % of the default box: ~50 GB of shapes.
  const CliRun pack =
      run("pack '" + test::bad_inputs_dir() + "fuller_in_default_box.toml' -o out.h5",
          "AGGPACK_MEMORY_LIMIT=8G");
  EXPECT_EQ(pack.exit_code, 2) << pack.err;
  EXPECT_EQ(pack.err.rfind("aggpack: error: limit exceeded for packer.target_fraction = 0.35", 0),
            0u)
      << pack.err;
  EXPECT_NE(pack.err.find("memory limit of 8.59 GB (AGGPACK_MEMORY_LIMIT=8G)"), std::string::npos)
      << pack.err;
  EXPECT_NE(pack.err.find("packer.shape_library"), std::string::npos) << pack.err;
  EXPECT_EQ(std::count(pack.err.begin(), pack.err.end(), '\n'), 1) << pack.err;
  EXPECT_TRUE(fs::is_empty(folder_));
  // --print-config refuses it the same way.
  EXPECT_EQ(run("pack '" + test::bad_inputs_dir() + "fuller_in_default_box.toml' --print-config",
                "AGGPACK_MEMORY_LIMIT=8G")
                .exit_code,
            2);
  // A bad limit is named.
  const CliRun bad =
      run("pack '" + test::bad_inputs_dir() + "fuller_in_default_box.toml' -o out.h5",
          "AGGPACK_MEMORY_LIMIT=lots");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("AGGPACK_MEMORY_LIMIT = lots"), std::string::npos) << bad.err;
}

// Valid but heavy (issue: "Found on 2026-12-03"): a shape library far above what the target
// needs is refused with the estimate, before any shape is grown.
TEST_F(RunawayCliTest, ShapeLibraryFarAboveTheTargetIsRefused) {
  const CliRun pack = run("pack '" + test::source_dir() +
                          "/examples/concrete-fuller.toml' --set packer.shape_library=1000000 "
                          "--set packer.target_fraction=0.1 -o x.h5");
  EXPECT_EQ(pack.exit_code, 2) << pack.err;
  EXPECT_EQ(pack.err.rfind("aggpack: error: limit exceeded for packer.shape_library = 1000000 "
                           "(allowed: at most ",
                           0),
            0U)
      << pack.err;
  EXPECT_NE(pack.err.find(" particles this target needs, at least 1000): every library shape is "
                          "grown before placement, so the run would need ~"),
            std::string::npos)
      << pack.err;
  EXPECT_EQ(std::count(pack.err.begin(), pack.err.end(), '\n'), 1) << pack.err;
  EXPECT_TRUE(fs::is_empty(folder_));
}

// A valid run that will take minutes and gigabytes says so in one line before it starts, even
// with --progress none; stopped (SIGTERM: a background job of a shell ignores SIGINT) once the
// line is there, it leaves nothing.
TEST_F(RunawayCliTest, HeavyRunIsAnnouncedBeforeItStarts) {
  const std::string err = folder_.string() + ".heavy.err";
  const std::string command =
      "cd '" + folder_.string() + "' && ('" + test::aggpack_binary() + "' pack '" +
      test::source_dir() +
      "/examples/triaxial-cylinder.toml' --set container.radius=1.0 --progress none -o t.h5 "
      ">/dev/null 2>'" +
      err + "' & pid=$!; for i in $(seq 1200); do grep -q 'large run' '" + err +
      "' && break; sleep 0.1; done; kill -TERM $pid; wait $pid)";
  const int status = std::system(command.c_str());
  EXPECT_NE(status, -1);
  const std::string text = test::file_text(err);
  std::filesystem::remove(err);
  // The first line: estimated particles (~10^6), memory (GB) and time.
  EXPECT_EQ(text.rfind("aggpack: a large run: ~", 0), 0U) << text;
  const std::string first = text.substr(0, text.find('\n'));
  EXPECT_NE(first.find(" particles, ~"), std::string::npos) << first;
  EXPECT_NE(first.find(" GB of memory, ~"), std::string::npos) << first;
  EXPECT_NE(first.find("(rough estimate; Ctrl-C stops it)"), std::string::npos) << first;
  const double particles = std::stod(first.substr(std::string("aggpack: a large run: ~").size()));
  EXPECT_GT(particles, 3e5) << first;
  EXPECT_LT(particles, 3e6) << first;
  EXPECT_TRUE(fs::is_empty(folder_)) << "no output or temporary file after Ctrl-C";
}

// A small run says nothing more than before.
TEST_F(RunawayCliTest, SmallRunHasNoHeadsUp) {
  const CliRun pack =
      run("pack --progress none -o small.h5 --set container.length=0.6 --set "
          "container.width=0.4 --set container.depth=0.4");
  EXPECT_EQ(pack.exit_code, 0) << pack.err;
  EXPECT_EQ(pack.err, "");
}

TEST_F(RunawayCliTest, ShapesStreamsItsRowsAcrossChunks) {
  // More than one chunk of 65,536: rows in index order, summary over all of them.
  const CliRun shapes = run("shapes -n 65600 -L 0.2 -o out.csv");
  ASSERT_EQ(shapes.exit_code, 0) << shapes.err;
  EXPECT_NE(shapes.out.find("wrote out.csv (65600 particles)"), std::string::npos);
  std::ifstream in(folder_ / "out.csv");
  std::string line;
  std::getline(in, line);  // header
  std::size_t rows = 0;
  bool is_ordered = true;
  while (std::getline(in, line)) {
    is_ordered = is_ordered && line.rfind(std::to_string(rows) + ",", 0) == 0;
    ++rows;
  }
  EXPECT_EQ(rows, 65600u);
  EXPECT_TRUE(is_ordered);
  EXPECT_NE(shapes.out.find("volume"), std::string::npos);
}

}  // namespace
}  // namespace aggpack
