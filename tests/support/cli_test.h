#pragma once
// End-to-end CLI tests: a scratch folder per test and the aggpack program run inside it, with
// stdout and stderr captured beside the folder, so the folder holds exactly what the command
// wrote. The program's path: support/paths.h.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "support/files.h"
#include "support/paths.h"

namespace aggpack::test {

/// What one CLI run gave.
struct CliRun {
  int exit_code = -1;  ///< -1 when the program did not exit normally (a signal)
  std::string out;
  std::string err;
};

/// Whether `aggpack --help` lists the subcommand (the sanitized build has no settle, repose,
/// sweep or render). (`aggpack NAME --help` is no test: CLI11 prints the main help and exits 0
/// for a name it does not know.) The help is read once per test program.
inline bool has_subcommand(const std::string& subcommand) {
  static const std::string help = [] {
    std::string text;
    FILE* pipe = popen(("'" + aggpack_binary() + "' --help 2>&1").c_str(), "r");
    if (pipe == nullptr) return text;
    char buffer[4096];
    while (const std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) text.append(buffer, n);
    pclose(pipe);
    return text;
  }();
  return help.find("\n  " + subcommand + " ") != std::string::npos;
}

/// Fixture: folder_ = <tmp>/<prefix><test name>_<pid>, created empty before and removed after
/// each test.
class CliTest : public ::testing::Test {
 protected:
  explicit CliTest(std::string prefix = "aggpack_cli_") : prefix_(std::move(prefix)) {}

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    folder_ = std::filesystem::temp_directory_path() /
              (prefix_ + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(folder_);
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  /// Runs `aggpack <arguments>` (a shell command line) inside folder_, with `environment`
  /// (e.g. "AGGPACK_MEMORY_LIMIT=1G") set for it.
  [[nodiscard]] CliRun run(const std::string& arguments,
                           const std::string& environment = "") const {
    const std::filesystem::path out = folder_.string() + ".stdout";
    const std::filesystem::path err = folder_.string() + ".stderr";
    const std::string command = "cd '" + folder_.string() + "' && " + environment + " '" +
                                aggpack_binary() + "' " + arguments + " >'" + out.string() +
                                "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    CliRun result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = file_text(out);
    result.err = file_text(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return result;
  }

  /// The names in folder_, sorted.
  [[nodiscard]] std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  /// folder_/name as a string.
  [[nodiscard]] std::string path(const std::string& name) const {
    return (folder_ / name).string();
  }

  std::filesystem::path folder_;

 private:
  std::string prefix_;
};

}  // namespace aggpack::test
