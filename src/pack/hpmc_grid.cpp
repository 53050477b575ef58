// The HPMC engine's cell grid (hpmc.h): building it for a sweep, cells of a position, adjacency,
// and the periodic box's wrapping of centres and images.

#include <algorithm>
#include <cmath>

#include "aggpack/pack/container.h"
#include "hpmc.h"

namespace aggpack::detail {

Hpmc::Image Hpmc::wrap(Vec3& position) const {
  Image periods = kSelf;
  if (!grid_.is_periodic) return periods;
  for (int axis = 0; axis < 3; ++axis) {
    if (!grid_.periodic[axis]) continue;
    const double period = grid_.period[axis];
    double& x = position[axis];
    if (x >= 0.0 && x < period) continue;
    double turns = std::floor(x / period);
    x -= turns * period;
    // Round-off leaves x a hair outside [0, period): it belongs at 0 (of the next period when
    // it came out as `period`).
    if (x >= period) {
      x = 0.0;
      turns += 1.0;
    } else if (x < 0.0) {
      x = 0.0;
    }
    periods[static_cast<std::size_t>(axis)] = static_cast<std::int8_t>(turns);
  }
  return periods;
}

Vec3 Hpmc::shift_of(const Image& image) const {
  return {image[0] * grid_.period[0], image[1] * grid_.period[1], image[2] * grid_.period[2]};
}

std::vector<Pose> Hpmc::wrapped_poses() const {
  std::vector<Pose> poses = poses_;
  for (Pose& pose : poses) (void)wrap(pose.position);
  return poses;
}

void Hpmc::build_grid(const Vec3& fractions) {
  const Aabb bounds = container_.bounds();
  const std::array<bool, 3> periodic = periodic_axes(container_);
  grid_.is_periodic = periodic[0] || periodic[1] || periodic[2];
  Vec3 shift = Vec3::Zero();
  std::size_t cells = 1;
  for (int axis = 0; axis < 3; ++axis) {
    const double extent = bounds.extent()[axis];
    grid_.periodic[axis] = periodic[static_cast<std::size_t>(axis)];
    grid_.period[axis] = grid_.periodic[axis] ? extent : 0.0;
    if (grid_.periodic[axis]) {
      // Cells tile the period. An even count keeps the checkerboard's two same-colour cells two
      // apart across the face too; a single cell has no same-colour neighbour along the axis.
      auto count = static_cast<std::int64_t>(std::floor(extent / grid_.width));
      if (count > 1 && count % 2 == 1) --count;
      count = std::max<std::int64_t>(1, count);
      grid_.dims[axis] = count;
      grid_.cell[axis] = extent / static_cast<double>(count);
      shift[axis] = fractions[axis] * grid_.cell[axis];
    } else {
      grid_.dims[axis] = static_cast<std::int64_t>(std::ceil(extent / grid_.width)) + 1;
      grid_.cell[axis] = grid_.width;
      shift[axis] = fractions[axis] * grid_.width;
    }
    cells *= static_cast<std::size_t>(grid_.dims[axis]);
  }
  grid_.origin = bounds.lower - shift;
  if (grid_.is_periodic) {
    for (Pose& pose : poses_) (void)wrap(pose.position);
  }
  grid_.start.assign(cells + 1, 0);
  grid_.cell_of.resize(poses_.size());
  for (std::size_t i = 0; i < poses_.size(); ++i) {
    const auto cell = static_cast<std::uint32_t>(cell_index(poses_[i].position));
    grid_.cell_of[i] = cell;
    ++grid_.start[cell + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) grid_.start[c + 1] += grid_.start[c];
  grid_.items.resize(poses_.size());
  std::vector<std::uint32_t> fill(grid_.start.begin(), grid_.start.end() - 1);
  // Ascending ids within a cell: the order moves are tried in.
  grid_.spheres.resize(poses_.size());
  grid_.slot_of.resize(poses_.size());
  for (std::size_t i = 0; i < poses_.size(); ++i) {
    const std::uint32_t slot = fill[grid_.cell_of[i]]++;
    grid_.items[slot] = static_cast<std::uint32_t>(i);
    grid_.slot_of[i] = slot;
    const Vec3& c = poses_[i].position;
    grid_.spheres[slot] = {c.x(), c.y(), c.z(), bodies_[body_of_[i]].outer};
  }
}

Hpmc::Image Hpmc::place(std::uint32_t i, const Pose& pose) {
  poses_[i] = pose;
  const Image periods = wrap(poses_[i].position);
  Grid::Sphere& sphere = grid_.spheres[grid_.slot_of[i]];
  sphere.x = poses_[i].position.x();
  sphere.y = poses_[i].position.y();
  sphere.z = poses_[i].position.z();
  return periods;
}

std::int64_t Hpmc::cell_index(const Vec3& position) const {
  std::int64_t c[3];
  for (int axis = 0; axis < 3; ++axis) {
    if (grid_.periodic[axis]) {
      // Wrapped: a centre just outside the period belongs to the cell across the face.
      const double t = std::floor((position[axis] - grid_.origin[axis]) / grid_.cell[axis]);
      const auto n = static_cast<double>(grid_.dims[axis]);
      c[axis] = static_cast<std::int64_t>(std::clamp(t - n * std::floor(t / n), 0.0, n - 1.0));
      continue;
    }
    const double t = std::floor((position[axis] - grid_.origin[axis]) / grid_.width);
    c[axis] =
        static_cast<std::int64_t>(std::clamp(t, 0.0, static_cast<double>(grid_.dims[axis] - 1)));
  }
  return (c[2] * grid_.dims[1] + c[1]) * grid_.dims[0] + c[0];
}

void Hpmc::cell_coordinates(std::int64_t cell, std::int64_t (&c)[3]) const {
  c[0] = cell % grid_.dims[0];
  c[1] = (cell / grid_.dims[0]) % grid_.dims[1];
  c[2] = cell / (grid_.dims[0] * grid_.dims[1]);
}

bool Hpmc::is_adjacent(std::uint32_t i, std::uint32_t j) const {
  std::int64_t a[3];
  std::int64_t b[3];
  cell_coordinates(grid_.cell_of[i], a);
  cell_coordinates(grid_.cell_of[j], b);
  for (int axis = 0; axis < 3; ++axis) {
    std::int64_t apart = a[axis] > b[axis] ? a[axis] - b[axis] : b[axis] - a[axis];
    if (grid_.periodic[axis]) apart = std::min(apart, grid_.dims[axis] - apart);
    if (apart > 1) return false;
  }
  return true;
}

}  // namespace aggpack::detail
