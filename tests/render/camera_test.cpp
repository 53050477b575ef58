// Camera math (no OpenGL): framing, presets, arcball, pan, zoom, projection.

#include <gtest/gtest.h>

#include <cmath>

#include "aggpack/core/error.h"
#include "aggpack/render/camera.h"

namespace aggpack {
namespace {

Aabb box(const Vec3& lower, const Vec3& upper) {
  Aabb bounds;
  bounds.expand(lower);
  bounds.expand(upper);
  return bounds;
}

Eigen::Vector3d to_ndc(const Camera& camera, double aspect, const Vec3& point) {
  const Eigen::Vector4f clip =
      camera.projection_matrix(aspect) * camera.view_matrix() *
      Eigen::Vector4f(static_cast<float>(point.x()), static_cast<float>(point.y()),
                      static_cast<float>(point.z()), 1.0f);
  return Eigen::Vector3d(clip.x() / clip.w(), clip.y() / clip.w(), clip.z() / clip.w());
}

TEST(Camera, FramingKeepsEveryCornerOfTheBoxInView) {
  const Aabb bounds = box(Vec3(0, 0, 0), Vec3(3.0, 1.0, 2.8));
  for (ViewPreset view :
       {ViewPreset::kIso, ViewPreset::kFront, ViewPreset::kSide, ViewPreset::kTop}) {
    for (int variant = 0; variant < 4; ++variant) {
      const bool is_orthographic = (variant & 1) != 0;
      const double aspect = (variant & 2) ? 2.0 : 1.0;
      const Camera camera = Camera::framing(bounds, view, aspect, is_orthographic);
      double widest = 0.0;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1) ? 3.0 : 0.0, (c & 2) ? 1.0 : 0.0, (c & 4) ? 2.8 : 0.0);
        const Eigen::Vector3d ndc = to_ndc(camera, aspect, corner);
        EXPECT_LE(std::abs(ndc.x()), 1.0) << view_preset_name(view);
        EXPECT_LE(std::abs(ndc.y()), 1.0) << view_preset_name(view);
        EXPECT_GT(ndc.z(), -1.0);
        EXPECT_LT(ndc.z(), 1.0);
        widest = std::max({widest, std::abs(ndc.x()), std::abs(ndc.y())});
      }
      // ... and fills most of it (not a speck in the middle).
      EXPECT_GT(widest, 0.85) << view_preset_name(view) << " variant " << variant;
    }
  }
}

TEST(Camera, PresetsLookAlongTheDocumentedAxes) {
  const Aabb bounds = box(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  EXPECT_TRUE(Camera::framing(bounds, ViewPreset::kFront).back().isApprox(-Vec3::UnitY(), 1e-12));
  EXPECT_TRUE(Camera::framing(bounds, ViewPreset::kSide).back().isApprox(Vec3::UnitX(), 1e-12));
  EXPECT_TRUE(Camera::framing(bounds, ViewPreset::kTop).back().isApprox(Vec3::UnitZ(), 1e-12));
  const Camera iso = Camera::framing(bounds, ViewPreset::kIso);
  EXPECT_GT(iso.back().x(), 0.0);
  EXPECT_LT(iso.back().y(), 0.0);
  EXPECT_GT(iso.back().z(), 0.0);
  // z is up on screen for the side views.
  EXPECT_TRUE(Camera::framing(bounds, ViewPreset::kFront).up().isApprox(Vec3::UnitZ(), 1e-12));
  EXPECT_GT(iso.up().z(), 0.5);
}

TEST(Camera, ParsesViewNamesAndRejectsOthers) {
  for (ViewPreset view :
       {ViewPreset::kIso, ViewPreset::kFront, ViewPreset::kSide, ViewPreset::kTop}) {
    EXPECT_EQ(parse_view_preset(view_preset_name(view)), view);
  }
  try {
    parse_view_preset("back");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "--view");
    EXPECT_NE(std::string(error.what()).find("iso, front, side, top"), std::string::npos);
  }
}

TEST(Camera, ArcballDragRightTurnsTheSceneToTheRight) {
  Camera camera = Camera::framing(box(Vec3(-1, -1, -1), Vec3(1, 1, 1)), ViewPreset::kFront);
  const Vec3 target = camera.target();
  const double distance = camera.distance();
  // A point on the +x side of the scene, seen at the right of the screen.
  const Vec3 point(0.0, -1.0, 0.0);  // the point nearest the eye
  const double before = to_ndc(camera, 1.0, point).x();
  camera.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.3, 0.0));
  const double after = to_ndc(camera, 1.0, point).x();
  EXPECT_GT(after, before + 0.05);  // the front of the object moved right with the cursor
  // Rotation keeps the orbit: same target and distance, orthonormal axes.
  EXPECT_TRUE(camera.target().isApprox(target));
  EXPECT_DOUBLE_EQ(camera.distance(), distance);
  EXPECT_NEAR(camera.right().dot(camera.up()), 0.0, 1e-12);
  EXPECT_NEAR(camera.orientation().norm(), 1.0, 1e-12);
  // Dragging back returns to the start.
  camera.rotate_arcball(Eigen::Vector2d(0.3, 0.0), Eigen::Vector2d(0.0, 0.0));
  EXPECT_NEAR(to_ndc(camera, 1.0, point).x(), before, 1e-6);
}

TEST(Camera, PanFollowsTheCursorAndZoomScalesTheDistance) {
  Camera camera =
      Camera::framing(box(Vec3(-1, -1, -1), Vec3(1, 1, 1)), ViewPreset::kFront, 1.0, true);
  const int height = 500;
  const Vec3 point = camera.target();
  const Eigen::Vector3d before = to_ndc(camera, 1.0, point);
  camera.pan(50.0, 0.0, height);  // cursor 50 px right
  const Eigen::Vector3d after = to_ndc(camera, 1.0, point);
  // The point follows the cursor: 50 px of a 500 px tall viewport is 0.2 in NDC.
  EXPECT_NEAR(after.x() - before.x(), 0.2, 1e-5);
  EXPECT_NEAR(after.y() - before.y(), 0.0, 1e-6);
  camera.pan(0.0, 50.0, height);  // cursor 50 px down
  EXPECT_NEAR(to_ndc(camera, 1.0, point).y() - after.y(), -0.2, 1e-5);

  const double distance = camera.distance();
  camera.zoom(0.5);
  EXPECT_DOUBLE_EQ(camera.distance(), 0.5 * distance);
  camera.zoom(1e-12);  // clamped, never zero
  EXPECT_GT(camera.distance(), 0.0);
  camera.zoom(-1.0);  // ignored
  EXPECT_GT(camera.distance(), 0.0);
  camera.reset(ViewPreset::kFront);
  EXPECT_DOUBLE_EQ(camera.distance(), distance);
  EXPECT_TRUE(camera.target().isApprox(Vec3::Zero()));
}

TEST(Camera, PixelsPerMetreMatchesTheProjection) {
  Camera camera = Camera::framing(box(Vec3(0, 0, 0), Vec3(1, 1, 1)), ViewPreset::kTop);
  const int height = 800;
  const Vec3 a = camera.target();
  const Vec3 b = a + 0.1 * camera.up();
  const double ndc_step = to_ndc(camera, 1.0, b).y() - to_ndc(camera, 1.0, a).y();
  EXPECT_NEAR(ndc_step * 0.5 * height, 0.1 * camera.pixels_per_metre(camera.distance(), height),
              1e-3);
}

TEST(Camera, EmptyBoundsFrameTheUnitCube) {
  const Camera camera = Camera::framing(Aabb{}, ViewPreset::kIso);
  EXPECT_TRUE(camera.target().isApprox(Vec3::Constant(0.5)));
  EXPECT_TRUE(std::isfinite(camera.distance()));
}

}  // namespace
}  // namespace aggpack
