#pragma once
// Shared by the repose / sweep commands (sim_commands.cpp), their seed ensembles and sweeps
// (sim_studies.cpp) and their printed lines (sim_print.cpp). Built only with AGGPACK_HAS_SIM.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "aggpack/sim/distributed.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/sim/sweep.h"

namespace aggpack::cli {

// Removes an output folder this run created if the run fails before writing into it.
class CreatedFolder {
 public:
  explicit CreatedFolder(const std::string& folder) : folder_(folder) {
    std::error_code error;
    is_created_ = !std::filesystem::exists(std::filesystem::symlink_status(folder, error));
  }
  CreatedFolder(const CreatedFolder&) = delete;
  CreatedFolder& operator=(const CreatedFolder&) = delete;
  ~CreatedFolder() {
    if (!is_created_ || is_kept_) return;
    std::error_code error;
    std::filesystem::remove(std::filesystem::path(folder_) / "cases", error);  // only if empty
    std::filesystem::remove(std::filesystem::path(folder_) / "runs", error);   // only if empty
    std::filesystem::remove(folder_, error);                                   // only if empty
  }
  void keep() { is_kept_ = true; }

 private:
  std::string folder_;
  bool is_created_ = false;
  bool is_kept_ = false;
};

struct ReposeFlags {
  std::string config_path;
  std::vector<std::string> overrides;
  std::string output = "repose-out";
  std::optional<double> friction;
  std::optional<double> alpha;
  std::optional<std::string> seed;    // as typed: parse_seed_flag
  std::optional<std::string> engine;  ///< --engine, same as --set physics.engine
  std::optional<double> time_limit;   ///< --time-limit, same as --set yade.time_limit
  std::string seeds;                  ///< an ensemble, "1-16" or "1,4,9" (overrides ensemble.seeds)
  bool has_seeds = false;
  std::optional<std::string> worker;  ///< --case K
  std::optional<std::string> of;      ///< --of N
  int threads = 0;
  int image_width = 1600;
  std::string progress = "auto";
  bool is_print_config = false;
  bool is_forced = false;
  bool is_without_plot = false;
  bool has_packing = false;
};

/// The flags' configuration: the TOML file, --set, then the flags that stand for keys (--mu,
/// --alpha, --seed, --engine, --time-limit) and --seeds. \throw ConfigError, InvalidInput.
SweepOptions resolve_repose_flags(const ReposeFlags& flags);

/// `repose --seeds` (sim_studies.cpp): in this process (`given`: a `--case K --of N` share) or
/// over the ranks of mpirun, then the summary (or `aggpack merge` for a share).
void run_ensemble_command(const ReposeFlags& flags, const SweepOptions& options,
                          const RunShare& given);

/// `aggpack sweep` (sim_studies.cpp), as run_ensemble_command over the alpha x mu_s cases.
void run_sweep_command(const ReposeFlags& flags);

/// The printed summary of one repose run (sim_print.cpp).
void print_repose_result(const ReposeResult& result);

/// One YADE progress line on stderr (sim_print.cpp).
void print_yade_progress(const YadeProgress& progress, const ReposeOptions& options);

/// The line a worker of a split run prints when its share is done (sim_print.cpp).
void print_share(const RunShare& share, std::size_t owned, std::size_t total,
                 const std::string& folder);

}  // namespace aggpack::cli
