#pragma once
// Wall-clock time for progress, time limits and reports: one steady clock and one conversion.

#include <chrono>

namespace aggpack {

using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace aggpack
