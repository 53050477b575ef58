#pragma once
// Basic geometric value types (Eigen). Lengths are in metres unless stated otherwise.

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace aggpack {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Rigid placement of a body: x_world = rotation * x_local + position.
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();

  [[nodiscard]] Vec3 apply(const Vec3& local) const { return rotation * local + position; }
  [[nodiscard]] Vec3 apply_inverse(const Vec3& world) const {
    return rotation.conjugate() * (world - position);
  }
};

/// Axis-aligned bounding box.
struct Aabb {
  Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 upper = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void expand(const Vec3& point) {
    lower = lower.cwiseMin(point);
    upper = upper.cwiseMax(point);
  }
  [[nodiscard]] bool is_empty() const { return (lower.array() > upper.array()).any(); }
  [[nodiscard]] Vec3 extent() const { return upper - lower; }
};

}  // namespace aggpack
