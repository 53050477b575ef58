// Running another program (aggpack/core/child_process.h).

#include "aggpack/core/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/core/text.h"

extern char** environ;

namespace aggpack {

namespace fs = std::filesystem;

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path != nullptr ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const std::string candidate = folder + "/" + name;
    std::error_code error;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate, error)) {
      return candidate;
    }
  }
  return "";
}

namespace {

// mkdtemp in `parent`; "" and errno when it fails.
std::string make_folder(const std::string& parent) {
  const std::string pattern = temporary_pattern(parent);
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (::mkdtemp(buffer.data()) == nullptr) return "";
  return buffer.data();
}

}  // namespace

TemporaryFolder::TemporaryFolder(const std::string& purpose) {
  std::error_code error;
  const CleanupSignalBlock block;
  path_ = make_folder(fs::temp_directory_path(error).string());
  if (path_.empty()) {
    throw IoError("cannot create a temporary folder for " + purpose + ": " +
                  std::string(std::strerror(errno)));
  }
  slot_ = register_temporary(path_, /*is_folder=*/true);
}

TemporaryFolder::TemporaryFolder(const std::string& parent, const std::string& beside) {
  const CleanupSignalBlock block;
  path_ = make_folder(parent);
  if (path_.empty()) {
    throw IoError(Wording{Sentence::kTemporaryFolder, {beside, std::strerror(errno)}});
  }
  slot_ = register_temporary(path_, /*is_folder=*/true);
}

TemporaryFolder::~TemporaryFolder() {
  if (!path_.empty()) {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  unregister_temporary(slot_);
}

void TemporaryFolder::forget_on_signal() {
  unregister_temporary(slot_);
  slot_ = -1;
}

void TemporaryFolder::release() {
  path_.clear();
  forget_on_signal();
}

namespace {

// The parent's environment with the command's entries replacing those of the same name.
std::vector<std::string> child_environment(const std::vector<std::string>& overrides) {
  std::vector<std::string> environment;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string text = *entry;
    const std::string name = text.substr(0, text.find('=') + 1);
    bool is_replaced = false;
    for (const std::string& entry_override : overrides) {
      is_replaced = is_replaced || entry_override.starts_with(name);
    }
    if (!is_replaced) environment.push_back(text);
  }
  environment.insert(environment.end(), overrides.begin(), overrides.end());
  return environment;
}

}  // namespace

ChildProcess::ChildProcess(const ChildCommand& command) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    throw IoError("cannot start " + command.program + ": " + std::string(std::strerror(errno)));
  }
  // Everything the child needs is made before fork(): between fork and exec a threaded process
  // may only call async-signal-safe functions.
  std::vector<std::string> environment = child_environment(command.environment);
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
  std::vector<std::string> arguments = {command.program};
  arguments.insert(arguments.end(), command.arguments.begin(), command.arguments.end());
  std::vector<char*> argv;
  for (auto& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  const std::string& error_file = command.error_file;
  const std::string& folder = command.folder;
  pid_ = ::fork();
  if (pid_ < 0) {
    const int reason = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw IoError("cannot start " + command.program + ": " + std::string(std::strerror(reason)));
  }
  if (pid_ == 0) {
    // Child: dies with aggpack (a SIGTERM to aggpack alone must not leave it running).
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    ::dup2(fds[1], STDOUT_FILENO);  // dup2 clears close-on-exec on the copy
    const int err = ::open(error_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (err >= 0) ::dup2(err, STDERR_FILENO);
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  out_ = fds[0];
}

ChildProcess::~ChildProcess() {
  if (out_ >= 0) ::close(out_);
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
}

bool ChildProcess::read_output(std::string& text, int timeout_ms) {
  pollfd fd{.fd = out_, .events = POLLIN, .revents = 0};
  const int ready = ::poll(&fd, 1, timeout_ms);
  if (ready <= 0) return true;  // nothing yet, or a signal came
  char buffer[4096];
  const ssize_t got = ::read(out_, buffer, sizeof buffer);
  if (got < 0) return errno == EINTR || errno == EAGAIN;
  if (got == 0) return false;
  text.append(buffer, static_cast<std::size_t>(got));
  return true;
}

int ChildProcess::wait(double& cpu_seconds) {
  int status = 0;
  struct rusage usage {};
  while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return status;
}

std::string describe_exit(int status) {
  return WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                           : "signal " + std::to_string(WTERMSIG(status));
}

std::string last_line_of(const std::string& path, const std::string& skip) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (!skip.empty() && line.find(skip) != std::string::npos) continue;
    last = line;
  }
  return clipped(last, 300);
}

}  // namespace aggpack
