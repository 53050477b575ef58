// The 3D view of aggpack-gui: drawing the scene (light frames while the view moves, full-detail
// pictures in steps), --benchmark-frames timing, screenshots and mouse / keyboard input.

#define GLFW_INCLUDE_NONE
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "aggpack/core/error.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

namespace {

// Full-detail pictures timed after the moving frames in --benchmark-frames.
constexpr int kBenchmarkStillFrames = 5;
// Time a frame may spend on steps of a full-detail picture before it shows what it has (s).
constexpr double kFullFrameStepSeconds = 0.025;

}  // namespace

void GuiApp::render_scene_if_needed(int width, int height) {
  is_picture_new_ = false;
  if (!scene_target_ || scene_target_->width() != width || scene_target_->height() != height) {
    scene_target_ = std::make_unique<OffscreenTarget>(width, height, 0);
    has_picture_ = false;
    is_scene_dirty_ = true;
  }
  // While a new scene goes to OpenGL the last picture stays (the renderer cannot draw), and the
  // frame that finished the upload draws nothing more.
  if (renderer_->is_upload_pending() || std::exchange(is_upload_finished_now_, false)) return;
  const bool is_moving = is_interacting();
  const bool is_light = is_moving && needs_light_frames_;
  if (!is_scene_dirty_ && (is_moving || !renderer_->is_frame_pending())) return;
  const double start = glfwGetTime();
  detail_.set_full_budget(style_.triangle_budget);
  if (is_moving && !is_light) {
    // A scene whose full-detail picture fits the frame-time target stays in full detail while
    // the view moves: drawn at once, no light frame, nothing to refine after.
    scene_target_->bind();
    last_stats_ = renderer_->draw(camera_, width, height, style_);
    glFinish();
    last_scene_seconds_ = glfwGetTime() - start;
    last_picture_latency_ = last_scene_seconds_;
    needs_light_frames_ = last_picture_latency_ > detail_.target_seconds();
    is_drawn_scaled_ = false;
    is_preview_ = false;
    is_scene_dirty_ = false;
    has_picture_ = true;
    is_picture_new_ = true;
    return;
  }
  if (is_light) {
    // While the view moves, a light frame whose detail the controller fits to the frame-time
    // target (fewer mesh triangles, then a lower resolution, then fewer particles), drawn at
    // once; it abandons a full frame under way. The full frame follows when the view rests.
    RenderStyle style = style_;
    const DetailLevel level = detail_.level();
    style.triangle_budget = level.triangle_budget;
    style.max_particles = level.max_particles;
    OffscreenTarget* target = scene_target_.get();
    is_drawn_scaled_ = level.resolution_scale < 1.0;
    if (is_drawn_scaled_) {
      // At a lower resolution: drawn into a smaller target that frame() stretches over the view.
      const int light_width =
          std::max(1, static_cast<int>(std::lround(width * level.resolution_scale)));
      const int light_height =
          std::max(1, static_cast<int>(std::lround(height * level.resolution_scale)));
      if (!light_target_ || light_target_->width() != light_width ||
          light_target_->height() != light_height) {
        light_target_ = std::make_unique<OffscreenTarget>(light_width, light_height, 0);
      }
      target = light_target_.get();
    }
    target->bind();
    last_stats_ = renderer_->draw(camera_, target->width(), target->height(), style);
    // Finish here so the time measures the scene, not whatever comes later in the frame.
    glFinish();
    last_scene_seconds_ = glfwGetTime() - start;
    is_preview_ = true;
    was_light_frame_ = true;
    is_scene_dirty_ = false;
    has_picture_ = true;
    is_picture_new_ = true;
    return;
  }
  // The full-detail frame, drawn in steps over several frames into a target of its own while
  // the last picture stays on screen, so no frame of the program waits for all of it.
  if (!full_target_ || full_target_->width() != width || full_target_->height() != height) {
    full_target_ = std::make_unique<OffscreenTarget>(width, height, 0);
  }
  full_target_->bind();
  if (is_scene_dirty_) {
    renderer_->begin_frame(camera_, width, height, style_);
    full_frame_start_ = start;
    full_frame_seconds_ = 0.0;
    is_scene_dirty_ = false;
    is_preview_ = false;
  }
  // One step at least; more while this frame has time (the view stays empty until the first).
  bool is_done = false;
  do {
    is_done = renderer_->step_frame();
  } while (!is_done && glfwGetTime() - start < kFullFrameStepSeconds);
  if (is_done) glFinish();  // so the time measures the scene
  full_frame_seconds_ += glfwGetTime() - start;
  if (!is_done) return;
  std::swap(scene_target_, full_target_);
  is_drawn_scaled_ = false;
  last_stats_ = renderer_->frame_stats();
  last_scene_seconds_ = full_frame_seconds_;
  last_picture_latency_ = glfwGetTime() - full_frame_start_;
  // Light frames while moving only when a full-detail picture takes longer than the target
  // (drawn in one go: the work of the steps, not the frames between them).
  needs_light_frames_ = full_frame_seconds_ > detail_.target_seconds();
  has_picture_ = true;
  is_picture_new_ = true;
}

bool GuiApp::is_interacting() const {
  return dragging_button_ >= 0 || glfwGetTime() - last_scroll_time_ < 0.3 ||
         benchmark_phase_ == BenchmarkPhase::kMoving;
}

void GuiApp::start_benchmark() {
  benchmark_phase_ = BenchmarkPhase::kMoving;
  benchmark_left_ = options_.benchmark_frames;
  benchmark_frame_start_ = glfwGetTime();
  moving_times_ = FrameTimes{};
  still_times_ = FrameTimes{};
  detail_.reset();  // start from full detail, as a drag does after a long rest
}

void GuiApp::print_benchmark(const char* label, const FrameTimes& t) const {
  const double n = std::max(1, t.frames);
  const double pictures = std::max(1, t.scenes);
  const DrawStats& d = t.drawn;
  std::printf(
      "benchmark: %s: %d frames of %zu particles, on average %.0f drawn per picture (%.0f as "
      "impostors, %.0f mesh triangles): %.1f ms/frame (%.1f frames/s)",
      label, t.frames, renderer_->particle_count(),
      static_cast<double>(d.particles_drawn) / pictures,
      static_cast<double>(d.point_particles) / pictures,
      static_cast<double>(d.triangles) / pictures, 1e3 * t.wall / n, n / t.wall);
  if (t.settled_frames > 0) {
    std::printf("; second half %.1f ms/frame (%.1f frames/s)",
                1e3 * t.settled_wall / t.settled_frames, t.settled_frames / t.settled_wall);
  }
  std::printf("; longest frame %.1f ms", 1e3 * t.longest);
  std::printf(
      "\n  ms/frame: scene %.1f (frustum+sort %.1f, submit %.1f, depth read-back %.1f, occlusion "
      "test %.1f, rest = waiting for the rasteriser), blit %.1f, panel build %.1f, panel draw "
      "%.1f, swap %.1f\n",
      1e3 * t.scene / n, 1e3 * d.frustum_sort_seconds / n, 1e3 * d.submit_seconds / n,
      1e3 * d.depth_readback_seconds / n, 1e3 * d.occlusion_test_seconds / n, 1e3 * t.blit / n,
      1e3 * t.panel / n, 1e3 * t.ui_draw / n, 1e3 * t.swap / n);
  std::fflush(stdout);
}

void GuiApp::note_present_times(double ui_draw_seconds, double swap_seconds) {
  if (benchmark_phase_ == BenchmarkPhase::kOff) return;
  FrameTimes& t = benchmark_phase_ == BenchmarkPhase::kMoving ? moving_times_ : still_times_;
  const double now = glfwGetTime();
  const double wall = now - benchmark_frame_start_;
  benchmark_frame_start_ = now;
  const bool is_moving = benchmark_phase_ == BenchmarkPhase::kMoving;
  t.ui_draw += ui_draw_seconds;
  t.swap += swap_seconds;
  t.wall += wall;
  t.longest = std::max(t.longest, wall);
  if (is_moving && t.frames >= options_.benchmark_frames / 2) {
    t.settled_wall += wall;
    ++t.settled_frames;
  }
  ++t.frames;
  if (!is_moving) {
    // Still: the phase counts finished full-detail pictures (each over one or more frames).
    if (!is_picture_new_) return;
    t.picture_latency += last_picture_latency_;
  }
  if (--benchmark_left_ > 0) return;
  if (benchmark_phase_ == BenchmarkPhase::kMoving) {
    const DetailLevel level = detail_.level();
    print_benchmark("camera moving (light frames, adaptive detail)", t);
    std::printf("  while moving: %s (a full-detail picture took %.1f ms; target %.0f ms)\n",
                needs_light_frames_ ? "light frames" : "full detail", 1e3 * last_picture_latency_,
                1e3 * detail_.target_seconds());
    std::printf(
        "  detail reached: triangle budget %zu, resolution %.0f %%, at most %zu particles (0 = "
        "all); target %.0f ms/frame\n",
        level.triangle_budget, 100.0 * level.resolution_scale, level.max_particles,
        1e3 * detail_.target_seconds());
    benchmark_phase_ = BenchmarkPhase::kStill;
    benchmark_left_ = kBenchmarkStillFrames;
  } else {
    print_benchmark("view still (full detail, each picture redrawn)", t);
    std::printf(
        "  full-detail pictures: %d, each finished %.1f ms after it was begun, over %.1f "
        "frames on average\n",
        t.scenes, 1e3 * t.picture_latency / std::max(1, t.scenes),
        static_cast<double>(t.frames) / std::max(1, t.scenes));
    std::fflush(stdout);
    benchmark_phase_ = BenchmarkPhase::kOff;
  }
}

void GuiApp::save_screenshot(const std::string& path) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  try {
    write_png(read_framebuffer(0, 0, width, height), path);
    std::printf("screenshot: wrote %s (%dx%d)\n", path.c_str(), width, height);
    std::fflush(stdout);
    set_status(trs(Text::kSavedScreenshot, path), false);
  } catch (const Error& error) {
    std::fprintf(stderr, "aggpack-gui: error: %s\n", error.what());
    set_status(error_words(error), true);
    exit_code_ = 3;
  }
}

void GuiApp::on_mouse_button(int button, int action) {
  if (action == GLFW_PRESS) {
    glfwGetCursorPos(window_, &cursor_x_, &cursor_y_);
    if ((button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_RIGHT) &&
        is_in_view(cursor_x_, cursor_y_)) {
      dragging_button_ = button;
    }
  } else if (action == GLFW_RELEASE && button == dragging_button_) {
    dragging_button_ = -1;
  }
}

void GuiApp::on_cursor(double x, double y) {
  const double dx = x - cursor_x_, dy = y - cursor_y_;
  if (dragging_button_ >= 0 && (dx != 0.0 || dy != 0.0)) {
    int width = 0, height = 0;
    glfwGetWindowSize(window_, &width, &height);
    const double left = panel_width();
    const double view_width = std::max(1.0, width - left);
    const double view_height = std::max(1, height);
    if (dragging_button_ == GLFW_MOUSE_BUTTON_LEFT) {
      // Arcball in the view's normalised coordinates; the shorter side spans [-1, 1].
      const double half = 0.5 * std::min(view_width, view_height);
      auto ndc = [&](double px, double py) {
        return Eigen::Vector2d((px - left - 0.5 * view_width) / half,
                               (0.5 * view_height - py) / half);
      };
      camera_.rotate_arcball(ndc(cursor_x_, cursor_y_), ndc(x, y));
    } else {
      camera_.pan(dx, dy, static_cast<int>(view_height));
    }
    is_scene_dirty_ = true;
  }
  cursor_x_ = x;
  cursor_y_ = y;
}

void GuiApp::on_scroll(double dy) {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  if (!is_in_view(x, y)) return;
  camera_.zoom(std::pow(0.85, dy));
  last_scroll_time_ = glfwGetTime();
  is_scene_dirty_ = true;
}

}  // namespace aggpack::gui
