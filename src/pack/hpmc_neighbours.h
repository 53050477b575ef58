#pragma once
// Internal: the HPMC engine's neighbour search (hpmc.h), walled and periodic; included by
// hpmc.cpp only.

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "hpmc.h"

namespace aggpack::detail {

template <class Visit>
bool Hpmc::for_each_image(std::uint32_t i, const Vec3& centre, std::uint32_t j, double gap,
                          Visit&& visit) const {
  const Grid::Sphere& sphere = grid_.spheres[grid_.slot_of[j]];
  const double reach = bodies_[body_of_[i]].outer + gap + sphere.radius;
  const double apart[3] = {sphere.x - centre.x(), sphere.y - centre.y(), sphere.z - centre.z()};
  // The nearest image is the closest one along every axis at once: when even it is out of
  // reach, so is every image (the common case, decided without the enumeration below).
  double nearest_squared = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    double d = apart[axis];
    if (grid_.periodic[axis]) d -= grid_.period[axis] * std::round(d / grid_.period[axis]);
    nearest_squared += d * d;
  }
  if (nearest_squared >= reach * reach) return true;
  // Per axis the periods that bring j within reach: along a periodic axis the nearest image and
  // the ones beside it (a period only just larger than the reach admits two), else none.
  std::int8_t periods[3][3];
  double along[3][3];
  int counts[3] = {0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    if (!grid_.periodic[axis]) {
      if (std::abs(apart[axis]) < reach) {
        periods[axis][counts[axis]] = 0;
        along[axis][counts[axis]++] = apart[axis];
      }
    } else {
      const double period = grid_.period[axis];
      const double nearest = -std::round(apart[axis] / period);
      for (double m = nearest - 1.0; m <= nearest + 1.0; m += 1.0) {
        const double d = apart[axis] + m * period;
        if (std::abs(d) < reach) {
          periods[axis][counts[axis]] = static_cast<std::int8_t>(m);
          along[axis][counts[axis]++] = d;
        }
      }
    }
    if (counts[axis] == 0) return true;
  }
  for (int a = 0; a < counts[0]; ++a) {
    for (int b = 0; b < counts[1]; ++b) {
      for (int c = 0; c < counts[2]; ++c) {
        const double dx = along[0][a];
        const double dy = along[1][b];
        const double dz = along[2][c];
        if (dx * dx + dy * dy + dz * dz >= reach * reach) continue;
        if (!visit(Image{periods[0][a], periods[1][b], periods[2][c]})) return false;
      }
    }
  }
  return true;
}

template <class Visit>
void Hpmc::for_each_close_periodic(std::uint32_t i, const Vec3& centre, double gap,
                                   Visit&& visit) const {
  std::int64_t c[3];
  cell_coordinates(grid_.cell_of[i], c);
  // Per axis the distinct neighbour cells: wrapped along a periodic axis (every cell when there
  // are at most three; images then come from for_each_image), clipped along a walled one.
  std::int64_t cells[3][3];
  int counts[3] = {0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t n = grid_.dims[axis];
    if (grid_.periodic[axis] && n <= 3) {
      for (std::int64_t m = 0; m < n; ++m) cells[axis][counts[axis]++] = m;
    } else if (grid_.periodic[axis]) {
      for (std::int64_t m = c[axis] - 1; m <= c[axis] + 1; ++m) {
        cells[axis][counts[axis]++] = (m + n) % n;
      }
    } else {
      for (std::int64_t m = std::max<std::int64_t>(0, c[axis] - 1);
           m <= std::min(n - 1, c[axis] + 1); ++m) {
        cells[axis][counts[axis]++] = m;
      }
    }
  }
  for (int z = 0; z < counts[2]; ++z) {
    for (int y = 0; y < counts[1]; ++y) {
      for (int x = 0; x < counts[0]; ++x) {
        const auto cell = static_cast<std::size_t>(
            (cells[2][z] * grid_.dims[1] + cells[1][y]) * grid_.dims[0] + cells[0][x]);
        for (std::uint32_t k = grid_.start[cell]; k < grid_.start[cell + 1]; ++k) {
          const std::uint32_t j = grid_.items[k];
          // Never i itself: its images are more than its own reach away (require_periodic_room).
          if (j == i) continue;
          if (!for_each_image(i, centre, j, gap,
                              [&](const Image& image) { return visit(j, image); })) {
            return;
          }
        }
      }
    }
  }
}

template <class Visit>
void Hpmc::for_each_close(std::uint32_t i, const Vec3& centre, double gap, Visit&& visit) const {
  if (grid_.is_periodic) {
    for_each_close_periodic(i, centre, gap, visit);
    return;
  }
  const double reach_i = bodies_[body_of_[i]].outer + gap;
  std::int64_t c[3];
  cell_coordinates(grid_.cell_of[i], c);
  for (std::int64_t z = std::max<std::int64_t>(0, c[2] - 1);
       z <= std::min(grid_.dims[2] - 1, c[2] + 1); ++z) {
    for (std::int64_t y = std::max<std::int64_t>(0, c[1] - 1);
         y <= std::min(grid_.dims[1] - 1, c[1] + 1); ++y) {
      const auto row = (z * grid_.dims[1] + y) * grid_.dims[0];
      const auto first = static_cast<std::size_t>(row + std::max<std::int64_t>(0, c[0] - 1));
      const auto last = static_cast<std::size_t>(row + std::min(grid_.dims[0] - 1, c[0] + 1));
      // The cells of a row are contiguous in the CSR arrays.
      for (std::uint32_t k = grid_.start[first]; k < grid_.start[last + 1]; ++k) {
        const Grid::Sphere& sphere = grid_.spheres[k];
        const double dx = sphere.x - centre.x();
        const double dy = sphere.y - centre.y();
        const double dz = sphere.z - centre.z();
        const double reach = reach_i + sphere.radius;
        if (dx * dx + dy * dy + dz * dz >= reach * reach) continue;
        const std::uint32_t j = grid_.items[k];
        if (j != i && !visit(j, kSelf)) return;
      }
    }
  }
}

}  // namespace aggpack::detail
