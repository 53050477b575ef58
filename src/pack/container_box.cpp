// The box container kind: [0, length] x [0, width] x [0, depth]. Everything aggpack needs to know
// about a box (parameters, geometry, physics walls, outline, scaling) is in this file.
#include "aggpack/pack/container_box.h"

#include <algorithm>
#include <limits>

namespace aggpack {

const std::vector<KindParam<BoxContainer>>& BoxContainer::params() {
  static const std::vector<KindParam<BoxContainer>> list{
      {"length", "box extent along x", &BoxContainer::length},
      {"width", "box extent along y", &BoxContainer::width},
      {"depth", "box extent along z (vertical)", &BoxContainer::depth}};
  return list;
}

Aabb BoxContainer::bounds() const {
  Aabb box;
  box.lower = Vec3::Zero();
  box.upper = Vec3(length, width, depth);
  return box;
}

double BoxContainer::volume() const { return length * width * depth; }

double BoxContainer::floor_area() const { return length * width; }

double BoxContainer::smallest_extent() const { return std::min({length, width, depth}); }

double BoxContainer::clearance(const Vec3& point) const {
  const Vec3 upper(length, width, depth);
  Vec3 below = (-point).cwiseMax(0.0);         // how far below the lower walls
  Vec3 above = (point - upper).cwiseMax(0.0);  // how far above the upper walls
  // A periodic axis has no walls: it adds nothing outside and bounds nothing inside.
  double inside = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (periodic[static_cast<std::size_t>(axis)]) {
      below[axis] = 0.0;
      above[axis] = 0.0;
    } else {
      inside = std::min({inside, point[axis], upper[axis] - point[axis]});
    }
  }
  const double outside = (below + above).norm();
  if (outside > 0.0) return -outside;
  return inside;
}

bool BoxContainer::contains(const ConvexPolyhedron& body, const Mat3& rotation,
                            const Vec3& position, double gap) const {
  // Per coordinate (not via clearance) to keep it branch-light in the packers' inner loop.
  // A periodic axis has no walls: its bounds are infinite.
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  Vec3 lower = Vec3::Constant(gap);
  Vec3 upper = Vec3(length, width, depth) - Vec3::Constant(gap);
  for (int axis = 0; axis < 3; ++axis) {
    if (periodic[static_cast<std::size_t>(axis)]) {
      lower[axis] = -kUnbounded;
      upper[axis] = kUnbounded;
    }
  }
  for (const Vec3& vertex : body.vertices()) {
    const Vec3 world = rotation * vertex + position;
    if ((world.array() < lower.array()).any() || (world.array() > upper.array()).any()) {
      return false;
    }
  }
  return true;
}

bool BoxContainer::is_in_centre_region(double margin, const Vec3& centre) const {
  Aabb region = bounds();
  for (int axis = 0; axis < 3; ++axis) {
    // A periodic axis: any centre in [0, extent] (the packers keep centres there).
    if (periodic[static_cast<std::size_t>(axis)]) continue;
    region.lower[axis] += margin;
    region.upper[axis] -= margin;
  }
  return (centre.array() >= region.lower.array()).all() &&
         (centre.array() <= region.upper.array()).all();
}

double BoxContainer::slab_volume(int axis, double lo, double hi) const {
  Vec3 extent = bounds().extent();
  extent[axis] = hi - lo;
  return extent.prod();
}

std::vector<ContainerWall> BoxContainer::walls(double thickness, double min_height) const {
  const double t = thickness;
  const double l = length;
  const double w = width;
  const double h = std::max(depth, min_height);
  return {ContainerWall::from_box({Vec3(-t, -t, -t), Vec3(l + t, w + t, 0.0)}),  // floor
          ContainerWall::from_box({Vec3(-t, -t, 0.0), Vec3(0.0, w + t, h)}),     // x = 0
          ContainerWall::from_box({Vec3(l, -t, 0.0), Vec3(l + t, w + t, h)}),    // x = length
          ContainerWall::from_box({Vec3(0.0, -t, 0.0), Vec3(l, 0.0, h)}),        // y = 0
          ContainerWall::from_box({Vec3(0.0, w, 0.0), Vec3(l, w + t, h)})};      // y = width
}

std::vector<OutlineSegment> BoxContainer::outline() const {
  std::vector<OutlineSegment> segments;
  const Aabb box = bounds();
  if (box.is_empty()) return segments;
  auto corner = [&box](int c) {
    return Vec3((c & 1) ? box.upper.x() : box.lower.x(), (c & 2) ? box.upper.y() : box.lower.y(),
                (c & 4) ? box.upper.z() : box.lower.z());
  };
  for (int c = 0; c < 8; ++c) {
    for (int bit : {1, 2, 4}) {
      if ((c & bit) == 0) segments.push_back({corner(c), corner(c | bit)});
    }
  }
  return segments;
}

Vec3 BoxContainer::ratio(const BoxContainer& other) const {
  return {other.length / length, other.width / width, other.depth / depth};
}

BoxContainer BoxContainer::scaled(const Vec3& factor) const {
  return {.length = length * factor.x(),
          .width = width * factor.y(),
          .depth = depth * factor.z(),
          .periodic = periodic};
}

std::vector<Vec3> BoxContainer::prism_floor(int /*sides*/) const {
  return {Vec3(0, 0, 0), Vec3(length, 0, 0), Vec3(length, width, 0), Vec3(0, width, 0)};
}

bool BoxContainer::is_on_prism_side(const Vec3& point, int /*sides*/, double tolerance) const {
  return point.x() <= tolerance || point.y() <= tolerance || point.x() >= length - tolerance ||
         point.y() >= width - tolerance;
}

}  // namespace aggpack
