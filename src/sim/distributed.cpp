// Ensembles and sweeps over several processes: run shares, run records and reading them back.

#include "aggpack/sim/distributed.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"

namespace aggpack {

namespace {

std::size_t parse_count(const std::string& flag, const std::string& text, std::size_t lo,
                        std::size_t hi, const std::string& allowed) {
  std::size_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  if (text.empty() || error != std::errc() || ptr != end || value < lo || value > hi) {
    throw InvalidInput(flag, text.empty() ? "\"\"" : text, allowed);
  }
  return value;
}

const char* kind_name(RunKind kind) { return kind == RunKind::kEnsemble ? "ensemble" : "sweep"; }

}  // namespace

RunShare parse_run_share(const std::optional<std::string>& worker,
                         const std::optional<std::string>& of) {
  if (!worker && !of) return {};
  if (!of) throw InvalidInput("--case", *worker, "only with --of N (the number of workers)");
  if (!worker) throw InvalidInput("--of", *of, "only with --case K (this worker, 1 to N)");
  RunShare share;
  share.of = parse_count("--of", *of, 1, kMaxWorkers,
                         "a whole number of workers in [1, " + std::to_string(kMaxWorkers) + "]");
  share.worker = parse_count("--case", *worker, 1, share.of,
                             "a whole number in [1, " + std::to_string(share.of) +
                                 "] (1-based: worker K of --of " + std::to_string(share.of) + ")");
  return share;
}

std::string config_hash(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ULL;
  const auto add = [&](char c) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ULL;
  };
  // Comments (the keys' documentation) are not part of the configuration: skip from a '#'
  // outside a string to the end of the line, and the blanks before it.
  bool is_quoted = false;
  bool is_comment = false;
  std::string blanks;
  for (const char c : text) {
    if (c == '\n') {
      is_comment = false;
      is_quoted = false;
      blanks.clear();
      add(c);
      continue;
    }
    if (is_comment) continue;
    if (c == '#' && !is_quoted) {
      is_comment = true;
      continue;
    }
    if (c == ' ' && !is_quoted) {
      blanks += c;
      continue;
    }
    for (const char b : blanks) add(b);
    blanks.clear();
    if (c == '"') is_quoted = !is_quoted;
    add(c);
  }
  return fmt::format("{:016x}", hash);
}

std::string run_record_name(const RunRecord& record) {
  if (record.kind == RunKind::kEnsemble) return fmt::format("seed-{}.json", record.ensemble.seed);
  const SweepCase& c = record.sweep;
  return fmt::format("alpha{:.2f}_mu{:.2f}", c.alpha, c.friction) +
         (c.seed_count > 1 ? fmt::format("_seed{}", c.seed) : std::string()) + ".json";
}

void write_run_record(const std::string& path, const RunRecord& record) {
  nlohmann::ordered_json json;
  json["aggpack_run_record"] = 1;
  json["kind"] = kind_name(record.kind);
  json["config_hash"] = record.hash;
  json["run_index"] = record.run_index;
  json["run_count"] = record.run_count;
  json["image_width"] = record.image_width;
  if (record.kind == RunKind::kEnsemble) {
    const EnsembleSeed& s = record.ensemble;
    json["result"] = {{"seed", s.seed},           {"valid", s.is_valid},
                      {"error", s.error},         {"angle_degrees", s.angle_degrees},
                      {"r_squared", s.r_squared}, {"particles", s.particle_count},
                      {"at_rest", s.is_at_rest}};
  } else {
    const SweepCase& c = record.sweep;
    json["result"] = {{"case_index", c.index},
                      {"alpha", c.alpha},
                      {"friction", c.friction},
                      {"seed", c.seed},
                      {"seed_count", c.seed_count},
                      {"valid", c.is_valid},
                      {"angle_degrees", c.angle_degrees},
                      {"r_squared", c.r_squared},
                      {"fit_bins", c.fit_bins},
                      {"at_rest", c.is_at_rest},
                      {"particles", c.particle_count},
                      {"mean_measured_alpha", c.mean_measured_alpha},
                      {"simulated_time_s", c.simulated_time}};
  }
  json["config"] = record.config;
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  file.stream() << json.dump(2) << '\n';
  file.commit();
}

RunRecord read_run_record(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  RunRecord record;
  try {
    const auto json = nlohmann::json::parse(text.str());
    if (json.value("aggpack_run_record", 0) != 1) {
      throw FormatError(path + " is not an aggpack run record (no \"aggpack_run_record\": 1)");
    }
    const std::string kind = json.at("kind").get<std::string>();
    if (kind != "ensemble" && kind != "sweep") {
      throw FormatError(path + ": kind \"" + kind + "\" is not ensemble or sweep");
    }
    record.kind = kind == "ensemble" ? RunKind::kEnsemble : RunKind::kSweep;
    record.config = json.at("config").get<std::string>();
    record.hash = json.at("config_hash").get<std::string>();
    record.run_index = json.at("run_index").get<std::size_t>();
    record.run_count = json.at("run_count").get<std::size_t>();
    record.image_width = json.value("image_width", 0);
    const auto& r = json.at("result");
    if (record.kind == RunKind::kEnsemble) {
      EnsembleSeed& s = record.ensemble;
      s.seed = r.at("seed").get<std::uint64_t>();
      s.is_valid = r.at("valid").get<bool>();
      s.error = r.at("error").get<std::string>();
      s.angle_degrees = r.at("angle_degrees").get<double>();
      s.r_squared = r.at("r_squared").get<double>();
      s.particle_count = r.at("particles").get<std::size_t>();
      s.is_at_rest = r.at("at_rest").get<bool>();
    } else {
      SweepCase& c = record.sweep;
      c.index = r.at("case_index").get<std::size_t>();
      c.alpha = r.at("alpha").get<double>();
      c.friction = r.at("friction").get<double>();
      c.seed = r.at("seed").get<std::uint64_t>();
      c.seed_count = r.at("seed_count").get<std::size_t>();
      c.is_valid = r.at("valid").get<bool>();
      c.angle_degrees = r.at("angle_degrees").get<double>();
      c.r_squared = r.at("r_squared").get<double>();
      c.fit_bins = r.at("fit_bins").get<std::size_t>();
      c.is_at_rest = r.at("at_rest").get<bool>();
      c.particle_count = r.at("particles").get<std::size_t>();
      c.mean_measured_alpha = r.at("mean_measured_alpha").get<double>();
      c.simulated_time = r.at("simulated_time_s").get<double>();
      c.seeds_used = c.is_valid ? 1 : 0;
    }
  } catch (const nlohmann::json::exception& error) {
    throw FormatError(path + " is not an aggpack run record: " + error.what());
  }
  if (record.hash != config_hash(record.config)) {
    throw FormatError(path + ": config_hash " + record.hash +
                      " does not match its configuration (edited?)");
  }
  if (record.run_index >= record.run_count) {
    throw FormatError(path + ": run_index " + std::to_string(record.run_index) +
                      " outside run_count " + std::to_string(record.run_count));
  }
  return record;
}

std::string describe_run(RunKind kind, const SweepOptions& plan, std::size_t run_index) {
  if (kind == RunKind::kEnsemble) {
    return run_index < plan.seeds.size() ? fmt::format("seed {}", plan.seeds[run_index])
                                         : fmt::format("run {}", run_index + 1);
  }
  const std::size_t seed_count = std::max<std::size_t>(1, plan.seeds.size());
  const std::size_t case_index = run_index / seed_count;
  const std::size_t frictions = plan.frictions.size();
  if (frictions == 0 || case_index >= plan.alphas.size() * frictions) {
    return fmt::format("run {}", run_index + 1);
  }
  std::string text = fmt::format("alpha {} mu_s {}", plan.alphas[case_index / frictions],
                                 plan.frictions[case_index % frictions]);
  if (!plan.seeds.empty()) text += fmt::format(" seed {}", plan.seeds[run_index % seed_count]);
  return text;
}

const RunRecord& RunFolder::any() const {
  for (const auto& run : runs) {
    if (run) return *run;
  }
  throw InvalidInput("run records", "none", "at least one");
}

RunFolder read_run_folder(const std::string& folder) {
  namespace fs = std::filesystem;
  const fs::path runs_folder = fs::path(folder) / "runs";
  std::error_code error;
  if (!fs::is_directory(runs_folder, error)) {
    throw InvalidInput("merge folder", folder,
                       "a folder with runs/ (written by repose --seeds or sweep, e.g. with "
                       "--case K --of N)");
  }
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(runs_folder)) {
    const std::string name = entry.path().filename().string();
    // Temporary files of unfinished writes start with '.'.
    if (name.empty() || name.front() == '.' || entry.path().extension() != ".json") continue;
    if (entry.is_regular_file()) paths.push_back(entry.path());
  }
  std::sort(paths.begin(), paths.end());
  if (paths.empty()) {
    throw InvalidInput("merge folder", folder, "run records in runs/*.json (none found)");
  }
  RunFolder result;
  std::vector<std::string> owners;
  std::string first_path;
  for (const auto& path : paths) {
    RunRecord record = read_run_record(path.string());
    if (result.runs.empty()) {
      result.runs.resize(record.run_count);
      owners.resize(record.run_count);
      first_path = path.string();
    } else {
      const RunRecord& first = result.any();
      if (record.kind != first.kind || record.hash != first.hash ||
          record.run_count != first.run_count) {
        throw InvalidInput(
            "run record " + path.string(),
            std::string(kind_name(record.kind)) + " of configuration " + record.hash,
            "records of one plan only: " + first_path + " is " + kind_name(first.kind) +
                " of configuration " + first.hash +
                " (another configuration, seed list or kind: use one folder per plan)");
      }
    }
    if (result.runs[record.run_index]) {
      throw InvalidInput("run record " + path.string(),
                         "run " + std::to_string(record.run_index + 1),
                         "each run once (also in " + owners[record.run_index] + ")");
    }
    owners[record.run_index] = path.string();
    result.runs[record.run_index] = std::move(record);
  }
  for (std::size_t i = 0; i < result.runs.size(); ++i) {
    if (!result.runs[i]) result.missing.push_back(i);
  }
  return result;
}

}  // namespace aggpack
