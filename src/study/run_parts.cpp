// A study run in parts (aggpack/study/run_parts.h): the workers' run records and their merge.

#include "aggpack/study/run_parts.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <system_error>
#include <utility>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"

namespace aggpack::study {

namespace {

// "seed 3 (run 3), seed 7 (run 7) and 12 more": the first missing runs, for the message.
std::string missing_list(const RunFolder& runs, const RunRecord& first, const SweepOptions& plan) {
  constexpr std::size_t kShown = 20;
  std::string list;
  for (std::size_t k = 0; k < runs.missing.size() && k < kShown; ++k) {
    const std::size_t i = runs.missing[k];
    list +=
        fmt::format("{}{} (run {})", k > 0 ? ", " : "", describe_run(first.kind, plan, i), i + 1);
  }
  if (runs.missing.size() > kShown) {
    list += fmt::format(" and {} more", runs.missing.size() - kShown);
  }
  return list;
}

}  // namespace

RunRecorder::RunRecorder(RunKind kind, const SweepOptions& options, std::string folder,
                         int image_width, const std::string& field)
    : folder_(std::move(folder)) {
  const std::size_t seed_count = std::max<std::size_t>(1, options.seeds.size());
  plan_.kind = kind;
  plan_.image_width = image_width;
  plan_.config = resolved_sweep_config(options);
  plan_.hash = config_hash(plan_.config);
  plan_.run_count = kind == RunKind::kEnsemble
                        ? options.seeds.size()
                        : options.alphas.size() * options.frictions.size() * seed_count;
  for (std::size_t k = 0; k < options.seeds.size(); ++k) seed_index_[options.seeds[k]] = k;
  is_ensemble_sweep_ = kind == RunKind::kSweep && !options.seeds.empty();
  // Workers share a folder: one whose runs/ holds records of another plan (configuration, seed
  // list or kind) is refused before anything runs, so that a folder never mixes plans.
  const std::filesystem::path runs = std::filesystem::path(folder_) / "runs";
  std::error_code error;
  if (std::filesystem::is_directory(runs, error)) {
    for (const auto& entry : std::filesystem::directory_iterator(runs, error)) {
      const std::string name = entry.path().filename().string();
      if (name.empty() || name.front() == '.' || entry.path().extension() != ".json") continue;
      const RunRecord other = read_run_record(entry.path().string());
      if (other.kind != plan_.kind || other.hash != plan_.hash) {
        throw InvalidInput(
            field,
            "a folder holding " + entry.path().string() + " (configuration " + other.hash + ")",
            "a new folder, or one of the same configuration and seed list (this "
            "run's configuration is " +
                plan_.hash + ")");
      }
    }
  }
  std::filesystem::create_directories(runs);
}

void RunRecorder::record(const EnsembleSeed& seed) const {
  RunRecord record = plan_;
  record.run_index = seed_index_.at(seed.seed);
  record.ensemble = seed;
  write_run_record((std::filesystem::path(folder_) / "runs" / run_record_name(record)).string(),
                   record);
}

void RunRecorder::record(const SweepCase& run) const {
  RunRecord record = plan_;
  const std::size_t seed_count = std::max<std::size_t>(1, seed_index_.size());
  record.run_index = run.index * seed_count + (is_ensemble_sweep_ ? seed_index_.at(run.seed) : 0);
  record.sweep = run;
  write_run_record((std::filesystem::path(folder_) / "runs" / (stem(run) + ".json")).string(),
                   record);
}

std::string RunRecorder::stem(const SweepCase& run) const {
  return fmt::format("alpha{:.2f}_mu{:.2f}", run.alpha, run.friction) +
         (is_ensemble_sweep_ ? fmt::format("_seed{}", run.seed) : std::string());
}

MergedRuns merge_runs(const std::string& folder) {
  const RunFolder runs = read_run_folder(folder);
  const RunRecord& first = runs.any();
  MergedRuns merged;
  merged.kind = first.kind;
  merged.run_count = runs.runs.size();
  merged.image_width =
      first.image_width >= 64 && first.image_width <= 16384 ? first.image_width : 0;
  with_sweep_key_names(
      [&] { merged.plan = parse_sweep_config(first.config, "run record configuration"); });
  if (!runs.missing.empty()) {
    throw InvalidInput(
        "merge " + folder,
        fmt::format("{} of {} runs", runs.runs.size() - runs.missing.size(), runs.runs.size()),
        "every run of the plan; missing " + missing_list(runs, first, merged.plan) +
            " (run i belongs to worker (i - 1) mod N + 1 of --of N: run those again, then merge)");
  }
  if (first.kind == RunKind::kEnsemble) {
    std::vector<EnsembleSeed> seeds;
    for (const auto& run : runs.runs) seeds.push_back(run->ensemble);
    merged.ensemble = summarize_ensemble(std::move(seeds));
    return merged;
  }
  std::vector<SweepCase> cases;
  for (const auto& run : runs.runs) cases.push_back(run->sweep);
  merged.cases = summarize_sweep(merged.plan, std::move(cases));
  return merged;
}

}  // namespace aggpack::study
