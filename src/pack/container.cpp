#include "aggpack/pack/container.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// Area of the disc of radius r centred at 0 with coordinate <= x: the full disc minus the
// circular segment beyond x (segment area = r^2 acos(x/r) - x sqrt(r^2 - x^2)).
double disc_area_below(double r, double x) {
  x = std::clamp(x, -r, r);
  const double segment = r * r * std::acos(x / r) - x * std::sqrt(std::max(0.0, r * r - x * x));
  return std::numbers::pi * r * r - segment;
}

}  // namespace

const std::vector<ContainerKindInfo>& container_kinds() {
  static const std::vector<ContainerKindInfo> kinds = [] {
    Container box;
    box.kind = ContainerKind::kBox;
    Container cylinder;
    cylinder.kind = ContainerKind::kCylinder;
    return std::vector<ContainerKindInfo>{
        {ContainerKind::kBox,
         "box",
         "box [0,length]x[0,width]x[0,depth]",
         {{"length", "box extent along x", [](const Container& c) { return c.length; },
           [](Container& c, double v) { c.length = v; }},
          {"width", "box extent along y", [](const Container& c) { return c.width; },
           [](Container& c, double v) { c.width = v; }},
          {"depth", "box extent along z (vertical)", [](const Container& c) { return c.depth; },
           [](Container& c, double v) { c.depth = v; }}},
         box},
        {ContainerKind::kCylinder,
         "cylinder",
         "cylinder about the z axis",
         {{"radius", "cylinder radius (axis x = y = 0)",
           [](const Container& c) { return c.radius; },
           [](Container& c, double v) { c.radius = v; }},
          {"height", "cylinder height (z from 0)", [](const Container& c) { return c.height; },
           [](Container& c, double v) { c.height = v; }}},
         cylinder}};
  }();
  return kinds;
}

const ContainerKindInfo& container_kind_info(ContainerKind kind) {
  for (const auto& info : container_kinds()) {
    if (info.kind == kind) return info;
  }
  throw InvalidInput("container.kind", std::to_string(static_cast<int>(kind)), "box or cylinder");
}

Aabb Container::bounds() const {
  Aabb box;
  if (kind == ContainerKind::kBox) {
    box.lower = Vec3::Zero();
    box.upper = Vec3(length, width, depth);
  } else {
    box.lower = Vec3(-radius, -radius, 0.0);
    box.upper = Vec3(radius, radius, height);
  }
  return box;
}

double Container::volume() const {
  if (kind == ContainerKind::kBox) return length * width * depth;
  return std::numbers::pi * radius * radius * height;
}

void validate(const Container& container) {
  if (!std::isfinite(container.wall_gap) || container.wall_gap < 0.0) {
    throw InvalidInput("container.wall_gap", format_value(container.wall_gap), "finite and >= 0");
  }
  double smallest = 0.0;
  if (container.kind == ContainerKind::kBox) {
    require_positive("container.length", container.length);
    require_positive("container.width", container.width);
    require_positive("container.depth", container.depth);
    smallest = std::min({container.length, container.width, container.depth});
  } else if (container.kind == ContainerKind::kCylinder) {
    require_positive("container.radius", container.radius);
    require_positive("container.height", container.height);
    smallest = std::min(2.0 * container.radius, container.height);
  } else {
    throw InvalidInput("container.kind", std::to_string(static_cast<int>(container.kind)),
                       "box or cylinder");
  }
  if (2.0 * container.wall_gap >= smallest) {
    throw InvalidInput(
        "container.wall_gap", format_value(container.wall_gap),
        "< half the smallest container extent (" + format_value(smallest / 2.0) + " m)");
  }
}

double wall_clearance(const Container& container, const Vec3& point) {
  if (container.kind == ContainerKind::kBox) {
    const Vec3 upper(container.length, container.width, container.depth);
    const Vec3 below = (-point).cwiseMax(0.0);         // how far below the lower walls
    const Vec3 above = (point - upper).cwiseMax(0.0);  // how far above the upper walls
    const double outside = (below + above).norm();
    if (outside > 0.0) return -outside;
    return std::min(point.minCoeff(), (upper - point).minCoeff());
  }
  const double radial = container.radius - std::hypot(point.x(), point.y());
  const double axial = std::min(point.z(), container.height - point.z());
  if (radial >= 0.0 && axial >= 0.0) return std::min(radial, axial);
  return -std::hypot(std::max(0.0, -radial), std::max(0.0, -axial));
}

double wall_clearance(const Container& container, const ConvexPolyhedron& body, const Pose& pose) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const Vec3& vertex : body.vertices()) {
    clearance = std::min(clearance, wall_clearance(container, pose.apply(vertex)));
  }
  return clearance;
}

bool contains(const Container& container, const ConvexPolyhedron& body, const Pose& pose) {
  // Inside the container shrunk by wall_gap <=> per-wall clearance >= wall_gap; checked per
  // coordinate (not via wall_clearance) to keep it branch-light in the packers' inner loop.
  const double gap = container.wall_gap;
  const Mat3 rotation = pose.rotation.toRotationMatrix();
  if (container.kind == ContainerKind::kBox) {
    const Vec3 lower = Vec3::Constant(gap);
    const Vec3 upper =
        Vec3(container.length, container.width, container.depth) - Vec3::Constant(gap);
    for (const Vec3& vertex : body.vertices()) {
      const Vec3 world = rotation * vertex + pose.position;
      if ((world.array() < lower.array()).any() || (world.array() > upper.array()).any()) {
        return false;
      }
    }
    return true;
  }
  const double radius = container.radius - gap;
  const double radius_squared = radius * radius;
  for (const Vec3& vertex : body.vertices()) {
    const Vec3 world = rotation * vertex + pose.position;
    if (world.z() < gap || world.z() > container.height - gap) return false;
    if (world.x() * world.x() + world.y() * world.y() > radius_squared) return false;
  }
  return true;
}

Aabb centre_region(const Container& container, double radius) {
  const double margin = radius + container.wall_gap;
  Aabb region = container.bounds();
  region.lower.array() += margin;
  region.upper.array() -= margin;
  return region;
}

bool is_in_centre_region(const Container& container, double radius, const Vec3& centre) {
  const double margin = radius + container.wall_gap;
  if (container.kind == ContainerKind::kBox) {
    const Aabb region = centre_region(container, radius);
    return (centre.array() >= region.lower.array()).all() &&
           (centre.array() <= region.upper.array()).all();
  }
  const double inner = container.radius - margin;
  return inner >= 0.0 && centre.z() >= margin && centre.z() <= container.height - margin &&
         centre.x() * centre.x() + centre.y() * centre.y() <= inner * inner;
}

double container_slab_volume(const Container& container, int axis, double lo, double hi) {
  if (axis < 0 || axis > 2) throw InvalidInput("axis", std::to_string(axis), "0, 1 or 2");
  const Aabb box = container.bounds();
  lo = std::max(lo, box.lower[axis]);
  hi = std::min(hi, box.upper[axis]);
  if (hi <= lo) return 0.0;
  if (container.kind == ContainerKind::kBox) {
    Vec3 extent = box.extent();
    extent[axis] = hi - lo;
    return extent.prod();
  }
  if (axis == 2) return std::numbers::pi * container.radius * container.radius * (hi - lo);
  return container.height *
         (disc_area_below(container.radius, hi) - disc_area_below(container.radius, lo));
}

}  // namespace aggpack
