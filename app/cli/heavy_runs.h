#pragma once
// What the commands that simulate or rework a packing will ask for, for their one-line heads-up
// before a heavy run (announce_heavy_run, progress.h): the inputs each command knows, turned into
// the estimators of aggpack/pack/resources.h (the one home of the costs). Needs the simulation
// module (AGGPACK_HAS_SIM).

#include "aggpack/pack/packing.h"
#include "aggpack/pack/resources.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/settle.h"

namespace aggpack::cli {

/// settle: the packing's bodies and shapes, the time step World will take (automatic from the
/// smallest particle's equivalent diameter unless given) and the steps to rest (expected_steps).
RunEstimate estimate_settle(const Packing& packing, const SettleOptions& options);

/// repose (Bullet): `runs` runs of the paper's lattice fill of `options` (its sites), `parallel`
/// at a time: stage 1 settles the fill, stage 2 moves the baffle out of the way and waits for
/// rest. The time step from particle.radius (about the paper's particles' equivalent diameter).
RunEstimate estimate_repose(const ReposeOptions& options, double runs, int parallel);

/// The heads-up of `runs` repose runs (an ensemble's seeds, a sweep's cases x seeds), of which
/// this process runs the ones `share` owns, as many at a time as threads are allowed (one run:
/// runs = 1). A particle library path that is not there is refused first (one-line error).
void announce_repose(const ReposeOptions& options, const RunShare& share, std::size_t runs);

}  // namespace aggpack::cli
