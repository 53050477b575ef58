#pragma once
// Internal to the repose test (repose.cpp, repose_measure.cpp): the measurement's defaults.

#include <cstddef>

#include "aggpack/sim/repose.h"

namespace aggpack::detail {

/// Running-median window of the slope fit, in bins: one particle diameter (2 R), odd, >= 3.
std::size_t repose_smoothing_bins(const ReposeOptions& options, double bin_width);

/// The profile's bin width: options.bin_width, or R / 2 when it is 0.
double repose_bin_width(const ReposeOptions& options);

}  // namespace aggpack::detail
