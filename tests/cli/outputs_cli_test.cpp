// Output files and messages end to end (issue 12, items 3 and 6; fixtures in
// tests/io/fixtures/bad-inputs/): --force never replaces a device, FIFO or folder; temporaries
// are gone after SIGTERM/SIGINT; 255-byte names; a failed [output] export leaves no native file;
// disk full is one line naming the file; config messages are one bounded line.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/export_fixture.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::ScratchFolder;

const std::string kBinary = test::aggpack_binary();

test::CommandResult aggpack(const std::string& arguments) {
  return test::run_command("'" + kBinary + "' " + arguments);
}

bool has_temporary(const ScratchFolder& folder) {
  const auto names = folder.entries();
  return std::any_of(names.begin(), names.end(), [](const std::string& name) {
    return name.find(".tmp.") != std::string::npos;
  });
}

// One line: the error and nothing else (a trailing newline).
void expect_one_line(const test::CommandResult& result) {
  EXPECT_EQ(std::count(result.output.begin(), result.output.end(), '\n'), 1) << result.output;
}

TEST(OutputsCli, ForceRefusesFifoDeviceAndFolder) {
  ScratchFolder folder;
  const std::string fifo = folder.file("fifo.stl");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const auto on_fifo =
      aggpack("export " + test::bad_inputs_dir() + "base_s.h5 -o " + fifo + " --force");
  EXPECT_EQ(on_fifo.exit_code, 3);
  EXPECT_EQ(on_fifo.output,
            "aggpack: error: refusing to replace " + fifo + ": not a regular file (FIFO)\n");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);

  const std::string sub = folder.file("sub.stl");
  fs::create_directory(sub);
  const auto on_folder =
      aggpack("export " + test::bad_inputs_dir() + "base_s.h5 -o " + sub + " --force");
  EXPECT_EQ(on_folder.exit_code, 3);
  EXPECT_EQ(on_folder.output,
            "aggpack: error: refusing to replace " + sub + ": not a regular file (directory)\n");

  // dev_node_replace.sh: a private copy of /dev/null (mknod needs root, as CI runs).
  if (::geteuid() == 0) {
    const std::string node = folder.file("null");
    ASSERT_EQ(::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
    const auto on_node = aggpack("export " + test::bad_inputs_dir() + "base_s.h5 --format stl -o " +
                                 node + " --force");
    EXPECT_EQ(on_node.exit_code, 3);
    EXPECT_EQ(on_node.output, "aggpack: error: refusing to replace " + node +
                                  ": not a regular file (character device)\n");
    EXPECT_EQ(fs::status(node).type(), fs::file_type::character);
    const auto pack_node = aggpack("pack --progress none -o " + node + " --force");
    EXPECT_EQ(pack_node.exit_code, 3) << pack_node.output;
    EXPECT_EQ(fs::status(node).type(), fs::file_type::character);
  }
  // The real /dev/null, without --force only (so that a regression cannot replace it).
  const auto dev_null =
      aggpack("export " + test::bad_inputs_dir() + "base_s.h5 --format stl -o /dev/null");
  EXPECT_EQ(dev_null.exit_code, 3);
  EXPECT_EQ(dev_null.output,
            "aggpack: error: refusing to replace /dev/null: not a regular file (character "
            "device)\n");
  // A link to a regular file: the file is replaced, the link stays.
  const std::string target = folder.file("target.stl");
  std::ofstream(target) << "old";
  const std::string link = folder.file("link.stl");
  fs::create_symlink(target, link);
  EXPECT_EQ(
      aggpack("export " + test::bad_inputs_dir() + "base_s.h5 -o " + link + " --force").exit_code,
      0);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_GT(fs::file_size(target), 1000U);
  EXPECT_FALSE(has_temporary(folder));
}

TEST(OutputsCli, NamesUpToNameMax) {
  ScratchFolder folder;
  const std::string stl = folder.file(std::string(251, 'n') + ".stl");  // 255 bytes
  const auto particle = aggpack("particle -o " + stl);
  EXPECT_EQ(particle.exit_code, 0) << particle.output;
  EXPECT_TRUE(fs::exists(stl));
  const std::string native = folder.file(std::string(252, 'p') + ".h5");  // 255 bytes
  const auto pack = aggpack(
      "pack --progress none --set container.length=0.6 --set "
      "container.width=0.4 --set container.depth=0.4 -o " +
      native);
  EXPECT_EQ(pack.exit_code, 0) << pack.output;
  EXPECT_TRUE(fs::exists(native));
  EXPECT_FALSE(has_temporary(folder));
}

// Starts `arguments` in a child, waits for a temporary to appear in `folder`, sends `signal`.
// Returns false if the run finished before a temporary was seen (the caller retries).
bool interrupt_when_writing(const ScratchFolder& folder, const std::vector<std::string>& arguments,
                            int signal_number) {
  const pid_t child = ::fork();
  if (child == 0) {
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kBinary.c_str()));
    for (const auto& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    if (::freopen("/dev/null", "w", stdout) == nullptr) std::_Exit(98);
    ::execv(kBinary.c_str(), argv.data());
    std::_Exit(99);
  }
  int status = 0;
  for (;;) {
    if (has_temporary(folder)) {
      ::kill(child, signal_number);
      ::waitpid(child, &status, 0);
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << "status " << status;
      return true;
    }
    if (::waitpid(child, &status, WNOHANG) == child) return false;
  }
}

TEST(OutputsCli, InterruptedExportLeavesNoTemporary) {
  ScratchFolder folder;
  const std::string native = folder.file("paper.h5");  // the paper's 1,050 particles
  ASSERT_EQ(aggpack("pack --progress none -o " + native).exit_code, 0);
  int caught = 0;
  for (const int signal_number : {SIGTERM, SIGINT}) {
    // A per-particle folder (1,050 files) and a 9 MB C3D10 .inp: each is written for a fraction
    // of a second; retried if the run ends before the poll sees its temporary.
    for (int attempt = 0; attempt < 20; ++attempt) {
      const std::string out = folder.file("out" + std::to_string(attempt));
      if (interrupt_when_writing(folder,
                                 {"export", native, "-o", out, "--per-particle", "--format", "stl"},
                                 signal_number)) {
        ++caught;
        EXPECT_FALSE(fs::exists(out));
        break;
      }
      fs::remove_all(out);
    }
    EXPECT_FALSE(has_temporary(folder));
    for (int attempt = 0; attempt < 20; ++attempt) {
      const std::string out = folder.file("out" + std::to_string(attempt) + ".inp");
      if (interrupt_when_writing(folder, {"export", native, "-o", out, "--quadratic"},
                                 signal_number)) {
        ++caught;
        EXPECT_FALSE(fs::exists(out));
        break;
      }
      fs::remove(out);
    }
    EXPECT_FALSE(has_temporary(folder));
  }
  EXPECT_EQ(caught, 4) << "every run finished before its temporary was seen";
}

TEST(OutputsCli, FailedOutputExportLeavesNoNativeFile) {
  ScratchFolder folder;
  // pack_output_proc.toml: refused before packing.
  const std::string native = folder.file("run.h5");
  const auto proc = aggpack("pack " + test::bad_inputs_dir() +
                            "pack_output_proc.toml --progress none -o " + native);
  EXPECT_EQ(proc.exit_code, 3);
  EXPECT_NE(proc.output.find("aggpack: error: output.stl: cannot write /proc/x.stl: cannot create "
                             "a file in "
                             "folder /proc"),
            std::string::npos)
      << proc.output;
  EXPECT_EQ(proc.output.find("placed"), std::string::npos) << "refused before packing";
  EXPECT_FALSE(fs::exists(native));
  // A late failure: the .vtu (40 kB) exceeds a 25 kB file size limit (sh counts 512-byte
  // blocks) that the .h5 (17 kB) fits.
  const std::string config = folder.file("c.toml");
  std::ofstream(config) << "[container]\nlength = 0.6\nwidth = 0.4\ndepth = 0.4\n[output]\nvtu = \""
                        << folder.file("x.vtu") << "\"\n";
  const std::string limited = "trap '' XFSZ; ulimit -f 50; '" + kBinary + "' pack " + config +
                              " --progress none -o " + native;
  const auto late = test::run_command(limited);
  EXPECT_EQ(late.exit_code, 3);
  EXPECT_NE(late.output.find("aggpack: error: cannot write " + folder.file("x.vtu") +
                             ": file too large (file size limit)\n"),
            std::string::npos)
      << late.output;
  EXPECT_FALSE(fs::exists(native)) << "the native file this run created is removed";
  // With --force, the file it replaced is put back.
  std::ofstream(native) << "old";
  EXPECT_EQ(test::run_command(limited + " --force").exit_code, 3);
  EXPECT_EQ(read_text(native), "old");
  EXPECT_FALSE(fs::exists(folder.file("x.vtu")));
  EXPECT_FALSE(has_temporary(folder));
}

// full_disk.sh: a 1 MiB tmpfs, when mounting is permitted (root in CI); the file size limit
// (EFBIG) path is exercised by the test above and the .h5 case below without mounting.
TEST(OutputsCli, DiskFullNamesTheFile) {
  ScratchFolder folder;
  const std::string native = folder.file("x.h5");
  const auto limited = test::run_command(
      "trap '' XFSZ; ulimit -f 16; '" + kBinary +
      "' pack --progress none --set container.length=0.6 --set container.width=0.4 --set "
      "container.depth=0.4 -o " +
      native);
  EXPECT_EQ(limited.exit_code, 3);
  EXPECT_NE(limited.output.find("\naggpack: error: cannot write " + native +
                                ": file too large (file size limit)\n"),
            std::string::npos)
      << limited.output;
  EXPECT_EQ(folder.entries().size(), 0U);

  const std::string disk = folder.file("disk");
  fs::create_directory(disk);
  if (::geteuid() != 0 ||
      test::run_command("mount -t tmpfs -o size=1m tmpfs '" + disk + "'").exit_code != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (not root or not permitted)";
  }
  test::run_command("dd if=/dev/zero of='" + disk + "/filler' bs=1k count=1020 status=none");
  const auto pack = aggpack(
      "pack --set container.length=0.6 --set container.width=0.4 --set container.depth=0.4 "
      "--progress none -o " +
      disk + "/x.h5");
  const auto stl = aggpack("export " + test::bad_inputs_dir() + "base_s.h5 -o " + disk + "/x.stl");
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(disk)) {
    left.push_back(entry.path().filename().string());
  }
  test::run_command("umount '" + disk + "'");
  EXPECT_EQ(pack.exit_code, 3);
  EXPECT_NE(pack.output.find("\naggpack: error: cannot write " + disk + "/x.h5: disk full\n"),
            std::string::npos)
      << pack.output;
  EXPECT_EQ(stl.exit_code, 3);
  EXPECT_EQ(stl.output, "aggpack: error: cannot write " + disk + "/x.stl: disk full\n");
  EXPECT_EQ(left, std::vector<std::string>{"filler"});
}

TEST(OutputsCli, ConfigMessagesAreOneBoundedLine) {
  // out_of_scope_invalid_values.toml: the lattice packer ignores these keys, but their values are
  // still wrong: an error for the run and for --print-config alike.
  ScratchFolder folder;
  const std::string fixture = test::bad_inputs_dir() + "out_of_scope_invalid_values.toml";
  const std::string expected = "aggpack: error: " + fixture +
                               ":4: invalid grading.kind = \"fullerr\" (allowed: uniform | fuller "
                               "| sieve); did you mean 'fuller'?\n";
  const auto run = aggpack("pack " + fixture + " --progress none -o " + folder.file("x.h5"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.output, expected);
  const auto print = aggpack("pack " + fixture + " --print-config");
  EXPECT_EQ(print.exit_code, 2);
  EXPECT_EQ(print.output, expected);
  EXPECT_TRUE(folder.entries().empty());
  // Valid but ignored: still only a warning.
  const auto ignored = aggpack("pack --set packer.target_count=10 --print-config");
  EXPECT_EQ(ignored.exit_code, 0);
  EXPECT_NE(ignored.output.find("packer.target_count is ignored"), std::string::npos);

  const auto newline =
      aggpack("pack --set \"$(printf 'packer.seed=5\\npacker.gapp=1')\" --print-config");
  EXPECT_EQ(newline.exit_code, 2);
  EXPECT_EQ(newline.output,
            "aggpack: error: --set packer.seed=5\\npacker.gapp=1: a --set value must be one line "
            "(it contains a line break)\n");

  const std::string huge(100000, 'k');
  for (const std::string& arguments :
       {"pack --set " + huge + "=1", "pack --set packer.kind=" + huge,
        "pack --set output.stl=x.stl --set output." + huge + "=y"}) {
    const auto result = aggpack(arguments + " --print-config");
    EXPECT_EQ(result.exit_code, 2);
    expect_one_line(result);
    EXPECT_LT(result.output.size(), 600U) << result.output.substr(0, 1000);
    EXPECT_NE(result.output.find("kkk...kkk"), std::string::npos) << result.output;
  }
  // The shape generator's vertex cap names the key the user typed.
  const auto cap = aggpack("pack --set particle.radius=5 --print-config");
  EXPECT_EQ(cap.exit_code, 2);
  EXPECT_EQ(cap.output.rfind("aggpack: error: limit exceeded for particle.edge_length = 0.1", 0),
            0U)
      << cap.output;
}

}  // namespace
}  // namespace aggpack
