// Output files (issue 12): only regular files are replaced (devices, FIFOs, sockets, folders and
// links to them are refused), names up to NAME_MAX work, temporaries are removed on SIGTERM and
// SIGINT, a failed write names the file and the reason, and OutputTransaction is all or nothing.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/core/text.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

class Scratch {
 public:
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "aggpack_atomic_XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  ~Scratch() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }
  [[nodiscard]] bool has_temporary() const {
    for (const auto& name : entries()) {
      if (name.find(".tmp.") != std::string::npos) return true;
    }
    return false;
  }

 private:
  fs::path path_;
};

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void write_text(const std::string& path, const std::string& text,
                Overwrite overwrite = Overwrite::kAllow) {
  AtomicFile file(path, overwrite);
  file.stream() << text;
  file.commit();
}

std::string error_of(const std::string& path, Overwrite overwrite = Overwrite::kAllow) {
  try {
    write_text(path, "new", overwrite);
  } catch (const IoError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(AtomicFile, RefusesWhatIsNotARegularFile) {
  Scratch scratch;
  const std::string fifo = scratch.file("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(error_of(fifo), "refusing to replace " + fifo + ": not a regular file (FIFO)");
  EXPECT_EQ(error_of(fifo, Overwrite::kForbid),
            "refusing to replace " + fifo + ": not a regular file (FIFO)");
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);

  const std::string folder = scratch.file("folder");
  fs::create_directory(folder);
  EXPECT_EQ(error_of(folder), "refusing to replace " + folder + ": not a regular file (directory)");
  EXPECT_TRUE(fs::is_directory(folder));

  const std::string socket_path = scratch.file("sock");
  const int socket_fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(socket_fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.size(), sizeof address.sun_path);
  std::strcpy(address.sun_path, socket_path.c_str());
  ASSERT_EQ(::bind(socket_fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  EXPECT_EQ(error_of(socket_path),
            "refusing to replace " + socket_path + ": not a regular file (socket)");
  EXPECT_EQ(fs::status(socket_path).type(), fs::file_type::socket);
  ::close(socket_fd);

  // check_writable (the up-front check of every command) says the same.
  EXPECT_THROW(check_writable(fifo, Overwrite::kAllow), IoError);
  EXPECT_FALSE(scratch.has_temporary());
}

TEST(AtomicFile, FollowsASymbolicLinkOnlyToARegularFile) {
  Scratch scratch;
  const std::string target = scratch.file("target.txt");
  const std::string link = scratch.file("link.txt");
  write_text(target, "old");
  fs::create_symlink(target, link);
  EXPECT_EQ(error_of(link, Overwrite::kForbid),
            "cannot write " + link + ": file exists (use --force to replace it)");
  write_text(link, "new");
  EXPECT_TRUE(fs::is_symlink(link)) << "the link stays";
  EXPECT_EQ(read_text(target), "new") << "the file it points to is replaced";

  const std::string to_folder = scratch.file("to_folder");
  fs::create_directory(scratch.file("folder"));
  fs::create_symlink(scratch.file("folder"), to_folder);
  EXPECT_EQ(error_of(to_folder), "refusing to replace " + to_folder +
                                     ": not a regular file (symbolic link to a directory)");
  const std::string dangling = scratch.file("dangling");
  fs::create_symlink(scratch.file("missing"), dangling);
  EXPECT_EQ(error_of(dangling),
            "refusing to replace " + dangling + ": symbolic link to a missing file");
  EXPECT_FALSE(fs::exists(scratch.file("missing")));
  EXPECT_FALSE(scratch.has_temporary());
}

TEST(AtomicFile, WritesNamesUpToNameMax) {
  Scratch scratch;
  const std::string name = std::string(251, 'n') + ".stl";  // 255 bytes, Linux's NAME_MAX
  write_text(scratch.file(name), "content");
  EXPECT_EQ(read_text(scratch.file(name)), "content");
  write_text(scratch.file(name), "again");  // replacing works too
  EXPECT_EQ(read_text(scratch.file(name)), "again");
  const std::string too_long = std::string(256, 'n');
  // The message shortens the long name in its middle ("nnn...nnn") and says its length.
  const std::string message = error_of(scratch.file(too_long));
  EXPECT_TRUE(message.starts_with("cannot write " + scratch.file("nnnnnnnnnn"))) << message;
  EXPECT_NE(message.find("n...n"), std::string::npos) << message;
  EXPECT_TRUE(
      message.ends_with("nnnnnnnnnn: file name too long (a name of 256 bytes, at most 255)"))
      << message;
  EXPECT_LT(message.size(), 200U) << message;
  EXPECT_EQ(scratch.entries().size(), 1U);
}

// A child writes into an AtomicFile (and a registered temporary folder), reports the temporary's
// path through a pipe and waits; the parent kills it with `signal_number`.
void expect_cleanup_on(int signal_number) {
  Scratch scratch;
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(ready[0]);
    AtomicFile file(scratch.file("out.bin"));
    file.stream() << std::string(1 << 20, 'x');
    file.stream().flush();
    const std::string folder = scratch.file(".aggpack.tmp.folder");
    fs::create_directory(folder);
    std::ofstream(folder + "/P000001.stl") << "solid";
    register_temporary(folder, /*is_folder=*/true);
    const std::string message = file.temporary_path() + "\n";
    if (::write(ready[1], message.data(), message.size()) < 0) std::_Exit(10);
    for (;;) ::pause();
  }
  ::close(ready[1]);
  char buffer[4096] = {};
  const ssize_t got = ::read(ready[0], buffer, sizeof buffer - 1);
  ::close(ready[0]);
  ASSERT_GT(got, 0);
  const std::string temporary(buffer, static_cast<std::size_t>(got) - 1);
  EXPECT_TRUE(fs::exists(temporary));
  EXPECT_NE(temporary.find("/.aggpack.tmp."), std::string::npos) << temporary;
  EXPECT_TRUE(scratch.has_temporary());
  ASSERT_EQ(::kill(child, signal_number), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "killed by the signal, not exited";
  EXPECT_EQ(WTERMSIG(status), signal_number);
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_TRUE(scratch.entries().empty()) << scratch.entries().front();
}

TEST(TemporaryPaths, RemovedOnSigterm) { expect_cleanup_on(SIGTERM); }

TEST(TemporaryPaths, RemovedOnSigint) { expect_cleanup_on(SIGINT); }

// A failed write names the file and the reason. File size limit (EFBIG, SIGXFSZ ignored) in a
// child process, so that the limit does not touch the test runner.
TEST(AtomicFile, FailedWriteNamesTheFileAndTheReason) {
  Scratch scratch;
  const std::string path = scratch.file("big.bin");
  int pipe_ends[2];
  ASSERT_EQ(::pipe(pipe_ends), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_ends[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{.rlim_cur = 64 * 1024, .rlim_max = 64 * 1024};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string message = "(no error)";
    try {
      AtomicFile file(path);
      file.stream() << std::string(1 << 20, 'x');
      file.commit();
    } catch (const IoError& error) {
      message = error.what();
    }
    if (::write(pipe_ends[1], message.data(), message.size()) < 0) std::_Exit(10);
    std::_Exit(0);
  }
  ::close(pipe_ends[1]);
  std::string message;
  char buffer[1024];
  for (ssize_t got = 0; (got = ::read(pipe_ends[0], buffer, sizeof buffer)) > 0;) {
    message.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(pipe_ends[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_EQ(message, "cannot write " + path + ": file too large (file size limit)");
  EXPECT_TRUE(scratch.entries().empty());
  EXPECT_EQ(english(write_failure_wording("x.stl", ENOSPC)), "cannot write x.stl: disk full");
  EXPECT_EQ(english(write_failure_wording("x.stl", EDQUOT)),
            "cannot write x.stl: disk quota exceeded");
}

TEST(OutputTransaction, RollsBackCreatedAndReplacedFiles) {
  Scratch scratch;
  const std::string created = scratch.file("created.h5");
  const std::string replaced = scratch.file("replaced.h5");
  write_text(replaced, "old");
  {
    OutputTransaction outputs;
    outputs.add(created);
    outputs.add(replaced);
    write_text(created, "new");
    write_text(replaced, "new");
    EXPECT_EQ(read_text(replaced), "new");
  }  // no commit: a later output failed
  EXPECT_FALSE(fs::exists(created));
  EXPECT_EQ(read_text(replaced), "old");
  EXPECT_EQ(scratch.entries().size(), 1U) << "no backup left";
  {
    OutputTransaction outputs;
    outputs.add(created);
    outputs.add(replaced);
    write_text(created, "new");
    write_text(replaced, "new");
    outputs.commit();
  }
  EXPECT_EQ(read_text(created), "new");
  EXPECT_EQ(read_text(replaced), "new");
  EXPECT_EQ(scratch.entries().size(), 2U) << "no backup left";
}

TEST(Text, ClippedKeepsMessagesOnOneBoundedLine) {
  EXPECT_EQ(clipped("a\nb\r\tc\x01"), "a\\nb\\r\\tc\\x01");
  const std::string huge(100000, 'k');
  const std::string cut = clipped(huge);
  EXPECT_LE(cut.size(), 210U);
  EXPECT_NE(cut.find("..."), std::string::npos);
  EXPECT_EQ(clipped("short"), "short");
  // UTF-8 is cut between characters, never inside one.
  std::string accents;
  for (int i = 0; i < 300; ++i) accents += "\xc3\xa9";  // é
  const std::string cut_accents = shortened(accents, 101);
  EXPECT_EQ(cut_accents.size() % 2, 1U) << "whole 2-byte characters plus the 3 dots";
}

}  // namespace
}  // namespace aggpack
