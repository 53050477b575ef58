// `repose`, `sweep` and `settle` bad input (issue 12, item 6): the message names the key or flag
// the user typed (not the library's field), --print-config rejects what the run rejects, and a
// rejected run leaves no empty output folder.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

struct Run {
  int exit_code = -1;
  std::string output;
};

Run aggpack(const std::string& arguments) {
  Run result;
  const std::string command = "'" + test::aggpack_binary() + "' " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  for (std::size_t got = 0; (got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) {
    result.output.append(buffer, got);
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

const std::string kExample = test::source_dir() + "/examples/repose-acrylic-048.toml";

class SimCliErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("aggpack_sim_cli_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  [[nodiscard]] std::string path(const std::string& name) const {
    return (folder_ / name).string();
  }
  fs::path folder_;
};

TEST_F(SimCliErrors, ReposeRejectsBeforeCreatingItsFolder) {
  // The lattice fill's vertex cap, found before any simulation: the user's key, exit 2, no folder.
  const std::string expected_start =
      "aggpack: error: limit exceeded for particle.edge_length = 0.00661463 (allowed: >= about";
  const auto run = aggpack("repose " + kExample + " --set particle.radius=0.5 -o " + path("rr"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.output.rfind(expected_start, 0), 0U) << run.output;
  EXPECT_FALSE(fs::exists(path("rr")));
  // --print-config rejects the same configuration.
  const auto print = aggpack("repose " + kExample + " --set particle.radius=0.5 --print-config");
  EXPECT_EQ(print.exit_code, 2);
  EXPECT_EQ(print.output, run.output);
  // A folder the user made is kept (empty or not).
  fs::create_directory(path("mine"));
  EXPECT_EQ(
      aggpack("repose " + kExample + " --set particle.radius=0.5 -o " + path("mine")).exit_code, 2);
  EXPECT_TRUE(fs::is_directory(path("mine")));
  // sweep checks the same way.
  const auto sweep = aggpack("sweep " + kExample + " --set particle.radius=0.5 -o " + path("ss"));
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_EQ(sweep.output.rfind(expected_start, 0), 0U) << sweep.output;
  EXPECT_FALSE(fs::exists(path("ss")));
}

TEST_F(SimCliErrors, MessagesNameTheUsersKeys) {
  const auto baffle = aggpack("repose --set trough.baffle_position=7 --print-config");
  EXPECT_EQ(baffle.exit_code, 2);
  EXPECT_EQ(baffle.output,
            "aggpack: error: invalid trough.baffle_position = 7 (allowed: (0, trough_length - "
            "baffle_thickness))\n");
  const auto radius = aggpack("repose --set particle.radius=-1 --print-config");
  EXPECT_EQ(radius.exit_code, 2);
  EXPECT_EQ(radius.output,
            "aggpack: error: --set particle.radius=-1: invalid particle.radius = -1 (allowed: "
            "(0, 1e6] m)\n");
  const auto friction = aggpack("repose --set physics.friction=11 --print-config");
  EXPECT_EQ(friction.output,
            "aggpack: error: --set physics.friction=11: invalid physics.friction = 11 (allowed: "
            "[0, 10])\n");
  const auto newline =
      aggpack("repose --set \"$(printf 'physics.friction=0.3\\ntrough.length=1')\" --print-config");
  EXPECT_EQ(newline.exit_code, 2);
  EXPECT_EQ(newline.output,
            "aggpack: error: --set physics.friction=0.3\\ntrough.length=1: a --set value must be "
            "one line (it contains a line break)\n");
  const auto mu = aggpack("settle in.h5 -o " + path("out.h5") + " --mu 20");
  EXPECT_EQ(mu.exit_code, 2);
  EXPECT_EQ(mu.output, "aggpack: error: invalid --mu = 20 (allowed: [0, 10])\n");
  const auto quiet = aggpack("settle in.h5 -o " + path("out.h5") + " --quiet-time -1");
  EXPECT_EQ(quiet.output, "aggpack: error: invalid --quiet-time = -1 (allowed: [0, 1000000])\n");
  // --seed is typed as a flag: -1 is refused (not wrapped to 2^64 - 1), naming the flag.
  for (const std::string command : {"repose", "sweep"}) {
    const auto seed = aggpack(command + " --seed -1 --print-config");
    EXPECT_EQ(seed.exit_code, 2);
    EXPECT_EQ(seed.output,
              "aggpack: error: invalid --seed = -1 (allowed: an integer in [0, 2^63 - 1])\n");
  }
  const auto key = aggpack("repose --set particle.seed=-1 --print-config");
  EXPECT_EQ(key.exit_code, 2);
  EXPECT_EQ(key.output.rfind("aggpack: error: --set particle.seed=-1: invalid particle.seed", 0),
            0U)
      << key.output;
}

}  // namespace
}  // namespace aggpack
