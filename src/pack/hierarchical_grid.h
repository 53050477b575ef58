#pragma once
// Internal: a hierarchical uniform grid of spheres (broad phase of the packers and of verify()).
// Level l has cells of size s_l = s_0 / 2^l and holds the spheres with s_l/4 < radius <= s_l/2
// (the finest level also holds all smaller ones); a query visits, on every non-empty level, the
// cells within (query radius + largest radius on that level) of the query centre. With one level
// this is the plain uniform grid with cell size = largest diameter; more levels keep wide
// gradings fast (a small particle never scans cells sized for the largest ones and vice versa).
// Each cell stores its entries contiguously and compactly (24 bytes: float centre relative to the
// grid corner, float radii, id): the broad phase is memory-latency bound (~100-250 entries looked
// at per candidate in a dense graded packing), so fewer, denser cache lines is what counts. Float
// round-off is covered by a margin: the outer test is widened and the inner radius handed to the
// caller narrowed by margin(), so the broad phase never misses a pair and "certainly overlapping"
// stays certain.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aggpack/geom/vec.h"

namespace aggpack::detail {

/// One stored sphere, compact: centre relative to the grid's lower corner, outer (bounding)
/// radius widened by the margin, inner radius (e.g. an inscribed ball) narrowed by twice the
/// margin, and its id (insertion order).
struct GridEntry {
  float x, y, z;
  float radius;
  float inner_radius;
  std::uint32_t id;
};

class HierarchicalGrid {
 public:
  static constexpr std::size_t kMaxLevels = 24;

  /// `bounds`: where the centres lie (others are clamped into edge cells, still correct).
  /// Radii in [min_radius, max_radius] (> 0). Levels are capped so no level exceeds max_cells.
  HierarchicalGrid(const Aabb& bounds, double min_radius, double max_radius,
                   double max_cells = 8.0e6)
      : lower_(bounds.lower) {
    const Vec3 extent = bounds.extent().cwiseMax(1e-300);
    // Float coordinates are good to ~1e-7 of the region; 1e-6 covers rounding of both ends of a
    // difference and of the squared sum with room to spare.
    margin_ = 1e-6 * (extent.maxCoeff() + 2.0 * max_radius);
    // A huge region with tiny particles: coarsen level 0 so its cell count stays bounded.
    const double cell = std::max(2.0 * max_radius, std::cbrt(extent.prod() / max_cells));
    const int wanted =
        1 + static_cast<int>(std::floor(std::log2(std::max(1.0, max_radius / min_radius))));
    for (int level = 0; level < std::clamp(wanted, 1, static_cast<int>(kMaxLevels)); ++level) {
      const double size = cell / std::pow(2.0, level);
      Level entry;
      entry.cell = size;
      entry.inverse_cell = 1.0 / size;
      double cells = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        const double count = std::max(1.0, std::ceil(extent[axis] / size));
        cells *= count;
        entry.dims[static_cast<std::size_t>(axis)] = static_cast<std::int64_t>(count);
      }
      if (level > 0 && cells > max_cells) break;
      entry.cells.resize(static_cast<std::size_t>(cells));
      levels_.push_back(std::move(entry));
    }
  }

  [[nodiscard]] std::size_t size() const { return count_; }
  [[nodiscard]] std::size_t level_count() const { return levels_.size(); }

  /// Adds sphere number size() (ids are insertion order).
  void insert(const Vec3& centre, double radius, double inner_radius = 0.0) {
    std::size_t level = 0;
    while (level + 1 < levels_.size() && radius <= levels_[level + 1].cell * 0.5) ++level;
    Level& entry = levels_[level];
    const Vec3 local = centre - lower_;
    entry.cells[cell_index(entry, centre)].push_back(
        {static_cast<float>(local.x()), static_cast<float>(local.y()),
         static_cast<float>(local.z()), static_cast<float>(radius + margin_),
         static_cast<float>(std::max(0.0, inner_radius - 2.0 * margin_)),
         static_cast<std::uint32_t>(count_)});
    entry.max_radius = std::max(entry.max_radius, radius);
    ++entry.count;
    ++count_;
  }

  /// Absolute round-off margin of the compact entries (m).
  [[nodiscard]] double margin() const { return margin_; }

  /// Calls visit(entry, distance_squared) for every stored sphere that may intersect the sphere
  /// (centre, radius): every one with |c - c_id| < radius + r_id is visited (a few up to margin()
  /// farther may be too). distance_squared is accurate to within margin() in distance. Stops
  /// early and returns false as soon as visit returns false.
  template <class Visit>
  bool for_each_near(const Vec3& centre, double radius, Visit&& visit) const {
    const Vec3 local = centre - lower_;
    const float qx = static_cast<float>(local.x());
    const float qy = static_cast<float>(local.y());
    const float qz = static_cast<float>(local.z());
    const auto query_radius = static_cast<float>(radius);
    auto scan = [&](const std::vector<GridEntry>& cell) {
      for (const GridEntry& item : cell) {
        const float dx = item.x - qx;
        const float dy = item.y - qy;
        const float dz = item.z - qz;
        const float distance_squared = dx * dx + dy * dy + dz * dz;
        const float limit = query_radius + item.radius;
        if (distance_squared < limit * limit && !visit(item, double{distance_squared})) {
          return false;
        }
      }
      return true;
    };
    // The cells holding the query centre first: a conflicting neighbour is most likely there, and
    // most packer queries end at their first conflict.
    std::array<std::size_t, kMaxLevels> own{};
    for (std::size_t level = 0; level < levels_.size(); ++level) {
      const Level& entry = levels_[level];
      own[level] = cell_index(entry, centre);
      if (entry.count != 0 && !scan(entry.cells[own[level]])) return false;
    }
    for (std::size_t level = 0; level < levels_.size(); ++level) {
      const Level& entry = levels_[level];
      if (entry.count == 0) continue;
      const double reach = radius + entry.max_radius + margin_;
      std::array<std::int64_t, 3> lo{};
      std::array<std::int64_t, 3> hi{};
      for (int axis = 0; axis < 3; ++axis) {
        lo[static_cast<std::size_t>(axis)] = clamp_cell(entry, axis, centre[axis] - reach);
        hi[static_cast<std::size_t>(axis)] = clamp_cell(entry, axis, centre[axis] + reach);
      }
      // Visit only cells whose box meets the reach sphere: per (z, y) row, the x range left
      // after the row's distance in y and z (saves ~40 % of the cells of the bounding cube).
      const double reach_squared = reach * reach;
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        const double row_dz = axis_gap(entry, 2, z, centre.z());
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
          const double row_dy = axis_gap(entry, 1, y, centre.y());
          const double rest = reach_squared - row_dz * row_dz - row_dy * row_dy;
          if (rest < 0.0) continue;
          const double half = std::sqrt(rest);
          const std::int64_t x0 = std::max(lo[0], clamp_cell(entry, 0, centre.x() - half));
          const std::int64_t x1 = std::min(hi[0], clamp_cell(entry, 0, centre.x() + half));
          const std::int64_t row = (z * entry.dims[1] + y) * entry.dims[0];
          for (std::int64_t x = x0; x <= x1; ++x) {
            const auto cell = static_cast<std::size_t>(row + x);
            if (cell != own[level] && !scan(entry.cells[cell])) return false;
          }
        }
      }
    }
    return true;
  }

 private:
  struct Level {
    double cell = 0.0;
    double inverse_cell = 0.0;
    std::array<std::int64_t, 3> dims{};
    std::vector<std::vector<GridEntry>> cells;
    double max_radius = 0.0;
    std::size_t count = 0;
  };

  [[nodiscard]] std::int64_t clamp_cell(const Level& entry, int axis, double coordinate) const {
    const double t = std::floor((coordinate - lower_[axis]) * entry.inverse_cell);
    return static_cast<std::int64_t>(
        std::clamp(t, 0.0, static_cast<double>(entry.dims[static_cast<std::size_t>(axis)] - 1)));
  }
  // Distance along `axis` from `coordinate` to cell `index`'s slab (0 inside it). Edge cells
  // extend to infinity (clamped centres live there), so their far side never counts.
  [[nodiscard]] double axis_gap(const Level& entry, int axis, std::int64_t index,
                                double coordinate) const {
    const double t = (coordinate - lower_[axis]) * entry.inverse_cell;
    const auto last = entry.dims[static_cast<std::size_t>(axis)] - 1;
    const double below = static_cast<double>(index) - t;      // > 0: cell starts after the point
    const double above = t - static_cast<double>(index + 1);  // > 0: cell ends before the point
    double gap = 0.0;
    if (below > 0.0 && index > 0) gap = below;
    if (above > 0.0 && index < last) gap = above;
    return gap * entry.cell;
  }
  [[nodiscard]] std::size_t cell_index(const Level& entry, const Vec3& centre) const {
    const std::int64_t x = clamp_cell(entry, 0, centre.x());
    const std::int64_t y = clamp_cell(entry, 1, centre.y());
    const std::int64_t z = clamp_cell(entry, 2, centre.z());
    return static_cast<std::size_t>((z * entry.dims[1] + y) * entry.dims[0] + x);
  }

  Vec3 lower_;
  double margin_ = 0.0;
  std::vector<Level> levels_;
  std::size_t count_ = 0;
};

}  // namespace aggpack::detail
