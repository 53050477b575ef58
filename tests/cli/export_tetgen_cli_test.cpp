// `aggpack export --tet-method tetgen` end to end on the packings where Debian's TetGen 1.5 used to
// abort the whole process: the paper's default packing and examples/concrete-fuller.toml. The
// export succeeds, reports the shapes that fell back to the centroid fan, and writes the same
// bytes for any thread count.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::file_text;

using ExportTetGenCliTest = test::CliTest;

// The packings are made with aggpack 0.1's growth (particle.growth = midpoint): the shapes TetGen
// is known to abort on (tests/mesh/fixtures/tetgen-abort) are among its particles.
TEST_F(ExportTetGenCliTest, PaperPackingExportsAndReportsTheFallbacks) {
  ASSERT_EQ(run("pack -o paper.h5 --progress none --set particle.growth=midpoint").exit_code, 0);
  // A time limit far above any shape's meshing time (milliseconds). Shape 0 once "timed out" at
  // the default 20 s in a loaded sanitized run, and at 600 s the test later hung to ctest's
  // timeout. Shape 0 is in the first worker, forked just after the progress ticker thread was
  // made, most likely while that thread was still starting (allocating outside
  // section_without_fork); tickers now start with start_thread_before_forks. Below ctest's
  // 600 s, a worker that hangs again fails here by shape, not as a timeout of the whole test.
  const std::string common =
      "export paper.h5 --format inp --tet-method tetgen --tet-time-limit 240";
  const CliRun one = run(common + " -o one.inp -j 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  // The four shapes of tests/mesh/fixtures/tetgen-abort; shape s is particle P<s+1>'s.
  EXPECT_NE(one.out.find("tetgen: 4 of 1050 shapes fell back to the centroid fan (shapes 324, "
                         "336, 599, 988; 4 particles P325, P337, P600, P989; TetGen died of "
                         "signal 6 (Aborted): 4)\n"),
            std::string::npos)
      << one.out;
  EXPECT_NE(one.out.find("1050 particles"), std::string::npos) << one.out;
  const CliRun two = run(common + " -o two.inp -j 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const std::string bytes = file_text(folder_ / "one.inp");
  EXPECT_GT(bytes.size(), 1000000U);
  EXPECT_TRUE(test::same_bytes(bytes, file_text(folder_ / "two.inp")))
      << "output depends on the thread count";
}

TEST_F(ExportTetGenCliTest, ConcreteFullerExampleExports) {
  const std::string config = test::source_dir() + "/examples/concrete-fuller.toml";
  ASSERT_EQ(run("pack '" + config + "' -o fuller.h5 --progress none --set particle.growth=midpoint")
                .exit_code,
            0);
  // A time limit far above any shape's meshing time, so only TetGen's aborts fall back (at the
  // default 20 s a slow machine or the sanitized build adds time-outs and the count moves).
  const CliRun result =
      run("export fuller.h5 --tet-method tetgen --tet-time-limit 240 -o fuller.dat");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("tetgen: 14 of 3439 shapes fell back to the centroid fan"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("TetGen died of signal 6 (Aborted): 14)\n"), std::string::npos)
      << result.out;
  EXPECT_TRUE(fs::exists(folder_ / "fuller.dat"));
}

}  // namespace
}  // namespace aggpack
