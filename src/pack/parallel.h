#pragma once
// Internal: a deterministic parallel loop over indices (TBB when available, else sequential).
// Each index must write only its own output slot, so the result never depends on the schedule.

#include <algorithm>
#include <cstddef>

#ifdef AGGPACK_HAS_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

namespace aggpack::detail {

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

/// Worker threads available to parallel_for_index (1 without TBB).
inline int concurrency() {
#ifdef AGGPACK_HAS_TBB
  return tbb::this_task_arena::max_concurrency();
#else
  return 1;
#endif
}

}  // namespace aggpack::detail
