// Every simulation ends (issue 12): sizes that would make the time step 0 or the masses
// non-finite are refused, a run whose max_time needs more than 10^8 steps is refused up front, a
// diverging (NaN) state stops the run with an error, and max_time is honoured.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/sim/settle.h"
#include "aggpack/sim/world.h"
#include "support/files.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

// One 0.1 m cube at `height` in a 1 m box.
Packing one_cube(double height = 0.5, double scale = 1.0) {
  Packing packing;
  packing.container = {.shape = BoxContainer{.length = 1.0, .width = 1.0, .depth = 1.0}};
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.particles.push_back(
      {.shape = 0, .pose = {.position = Vec3(0.5, 0.5, height)}, .scale = scale});
  return packing;
}

TEST(SimulationLimits, SizesThatBreakTheTimeStepAreRefused) {
  for (const double scale : {1e-200, 1e-12, 1e200}) {
    try {
      World world(one_cube(0.5, scale), {});
      FAIL() << "scale " << scale << " accepted";
    } catch (const InvalidInput& error) {
      EXPECT_EQ(error.field(), "particle 0 scale") << error.what();
    }
  }
  // Two particles whose sizes differ by more than 10^6 cannot share Bullet's tolerances.
  Packing mixed = one_cube();
  mixed.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.2, 0.2, 0.2)}, .scale = 1e-7});
  EXPECT_THROW(World(mixed, {}), InvalidInput);
  EXPECT_NO_THROW(World(one_cube(0.5, 1e-3), {}));
}

TEST(SimulationLimits, TooManyStepsAreRefusedBeforeStepping) {
  SettleOptions options;
  options.physics.time_step = 1e-9;  // 30 s would take 3 x 10^10 steps
  try {
    (void)settle(one_cube(), options);
    FAIL() << "expected LimitExceeded";
  } catch (const LimitExceeded& error) {
    EXPECT_NE(std::string(error.what()).find("max_time = 30 s"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("10^8 time steps"), std::string::npos);
  }
  World world(one_cube(), {.time_step = 1e-9});
  EXPECT_THROW((void)steps_per_check(world, {}), LimitExceeded);
  EXPECT_EQ(world.step_count(), 0u);
}

TEST(SimulationLimits, NonFiniteStateStopsTheRun) {
  World world(one_cube(), {});
  EXPECT_TRUE(world.is_finite());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  world.set_velocity(0, Vec3(nan, 0.0, 0.0), Vec3::Zero());
  EXPECT_FALSE(world.is_finite());
  try {
    (void)run_until_rest(world, {.max_time = 10.0});
    FAIL() << "expected the run to stop";
  } catch (const Error& error) {
    EXPECT_EQ(error.kind(), ErrorKind::kLimitExceeded);
    EXPECT_NE(std::string(error.what()).find("diverged"), std::string::npos) << error.what();
  }
  // Stopped after the first block of steps, not at max_time.
  EXPECT_LT(world.time(), 0.1);
}

TEST(SimulationLimits, MaxTimeIsHonoured) {
  SettleOptions options;
  options.rest.max_time = 0.05;  // the cube needs ~0.3 s to reach the floor
  const SettleResult result = settle(one_cube(0.5), options);
  EXPECT_FALSE(result.report.is_at_rest);
  EXPECT_GE(result.report.simulated_time, 0.05);
  EXPECT_LE(result.report.simulated_time, 0.05 + options.rest.check_interval + 1e-9);
}

TEST(SimulationLimits, SettleOnAParticleAtScale1e200EndsWithOneLine) {
  // tests/io/fixtures/bad-inputs/settle_hang_scale_1e-200.h5 (issue 12): settle printed
  // "kinetic energy -nan J" and never ended.
  const fs::path folder =
      fs::temp_directory_path() / ("aggpack_settle_limits_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string input = test::bad_inputs_dir() + "settle_hang_scale_1e-200.h5";
  const std::string command =
      "cd '" + folder.string() + "' && '" + test::aggpack_binary() + "' settle '" + input +
      "' -o out.h5 --max-time 0.02 --progress lines " + ">stdout.txt 2>stderr.txt";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string err = test::file_text(folder / "stderr.txt");
  // Refused by World (or by the native reader, which may reject the scale first): one line that
  // names the file and the scale.
  EXPECT_EQ(err.rfind("aggpack: error: ", 0), 0u) << err;
  EXPECT_NE(err.find(input), std::string::npos) << err;
  EXPECT_NE(err.find("scale"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(folder / "out.h5"));
  fs::remove(folder / "stdout.txt");
  fs::remove(folder / "stderr.txt");
  EXPECT_TRUE(fs::is_empty(folder)) << "temporary files left";
  fs::remove_all(folder);
}

}  // namespace
}  // namespace aggpack
