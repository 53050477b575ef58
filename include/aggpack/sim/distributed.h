#pragma once
// Ensembles and sweeps spread over processes or machines (issue 15 item 6): worker K of N runs
// its share of the independent runs (`--case K --of N`), each run leaves one run record in
// DIR/runs/, and `aggpack merge DIR` rebuilds the summary (ensemble.json|csv|png, sweep.csv|png)
// from the records, byte for byte the single-process result. The single-process run writes the
// same records, so a folder looks the same however it was made.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/sweep.h"

namespace aggpack {

/// Which runs a worker owns: run i (in plan order) belongs to worker (i mod of) + 1, round robin.
/// worker is 1-based; of = 1 (worker 1 of 1) is the whole plan.
struct RunShare {
  std::size_t worker = 1;
  std::size_t of = 1;
  [[nodiscard]] bool is_split() const { return of > 1; }
  [[nodiscard]] bool owns(std::size_t run_index) const { return run_index % of == worker - 1; }
};

/// Most workers one plan may be split into.
inline constexpr std::size_t kMaxWorkers = 100000;

/// The share of `--case K --of N` as typed: both or neither; N in [1, 100000], K in [1, N].
/// \throw InvalidInput naming the flag, the value and the allowed range.
RunShare parse_run_share(const std::optional<std::string>& worker,
                         const std::optional<std::string>& of);

/// "1-4,9": the seed list in parse_seed_list's syntax, consecutive runs as ranges.
std::string format_seed_list(const std::vector<std::uint64_t>& seeds);

/// 16 hex digits: FNV-1a 64 of `text` (the resolved configuration) without its TOML comments
/// (the keys' documentation) and the blanks before them, to tell configurations apart.
std::string config_hash(const std::string& text);

/// What kind of plan a run belongs to.
enum class RunKind { kEnsemble, kSweep };

/// One run's record, DIR/runs/<name>.json: the plan (kind, configuration text and its hash), the
/// run's place in it, and the summary the merge needs. No wall-clock times: the same run gives
/// the same bytes.
struct RunRecord {
  RunKind kind = RunKind::kEnsemble;
  std::string config;         ///< the resolved configuration (TOML) of the whole plan
  std::string hash;           ///< config_hash(config)
  std::size_t run_index = 0;  ///< place in the plan: case index * seeds + seed index
  std::size_t run_count = 0;  ///< runs in the plan
  int image_width = 0;        ///< the run's --width (merge draws ensemble.png with it); 0 unknown
  EnsembleSeed ensemble;      ///< kEnsemble: the seed's summary
  SweepCase sweep;            ///< kSweep: the run's summary (wall_seconds not recorded)
};

/// An ensemble record's file name in DIR/runs/: "seed-<k>.json". (`sweep` names its records as
/// its cases/ files, "alpha<a>_mu<m>[_seed<k>].json"; merge finds records by content, not name.)
std::string run_record_name(const RunRecord& record);

/// Writes the record atomically (temporary file + rename). \throw IoError.
void write_run_record(const std::string& path, const RunRecord& record);

/// Reads a record. \throw FormatError naming the file when it is not one.
RunRecord read_run_record(const std::string& path);

/// The name of run `run_index` of a plan, for messages: "seed 3", "alpha 0.5 mu_s 0.3 seed 2".
std::string describe_run(RunKind kind, const SweepOptions& plan, std::size_t run_index);

/// The records of DIR/runs/ (files *.json), checked to be one plan: the same kind and
/// configuration hash, each run once. `runs` in plan order, unset where no record is; `missing`
/// the indices without one.
struct RunFolder {
  std::vector<std::optional<RunRecord>> runs;
  std::vector<std::size_t> missing;
  [[nodiscard]] const RunRecord& any() const;  ///< the first record present
};

/// \throw InvalidInput when DIR/runs/ has no record, or records of another plan (naming both
/// files and what differs); FormatError for a file that is not a record.
RunFolder read_run_folder(const std::string& folder);

}  // namespace aggpack
