#pragma once
// JSON text of packing statistics and pack reports (nlohmann-json, in aggpack_io).

#include <string>
#include <vector>

#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/progress.h"
#include "aggpack/pack/statistics.h"

namespace aggpack {

/// The statistics as a JSON object (pretty-printed with `indent` spaces; -1 = one line).
/// Keys: particle_count, shape_count, solid_volume_m3, container_volume_m3, solid_fraction,
/// profiles {x|y|z: {lower_m, bin_width_m, solid_fraction[]}}, grading [{size_m, target_percent,
/// achieved_percent}], descriptors {name: {unit, mean, standard_deviation, minimum, maximum,
/// count}}.
std::string to_json(const PackingStatistics& statistics, int indent = 2);

/// A pack report as a JSON object (stop_reason, is_target_reached, placed, requested, rejected,
/// shrunk,
/// attempts, solid_volume_m3, container_volume_m3, solid_fraction, target_solid_fraction,
/// shape_seconds, placement_seconds).
std::string to_json(const PackReport& report, int indent = 2);

/// An achieved-vs-target grading table as a JSON array [{size_m, target_percent,
/// achieved_percent}] (the "grading" of the statistics).
std::string to_json(const std::vector<GradingPoint>& grading, int indent = 2);

/// A densify report as a JSON object (stop, sweeps, moves_tried, moves_accepted, compressions,
/// start_fraction, solid_fraction, bulk_fraction, bulk_lower_m, bulk_upper_m, surface_height_m,
/// seconds, verified_pairs, min_distance_m).
std::string to_json(const DensifyReport& report, int indent = 2);

}  // namespace aggpack
