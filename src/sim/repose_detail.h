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

namespace aggpack::detail {

/// The fill in the trough as every engine starts from it: checked (InvalidInput naming "repose
/// fill"), turned about its lattice sites (lattice fills), the trough as its container, packer
/// "<fill packer>+repose". Sets result.initial, particle_count, solid_volume and
/// mean_measured_alpha; returns the packing.
Packing prepare_repose(const ReposeOptions& options, PackResult fill, ReposeResult& result);

/// The measurement of result.final as every engine reports it (result.smallest_size set):
/// particles outside the trough, the profile, the slope fit and its sensitivity; the final
/// packing's provenance is the initial one's.
void finish_repose(const ReposeOptions& options, ReposeResult& result);

}  // namespace aggpack::detail
