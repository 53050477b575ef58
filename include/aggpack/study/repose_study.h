#pragma once
// The study layer of the angle-of-repose test: one run, a seed ensemble and an alpha x mu_s
// sweep as library calls that the CLI (`aggpack repose [--seeds]`, `aggpack sweep`) and the
// Python module (`aggpack.repose(..., seeds=...)`, `aggpack.sweep`) share. The simulation module
// (aggpack/sim) simulates what it is given, a fill and a trough; this layer makes each run's fill
// with the pipeline's pack() and writes YADE scripts with the io module, runs the runs side by
// side (one run per worker, each single-threaded inside, so results do not depend on the thread
// count), reports each finished run, and stops starting runs when cancelled.
// Built with the simulation module (AGGPACK_HAS_SIM).

#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "aggpack/pack/lattice_packer.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/sim/sweep.h"

namespace aggpack::study {

/// The paper's fill for the test: the lattice placement (alpha, radius, edge_length, form or the
/// shape library, seed) in the box [0, baffle_position] x [0, width()] x [0, fill_height].
LatticeOptions repose_fill_options(const ReposeOptions& options);

/// Everything a repose run checks before it starts, so that a command can refuse bad input before
/// it announces or creates anything: validate(options) (the simulation's keys), what the fill
/// would refuse (validate(repose_fill_options): too large a radius, too many vertices) and a
/// shape library path that is not there (listed, not read). Fields are named as the options
/// name them ("repose.radius", "particle.library"); with_sweep_key_names gives the config keys.
/// \throw InvalidInput, IoError.
void check_repose_inputs(const ReposeOptions& options);

/// The fill of a repose case: the pipeline's pack() of repose_fill_options(options), each
/// particle then turned by a random rotation about its lattice site when
/// options.is_orientation_random (stream Rng(seed ^ 0x726f74, i); it stays inside its site's
/// sphere, so nothing overlaps). What every study call runs on unless told otherwise (a
/// ReposeFill; called concurrently by ensembles and sweeps).
PackResult repose_fill(const ReposeOptions& options);

/// The YADE script of a repose run on `initial` (engine yade): the io module's
/// write_yade_repose_script (aggpack/io/yade_repose.h) with the options' trough, friction,
/// gravity, YADE parameters and rest criteria. A YadeScriptWriter (aggpack/sim/repose_yade.h).
void write_repose_yade_script(const Packing& initial, const ReposeOptions& options,
                              std::ostream& out);

/// Follows and steers one repose run.
struct ReposeControl {
  ReposeProgress on_progress;    ///< Bullet: per stage, simulated time and kinetic energy
  YadeProgressCallback on_yade;  ///< engine yade: YADE's progress lines
  ReposeFill fill;               ///< empty: repose_fill (the pipeline's lattice fill)
};

/// One run of the test on options.engine (Bullet or YADE) with the fill `control.fill` makes.
/// \throw InvalidInput, LimitExceeded, IoError (as run_repose and run_repose_yade).
ReposeResult run_repose(const ReposeOptions& options, const ReposeControl& control = {});

/// Follows and steers an ensemble or a sweep.
struct StudyControl {
  /// Ensembles: called once per finished seed (study::run_repose_ensemble), in completion
  /// order, never two at a time. Must not throw.
  EnsembleSeedCallback on_seed;
  /// Sweeps: called once per finished run (case, or case and seed). Must not throw.
  SweepCaseCallback on_run;
  /// Set to true to stop: runs not yet started are skipped (a run that has started finishes).
  const std::atomic<bool>* cancel = nullptr;
  /// Worker K of N (distributed.h): only the runs it owns run. nullptr: every run.
  const RunShare* share = nullptr;
  ReposeFill fill;  ///< empty: repose_fill (the pipeline's lattice fill)
  [[nodiscard]] bool is_cancelled() const { return cancel != nullptr && cancel->load(); }
};

/// The seed ensemble of `base` (base.seed replaced by each seed; particle.seed: the fill's
/// shapes and turns), in parallel over seeds: each seed's angle and their mean, sd and 95 %
/// interval. A seed whose run throws an aggpack Error is recorded as failed with the message.
/// When cancelled, the result holds the seeds that ran (plan order) and is_cancelled is set.
/// \throw InvalidInput for no seeds, more than kMaxEnsembleSeeds or invalid options.
EnsembleResult run_repose_ensemble(const ReposeOptions& base,
                                   const std::vector<std::uint64_t>& seeds,
                                   const StudyControl& control = {});

/// A sweep's runs.
struct SweepRuns {
  /// One summary per run that ran, in plan order (run i = case i / seeds, seed i % seeds; one run
  /// per case without seeds), or only those control.share owns.
  std::vector<SweepCase> runs;
  bool is_cancelled = false;  ///< control.cancel stopped it: some runs did not run
};

/// The runs of a sweep, no aggregation (`aggpack sweep` and its workers write one record per run).
/// \throw InvalidInput (as validate(SweepOptions) and run_repose).
SweepRuns run_sweep_runs(const SweepOptions& options, const StudyControl& control = {});

/// A whole sweep.
struct SweepResult {
  /// Its table (summarize_sweep of every run: one row per case in index order, with the seeds'
  /// statistics when options.seeds is not empty); when cancelled, the runs that ran instead.
  std::vector<SweepCase> cases;
  bool is_cancelled = false;  ///< control.cancel stopped it
};

/// The whole sweep (without control.share). \throw InvalidInput (as run_sweep_runs).
SweepResult run_sweep(const SweepOptions& options, const StudyControl& control = {});

}  // namespace aggpack::study
