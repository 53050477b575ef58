#pragma once
// Running another program for the user (YADE for the repose test, CalculiX for an RVE's
// stiffness): finding it on PATH, a flat temporary folder for its files that is removed on every
// exit path and by the cleanup signal handler (core/temp_paths.h), and the child process itself,
// which dies with aggpack and is killed and reaped unless it was waited for.

#include <sys/types.h>

#include <string>
#include <vector>

namespace aggpack {

/// The program `name` on PATH (an executable regular file), or "" when it is not there.
std::string find_on_path(const std::string& name);

/// A flat temporary folder, removed with everything directly in it by the destructor (unless
/// released) and by SIGINT/SIGTERM/SIGHUP (unless forgotten on signals).
class TemporaryFolder {
 public:
  /// In the system's temporary directory. \throw IoError "cannot create a temporary folder for
  /// <purpose>: <reason>".
  explicit TemporaryFolder(const std::string& purpose);
  /// In `parent`, e.g. to be renamed onto `beside` there. \throw IoError "cannot create a
  /// temporary folder beside <beside>: <reason>" (its sentence, error_words.h).
  TemporaryFolder(const std::string& parent, const std::string& beside);
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  ~TemporaryFolder();
  [[nodiscard]] std::string file(const std::string& name) const { return path_ + "/" + name; }
  [[nodiscard]] const std::string& path() const { return path_; }
  /// A signal no longer removes it (it holds something of the user's); the destructor still does.
  void forget_on_signal();
  /// Neither the destructor nor a signal removes it (it was renamed into place).
  void release();

 private:
  std::string path_;
  int slot_ = -1;
};

/// What a child runs and where.
struct ChildCommand {
  std::string program;                 ///< a path (find_on_path's answer)
  std::vector<std::string> arguments;  ///< after argv[0], which is `program`
  std::string folder;                  ///< its working folder
  /// NAME=VALUE entries that replace the parent's NAME (or are added).
  std::vector<std::string> environment;
  std::string error_file;  ///< its standard error goes here (created or truncated)
};

/// A running child whose standard output is a pipe to aggpack (read_output()). The child gets
/// SIGKILL when aggpack ends (PR_SET_PDEATHSIG), and the destructor kills and reaps it unless
/// wait() did. \throw IoError when it cannot start ("cannot start <program>: <reason>"); a program
/// that fails to exec exits with status 127, a folder it cannot enter with 126.
class ChildProcess {
 public:
  explicit ChildProcess(const ChildCommand& command);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();
  /// Waits up to `timeout_ms` for its standard output and appends what came to `text`. False
  /// once it closed its output (it ended or is about to); true otherwise, also when nothing came.
  bool read_output(std::string& text, int timeout_ms);
  /// Waits for its end; returns waitpid's status and sets its user + system CPU seconds.
  int wait(double& cpu_seconds);

 private:
  pid_t pid_ = -1;
  int out_ = -1;
};

/// "exit status N" or "signal N" of a waitpid status, for messages.
std::string describe_exit(int status);

/// The last line of a text file that says something, skipping lines containing `skip` (when not
/// empty), at most 300 characters; "" when there is none.
std::string last_line_of(const std::string& path, const std::string& skip = "");

}  // namespace aggpack
