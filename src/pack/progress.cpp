#include "aggpack/pack/progress.h"

#include <cstdio>

namespace aggpack {

std::string to_string(StopReason reason) {
  switch (reason) {
    case StopReason::kTargetReached:
      return "target reached";
    case StopReason::kAttemptBudget:
      return "total attempt budget exhausted";
    case StopReason::kConsecutiveFailures:
      return "too many particles in a row could not be placed";
    case StopReason::kSizeListExhausted:
      return "size list exhausted (some particles rejected)";
    case StopReason::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

std::string PackReport::summary() const {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "placed %llu of %llu particles (%llu rejected), solid %.6g m^3 of %.6g m^3 "
                "(%.2f %%), %s",
                static_cast<unsigned long long>(placed), static_cast<unsigned long long>(requested),
                static_cast<unsigned long long>(rejected), solid_volume, container_volume,
                100.0 * solid_fraction, to_string(stop_reason).c_str());
  return buffer;
}

}  // namespace aggpack
