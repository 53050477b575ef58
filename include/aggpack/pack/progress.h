#pragma once
// What every packer reports, and how callers follow progress and cancel a long run.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "aggpack/pack/packing.h"

namespace aggpack {

/// Which part of a run a progress snapshot is about.
enum class PackStage {
  kShapes,     ///< growing the particle shapes (random packer: the size list)
  kPlacement,  ///< placing them
  kDensify     ///< densifying a fill (the pipeline's "dense" kind; placed = sweeps)
};

/// A progress snapshot, passed to PackControl::on_progress.
struct PackProgress {
  PackStage stage = PackStage::kPlacement;
  double fraction = 0.0;        ///< fraction of this stage done, [0, 1] (placement: toward the
                                ///< target count or volume fraction)
  std::uint64_t placed = 0;     ///< particles placed so far
  std::uint64_t attempted = 0;  ///< particles tried so far (placed + rejected)
  std::uint64_t total = 0;      ///< particles in the run's size list
  double solid_fraction = 0.0;  ///< solid volume placed / container volume so far
};

/// Progress callback. Called from the packing thread, at most every `progress_interval` seconds
/// and once at the end; keep it cheap. It must not throw.
using ProgressCallback = std::function<void(const PackProgress&)>;

/// How the caller follows and stops a run. All members optional.
struct PackControl {
  ProgressCallback on_progress{};             ///< progress callback, or empty
  double progress_interval = 0.1;             ///< seconds between callbacks, >= 0
  const std::atomic<bool>* cancel = nullptr;  ///< set to true to stop; the packer returns
                                              ///< what it placed with StopReason::kCancelled
};

/// Why a packer stopped.
enum class StopReason {
  kTargetReached,        ///< the count / volume-fraction target was reached (lattice: all sites)
  kAttemptBudget,        ///< max_total_attempts used up before the target
  kConsecutiveFailures,  ///< max_consecutive_failures particles in a row could not be placed
  kSizeListExhausted,    ///< every particle of the size list was tried; some could not be placed
  kCancelled             ///< PackControl::cancel was set
};

/// "target reached", "attempt budget exhausted", ...
std::string to_string(StopReason reason);

/// What a packer did. Counts are exact; times are wall-clock and not reproducible.
struct PackReport {
  StopReason stop_reason = StopReason::kTargetReached;
  bool is_target_reached = false;
  std::uint64_t placed = 0;            ///< particles in the packing
  std::uint64_t requested = 0;         ///< particles in the size list / lattice sites
  std::uint64_t rejected = 0;          ///< particles that used up their attempts and were skipped
  std::uint64_t shrunk = 0;            ///< lattice contact mode: particles scaled down about their
                                       ///< centre because they touched an earlier neighbour
  std::uint64_t attempts = 0;          ///< placement attempts used (candidate poses tested)
  double solid_volume = 0.0;           ///< sum of exact particle volumes (m^3)
  double container_volume = 0.0;       ///< m^3
  double solid_fraction = 0.0;         ///< solid_volume / container_volume
  double target_solid_fraction = 0.0;  ///< random packer by fraction; 0 otherwise
  double shape_seconds = 0.0;          ///< wall time generating shapes (s)
  double placement_seconds = 0.0;      ///< wall time placing them (s)
  /// One line: "placed 1050 of 1050 particles, solid 0.84 m^3 (10.0 %), target reached".
  [[nodiscard]] std::string summary() const;
};

/// A packing and the report of how it was made.
struct PackResult {
  Packing packing{};
  PackReport report{};
  /// A packing of library shapes: the library index of each stored shape (packing.shapes[k] is
  /// library shape library_shapes[k]); only the shapes some particle uses are stored, in order of
  /// first use. Empty for grown particles.
  std::vector<std::uint32_t> library_shapes{};
};

}  // namespace aggpack
