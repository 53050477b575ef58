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

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pipeline/pipeline.h"

namespace aggpack::gui {

namespace {

constexpr float kPanelWidth = 360.0f;

// Colour bar for the scale colour modes.
void draw_legend(const ParticleColors& colors) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const float height = 12.0f;
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const Rgb c = scale_color((k + 0.5) / kSteps);
    const float x0 = origin.x + width * static_cast<float>(k) / kSteps;
    const float x1 = origin.x + width * static_cast<float>(k + 1) / kSteps;
    draw->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1, origin.y + height),
                        IM_COL32(c.r, c.g, c.b, 255));
  }
  ImGui::Dummy(ImVec2(width, height));
  ImGui::Text("%.4g", colors.minimum);
  ImGui::SameLine(width - ImGui::CalcTextSize(fmt::format("{:.4g}", colors.maximum).c_str()).x);
  ImGui::Text("%.4g", colors.maximum);
  ImGui::TextDisabled("%s", colors.quantity.c_str());
}

}  // namespace

GuiApp::GuiApp(GLFWwindow* window, GuiOptions options)
    : window_(window), options_(std::move(options)) {
  // The configuration fills the fields (defaults: the paper's case); errors are the CLI's.
  const PackConfig config = options_.config_path
                                ? load_pack_config(*options_.config_path, options_.overrides)
                                : parse_pack_config("", "defaults", options_.overrides);
  fields_ = ConfigFields::from_config(config);
  style_ = options_.style;
  view_ = options_.view;
  export_base_ = options_.export_base;
  mesomodel_itz_mm_ = options_.mesomodel_itz_mm;
  renderer_ = std::make_unique<PackingRenderer>();
  // Show the empty container until there is a packing.
  Packing empty;
  empty.container = config.container();
  renderer_->set_packing(empty);
  reset_view();
  if (options_.open_path) {
    open_path_ = *options_.open_path;
    start_open(open_path_);
    is_waiting_for_first_job_ = true;
  } else if (options_.is_pack_at_start) {
    is_waiting_for_first_job_ = true;
    start_pack();
  } else if (options_.screenshot_path || options_.is_quit_when_done) {
    frames_since_job_ = 0;  // nothing to wait for: screenshot / quit after two frames
  }
}

GuiApp::~GuiApp() {
  job_.request_cancel();
  job_.wait();
}

bool GuiApp::is_busy() const {
  return job_.is_running() || benchmark_phase_ != BenchmarkPhase::kOff ||
         is_waiting_for_first_job_ || is_preview_ || is_scene_dirty_ ||
         (renderer_ && renderer_->is_frame_pending()) ||
         (frames_since_job_ >= 0 && frames_since_job_ < 3) || dragging_button_ >= 0;
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

void GuiApp::start_pack() {
  if (job_.is_running()) return;
  // Validate on this thread so a bad field is reported at once, with the CLI's message.
  PackConfig config;
  try {
    config = fields_.build();
  } catch (const Error& error) {
    set_status(error.what(), true);
    if (is_waiting_for_first_job_) exit_code_ = 2;
    return;
  }
  set_status("Packing...", false);
  job_.start("Packing", [config](BackgroundJob& job) {
    PackControl control;
    control.cancel = job.cancel_flag();
    control.progress_interval = 0.05;
    control.on_progress = [&job](const PackProgress& progress) {
      job.set_progress(progress.fraction);
      job.set_detail(
          fmt::format("{} {} of {}, solid fraction {:.1f} %",
                      progress.stage == PackStage::kDensify ? "densify: sweep" : "placed",
                      progress.placed, progress.total, 100.0 * progress.solid_fraction));
    };
    PipelineResult result = pack(config, control);
    JobResult out;
    const bool is_cancelled = result.report.stop_reason == StopReason::kCancelled;
    out.is_ok = true;
    out.message = fmt::format(
        "{} {} particles, solid fraction {:.2f} %.\n{}",
        is_cancelled ? "Cancelled:" : "Packing finished!", result.packing.particles.size(),
        100.0 * result.report.solid_fraction,
        result.fill ? "fill: " + result.fill->report.summary() : result.report.summary());
    // The dense kind: the densifier, the asked fraction, and what fell short of it.
    if (result.densify) out.message += "\ndensify: " + result.densify->summary();
    if (result.fill && result.fill->asked_fraction > 0) {
      out.message += fmt::format(" (asked {:.2f} %)", 100.0 * result.fill->asked_fraction);
    }
    for (const std::string& line : dense_shortfalls(result)) out.message += "\nWarning: " + line;
    out.packing = std::make_shared<const Packing>(std::move(result.packing));
    return out;
  });
}

void GuiApp::start_open(const std::string& path) {
  if (job_.is_running()) return;
  set_status("Opening " + path + "...", false);
  job_.start("Opening", [path](BackgroundJob&) {
    JobResult out;
    auto packing = std::make_shared<const Packing>(read_packing(path));
    out.is_ok = true;
    double solid = 0.0;
    for (std::size_t i = 0; i < packing->particles.size(); ++i) {
      solid += mass_properties(packing->local_body(i)).volume;
    }
    const double volume = packing->container.volume();
    out.message = fmt::format("Opened {}: {} particles, solid fraction {:.2f} %.", path,
                              packing->particles.size(), volume > 0 ? 100.0 * solid / volume : 0.0);
    out.config_toml = packing->provenance.config_toml;
    out.packing = std::move(packing);
    return out;
  });
}

void GuiApp::start_export(const std::string& format) {
  if (job_.is_running() || !packing_) return;
  const ExportOptions options{.format = parse_export_format(format),
                              .overwrite = Overwrite::kAllow};
  const std::string path = export_base_ + "." + format_name(options.format);
  set_status("Writing " + path + "...", false);
  job_.start("Exporting", [packing = packing_, options, path](BackgroundJob&) {
    JobResult out;
    const ExportSummary summary = write(*packing, path, options);
    out.message = fmt::format("Wrote {}: {} particles, {} nodes, {} elements.", path,
                              summary.particles, summary.nodes, summary.elements);
    out.is_ok = true;
    return out;
  });
}

void GuiApp::show_packing(std::shared_ptr<const Packing> packing) {
  const Aabb old_bounds = renderer_->scene_bounds();
  renderer_->set_packing(*packing);
  packing_ = std::move(packing);
  // Keep the user's camera when the scene did not move (re-pack with new shape parameters);
  // refit when the container changed.
  const Aabb& bounds = renderer_->scene_bounds();
  const bool is_same_scene =
      !old_bounds.is_empty() && !bounds.is_empty() &&
      (old_bounds.lower - bounds.lower).norm() + (old_bounds.upper - bounds.upper).norm() <
          1e-3 * bounds.extent().norm();
  if (!is_same_scene) reset_view();
  is_scene_dirty_ = true;
}

void GuiApp::poll_job() {
  JobResult result;
  if (!job_.take_result(result)) return;
  std::string message = result.message;
  if (!result.config_toml.empty()) {
    // An opened file: its stored configuration fills the panel, so Pack repeats or varies it.
    try {
      fields_ = ConfigFields::from_config(parse_pack_config(result.config_toml, "stored config"));
      message += " The panel shows its configuration.";
    } catch (const Error&) {
      message += " Its stored configuration is not readable; the panel is unchanged.";
    }
  }
  set_status(message, !result.is_ok);
  if (result.packing) show_packing(result.packing);
  if (is_waiting_for_first_job_ && result.is_ok && options_.mesomodel_export &&
      !is_mesomodel_script_started_) {  // scripted: the mesomodel export follows, wait for it
    is_mesomodel_script_started_ = true;
    start_mesomodel_export(*options_.mesomodel_export);
    if (job_.is_running()) return;
    exit_code_ = 2;  // refused before it started (the status line says why)
  }
  if (is_waiting_for_first_job_) {
    is_waiting_for_first_job_ = false;
    frames_since_job_ = 0;
    if (!result.is_ok) exit_code_ = 2;
    if (options_.benchmark_frames > 0) start_benchmark();
  }
}

void GuiApp::frame() {
  poll_job();
  const double frame_start = glfwGetTime();
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
  const int view_x = static_cast<int>(std::lround(panel_width() * scale));
  const int view_width = std::max(1, fb_width - view_x);
  const int view_height = std::max(1, fb_height);

  const bool is_benchmark = benchmark_phase_ != BenchmarkPhase::kOff;
  if (is_benchmark && !renderer_->is_frame_pending()) {
    // Turn the scene a little every frame (still: every finished picture) so it is redrawn.
    camera_.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.02, 0.0));
    is_scene_dirty_ = true;
  }
  const double scene_start = glfwGetTime();
  render_scene_if_needed(view_width, view_height);
  const double blit_start = glfwGetTime();
  if (is_drawn_scaled_) {
    light_target_->blit_stretched(0, view_x, 0, view_width, view_height);
  } else {
    scene_target_->blit(0, view_x, 0);
  }
  if (is_benchmark) glFinish();
  const double panel_start = glfwGetTime();
  draw_panel();
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

  if (frames_since_job_ >= 0) ++frames_since_job_;
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
  // Scripted runs: act once the first job's result has been on screen for two frames (the
  // status line and the scene are then drawn) and any benchmark is over.
  if (frames_since_job_ < 2 || benchmark_phase_ != BenchmarkPhase::kOff || is_script_done_ ||
      is_scene_dirty_ || renderer_->is_frame_pending()) {
    return;
  }
  is_script_done_ = true;
  // The status line of the finished job (a screenshot below replaces it on screen) and the
  // configuration the panel would pack next (the keys of `aggpack pack --set`).
  std::printf("status: %s\n", status_.c_str());
  std::string panel;
  for (const auto& entry : fields_.set_entries()) panel += " " + entry;
  std::printf("panel:%s\n", panel.c_str());
  if (options_.screenshot_path) save_screenshot(*options_.screenshot_path);
  std::fflush(stdout);
  if (options_.is_quit_when_done) should_quit_ = true;
}

void GuiApp::draw_panel() {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(panel_width()), static_cast<float>(height)));
  ImGui::Begin("aggpack", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  // Pack / Cancel, the progress and the status first: always in view, however many keys the
  // chosen packer shows below (the dense kind adds its densify keys).
  draw_job_section();
  ImGui::PushItemWidth(-150.0f);
  draw_config_section("Container", {"container"});
  draw_config_section("Particle shape", {"particle"});
  draw_config_section("Packer and grading", {"packer", "grading", "densify"});
  ImGui::PopItemWidth();
  draw_file_section();
  draw_view_section();
  ImGui::End();
}

void GuiApp::draw_job_section() {
  if (job_.is_running()) {
    ImGui::BeginDisabled();
    ImGui::Button("Pack", ImVec2(120, 0));
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(-1, 0))) job_.request_cancel();
    const std::string detail = job_.detail();
    ImGui::ProgressBar(static_cast<float>(job_.progress()), ImVec2(-1, 0),
                       detail.empty() ? job_.name().c_str() : nullptr);
    if (!detail.empty()) ImGui::TextWrapped("%s", detail.c_str());
  } else {
    if (ImGui::Button("Pack", ImVec2(120, 0))) start_pack();
    ImGui::SameLine();
    ImGui::TextDisabled("(Enter)");
  }
  if (is_status_error_) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", status_.c_str());
    ImGui::PopStyleColor();
  } else {
    ImGui::TextWrapped("%s", status_.c_str());
  }
  ImGui::Separator();
}

void GuiApp::draw_file_section() {
  if (!ImGui::CollapsingHeader("Open and export", ImGuiTreeNodeFlags_DefaultOpen)) return;
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer), "%s", open_path_.c_str());
  ImGui::PushItemWidth(-70.0f);
  if (ImGui::InputText("##open", buffer, sizeof(buffer))) open_path_ = buffer;
  ImGui::PopItemWidth();
  ImGui::SameLine();
  if (ImGui::Button("Open", ImVec2(-1, 0)) && !job_.is_running()) start_open(open_path_);
  std::snprintf(buffer, sizeof(buffer), "%s", export_base_.c_str());
  ImGui::PushItemWidth(-70.0f);
  if (ImGui::InputText("##export", buffer, sizeof(buffer))) export_base_ = buffer;
  ImGui::PopItemWidth();
  ImGui::SameLine();
  ImGui::TextDisabled("name");
  const bool can_export = packing_ != nullptr && !job_.is_running();
  if (!can_export) ImGui::BeginDisabled();
  int k = 0;
  for (const FormatInfo& info : export_formats()) {  // five buttons a line
    if (k++ % 5 != 0) ImGui::SameLine();
    if (ImGui::Button(std::string(info.title).c_str())) start_export(std::string(info.name));
  }
  if (!can_export) ImGui::EndDisabled();
  draw_mesomodel_export(can_export);
}

void GuiApp::draw_view_section() {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  bool is_changed = false;
  int color = static_cast<int>(style_.color);
  ImGui::Text("Colour by");
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("particle", &color, 0);
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("size", &color, 1);
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("alpha", &color, 2);
  style_.color = static_cast<ColorMode>(color);
  is_changed |= ImGui::Checkbox("wireframe", &style_.is_wireframe);
  ImGui::SameLine();
  is_changed |= ImGui::Checkbox("container", &style_.show_container);
  ImGui::SameLine();
  bool is_orthographic = camera_.is_orthographic();
  if (ImGui::Checkbox("ortho", &is_orthographic)) {
    camera_.set_orthographic(is_orthographic);
    reset_view();
  }
  const ViewPreset presets[] = {ViewPreset::kIso, ViewPreset::kFront, ViewPreset::kSide,
                                ViewPreset::kTop};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) ImGui::SameLine();
    if (ImGui::Button(view_preset_name(presets[k]))) {
      view_ = presets[k];
      reset_view();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset View (R)")) reset_view();
  float coarse = static_cast<float>(style_.coarse_below_pixels);
  if (ImGui::SliderFloat("coarse below px", &coarse, 0.0f, 64.0f, "%.0f")) {
    style_.coarse_below_pixels = coarse;
    is_changed = true;
  }
  int budget = static_cast<int>(style_.triangle_budget / 1000);
  if (ImGui::SliderInt("triangle budget (k)", &budget, 0, 5000,
                       budget == 0 ? "no limit" : "%d k")) {
    style_.triangle_budget = static_cast<std::size_t>(budget) * 1000;
    is_scene_dirty_ = true;
  }
  if (style_.color != ColorMode::kParticle && renderer_->particle_count() > 0) {
    draw_legend(renderer_->colors(style_.color));
  }
  ImGui::TextDisabled("%zu particles, %zu distinct shapes", renderer_->particle_count(),
                      renderer_->shape_count());
  ImGui::TextDisabled("in view %zu, drawn %zu (%zu coarse, %zu points)",
                      last_stats_.particles_in_frustum, last_stats_.particles_drawn,
                      last_stats_.coarse_particles, last_stats_.point_particles);
  ImGui::TextDisabled("%.2f M triangles", last_stats_.triangles / 1e6);
  ImGui::TextDisabled("scene %.1f ms%s; UI %.0f frames/s", 1e3 * last_scene_seconds_,
                      renderer_->is_frame_pending() ? " (refining)"
                      : is_preview_                 ? " (light frame)"
                                                    : "",
                      ImGui::GetIO().Framerate);
  const DetailLevel level = detail_.level();
  ImGui::TextDisabled(
      "moving: %zu k triangles, %.0f %% resolution, %s particles (%.0f ms target)",
      level.triangle_budget / 1000, 100.0 * level.resolution_scale,
      level.max_particles == 0 ? "all" : fmt::format("{} k", level.max_particles / 1000).c_str(),
      1e3 * detail_.target_seconds());
  ImGui::TextDisabled("left drag: rotate, right drag: pan, wheel: zoom,");
  ImGui::TextDisabled("R: reset view, Enter: pack, Esc: cancel, F12: screenshot");
  if (is_changed) is_scene_dirty_ = true;
}

}  // namespace aggpack::gui
