#pragma once
// The PNG of `aggpack calibrate --plot` (calibrate_plot.cpp).

#include <string>

#include "aggpack/shape/calibrate.h"

namespace aggpack::cli {

/// Mean +- sd of the target descriptor at every evaluated alpha, the target as a horizontal line
/// and the alpha found as a vertical one.
void write_calibration_plot(const std::string& path, const CalibrationOptions& options,
                            const CalibrationResult& result);

}  // namespace aggpack::cli
