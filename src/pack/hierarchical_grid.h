#pragma once
// Internal: a hierarchical uniform grid of spheres (broad phase of the packers and of verify()).
// Level l has cells of size s_l = s_0 / 2^l and holds the spheres with s_l/4 < radius <= s_l/2
// (the finest level also holds all smaller ones); a query visits, on every non-empty level, the
// cells within (query radius + s_l/2) of the query centre. With one level this is the plain
// uniform grid with cell size = largest diameter; more levels keep wide gradings fast (a small
// particle never scans cells sized for the largest ones and vice versa).
// Cells are linked lists (head per cell, next per item), so inserts never reallocate per cell.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aggpack/geom/vec.h"

namespace aggpack::detail {

class HierarchicalGrid {
 public:
  /// `bounds`: where the centres lie (others are clamped into edge cells, still correct).
  /// Radii in [min_radius, max_radius] (> 0). Levels are capped so no level exceeds max_cells.
  HierarchicalGrid(const Aabb& bounds, double min_radius, double max_radius,
                   double max_cells = 16.0e6)
      : lower_(bounds.lower) {
    const Vec3 extent = bounds.extent().cwiseMax(1e-300);
    double cell = 2.0 * max_radius;
    // A huge region with tiny particles: coarsen level 0 so its cell count stays bounded.
    cell = std::max(cell, std::cbrt(extent.prod() / max_cells));
    const int wanted =
        1 + static_cast<int>(std::floor(std::log2(std::max(1.0, max_radius / min_radius))));
    for (int level = 0; level < std::max(1, wanted); ++level) {
      const double size = cell / std::pow(2.0, level);
      Level entry;
      entry.cell = size;
      entry.inverse_cell = 1.0 / size;
      double cells = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        const double count = std::max(1.0, std::ceil(extent[axis] / size));
        cells *= count;
        entry.dims[axis] = static_cast<std::int64_t>(count);
      }
      if (level > 0 && cells > max_cells) break;
      entry.head.assign(static_cast<std::size_t>(cells), -1);
      levels_.push_back(std::move(entry));
    }
  }

  [[nodiscard]] std::size_t size() const { return items_.size(); }
  [[nodiscard]] std::size_t level_count() const { return levels_.size(); }

  /// Adds sphere number size() (ids are insertion order).
  void insert(const Vec3& centre, double radius) {
    int level = 0;
    while (level + 1 < static_cast<int>(levels_.size()) &&
           radius <= levels_[static_cast<std::size_t>(level + 1)].cell * 0.5) {
      ++level;
    }
    Level& entry = levels_[static_cast<std::size_t>(level)];
    const std::size_t cell = cell_index(entry, centre);
    const auto id = static_cast<std::int32_t>(items_.size());
    items_.push_back({centre, radius});
    next_.push_back(entry.head[cell]);
    entry.head[cell] = id;
    entry.max_radius = std::max(entry.max_radius, radius);
    ++entry.count;
  }

  /// Calls visit(id, distance_squared) for every stored sphere that intersects the sphere
  /// (centre, radius) (strictly: |c - c_id| < radius + r_id). Stops early and returns false as
  /// soon as visit returns false.
  template <class Visit>
  bool for_each_near(const Vec3& centre, double radius, Visit&& visit) const {
    for (const Level& entry : levels_) {
      if (entry.count == 0) continue;
      const double reach = radius + entry.max_radius;
      std::array<std::int64_t, 3> lo{};
      std::array<std::int64_t, 3> hi{};
      for (int axis = 0; axis < 3; ++axis) {
        lo[axis] = clamp_cell(entry, axis, centre[axis] - reach);
        hi[axis] = clamp_cell(entry, axis, centre[axis] + reach);
      }
      for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
          for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
            const auto cell = static_cast<std::size_t>((z * entry.dims[1] + y) * entry.dims[0] + x);
            for (std::int32_t id = entry.head[cell]; id >= 0;
                 id = next_[static_cast<std::size_t>(id)]) {
              const Item& item = items_[static_cast<std::size_t>(id)];
              const double distance_squared = (item.centre - centre).squaredNorm();
              const double limit = radius + item.radius;
              if (distance_squared < limit * limit &&
                  !visit(static_cast<std::uint32_t>(id), distance_squared)) {
                return false;
              }
            }
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
    std::vector<std::int32_t> head;
    double max_radius = 0.0;
    std::size_t count = 0;
  };
  struct Item {
    Vec3 centre;
    double radius;
  };

  [[nodiscard]] std::int64_t clamp_cell(const Level& entry, int axis, double coordinate) const {
    const double t = std::floor((coordinate - lower_[axis]) * entry.inverse_cell);
    return static_cast<std::int64_t>(std::clamp(t, 0.0, static_cast<double>(entry.dims[axis] - 1)));
  }
  [[nodiscard]] std::size_t cell_index(const Level& entry, const Vec3& centre) const {
    const std::int64_t x = clamp_cell(entry, 0, centre.x());
    const std::int64_t y = clamp_cell(entry, 1, centre.y());
    const std::int64_t z = clamp_cell(entry, 2, centre.z());
    return static_cast<std::size_t>((z * entry.dims[1] + y) * entry.dims[0] + x);
  }

  Vec3 lower_;
  std::vector<Level> levels_;
  std::vector<Item> items_;
  std::vector<std::int32_t> next_;
};

}  // namespace aggpack::detail
