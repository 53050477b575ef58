#pragma once
// Packing statistics: count, solid volume fraction (global and per axis), achieved grading,
// shape-descriptor summaries. JSON output lives in aggpack_io (aggpack/io/packing_stats_json.h).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/pack/grading.h"
#include "aggpack/pack/packing.h"
#include "aggpack/shape/descriptors.h"

namespace aggpack {

/// Solid fraction along one axis, in equal-width bins across the container's bounds.
/// Exact: each particle is cut by the bin planes (convex-polyhedron slicing), and each bin's solid
/// volume is divided by the container's volume in that slab (circular segments for a cylinder).
struct AxisProfile {
  int axis = 0;                          ///< 0 = x, 1 = y, 2 = z
  double lower = 0.0;                    ///< first bin's lower edge (m)
  double bin_width = 0.0;                ///< m
  std::vector<double> solid_fraction{};  ///< per bin, [0, 1]
};

/// Summary of one shape descriptor over all particles.
struct DescriptorSummary {
  std::string name{};  ///< descriptor_columns() name, e.g. "sphericity"
  std::string unit{};  ///< "m", "m^3", "-", ...
  SummaryStatistics stats{};
};

struct PackingStatistics {
  std::size_t particle_count = 0;
  std::size_t shape_count = 0;                   ///< distinct stored shapes
  double solid_volume = 0.0;                     ///< m^3, exact sum of particle volumes
  double container_volume = 0.0;                 ///< m^3
  double solid_fraction = 0.0;                   ///< solid_volume / container_volume
  std::array<AxisProfile, 3> profiles{};         ///< x, y, z
  std::vector<GradingPoint> grading{};           ///< empty when no target grading was given
  std::vector<DescriptorSummary> descriptors{};  ///< measured per particle (true size)
};

/// Options of compute_statistics.
struct StatisticsOptions {
  int bins = 10;                      ///< bins per axis profile, [1, 10000]
  std::optional<Grading> target{};    ///< compare the achieved grading with this one
  std::vector<double> sieve_sizes{};  ///< sizes for the grading table (m); empty = report_sizes()
  bool has_descriptors = true;        ///< measure shape descriptors (one describe() per particle)
};

/// Computes the statistics of a packing (parallel over particles where TBB is available;
/// the result does not depend on the thread count).
/// \throw InvalidInput naming the field for bad options or an empty/invalid container.
PackingStatistics compute_statistics(const Packing& packing, const StatisticsOptions& options = {});

/// A readable multi-line summary (count, volumes, fraction, profiles, grading table, descriptors).
std::string format_statistics(const PackingStatistics& statistics);

/// The achieved-vs-target grading table of format_statistics (a title line and one row per sieve
/// size: size, target, achieved, difference in volume % passing); "" when `grading` is empty.
std::string format_grading(const std::vector<GradingPoint>& grading);

/// Volume (m^3) of the part of a convex body with coordinate `axis` <= `level` (exact slicing).
double volume_below(const ConvexPolyhedron& body, int axis, double level);

}  // namespace aggpack
