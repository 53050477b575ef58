#pragma once
// Runs work that may crash, abort or hang (third-party code such as TetGen, whose failed
// assertions call abort()) in forked worker processes, so that such a failure costs only the item
// it happened on and never the calling process.

#include <cstddef>
#include <functional>
#include <shared_mutex>
#include <string>
#include <thread>
#include <vector>

#include "aggpack/core/error_words.h"

namespace aggpack {

/// What happened to one item of run_isolated.
struct IsolatedOutcome {
  bool is_done = false;  ///< the work function returned for this item; `bytes` is its result
  std::string bytes;     ///< the work function's result (when is_done)
  /// Why not (when !is_done), e.g. "died of signal 6 (Aborted)", "timed out after 60 s",
  /// "threw: <message>", "exited with code 1".
  std::string failure;
  Wording failure_wording{};  ///< `failure` in words (core/error_words.h)
};

struct IsolatedOptions {
  /// Worker processes run at the same time, >= 0; 0 = the number of threads TBB may use (the
  /// CLI's --threads), 1 without TBB.
  int workers = 0;
  /// Seconds one item may take before its worker is killed and the item fails, in
  /// [0.001, 604800] (a week).
  double time_limit = 60.0;
  /// Called in the calling process each time an item's outcome is settled (its result arrived
  /// or it failed): (items settled so far, count). For a progress display; must not throw.
  std::function<void(std::size_t settled, std::size_t count)> on_settled = {};
};

/// Runs work(i) for every i in [0, count) in forked worker processes and returns the outcomes in
/// item order. Each worker meshes a contiguous batch of items and streams each result back over a
/// pipe as soon as it is done; when a worker dies (signal, exit) or overruns the time limit, the
/// item it was working on fails and a new worker takes the rest of its batch. An item's outcome
/// depends only on work(i), never on the worker count or the scheduling.
///
/// `work` runs in a child forked from a possibly multithreaded process: it must only compute and
/// return (no threads or TBB, no locks other threads may hold, no output: the child's stdout and
/// stderr go to /dev/null). Its exceptions become failures ("threw: ..."). The child leaves with
/// _exit, so no destructors, atexit handlers or leak checks run there.
/// \throw InvalidInput (options), IoError (pipe or fork failed; no worker is left behind).
std::vector<IsolatedOutcome> run_isolated(std::size_t count,
                                          const std::function<std::string(std::size_t)>& work,
                                          const IsolatedOptions& options = {});

/// A section during which run_isolated does not fork, for a thread of ours that runs beside it and
/// allocates (the CLI's progress tickers hold one while they format and print). A child forked
/// while another thread is inside the allocator inherits its lock taken: glibc's malloc guards
/// against that at fork, but the sanitizers' allocator of GCC 12 does not, and a worker of a
/// sanitized CI run hung for ever that way. Hold it briefly: forking waits for it.
[[nodiscard]] std::shared_lock<std::shared_mutex> section_without_fork();

/// Starts a thread running `body` and returns once `body` has begun, for a thread of ours that
/// runs beside run_isolated. A new thread allocates while it starts (glibc's
/// pthread_getattr_np, the sanitizer runtime's own set-up) outside any section_without_fork; a
/// child forked at that moment would inherit the allocator's lock taken, as above.
[[nodiscard]] std::thread start_thread_before_forks(std::function<void()> body);

}  // namespace aggpack
