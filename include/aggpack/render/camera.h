#pragma once
// Orbit camera for viewing a packing: a target point, a distance and an orientation, with the
// interactions of the GUI (arcball rotate, pan, zoom) and the fixed views of `aggpack render`.
// Pure math: no OpenGL, so it is tested without a context. World units are metres, z is up.

#include <string>

#include <Eigen/Core>

#include "aggpack/geom/vec.h"

namespace aggpack {

/// Fixed viewing directions (z up). kIso looks from the front-right-top corner (+x, -y, +z);
/// kFront looks along +y (from -y), kSide along -x (from +x), kTop down along -z.
enum class ViewPreset { kIso, kFront, kSide, kTop };

/// "iso" | "front" | "side" | "top". \throw InvalidInput naming `field` otherwise.
ViewPreset parse_view_preset(const std::string& text, const std::string& field = "--view");
/// The name parse_view_preset accepts for `view`.
const char* view_preset_name(ViewPreset view);

/// An orbit camera. A value type: copy it freely.
class Camera {
 public:
  /// Camera looking at `bounds` from `view`, at a distance where the whole box is in sight in a
  /// viewport of `aspect` = width / height (> 0), with perspective or orthographic projection.
  /// An empty box is treated as the unit cube at the origin.
  static Camera framing(const Aabb& bounds, ViewPreset view = ViewPreset::kIso, double aspect = 1.0,
                        bool is_orthographic = false);

  /// Orients the camera to `view` and refits the distance and target to the scene bounds for a
  /// viewport of `aspect` = width / height (> 0; other values are taken as 1) and the current
  /// projection.
  void reset(ViewPreset view, double aspect = 1.0);

  /// Arcball rotation (Shoemake) between two cursor positions in normalised device coordinates
  /// (x right, y up, both in [-1, 1] across the viewport). The scene turns with the cursor.
  void rotate_arcball(const Eigen::Vector2d& from_ndc, const Eigen::Vector2d& to_ndc);
  /// Moves the target in the view plane so the scene follows a cursor move of (dx, dy) pixels
  /// (x right, y down as window systems report) in a viewport `viewport_height` pixels tall.
  void pan(double dx_pixels, double dy_pixels, int viewport_height);
  /// Multiplies the distance to the target by `factor` (> 0; < 1 zooms in). Clamped to
  /// [1e-3, 1e3] times the scene radius.
  void zoom(double factor);

  /// World-to-camera matrix (camera looks down its -z axis).
  [[nodiscard]] Eigen::Matrix4f view_matrix() const;
  /// Camera-to-clip matrix for `aspect` = width / height (> 0). Near and far planes enclose the
  /// scene sphere.
  [[nodiscard]] Eigen::Matrix4f projection_matrix(double aspect) const;
  /// Eye position in world coordinates (m).
  [[nodiscard]] Vec3 eye() const;
  /// Unit camera axes in world coordinates.
  [[nodiscard]] Vec3 right() const { return orientation_ * Vec3::UnitX(); }
  [[nodiscard]] Vec3 up() const { return orientation_ * Vec3::UnitY(); }
  /// Unit vector from the target towards the eye.
  [[nodiscard]] Vec3 back() const { return orientation_ * Vec3::UnitZ(); }

  /// Pixels per metre at view depth `depth` (> 0, m, along the viewing direction) for a viewport
  /// `viewport_height` pixels tall: converts sizes in the scene to sizes on screen.
  [[nodiscard]] double pixels_per_metre(double depth, int viewport_height) const;

  [[nodiscard]] const Vec3& target() const { return target_; }
  [[nodiscard]] double distance() const { return distance_; }
  [[nodiscard]] const Quat& orientation() const { return orientation_; }
  /// Vertical field of view (radians).
  [[nodiscard]] double field_of_view() const { return field_of_view_; }
  [[nodiscard]] bool is_orthographic() const { return is_orthographic_; }
  /// Switches between perspective (default) and orthographic projection, keeping target and
  /// distance (call reset() to refit).
  void set_orthographic(bool is_orthographic) { is_orthographic_ = is_orthographic; }

 private:
  Aabb scene_;                                 // bounds the camera was fitted to
  Vec3 target_ = Vec3::Zero();                 // point the camera orbits (m)
  double distance_ = 1.0;                      // eye to target (m)
  double scene_radius_ = 1.0;                  // half the diagonal of scene_ (m)
  Quat orientation_ = Quat::Identity();        // camera axes in world coordinates
  double field_of_view_ = 0.5235987755982988;  // 30 degrees
  bool is_orthographic_ = false;
};

}  // namespace aggpack
