#pragma once
// The PNG of `aggpack calibrate --plot` (calibrate_plot.cpp).

#include <string>

#include "aggpack/shape/calibrate.h"

namespace aggpack::cli {

/// The search's course: each target's relative miss (%) at every evaluation, in order, with the
/// accepted band (+- tolerance) and the point found.
void write_calibration_plot(const std::string& path, const CalibrationOptions& options,
                            const CalibrationResult& result);

}  // namespace aggpack::cli
