// The cylinder container kind: axis along z through x = y = 0, z in [0, height]. Everything
// aggpack needs to know about a cylinder (parameters, geometry, physics walls, outline, scaling)
// is in this file.
#include "aggpack/pack/container_cylinder.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace aggpack {

namespace {

constexpr int kWallSegments = 64;     // boxes approximating the side wall for the physics
constexpr int kOutlineSegments = 96;  // segments of each drawn circle

// Area of the disc of radius r centred at 0 with coordinate <= x: the full disc minus the
// circular segment beyond x (segment area = r^2 acos(x/r) - x sqrt(r^2 - x^2)).
double disc_area_below(double r, double x) {
  x = std::clamp(x, -r, r);
  const double segment = r * r * std::acos(x / r) - x * std::sqrt(std::max(0.0, r * r - x * x));
  return std::numbers::pi * r * r - segment;
}

}  // namespace

const std::vector<KindParam<CylinderContainer>>& CylinderContainer::params() {
  static const std::vector<KindParam<CylinderContainer>> list{
      {"radius", "cylinder radius (axis x = y = 0)", &CylinderContainer::radius},
      {"height", "cylinder height (z from 0)", &CylinderContainer::height}};
  return list;
}

Aabb CylinderContainer::bounds() const {
  Aabb box;
  box.lower = Vec3(-radius, -radius, 0.0);
  box.upper = Vec3(radius, radius, height);
  return box;
}

double CylinderContainer::volume() const { return std::numbers::pi * radius * radius * height; }

double CylinderContainer::floor_area() const { return std::numbers::pi * radius * radius; }

double CylinderContainer::smallest_extent() const { return std::min(2.0 * radius, height); }

double CylinderContainer::clearance(const Vec3& point) const {
  const double radial = radius - std::hypot(point.x(), point.y());
  const double axial = std::min(point.z(), height - point.z());
  if (radial >= 0.0 && axial >= 0.0) return std::min(radial, axial);
  return -std::hypot(std::max(0.0, -radial), std::max(0.0, -axial));
}

bool CylinderContainer::contains(const ConvexPolyhedron& body, const Mat3& rotation,
                                 const Vec3& position, double gap) const {
  const double inner = radius - gap;
  const double inner_squared = inner * inner;
  for (const Vec3& vertex : body.vertices()) {
    const Vec3 world = rotation * vertex + position;
    if (world.z() < gap || world.z() > height - gap) return false;
    if (world.x() * world.x() + world.y() * world.y() > inner_squared) return false;
  }
  return true;
}

bool CylinderContainer::is_in_centre_region(double margin, const Vec3& centre) const {
  const double inner = radius - margin;
  return inner >= 0.0 && centre.z() >= margin && centre.z() <= height - margin &&
         centre.x() * centre.x() + centre.y() * centre.y() <= inner * inner;
}

double CylinderContainer::slab_volume(int axis, double lo, double hi) const {
  if (axis == 2) return std::numbers::pi * radius * radius * (hi - lo);
  return height * (disc_area_below(radius, hi) - disc_area_below(radius, lo));
}

std::vector<ContainerWall> CylinderContainer::walls(double thickness, double min_height) const {
  const double t = thickness;
  const double r = radius;
  const double h = std::max(height, min_height);
  std::vector<ContainerWall> list{
      ContainerWall::from_box({Vec3(-r - t, -r - t, -t), Vec3(r + t, r + t, 0.0)})};  // floor
  // The side wall: boxes whose inner faces are tangent to the cylinder, each a little wider than
  // its chord so that neighbours overlap.
  const double half_chord = r * std::tan(std::numbers::pi / kWallSegments) * 1.02;
  for (int k = 0; k < kWallSegments; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kWallSegments;
    list.push_back({Vec3((r + 0.5 * t) * std::cos(angle), (r + 0.5 * t) * std::sin(angle), 0.5 * h),
                    Vec3(0.5 * t, half_chord, 0.5 * h), angle});
  }
  return list;
}

std::vector<OutlineSegment> CylinderContainer::outline() const {
  std::vector<OutlineSegment> segments;
  for (int k = 0; k < kOutlineSegments; ++k) {
    const double a0 = 2.0 * std::numbers::pi * k / kOutlineSegments;
    const double a1 = 2.0 * std::numbers::pi * (k + 1) / kOutlineSegments;
    for (double z : {0.0, height}) {
      segments.push_back({Vec3(radius * std::cos(a0), radius * std::sin(a0), z),
                          Vec3(radius * std::cos(a1), radius * std::sin(a1), z)});
    }
    if (k % (kOutlineSegments / 4) == 0) {
      segments.push_back({Vec3(radius * std::cos(a0), radius * std::sin(a0), 0.0),
                          Vec3(radius * std::cos(a0), radius * std::sin(a0), height)});
    }
  }
  return segments;
}

Vec3 CylinderContainer::ratio(const CylinderContainer& other) const {
  const double radial = other.radius / radius;
  return {radial, radial, other.height / height};
}

CylinderContainer CylinderContainer::scaled(const Vec3& factor) const {
  return {radius * factor.x(), height * factor.z()};
}

std::vector<Vec3> CylinderContainer::prism_floor(int sides) const {
  // Side k is tangent to the circle at angle 2 pi k / sides; its corners lie halfway between.
  const double corner = radius / std::cos(std::numbers::pi / sides);
  std::vector<Vec3> ring;
  ring.reserve(static_cast<std::size_t>(sides));
  for (int k = 0; k < sides; ++k) {
    const double angle = std::numbers::pi * (2.0 * k + 1.0) / sides;
    ring.emplace_back(corner * std::cos(angle), corner * std::sin(angle), 0.0);
  }
  return ring;
}

bool CylinderContainer::is_on_prism_side(const Vec3& point, int sides, double tolerance) const {
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / sides;
    if (std::cos(angle) * point.x() + std::sin(angle) * point.y() >= radius - tolerance) {
      return true;
    }
  }
  return false;
}

}  // namespace aggpack
