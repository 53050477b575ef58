// The repose test in YADE (aggpack/sim/repose_yade.h): the script from the caller's writer,
// `yade -n -x` as a subprocess in a temporary folder, its progress lines, the time limit, and
// the poses it wrote read back into the final packing.

#include "aggpack/sim/repose_yade.h"

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/core/child_process.h"
#include "aggpack/core/clock.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/sim/settle.h"
#include "repose_detail.h"

namespace aggpack {

namespace {

// The YADE process: `yade -n -x repose.py` in the scratch folder, one core per run (like
// Bullet's runs), its log as standard error. YADE makes a yade-XXXXXX folder in $TMPDIR at start
// and leaves it behind (always when it is killed at the time limit, often when it ends
// normally): TMPDIR is the scratch folder, which is removed with everything in it.
ChildCommand yade_command(const std::string& program, const TemporaryFolder& folder) {
  return {.program = program,
          .arguments = {"-n", "-x", "repose.py"},
          .folder = folder.path(),
          .environment = {"OMP_NUM_THREADS=1", "TMPDIR=" + folder.path()},
          .error_file = folder.file("yade.log")};
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

  const TemporaryFolder folder("YADE");
  {
    std::ofstream script(folder.file("repose.py"));
    write_script(packing, resolved, script);
    script.flush();
    if (!script) throw IoError("cannot write the YADE script in " + folder.path());
  }
  ChildProcess yade(yade_command(program, folder));
  std::string pending;
  const double limit = options.yade.time_limit;
  YadeProgress last;
  while (true) {
    if (limit > 0.0 && seconds_since(start) > limit) {
      throw LimitExceeded("yade.time_limit", format_value(limit) + " s",
                          "a YADE run that ends within it (stopped at " +
                              format_value(last.total_time) + " s simulated, stage " +
                              std::to_string(last.stage) + ")");
    }
    if (!yade.read_output(pending, 200)) break;  // YADE closed its output: it ended
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
    // YADE's warnings about degenerate polyhedra intersections are left out.
    throw IoError("yade failed (" + describe_exit(status) +
                  "): " + last_line_of(folder.file("yade.log"), "WARNING"));
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
