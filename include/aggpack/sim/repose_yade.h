#pragma once
// The repose test in YADE (`aggpack repose --engine yade`): the same fill as the Bullet run
// (prepare_repose: same seed, same particles, same turns), written as a YADE script by a writer
// the caller passes (the study layer's write_repose_yade_script: the io module's YADE deck code),
// run as a subprocess (`yade -n -x` in a temporary folder, removed on every exit and on
// SIGINT/SIGTERM/SIGHUP), its progress lines passed on, then the poses YADE wrote read back into
// the final packing, which is measured exactly as Bullet's (profile, slope fit, sensitivity).

#include <functional>
#include <iosfwd>

#include "aggpack/sim/repose.h"

namespace aggpack {

/// Writes the YADE script of one run: `initial` (the fill in the trough) under `options` (their
/// yade.young already resolved). The script must write the result file of
/// aggpack/io/yade_repose.h ("poses.txt") in its working folder.
using YadeScriptWriter =
    std::function<void(const Packing& initial, const ReposeOptions& options, std::ostream& out)>;

/// A progress line of a YADE run.
struct YadeProgress {
  int stage = 1;              ///< 1 settle, 2 baffle and rest
  double time = 0.0;          ///< simulated s of the stage
  double total_time = 0.0;    ///< simulated s since the start
  double energy = 0.0;        ///< J
  double threshold = 0.0;     ///< J, rest threshold (0 while the baffle moves)
  double wall_seconds = 0.0;  ///< since YADE started
  std::size_t iterations = 0;
};
using YadeProgressCallback = std::function<void(const YadeProgress& progress)>;

/// YADE's contact stiffness for `options` on `initial` (options.yade.young, or its automatic
/// value, see YadeOptions::young).
double yade_young(const ReposeOptions& options, const Packing& initial);

/// Runs the test in YADE. \throw InvalidInput when `yade` is not on PATH (naming the Debian
/// package), LimitExceeded when options.yade.time_limit passes, IoError when YADE fails or its
/// result cannot be read, and what validate() and prepare_repose throw.
ReposeResult run_repose_yade(const ReposeOptions& options, PackResult fill,
                             const YadeScriptWriter& write_script,
                             const YadeProgressCallback& progress = {});

/// run_repose or run_repose_yade by options.engine (yade needs `write_script`, else InvalidInput
/// naming "repose.engine"). Bullet's per-stage progress is not passed on here.
ReposeResult run_repose_engine(const ReposeOptions& options, PackResult fill,
                               const YadeScriptWriter& write_script);

}  // namespace aggpack
