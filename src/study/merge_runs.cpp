// Merging the run records of a study run in parts (aggpack/study/merge.h).

#include "aggpack/study/merge.h"

#include <fmt/core.h>

#include <cstddef>
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
