#include "aggpack/render/camera.h"

#include <algorithm>
#include <cmath>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// Camera axes from the direction towards the eye and an approximate up vector.
Quat orientation_from(const Vec3& back, const Vec3& up_hint) {
  const Vec3 z = back.normalized();
  const Vec3 x = up_hint.cross(z).normalized();
  const Vec3 y = z.cross(x);
  Mat3 axes;
  axes.col(0) = x;
  axes.col(1) = y;
  axes.col(2) = z;
  return Quat(axes).normalized();
}

// Shoemake/Bell arcball: points inside the unit disc lie on the sphere, points outside on the
// hyperbolic sheet, so dragging past the rim keeps turning smoothly.
Vec3 arcball_point(const Eigen::Vector2d& ndc) {
  const double squared = ndc.squaredNorm();
  if (squared <= 0.5) return Vec3(ndc.x(), ndc.y(), std::sqrt(1.0 - squared));
  return Vec3(ndc.x(), ndc.y(), 0.5 / std::sqrt(squared)).normalized();
}

}  // namespace

ViewPreset parse_view_preset(const std::string& text, const std::string& field) {
  if (text == "iso") return ViewPreset::kIso;
  if (text == "front") return ViewPreset::kFront;
  if (text == "side") return ViewPreset::kSide;
  if (text == "top") return ViewPreset::kTop;
  throw InvalidInput(field, text, "iso, front, side, top");
}

const char* view_preset_name(ViewPreset view) {
  switch (view) {
    case ViewPreset::kIso:
      return "iso";
    case ViewPreset::kFront:
      return "front";
    case ViewPreset::kSide:
      return "side";
    case ViewPreset::kTop:
      return "top";
  }
  return "iso";
}

Camera Camera::framing(const Aabb& bounds, ViewPreset view, double aspect, bool is_orthographic) {
  Camera camera;
  camera.is_orthographic_ = is_orthographic;
  camera.scene_ = bounds;
  if (bounds.is_empty()) {
    camera.scene_ = Aabb{};
    camera.scene_.expand(Vec3::Zero());
    camera.scene_.expand(Vec3::Ones());
  }
  camera.reset(view, aspect);
  return camera;
}

void Camera::reset(ViewPreset view, double aspect) {
  if (!(aspect > 0.0) || !std::isfinite(aspect)) aspect = 1.0;
  target_ = 0.5 * (scene_.lower + scene_.upper);
  scene_radius_ = std::max(0.5 * scene_.extent().norm(), 1e-9);
  switch (view) {
    case ViewPreset::kIso:
      orientation_ = orientation_from(Vec3(0.8, -1.5, 0.95), Vec3::UnitZ());
      break;
    case ViewPreset::kFront:
      orientation_ = orientation_from(-Vec3::UnitY(), Vec3::UnitZ());
      break;
    case ViewPreset::kSide:
      orientation_ = orientation_from(Vec3::UnitX(), Vec3::UnitZ());
      break;
    case ViewPreset::kTop:
      orientation_ = orientation_from(Vec3::UnitZ(), Vec3::UnitY());
      break;
  }
  // Fit the box itself, not only its bounding sphere: project the corners on the camera axes
  // and back off until the widest of them fits the vertical field of view with a 5% margin
  // (the sphere alone leaves flat boxes small in the picture).
  const double tan_half = std::tan(0.5 * field_of_view_);
  double needed = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 point((corner & 1) ? scene_.upper.x() : scene_.lower.x(),
                     (corner & 2) ? scene_.upper.y() : scene_.lower.y(),
                     (corner & 4) ? scene_.upper.z() : scene_.lower.z());
    const Vec3 local = orientation_.conjugate() * (point - target_);
    const double half_size = std::max(std::abs(local.x()) / aspect, std::abs(local.y()));
    // Perspective: the corner at depth local.z fits when distance - local.z >= half / tan.
    // Orthographic: the half height is distance * tan, whatever the depth.
    needed = std::max(needed, half_size / tan_half + (is_orthographic_ ? 0.0 : local.z()));
  }
  distance_ = std::max(needed * 1.05, 1e-3 * scene_radius_);
  // Orthographic still needs the eye outside the scene for the near plane.
  if (is_orthographic_) distance_ = std::max(distance_, 1.05 * scene_radius_);
}

void Camera::rotate_arcball(const Eigen::Vector2d& from_ndc, const Eigen::Vector2d& to_ndc) {
  const Vec3 from = arcball_point(from_ndc);
  const Vec3 to = arcball_point(to_ndc);
  if ((from - to).squaredNorm() < 1e-18) return;
  // The rotation that carries `from` to `to` in camera coordinates turns the scene; the camera
  // turns the opposite way about the target.
  const Quat turn = Quat::FromTwoVectors(from, to);
  orientation_ = (orientation_ * turn.conjugate()).normalized();
}

void Camera::pan(double dx_pixels, double dy_pixels, int viewport_height) {
  const double metres_per_pixel = 1.0 / pixels_per_metre(distance_, std::max(viewport_height, 1));
  target_ += (-dx_pixels * right() + dy_pixels * up()) * metres_per_pixel;
}

void Camera::zoom(double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) return;
  distance_ = std::clamp(distance_ * factor, 1e-3 * scene_radius_, 1e3 * scene_radius_);
}

Vec3 Camera::eye() const { return target_ + distance_ * back(); }

double Camera::pixels_per_metre(double depth, int viewport_height) const {
  const double tan_half = std::tan(0.5 * field_of_view_);
  const double visible_height = 2.0 * tan_half * (is_orthographic_ ? distance_ : depth);
  return static_cast<double>(viewport_height) / std::max(visible_height, 1e-12);
}

Eigen::Matrix4f Camera::view_matrix() const {
  const Mat3 to_camera = orientation_.conjugate().toRotationMatrix();
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.topLeftCorner<3, 3>() = to_camera;
  view.topRightCorner<3, 1>() = -(to_camera * eye());
  return view.cast<float>();
}

Eigen::Matrix4f Camera::projection_matrix(double aspect) const {
  aspect = aspect > 0.0 ? aspect : 1.0;
  // Near/far enclose the scene sphere around the (possibly panned) target, with room for the
  // scene to sit off-centre after a pan.
  const double reach = 2.0 * scene_radius_ + (target_ - 0.5 * (scene_.lower + scene_.upper)).norm();
  const double far_plane = distance_ + reach;
  const double near_plane = std::max(distance_ - reach, far_plane * 1e-4);
  const double tan_half = std::tan(0.5 * field_of_view_);
  Eigen::Matrix4d projection = Eigen::Matrix4d::Zero();
  if (is_orthographic_) {
    const double half_height = distance_ * tan_half;
    projection(0, 0) = 1.0 / (aspect * half_height);
    projection(1, 1) = 1.0 / half_height;
    projection(2, 2) = -2.0 / (far_plane - near_plane);
    projection(2, 3) = -(far_plane + near_plane) / (far_plane - near_plane);
    projection(3, 3) = 1.0;
  } else {
    projection(0, 0) = 1.0 / (aspect * tan_half);
    projection(1, 1) = 1.0 / tan_half;
    projection(2, 2) = -(far_plane + near_plane) / (far_plane - near_plane);
    projection(2, 3) = -2.0 * far_plane * near_plane / (far_plane - near_plane);
    projection(3, 2) = -1.0;
  }
  return projection.cast<float>();
}

}  // namespace aggpack
