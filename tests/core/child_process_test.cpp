// Running another program (core/child_process.h): PATH lookup, the temporary folder's lifetime,
// a child's output, error file, environment, working folder and exit status, and a child left
// running being killed by the destructor.

#include "aggpack/core/child_process.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cerrno>
#include <csignal>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "aggpack/core/error.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ChildProcess, FindsProgramsOnThePath) {
  EXPECT_FALSE(find_on_path("sh").empty());
  EXPECT_TRUE(find_on_path("aggpack-no-such-program").empty());
}

TEST(ChildProcess, TemporaryFolderIsRemovedUnlessReleased) {
  std::string path;
  {
    const TemporaryFolder folder("a test");
    path = folder.path();
    std::ofstream(folder.file("a.txt")) << "x";
    EXPECT_TRUE(fs::is_directory(path));
  }
  EXPECT_FALSE(fs::exists(path));
  {
    TemporaryFolder folder(fs::temp_directory_path().string(), "beside");
    path = folder.path();
    folder.release();
  }
  EXPECT_TRUE(fs::is_directory(path));
  fs::remove_all(path);
  EXPECT_THROW(TemporaryFolder("/nonexistent-aggpack-folder", "x"), IoError);
}

TEST(ChildProcess, RunsInItsFolderWithItsEnvironmentAndReportsItsExit) {
  const TemporaryFolder folder("a test");
  ChildProcess child(
      {.program = find_on_path("sh"),
       .arguments = {"-c", "pwd; echo \"$AGGPACK_CHILD_TEST\"; echo oops >&2; exit 3"},
       .folder = folder.path(),
       .environment = {"AGGPACK_CHILD_TEST=given"},
       .error_file = folder.file("err.txt")});
  std::string output;
  while (child.read_output(output, 100)) {
  }
  double cpu = -1.0;
  const int status = child.wait(cpu);
  EXPECT_EQ(describe_exit(status), "exit status 3");
  EXPECT_EQ(output, fs::canonical(folder.path()).string() + "\ngiven\n");
  EXPECT_EQ(text_of(folder.file("err.txt")), "oops\n");
  EXPECT_EQ(last_line_of(folder.file("err.txt")), "oops");
  EXPECT_EQ(last_line_of(folder.file("err.txt"), "oops"), "");
  EXPECT_GE(cpu, 0.0);
}

TEST(ChildProcess, ProgramThatCannotRunExitsWith127) {
  const TemporaryFolder folder("a test");
  ChildProcess child({.program = folder.file("missing"),
                      .arguments = {},
                      .folder = folder.path(),
                      .environment = {},
                      .error_file = folder.file("err.txt")});
  double cpu = 0.0;
  EXPECT_EQ(describe_exit(child.wait(cpu)), "exit status 127");
}

TEST(ChildProcess, DestructorKillsAChildStillRunning) {
  const TemporaryFolder folder("a test");
  pid_t pid = 0;
  {
    ChildProcess child({.program = find_on_path("sh"),
                        .arguments = {"-c", "echo $$; exec sleep 300"},
                        .folder = folder.path(),
                        .environment = {},
                        .error_file = folder.file("err.txt")});
    std::string output;
    while (output.find('\n') == std::string::npos && child.read_output(output, 100)) {
    }
    pid = static_cast<pid_t>(std::stol(output));
    ASSERT_EQ(::kill(pid, 0), 0) << "running";
  }
  // Killed and reaped by the destructor: the process is gone.
  EXPECT_EQ(::kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

}  // namespace
}  // namespace aggpack
