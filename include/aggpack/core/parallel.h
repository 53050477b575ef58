#pragma once
// The one parallel loop of the project (TBB when built with it, else sequential), and the thread
// limit behind `--threads`. Every parallel site calls parallel_for_index: each index writes only
// its own output slot (results are then gathered in index order), so outputs are byte-identical
// at any thread count.

#include <algorithm>
#include <cstddef>
#include <memory>

#ifdef AGGPACK_HAS_TBB
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

namespace aggpack {

/// Calls `function(i)` for every i in [begin, end), in parallel when TBB is available.
/// Precondition: `function(i)` writes only state owned by index i (or per-worker scratch picked
/// with worker_slot()), so the result does not depend on the schedule.
template <class Function>
void parallel_for_index(std::size_t begin, std::size_t end, Function&& function) {
  if (end <= begin) return;
#ifdef AGGPACK_HAS_TBB
  if (end - begin > 1) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) function(i);
                      });
    return;
  }
#endif
  for (std::size_t i = begin; i < end; ++i) function(i);
}

/// This worker's slot, in [0, concurrency()] (0 outside a parallel loop): an index for
/// per-thread scratch space.
inline std::size_t worker_slot() {
#ifdef AGGPACK_HAS_TBB
  return static_cast<std::size_t>(std::max(0, tbb::this_task_arena::current_thread_index()));
#else
  return 0;
#endif
}

/// Worker threads of the task arena (1 without TBB): the size for per-worker scratch.
inline int concurrency() {
#ifdef AGGPACK_HAS_TBB
  return tbb::this_task_arena::max_concurrency();
#else
  return 1;
#endif
}

/// Threads parallel_for_index may use now: concurrency() capped by limit_threads(), at least 1.
inline int allowed_threads() {
#ifdef AGGPACK_HAS_TBB
  const auto allowed = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return std::max(1, std::min(concurrency(), allowed));
#else
  return 1;
#endif
}

/// Caps the threads of parallel_for_index while it lives (the smallest live cap wins), e.g. to
/// check that 1 and 2 threads give the same result. Precondition: threads >= 1.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads)
#ifdef AGGPACK_HAS_TBB
      : control_(tbb::global_control::max_allowed_parallelism,
                 static_cast<std::size_t>(std::max(1, threads)))
#endif
  {
    (void)threads;
  }

 private:
#ifdef AGGPACK_HAS_TBB
  tbb::global_control control_;
#endif
};

/// Caps the threads of every later parallel loop for the rest of the process (`--threads N`);
/// 0 keeps the default (all cores). Precondition: threads >= 0 (checked by the caller).
inline void limit_threads(int threads) {
  // One process-wide limit, as `--threads` means; held until exit.
  static std::unique_ptr<ThreadLimit> limit;
  if (threads > 0) limit = std::make_unique<ThreadLimit>(threads);
}

}  // namespace aggpack
