#include "aggpack/core/error.h"

#include <cmath>
#include <cstdio>

namespace aggpack {

std::string format_value(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

void require_in_range(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw InvalidInput(field, format_value(value),
                       "[" + format_value(lo) + ", " + format_value(hi) + "]");
  }
}

void require_positive(const std::string& field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InvalidInput(field, format_value(value), "finite and > 0");
  }
}

}  // namespace aggpack
