#pragma once
// Gravity settling (issue 6): a packing falls in its container under gravity until it is at rest,
// giving a dense packing (`aggpack settle run.h5 -o dense.h5`).

#include <cstddef>
#include <functional>

#include "aggpack/pack/packing.h"
#include "aggpack/sim/world.h"

namespace aggpack {

/// When a run counts as at rest, and how long it may take.
struct RestCriterion {
  /// At rest when the kinetic energy stays below this fraction of M g d (M the total mass, d the
  /// median equivalent diameter: the work to lift every particle by its size) for `quiet_time`;
  /// in [1e-12, 1]. 3e-5 is an r.m.s. speed of 0.8% of sqrt(g d): 8 mm/s for the paper's
  /// particles, above the residual jitter of Bullet's iterative solver in a deep pile.
  double kinetic_energy_ratio = 3e-5;
  double quiet_time = 0.25;      ///< s the energy must stay below the threshold, >= 0
  double check_interval = 0.02;  ///< s between energy checks, > 0
  /// Simulated time (s) before rest is tested at all, >= 0; settle() adds the free-fall time of
  /// the highest particle to the floor.
  double min_time = 0.0;
  double max_time = 30.0;  ///< simulated seconds before giving up (not at rest), > 0
};

/// Throws InvalidInput naming the field unless the criterion is usable.
void validate(const RestCriterion& criterion);

/// Options of settle().
struct SettleOptions {
  PhysicsOptions physics{};  ///< materials, gravity, time step
  RestCriterion rest{};      ///< when to stop
  /// A particle counts as having left the container when a vertex lies farther than this
  /// fraction of d_min outside it (Bullet lets walls be penetrated slightly), >= 0.
  double containment_tolerance = 0.01;
};

/// What a settling run measured. Fractions are bulk (height-based): solid volume over
/// footprint area x height of the highest particle point above the floor.
struct SettleReport {
  bool is_at_rest = false;      ///< false when max_time ran out first
  double simulated_time = 0.0;  ///< s
  std::size_t steps = 0;
  double time_step = 0.0;                 ///< s
  double wall_seconds = 0.0;              ///< wall-clock time of the simulation (not reproducible)
  double kinetic_energy = 0.0;            ///< J at the end
  double kinetic_energy_threshold = 0.0;  ///< J
  double solid_volume = 0.0;              ///< m^3
  double height_before = 0.0;             ///< m, highest particle point before
  double height_after = 0.0;              ///< m
  double solid_fraction_before = 0.0;
  double solid_fraction_after = 0.0;
  std::size_t overlapping_pairs = 0;     ///< pairs whose exact polyhedra touch or overlap
  double max_overlap = 0.0;              ///< m, deepest exact overlap (pairs and walls)
  double max_overlap_fraction = 0.0;     ///< max_overlap / d_min
  double max_contact_penetration = 0.0;  ///< m, deepest Bullet contact at the end
  double smallest_size = 0.0;            ///< d_min (m)
  std::size_t escaped_particles = 0;     ///< particles outside the container (tolerance above)
  double min_wall_clearance = 0.0;       ///< m, smallest vertex-to-wall distance (< 0: outside)
};

struct SettleResult {
  Packing packing;  ///< the settled packing; provenance.packer gets "+settled"
  SettleReport report;
};

/// Progress: simulated time (s), kinetic energy (J), threshold (J). Called every check
/// interval from the calling thread; must not throw.
using SettleProgress = std::function<void(double time, double kinetic_energy, double threshold)>;

/// Lets `packing` fall in its container (floor and side walls; open top) until it is at rest.
/// Deterministic: the same packing and options give the same result.
/// \throw InvalidInput for bad options or an empty packing.
SettleResult settle(const Packing& packing, const SettleOptions& options = {},
                    const SettleProgress& progress = {});

/// Runs `world` until it is at rest by `criterion` or max_time passes; returns true when at rest.
/// Used by settle() and the repose test. \throw InvalidInput for a bad criterion.
bool run_until_rest(World& world, const RestCriterion& criterion,
                    const SettleProgress& progress = {});

/// Most time steps one run (a settle, a repose stage) may take: max_time / time step above this is
/// refused up front (a time step made tiny by a tiny particle would otherwise never end).
inline constexpr double kMaxSimulationSteps = 1e8;

/// Whole time steps between rest checks: check_interval / time step, at least 1.
/// \throw LimitExceeded (field max_time) when max_time / time step exceeds kMaxSimulationSteps.
std::size_t steps_per_check(const World& world, const RestCriterion& criterion);

/// \throw Error of kind kLimitExceeded ("<what>: the simulation diverged at t = ... s ...")
/// unless `kinetic_energy` and every particle's position and velocity are finite. Every iterative
/// command calls it after each block of steps: Bullet turns bad input into NaN silently.
void require_finite_state(const World& world, double kinetic_energy, const char* what);

/// Highest point of any particle above z = 0 (m).
double packing_height(const Packing& packing);

/// Bulk solid fraction: solid volume / (container footprint area x height); 0 if height <= 0.
double bulk_solid_fraction(const Packing& packing, double height);

}  // namespace aggpack
