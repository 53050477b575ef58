#include "gui_app.h"

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
#include <map>
#include <string_view>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/shape/generator.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

namespace {

constexpr float kPanelWidth = 360.0f;

}  // namespace

GuiApp::GuiApp(GLFWwindow* window, GuiOptions options)
    : window_(window), options_(std::move(options)) {
  // The configuration fills the fields (defaults: the paper's case); errors are the CLI's.
  const PackConfig config = options_.config_path
                                ? load_pack_config(*options_.config_path, options_.overrides)
                                : parse_pack_config("", "defaults", options_.overrides);
  fields_ = ConfigFields::from_config(config);
  settings_ = GuiSettings::load(GuiSettings::folder_of(options_.settings_dir));
  choose_language();
  style_ = options_.style;
  if (style_.color == ColorMode::kParticle) style_.color = static_cast<ColorMode>(settings_.color);
  style_.show_container = settings_.show_container;
  show_fps_ = settings_.show_fps;
  view_ = options_.view;
  export_base_ = options_.export_base;
  mesomodel_itz_mm_ = options_.mesomodel_itz_mm;
  mesomodel_itz_kind_ = options_.mesomodel_itz_kind;
  renderer_ = std::make_unique<PackingRenderer>();
  warm_up_renderer();
  // Show the empty container until there is a packing.
  Packing empty;
  empty.container = config.container();
  renderer_->set_packing(empty);
  reset_view();
  if (options_.open_path) {
    open_path_ = *options_.open_path;
    start_open(open_path_);
    script_.start(true, false);
  } else if (options_.is_pack_at_start) {
    script_.start(true, false);
    start_pack();
  } else {
    script_.start(false, options_.screenshot_path || options_.is_quit_when_done);
  }
}

void GuiApp::warm_up_renderer() {
  // The software renderer compiles a shader the first time it draws with it (over 100 ms on
  // llvmpipe): draw three particles once, meshes (instanced and single) and discs, at start-up
  // rather than in the first frame that shows a packing.
  Packing tiny;
  const GeneratorOptions shape{.alpha = 0.5, .radius_min = 0.1, .radius_max = 0.1, .seed = 1};
  tiny.shapes = {generate_particle(shape, 0).body, generate_particle(shape, 1).body};
  for (std::uint32_t k = 0; k < 3; ++k) {
    Particle particle;
    particle.shape = k / 2;
    particle.pose.position = Vec3(0.3 * k, 0.0, 0.0);
    tiny.particles.push_back(particle);
  }
  renderer_->set_packing(tiny);
  OffscreenTarget target(64, 64, 0);
  target.bind();
  const Camera camera = Camera::framing(renderer_->scene_bounds());
  RenderStyle style;
  style.coarse_below_pixels = 0.0;
  (void)renderer_->draw(camera, 64, 64, style);
  style.point_below_pixels = 1e6;
  (void)renderer_->draw(camera, 64, 64, style);
  glFinish();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

GuiApp::~GuiApp() {
  job_.request_cancel();
  job_.wait();
  settings_.color = static_cast<int>(style_.color);
  settings_.show_fps = show_fps_;
  settings_.show_container = style_.show_container;
  settings_.save(GuiSettings::folder_of(options_.settings_dir));
}

bool GuiApp::is_busy() const {
  return job_.is_running() || benchmark_phase_ != BenchmarkPhase::kOff || script_.is_busy() ||
         is_preview_ || is_scene_dirty_ ||
         (renderer_ && (renderer_->is_frame_pending() || renderer_->is_upload_pending())) ||
         dragging_button_ >= 0;
}

int GuiApp::panel_width() const {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  return std::min(static_cast<int>(kPanelWidth), width / 2);
}

bool GuiApp::is_in_view(double x, double /*y*/) const {
  return x >= panel_width() && !ImGui::GetIO().WantCaptureMouse;
}

void GuiApp::set_status(std::string text, bool is_error) {
  status_ = std::move(text);
  is_status_error_ = is_error;
}

void GuiApp::reset_view() {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  const double view_width = std::max(1, width - panel_width());
  const bool is_orthographic = camera_.is_orthographic();
  camera_ = Camera::framing(renderer_->scene_bounds(), view_, view_width / std::max(1, height),
                            is_orthographic);
  is_scene_dirty_ = true;
}

void GuiApp::show_packing(std::shared_ptr<const Packing> packing, std::shared_ptr<SceneData> scene,
                          std::vector<std::string> entries) {
  if (!scene) scene = prepare_scene(*packing);
  try {
    upload_.begin(*renderer_, std::move(packing), std::move(scene), std::move(entries));
  } catch (const Error& error) {
    set_status(error_words(error), true);
    return;
  }
  finish_upload_if_done();
}

void GuiApp::finish_upload_if_done() {
  if (!upload_.step(*renderer_)) return;
  is_upload_finished_now_ = true;
  const Aabb old_bounds = packing_ ? last_bounds_ : Aabb{};
  UploadScheduler::Uploaded uploaded = upload_.take();
  packing_ = std::move(uploaded.packing);
  packing_entries_ = std::move(uploaded.entries);
  // Keep the user's camera when the scene did not move (re-pack with new shape parameters);
  // refit when the container changed.
  const Aabb& bounds = renderer_->scene_bounds();
  const bool is_same_scene =
      !old_bounds.is_empty() && !bounds.is_empty() &&
      (old_bounds.lower - bounds.lower).norm() + (old_bounds.upper - bounds.upper).norm() <
          1e-3 * bounds.extent().norm();
  if (!is_same_scene) reset_view();
  last_bounds_ = bounds;
  is_scene_dirty_ = true;
}

void GuiApp::frame() {
  const double frame_start = glfwGetTime();
  poll_job();
  finish_upload_if_done();
  update_field_errors();
  if (was_light_frame_ && last_frame_start_ >= 0.0) {
    detail_.update(frame_start - last_frame_start_, last_stats_.triangles,
                   last_stats_.particles_drawn);
  }
  was_light_frame_ = false;
  last_frame_start_ = frame_start;
  if (is_preview_ && !is_interacting()) is_scene_dirty_ = true;  // refine after the move
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window_, &fb_width, &fb_height);
  int win_width = 0, win_height = 0;
  glfwGetWindowSize(window_, &win_width, &win_height);
  const double scale = win_width > 0 ? static_cast<double>(fb_width) / win_width : 1.0;
  // The view: right of the panel, between the menu bar and the status bar (last frame's sizes).
  const int view_x = static_cast<int>(std::lround(panel_width() * scale));
  const int view_y = static_cast<int>(std::lround(status_height_ * scale));
  const int view_width = std::max(1, fb_width - view_x);
  const int view_height =
      std::max(1, fb_height - view_y - static_cast<int>(std::lround(menu_height_ * scale)));

  const bool is_benchmark = benchmark_phase_ != BenchmarkPhase::kOff;
  if (is_benchmark && !renderer_->is_frame_pending()) {
    // Turn the scene a little every frame (still: every finished picture) so it is redrawn.
    camera_.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.02, 0.0));
    is_scene_dirty_ = true;
  }
  const double scene_start = glfwGetTime();
  render_scene_if_needed(view_width, view_height);
  const double blit_start = glfwGetTime();
  // Behind the panels: the window is cleared once, then the scene is copied into the view.
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb_width, fb_height);
  glClearColor(style_.background.r / 255.0f, style_.background.g / 255.0f,
               style_.background.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (is_drawn_scaled_) {
    light_target_->blit_stretched(0, view_x, view_y, view_width, view_height);
  } else if (has_picture_) {
    scene_target_->blit(0, view_x, view_y);
  }
  if (is_benchmark) glFinish();
  const double panel_start = glfwGetTime();
  draw_menu_bar();
  draw_status_bar();
  draw_panel();
  draw_view_overlays();
  draw_help_window();
  draw_file_dialog();
  if (is_benchmark) {
    FrameTimes& t = benchmark_phase_ == BenchmarkPhase::kMoving ? moving_times_ : still_times_;
    t.scene += blit_start - scene_start;
    t.blit += panel_start - blit_start;
    t.panel += glfwGetTime() - panel_start;
    // Once per finished picture: a full-detail one keeps its stats over the frames it takes.
    if (is_picture_new_) {
      t.drawn += last_stats_;
      ++t.scenes;
    }
  }

  script_.count_frame();
}

void GuiApp::after_render() {
  // --benchmark-frames with --screenshot: also the last moving (light) frame, FILE-moving.png.
  if (benchmark_phase_ == BenchmarkPhase::kMoving && benchmark_left_ == 1 &&
      options_.screenshot_path) {
    std::filesystem::path path(*options_.screenshot_path);
    path.replace_filename(path.stem().string() + "-moving" + path.extension().string());
    const double start = glfwGetTime();
    save_screenshot(path.string());
    benchmark_frame_start_ += glfwGetTime() - start;  // writing the PNG is not part of the frame
  }
  if (is_screenshot_requested_) {
    is_screenshot_requested_ = false;
    save_screenshot(options_.screenshot_path.value_or("aggpack-gui.png"));
  }
  script_.after_render();
}

}  // namespace aggpack::gui
