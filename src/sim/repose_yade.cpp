// The repose test in YADE (aggpack/sim/repose_yade.h): the script from the caller's writer,
// `yade -n -x` as a subprocess in a temporary folder, its progress lines, the time limit, and
// the poses it wrote read back into the final packing.

#include "aggpack/sim/repose_yade.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/core/clock.h"
#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/core/text.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/sim/settle.h"
#include "repose_detail.h"

namespace aggpack {

namespace {

namespace fs = std::filesystem;
// The program `name` on PATH, or "" when it is not there.
std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path != nullptr ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const std::string candidate = folder + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) {
      return candidate;
    }
  }
  return "";
}

// A flat temporary folder, removed on every exit path and by the signal handler (temp_paths.h).
class ScratchFolder {
 public:
  ScratchFolder() {
    std::error_code error;
    const std::string pattern = temporary_pattern(fs::temp_directory_path(error).string());
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    const CleanupSignalBlock block;
    if (::mkdtemp(buffer.data()) == nullptr) {
      throw IoError("cannot create a temporary folder for YADE: " +
                    std::string(std::strerror(errno)));
    }
    path_ = buffer.data();
    slot_ = register_temporary(path_, /*is_folder=*/true);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
    unregister_temporary(slot_);
  }
  [[nodiscard]] std::string file(const std::string& name) const { return path_ + "/" + name; }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
  int slot_ = -1;
};

// The YADE process; killed (and reaped) unless it was waited for.
class YadeProcess {
 public:
  YadeProcess(const std::string& program, const ScratchFolder& folder) {
    int fds[2];
    if (::pipe(fds) != 0) throw IoError("cannot start yade: " + std::string(std::strerror(errno)));
    const std::string log = folder.file("yade.log");
    // Everything the child needs is made before fork(): between fork and exec a threaded process
    // (seeds run side by side) may only call async-signal-safe functions.
    std::vector<std::string> environment;
    for (char** entry = environ; *entry != nullptr; ++entry) {
      if (std::strncmp(*entry, "OMP_NUM_THREADS=", 16) != 0 &&
          std::strncmp(*entry, "TMPDIR=", 7) != 0) {
        environment.emplace_back(*entry);
      }
    }
    environment.emplace_back("OMP_NUM_THREADS=1");  // one core per run, like Bullet's runs
    // YADE makes a yade-XXXXXX folder in $TMPDIR at start and leaves it behind (always when it
    // is killed at the time limit, often when it ends normally): put it in the scratch folder,
    // which is removed with everything in it.
    environment.emplace_back("TMPDIR=" + folder.path());
    std::vector<char*> envp;
    for (auto& entry : environment) envp.push_back(entry.data());
    envp.push_back(nullptr);
    std::string arg0 = program;
    std::string arg1 = "-n";
    std::string arg2 = "-x";
    std::string arg3 = "repose.py";
    char* const argv[] = {arg0.data(), arg1.data(), arg2.data(), arg3.data(), nullptr};
    pid_ = ::fork();
    if (pid_ < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      throw IoError("cannot start yade: " + std::string(std::strerror(errno)));
    }
    if (pid_ == 0) {
      // Child: dies with aggpack (a SIGTERM to aggpack alone must not leave YADE running).
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      ::close(fds[0]);
      ::dup2(fds[1], STDOUT_FILENO);
      const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, STDERR_FILENO);
      if (::chdir(folder.path().c_str()) != 0) ::_exit(126);
      ::execve(program.c_str(), argv, envp.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    out_ = fds[0];
  }
  YadeProcess(const YadeProcess&) = delete;
  YadeProcess& operator=(const YadeProcess&) = delete;
  ~YadeProcess() {
    if (out_ >= 0) ::close(out_);
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  [[nodiscard]] int output() const { return out_; }
  /// Waits for the end; returns the exit status (waitpid's) and sets the CPU seconds.
  int wait(double& cpu_seconds) {
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return status;
  }

 private:
  pid_t pid_ = -1;
  int out_ = -1;
};

// The last line of YADE's log that says something (its warnings about degenerate polyhedra
// intersections are left out).
std::string last_log_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (line.find("WARNING") != std::string::npos) continue;
    last = line;
  }
  return clipped(last, 300);
}

bool parse_progress(const std::string& line, YadeProgress& p) {
  unsigned long iterations = 0;
  const int read =
      std::sscanf(line.c_str(),
                  "aggpack-yade-progress stage %d time %lf total %lf energy %lf "
                  "threshold %lf iterations %lu",
                  &p.stage, &p.time, &p.total_time, &p.energy, &p.threshold, &iterations);
  p.iterations = iterations;
  return read == 6;
}

struct Pose7 {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();
};

// The poses file (aggpack/io/yade_repose.h): "initial|settled|final i x y z qw qx qy qz" lines,
// then the summary lines.
struct YadeOutput {
  std::map<std::string, std::vector<Pose7>> poses;
  std::map<std::string, std::vector<double>> summary;
};

YadeOutput read_output(const std::string& path, std::size_t count) {
  std::ifstream in(path);
  if (!in) throw IoError("yade wrote no result (" + path + ")");
  YadeOutput output;
  std::string line;
  bool is_complete = false;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "end") {
      is_complete = true;
      break;
    }
    if (tag == "initial" || tag == "settled" || tag == "final") {
      std::size_t index = 0;
      Pose7 pose;
      double w = 0.0;
      double x = 0.0;
      double y = 0.0;
      double z = 0.0;
      fields >> index >> pose.position.x() >> pose.position.y() >> pose.position.z() >> w >> x >>
          y >> z;
      if (!fields || index >= count) throw IoError("unreadable yade result line: " + clipped(line));
      pose.rotation = Quat(w, x, y, z).normalized();
      auto& list = output.poses[tag];
      if (list.size() != index) throw IoError("yade result out of order: " + clipped(line));
      list.push_back(pose);
      continue;
    }
    std::vector<double> values;
    double value = 0.0;
    while (fields >> value) values.push_back(value);
    output.summary[tag] = values;
  }
  if (!is_complete) throw IoError("yade's result is incomplete (" + path + ")");
  for (const char* tag : {"initial", "settled", "final"}) {
    if (output.poses[tag].size() != count) {
      throw IoError(std::string("yade's result lacks ") + tag + " poses");
    }
  }
  const std::map<std::string, std::size_t> sizes = {
      {"stage1", 2}, {"stage2", 4}, {"confirm", 4}, {"run", 2}};
  for (const auto& [tag, size] : sizes) {
    if (output.summary[tag].size() != size) throw IoError("yade's result lacks " + tag);
  }
  return output;
}

// `initial` moved as YADE moved each body: YADE's body frame is its own (principal axes), so the
// change from its initial pose to `now` is applied to aggpack's pose.
Packing moved(const Packing& initial, const std::vector<Pose7>& start,
              const std::vector<Pose7>& now) {
  Packing packing = initial;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Quat turn = (now[i].rotation * start[i].rotation.conjugate()).normalized();
    Pose& pose = packing.particles[i].pose;
    pose.position = now[i].position + turn * (pose.position - start[i].position);
    pose.rotation = (turn * pose.rotation).normalized();
  }
  return packing;
}

std::vector<double> equivalent_sizes(const Packing& packing) {
  std::vector<double> volumes(packing.shapes.size());
  for (std::size_t k = 0; k < packing.shapes.size(); ++k) {
    volumes[k] = mass_properties(packing.shapes[k]).volume;
  }
  std::vector<double> sizes;
  sizes.reserve(packing.particles.size());
  for (const Particle& particle : packing.particles) {
    sizes.push_back(
        std::cbrt(6.0 * volumes[particle.shape] * std::pow(particle.scale, 3) / std::numbers::pi));
  }
  std::sort(sizes.begin(), sizes.end());
  return sizes;
}

}  // namespace

double yade_young(const ReposeOptions& options, const Packing& initial) {
  if (options.yade.young > 0.0) return options.yade.young;
  const std::vector<double> sizes = equivalent_sizes(initial);
  const double median = sizes.empty() ? 2.0 * options.radius : sizes[sizes.size() / 2];
  return options.physics.density * options.physics.gravity.norm() * options.fill_height /
         (0.005 * median);
}

ReposeResult run_repose_yade(const ReposeOptions& options, PackResult fill,
                             const YadeScriptWriter& write_script,
                             const YadeProgressCallback& progress) {
  validate(options);
  if (!write_script) {
    throw InvalidInput("repose.engine", "yade",
                       "bullet, or yade from a front end that writes YADE's script");
  }
  const std::string program = find_on_path("yade");
  if (program.empty()) {
    throw InvalidInput("repose.engine", "yade",
                       "bullet, or yade with YADE installed: no program yade on PATH (Debian "
                       "package yade: apt-get install yade)");
  }
  ReposeResult result;
  const auto start = Clock::now();
  const Packing packing = detail::prepare_repose(options, std::move(fill), result);
  ReposeOptions resolved = options;
  resolved.yade.young = yade_young(options, packing);
  result.yade_young = resolved.yade.young;
  result.smallest_size = equivalent_sizes(packing).front();

  ScratchFolder folder;
  {
    std::ofstream script(folder.file("repose.py"));
    write_script(packing, resolved, script);
    script.flush();
    if (!script) throw IoError("cannot write the YADE script in " + folder.path());
  }
  YadeProcess yade(program, folder);
  std::string pending;
  char buffer[4096];
  const double limit = options.yade.time_limit;
  YadeProgress last;
  while (true) {
    if (limit > 0.0 && seconds_since(start) > limit) {
      throw LimitExceeded("yade.time_limit", format_value(limit) + " s",
                          "a YADE run that ends within it (stopped at " +
                              format_value(last.total_time) + " s simulated, stage " +
                              std::to_string(last.stage) + ")");
    }
    pollfd fd{.fd = yade.output(), .events = POLLIN, .revents = 0};
    const int ready = ::poll(&fd, 1, 200);
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t got = ::read(yade.output(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;  // YADE closed its output: it ended
    pending.append(buffer, static_cast<std::size_t>(got));
    for (std::size_t end = pending.find('\n'); end != std::string::npos; end = pending.find('\n')) {
      const std::string line = pending.substr(0, end);
      pending.erase(0, end + 1);
      YadeProgress p;
      if (parse_progress(line, p)) {
        p.wall_seconds = seconds_since(start);
        last = p;
        if (progress) progress(p);
      }
    }
  }
  const int status = yade.wait(result.engine_cpu_seconds);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string why = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status));
    throw IoError("yade failed (" + why + "): " + last_log_line(folder.file("yade.log")));
  }
  const YadeOutput output = read_output(folder.file("poses.txt"), packing.particles.size());
  const auto& initial = output.poses.at("initial");
  result.settled = moved(packing, initial, output.poses.at("settled"));
  result.final = moved(packing, initial, output.poses.at("final"));
  const auto& stage1 = output.summary.at("stage1");
  const auto& stage2 = output.summary.at("stage2");
  const auto& confirm = output.summary.at("confirm");
  const auto& run = output.summary.at("run");
  result.is_stage1_at_rest = stage1[0] != 0.0;
  result.stage1_time = stage1[1];
  result.stage1_height = packing_height(result.settled);
  result.is_stage2_at_rest = stage2[0] != 0.0;
  result.stage2_time = stage2[1];
  result.baffle_travel = stage2[2];
  result.is_baffle_removed = stage2[3] != 0.0;
  result.confirmation.window = confirm[0];
  result.confirmation.restarts = static_cast<std::size_t>(confirm[1]);
  result.confirmation.speed_restarts = result.confirmation.restarts;
  result.confirmation.max_speed = confirm[2];
  result.confirmation.speed_limit = confirm[3];
  result.time_step = run[0];
  result.yade_iterations = static_cast<std::size_t>(run[1]);
  result.stage2_seconds = seconds_since(start);
  detail::finish_repose(options, result);
  return result;
}

ReposeResult run_repose_engine(const ReposeOptions& options, PackResult fill,
                               const YadeScriptWriter& write_script) {
  if (options.engine == ReposeEngine::kYade) {
    return run_repose_yade(options, std::move(fill), write_script);
  }
  return run_repose(options, std::move(fill));
}

}  // namespace aggpack
