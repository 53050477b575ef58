#pragma once
// The densifying packer (issue 14): hard-particle Monte Carlo (HPMC) on rigid convex polyhedra,
// exactly overlap-free at every step.
//
// A sweep tries one rigid move (a translation or a rotation about the centroid) per particle; a
// move is accepted only when the moved particle stays inside the container minus wall_gap
// (exact vertex test) and is separated by more than `gap` from every neighbour by the exact test
// (is_separated, aggpack/geom/overlap.h). Sweeps run in parallel on a checkerboard of grid cells
// (HOOMD-blue HPMC style: cells at least one interaction range wide, eight colours, a particle's
// move must keep its centre in its cell, the grid is shifted randomly every sweep); every random
// number comes from a stream derived from (seed, sweep, particle), so the result is
// byte-identical at any thread count. Step sizes adapt toward a target acceptance rate.
//
// Modes:
//  - kFixed: between sweeps the container is squeezed toward the target container, rescaling
//    particle POSITIONS only (shapes are never deformed), HOOMD-blue QuickCompress style: the
//    squeeze itself is not checked; the particles it made overlap (exact test) are flagged and
//    repaired by sweeps in which a flagged particle is pushed away from its partners; a push
//    may not raise its number of partners (it may trade a resolved partner for a new one, which
//    is then flagged: overlap transfer) nor bring a kept partner's centre closer, and a clean
//    particle may overlap nothing. Squeezes continue while at most 15 % of the particles are
//    flagged (their size adapts to flag 10-25 % each); after 64 squeezes no more until no
//    particle is flagged: that overlap-free state is a checkpoint. A repair that stalls undoes
//    part of the squeezes, finally all. Only checkpoints are ever returned.
//    Stops once the target container is reached (and the target fraction, if any).
//  - kBed: gravity bed. Moves that raise a particle are accepted with the Metropolis weight of
//    its potential energy m g dz at a falling temperature; the run stops when the bed's mean
//    height stops sinking. The bulk fraction is measured in a slab below the free surface.
// Continuing from a saved packing is just densify() on that packing.
//
// At the end of every run the packing is verified pair by pair (verify(), aggpack/pack/verify.h);
// a failure throws (it would be a bug).

#include <cstdint>
#include <optional>
#include <string>

#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"

namespace aggpack {

enum class DensifyMode {
  kFixed,  ///< compress toward the target container / fraction, then stop
  kBed     ///< gravity bed: bias moves downward until the bed stops compacting
};

/// "fixed", "bed".
std::string to_string(DensifyMode mode);
/// Parses "fixed" / "bed". \throw InvalidInput naming `field`.
DensifyMode parse_densify_mode(const std::string& field, const std::string& text);

/// Options of densify(). Lengths in metres. Every option is validated by validate(); each bad
/// value gives its own one-line InvalidInput naming "densify.<option>".
struct DensifyOptions {
  DensifyMode mode = DensifyMode::kFixed;
  /// kFixed: the container to compress toward: same kind as the start container, no extent
  /// larger than the start's, same wall_gap. Empty: the start container, shrunk uniformly as far
  /// as target_fraction asks (or not at all when target_fraction is 0). Ignored for kBed.
  std::optional<Container> target_container{};
  /// kFixed: stop once the solid fraction reaches this, [0, 0.95); 0 = no fraction target.
  double target_fraction = 0.0;
  double gap = 0.0;                 ///< minimum particle-particle distance (m), >= 0 (packer.gap)
  std::uint64_t seed = 1;           ///< master seed of every random stream
  std::uint64_t max_sweeps = 2000;  ///< sweep budget, [1, 1e9]
  /// Wall-time budget (s), >= 0; 0 = none. A run stopped by time is not reproducible (it
  /// depends on the machine); sweep budgets are.
  double max_seconds = 0.0;
  double target_acceptance = 0.3;     ///< acceptance rate the step sizes adapt to, (0, 1)
  double translation_step = 0.1;      ///< initial translation step / bounding radius, (0, 1]
  double rotation_step = 0.1;         ///< initial rotation step (rad), (0, pi]
  double rotation_probability = 0.5;  ///< share of trial moves that rotate, [0, 1]
  /// kFixed: squeezes happen only on sweeps whose number is a multiple of this, [1, 1000].
  std::uint32_t compress_interval = 4;
  /// kFixed: largest relative shrink of any container extent in one squeeze, (0, 0.1]; the
  /// step starts at a quarter of it and adapts (x1.2 when a squeeze flags < 10 % of the
  /// particles, halved and retried above 25 %, x0.7 for every stalled repair).
  double max_compression = 0.01;
  /// kBed: initial temperature: a particle of mean volume rising by one mean bounding radius is
  /// accepted with probability exp(-1 / T), >= 0 (0 = never rise).
  double bed_temperature = 0.1;
  double bed_cooling = 0.9997;  ///< kBed: temperature factor per sweep, (0, 1]
  /// Stall window (sweeps), [1, 1e9]: kFixed stops as jammed when the fraction (of the last
  /// overlap-free checkpoint) gained less than stall_tolerance over the window; kBed stops as
  /// settled when the mean height sank less than stall_tolerance mean bounding radii.
  std::uint64_t stall_sweeps = 400;
  double stall_tolerance = 1e-4;  ///< see stall_sweeps, >= 0
};

/// \throw InvalidInput naming "densify.<option>" for the first bad option.
void validate(const DensifyOptions& options);

/// Throws InvalidInput naming `container.periodic` when a bed (`mode` kBed) has a periodic z
/// axis: the bed settles on its floor. Periodic x and y are fine in both modes.
void refuse_periodic_bed(const Container& container, DensifyMode mode);

enum class DensifyStop {
  kTargetReached,  ///< kFixed: target container (and fraction) reached
  kSettled,        ///< kBed: the mean height stopped sinking
  kJammed,         ///< kFixed: the fraction stopped rising before the target
  kSweepBudget,    ///< max_sweeps used up
  kTimeBudget,     ///< max_seconds used up
  kCancelled       ///< PackControl::cancel was set
};

/// "target reached", "settled", "jammed", ...
std::string to_string(DensifyStop stop);

struct DensifyReport {
  DensifyStop stop = DensifyStop::kTargetReached;
  std::uint64_t sweeps = 0;          ///< sweeps run
  std::uint64_t moves_tried = 0;     ///< trial moves
  std::uint64_t moves_accepted = 0;  ///< accepted trial moves
  std::uint64_t compressions = 0;    ///< squeezes repaired and kept (kFixed)
  double start_fraction = 0.0;       ///< solid fraction of the start packing
  double solid_fraction = 0.0;       ///< final solid volume / container volume
  /// kBed: bulk fraction in [bulk_lower, bulk_upper] (exact slab volumes); 0 for kFixed.
  double bulk_fraction = 0.0;
  double bulk_lower = 0.0;         ///< m
  double bulk_upper = 0.0;         ///< m
  double surface_height = 0.0;     ///< kBed: estimated free-surface height (m)
  double translation_step = 0.0;   ///< final translation step / bounding radius
  double rotation_step = 0.0;      ///< final rotation step (rad)
  double seconds = 0.0;            ///< wall time (s), not reproducible
  std::size_t verified_pairs = 0;  ///< pairs checked by the final verification
  double min_distance = 0.0;       ///< smallest pair distance in the final packing (m)
  /// One line: "fixed: 0.412 -> 0.613 solid in 800 sweeps (12.1 s), target reached".
  [[nodiscard]] std::string summary() const;
};

struct DensifyResult {
  Packing packing{};
  DensifyReport report{};
};

/// Densifies `start` (which must be overlap-free within options.gap and contained; checked, an
/// InvalidInput names "start packing" otherwise). Progress: PackProgress with stage kPlacement,
/// `fraction` = share of the sweep budget used (or of the way to the target), `placed` = sweeps,
/// `solid_fraction` = current fraction (kBed: the running estimate V / (A 2 z_mean) of the bed's
/// fraction, from the solid volume V, the container's cross-section A and the volume-weighted
/// mean centroid height). The returned packing keeps shapes, classes and
/// provenance of `start` except provenance.packer = "dense".
/// \throw InvalidInput for bad options or a bad start packing.
DensifyResult densify(Packing start, const DensifyOptions& options,
                      const PackControl& control = {});

/// kBed's bulk measurement, usable on any packing: the free-surface height (median over columns
/// of width 2 * largest bounding radius of the highest particle top) and the solid fraction in
/// the slab [bottom + 2 r_max, surface - 4 r_max] (falls back to [bottom, surface / 2] when
/// that slab is empty). Sets report.bulk_* and report.surface_height.
void measure_bulk(const Packing& packing, DensifyReport& report);

}  // namespace aggpack
