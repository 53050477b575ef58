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
#include <limits>
#include <map>
#include <string_view>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pipeline/pipeline.h"
#include "aggpack/shape/generator.h"

namespace aggpack::gui {

namespace {

constexpr float kPanelWidth = 360.0f;

// The last item's tooltip.
void item_tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

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

// Builds the job's packing's scene on the worker (the window uploads it in pieces).
void build_scene(BackgroundJob& job, JobResult& out) {
  job.set_name("Building the scene");
  job.set_progress(0.0);
  job.set_detail(fmt::format("{} particles", out.packing->particles.size()));
  out.scene = prepare_scene(*out.packing, [&job](double fraction) { job.set_progress(fraction); });
}

// "ETA 12 s" from the time taken so far and the fraction done ("" too early to say).
std::string eta_text(double elapsed, double fraction) {
  if (fraction < 0.02 || elapsed < 1.0 || fraction >= 1.0) return "";
  const double left = elapsed * (1.0 - fraction) / fraction;
  if (left < 60.0) return fmt::format(", about {:.0f} s left", left);
  return fmt::format(", about {:.0f} min {:02.0f} s left", std::floor(left / 60.0),
                     std::fmod(left, 60.0));
}

}  // namespace

std::string plain_error(std::string message) {
  // The panel is the origin: no "gui: " or "--set KEY=VALUE: " before the message.
  for (const std::string_view prefix :
       {std::string_view("gui: "), std::string_view("defaults: ")}) {
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
  }
  if (message.rfind("--set ", 0) == 0) {
    const auto colon = message.find(": ");
    if (colon != std::string::npos) message.erase(0, colon + 2);
  }
  // "invalid KEY = VALUE (allowed: RANGE)" -> "KEY: VALUE is not allowed; allowed: RANGE".
  const std::string lead = "invalid ";
  const auto equals = message.find(" = ");
  const auto allowed = message.find(" (allowed: ");
  if (message.rfind(lead, 0) == 0 && equals != std::string::npos && allowed != std::string::npos &&
      equals < allowed) {
    const std::string key = message.substr(lead.size(), equals - lead.size());
    // Only a configuration key ("particle.alpha"); other subjects keep their sentence.
    if (key.find(' ') != std::string::npos || key.find('.') == std::string::npos) return message;
    const std::string value = message.substr(equals + 3, allowed - equals - 3);
    std::string rest = message.substr(allowed + 11);
    const auto close = rest.rfind(')');
    if (close != std::string::npos) rest.erase(close, 1);
    return key + ": " + value + " is not allowed; allowed: " + rest;
  }
  return message;
}

GuiApp::GuiApp(GLFWwindow* window, GuiOptions options)
    : window_(window), options_(std::move(options)) {
  // The configuration fills the fields (defaults: the paper's case); errors are the CLI's.
  const PackConfig config = options_.config_path
                                ? load_pack_config(*options_.config_path, options_.overrides)
                                : parse_pack_config("", "defaults", options_.overrides);
  fields_ = ConfigFields::from_config(config);
  settings_ = GuiSettings::load(GuiSettings::folder_of(options_.settings_dir));
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
    is_waiting_for_first_job_ = true;
  } else if (options_.is_pack_at_start) {
    is_waiting_for_first_job_ = true;
    start_pack();
  } else if (options_.screenshot_path || options_.is_quit_when_done) {
    frames_since_job_ = 0;  // nothing to wait for: screenshot / quit after two frames
  }
  is_timing_frames_script_ = is_waiting_for_first_job_;
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
  return job_.is_running() || benchmark_phase_ != BenchmarkPhase::kOff ||
         is_waiting_for_first_job_ || is_preview_ || is_scene_dirty_ ||
         (renderer_ && (renderer_->is_frame_pending() || renderer_->is_upload_pending())) ||
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
  update_field_errors();
  try {
    config = fields_.build();
  } catch (const Error& error) {
    set_status(plain_error(error.what()), true);
    if (is_waiting_for_first_job_) exit_code_ = 2;
    return;
  }
  set_status("Packing...", false);
  job_entries_ = fields_.set_entries();
  job_kind_ = "pack";
  job_.start("Packing", [config](BackgroundJob& job) {
    PackControl control;
    control.cancel = job.cancel_flag();
    control.progress_interval = 0.05;
    control.on_progress = [&job](const PackProgress& progress) {
      job.set_progress(progress.fraction);
      // The lattice kind measures the volume at the end only: no live solid fraction.
      const std::string solid =
          progress.solid_fraction > 0.0
              ? fmt::format(", solid {:.1f} %", 100.0 * progress.solid_fraction)
              : std::string();
      job.set_detail(fmt::format(
          "{} {} of {}{}", progress.stage == PackStage::kDensify ? "densify: sweep" : "placed",
          progress.placed, progress.total, solid));
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
    build_scene(job, out);
    return out;
  });
}

void GuiApp::start_open(const std::string& path) {
  if (job_.is_running()) return;
  set_status("Opening " + path + "...", false);
  job_kind_ = "open";
  job_.start("Opening", [path](BackgroundJob& job) {
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
    build_scene(job, out);
    return out;
  });
}

void GuiApp::start_export(const std::string& format, DeckKind deck, const std::string& path) {
  if (job_.is_running() || !packing_) return;
  ExportOptions options{.format = parse_export_format(format), .overwrite = Overwrite::kAllow};
  if (deck != DeckKind::kNone) {  // a complete solver model around the mesh (export --deck)
    options.deck = deck_options_;
    options.deck.kind = deck;
    options.material = deck_material_;
  }
  try {  // the fields' errors at once, before the job
    validate(options, options.format);
  } catch (const Error& error) {
    set_status(plain_error(error.what()), true);
    return;
  }
  set_status("Writing " + path + "...", false);
  const std::string what = deck == DeckKind::kNone ? std::string() : deck_title(deck) + ", ";
  job_.start("Exporting", [packing = packing_, options, path, what](BackgroundJob&) {
    JobResult out;
    const ExportSummary summary = write(*packing, path, options);
    out.message = fmt::format("Wrote {}: {}{} particles, {} nodes, {} elements.", path, what,
                              summary.particles, summary.nodes, summary.elements);
    out.is_ok = true;
    return out;
  });
}

void GuiApp::show_packing(std::shared_ptr<const Packing> packing, std::shared_ptr<SceneData> scene,
                          std::vector<std::string> entries) {
  if (!scene) scene = prepare_scene(*packing);
  try {
    renderer_->begin_upload(std::move(scene));
  } catch (const Error& error) {
    set_status(error.what(), true);
    return;
  }
  pending_packing_ = std::move(packing);
  pending_entries_ = std::move(entries);
  finish_upload_if_done();
}

void GuiApp::finish_upload_if_done() {
  if (!pending_packing_) return;
  // Steps while the frame has time (about 25 ms): the window stays live while a large scene
  // goes to OpenGL, and a loaded machine uploads less per frame. Each step allocates one buffer
  // or copies at most 4 MB; a step starts only if it fits the time left at the cost per byte
  // measured so far (llvmpipe clears new storage; fresh memory costs 1-3 ms per MB on this VM).
  // The first step of a frame always runs.
  constexpr std::size_t kUploadPieceBytes = std::size_t{4} << 20;
  constexpr double kUploadSecondsPerFrame = 0.025;
  const double start = glfwGetTime();
  bool is_uploaded = false;
  for (bool is_first = true;; is_first = false) {
    const std::size_t bytes = renderer_->next_upload_bytes(kUploadPieceBytes);
    const double now = glfwGetTime();
    if (!is_first && now - start + static_cast<double>(bytes) * upload_seconds_per_byte_ >
                         kUploadSecondsPerFrame) {
      break;
    }
    is_uploaded = renderer_->upload_step(kUploadPieceBytes);
    if (bytes >= (std::size_t{1} << 20)) {  // large enough to time
      const double rate = (glfwGetTime() - now) / static_cast<double>(bytes);
      upload_seconds_per_byte_ = 0.5 * (upload_seconds_per_byte_ + rate);
    }
    if (is_uploaded) break;
  }
  if (!is_uploaded) return;
  is_upload_finished_now_ = true;
  const Aabb old_bounds = packing_ ? last_bounds_ : Aabb{};
  packing_ = std::move(pending_packing_);
  packing_entries_ = std::move(pending_entries_);
  pending_packing_.reset();
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

void GuiApp::poll_job() {
  JobResult result;
  if (!job_.take_result(result)) return;
  std::string message = result.message;
  std::vector<std::string> entries = job_entries_;
  if (!result.config_toml.empty()) {
    // An opened file: its stored configuration fills the panel, so Pack repeats or varies it.
    try {
      fields_ = ConfigFields::from_config(parse_pack_config(result.config_toml, "stored config"));
      message += " The panel shows its configuration.";
    } catch (const Error&) {
      message += " Its stored configuration is not readable; the panel is unchanged.";
    }
  }
  if (result.packing && job_kind_ == "open") entries = fields_.set_entries();
  set_status(plain_error(message), !result.is_ok);
  if (result.packing) show_packing(result.packing, result.scene, std::move(entries));
  if (is_waiting_for_first_job_ && result.is_ok && options_.mesomodel_export &&
      !is_mesomodel_script_started_) {  // scripted: the mesomodel export follows, wait for it
    is_mesomodel_script_started_ = true;
    // Scripted: the packing is shown at once (its upload finished in this frame) to be meshed.
    while (pending_packing_) {
      if (renderer_->upload_step(std::numeric_limits<std::size_t>::max())) finish_upload_if_done();
    }
    start_mesomodel_export(*options_.mesomodel_export);
    if (job_.is_running()) return;
    exit_code_ = 2;  // refused before it started (the status line says why)
  }
  if (is_waiting_for_first_job_) {
    is_waiting_for_first_job_ = false;
    frames_since_job_ = 0;
    if (!result.is_ok) exit_code_ = 2;
  }
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
  // status line and the scene are then drawn) and any benchmark is over; then the --edit
  // values, then the --export dialog, answering its questions with --answer.
  if (frames_since_job_ < 2 || benchmark_phase_ != BenchmarkPhase::kOff || is_script_done_ ||
      is_scene_dirty_ || renderer_->is_frame_pending() || renderer_->is_upload_pending() ||
      job_.is_running() || is_waiting_for_first_job_) {
    return;
  }
  if (options_.benchmark_frames > 0 && !is_benchmark_started_) {
    // Once the packing is shown (uploaded, its first full-detail picture drawn).
    is_benchmark_started_ = true;
    start_benchmark();
    return;
  }
  if (!are_edits_applied_) {
    are_edits_applied_ = true;
    if (!options_.edits.empty()) {
      apply_edits();
      frames_since_job_ = 0;
      return;
    }
  }
  if (options_.export_format && !is_export_script_started_) {
    is_export_script_started_ = true;
    open_dialog(FileDialog::Kind::kExport, *options_.export_format, options_.export_deck);
    frames_since_job_ = 0;
    if (dialog_.kind != FileDialog::Kind::kNone) return;
  }
  if (dialog_.kind != FileDialog::Kind::kNone) {
    if (dialog_.scripted != 0) return;  // the last answer is not taken yet
    const bool is_yes = options_.answer == "yes";
    switch (dialog_.stage) {
      case FileDialog::Stage::kAskStale: {
        std::string keys;
        for (const std::string& key : changed_keys()) keys += " " + key;
        std::printf("dialog: asks: export an out-of-date packing? (changed:%s)\n", keys.c_str());
        break;
      }
      case FileDialog::Stage::kAskOverwrite:
        std::printf("dialog: asks: replace %s?\n", dialog_.path().c_str());
        break;
      case FileDialog::Stage::kBrowse:
        std::printf("dialog: export %s to %s\n",
                    dialog_.deck == DeckKind::kNone ? dialog_.format.c_str()
                                                    : deck_title(dialog_.deck).c_str(),
                    dialog_.path().c_str());
        break;
    }
    const bool is_question = dialog_.stage != FileDialog::Stage::kBrowse;
    if (is_question) std::printf("dialog: answer %s\n", is_yes ? "yes" : "no");
    if (is_question && options_.screenshot_path && !is_screenshot_taken_) {
      save_screenshot(*options_.screenshot_path);  // the question on screen
      is_screenshot_taken_ = true;
      is_frame_timing_skipped_ = true;
    }
    std::fflush(stdout);
    dialog_.scripted = !is_question || is_yes ? 1 : 2;
    frames_since_job_ = 0;
    return;
  }
  is_script_done_ = true;
  // The status line of the finished job (a screenshot below replaces it on screen) and the
  // configuration the panel would pack next (the keys of `aggpack pack --set`).
  std::printf("status: %s\n", status_.c_str());
  std::string panel;
  for (const auto& entry : fields_.set_entries()) panel += " " + entry;
  std::printf("panel:%s\n", panel.c_str());
  std::printf("result: %s\n", !packing_ ? "none" : is_result_stale() ? "out of date" : "current");
  for (const auto& [key, message] : field_errors_) {
    std::printf("field error: %s: %s\n", key.c_str(), message.c_str());
  }
  for (const auto& [field, message] : mesomodel_field_errors()) {
    std::printf("field error: %s: %s\n", field.c_str(), message.c_str());
  }
  if (!form_error_.empty()) std::printf("form error: %s\n", form_error_.c_str());
  if (is_timing_frames_script_) {
    std::printf(
        "longest frame: %.0f ms (of %d frames while packing/opening and showing %zu "
        "particles; the first frame, start-up, took %.0f ms)\n",
        1e3 * longest_frame_, timed_frames_, renderer_->particle_count(), 1e3 * first_frame_);
  }
  if (options_.screenshot_path && !is_screenshot_taken_) save_screenshot(*options_.screenshot_path);
  std::fflush(stdout);
  if (options_.is_quit_when_done) should_quit_ = true;
}

void GuiApp::note_frame_start() { frame_work_start_ = glfwGetTime(); }

void GuiApp::note_frame_end() {
  if (!is_timing_frames_script_ || is_script_done_) return;
  if (std::exchange(is_frame_timing_skipped_, false)) return;  // a screenshot was written
  const double seconds = glfwGetTime() - frame_work_start_;
  // The window's first frame compiles shaders and builds the font atlas (start-up, before the
  // window is shown): reported apart.
  if (timed_frames_ == 0 && first_frame_ < 0.0) {
    first_frame_ = seconds;
    return;
  }
  longest_frame_ = std::max(longest_frame_, seconds);
  if (options_.is_frame_log) {
    std::printf("frame %d: %.1f ms%s%s\n", timed_frames_, 1e3 * seconds,
                job_.is_running() ? " (job running)" : "",
                renderer_->is_upload_pending() ? " (uploading)" : "");
  }
  ++timed_frames_;
}

bool GuiApp::is_result_stale() const {
  return packing_ != nullptr && !pending_packing_ && last_entries_ != packing_entries_;
}

std::vector<std::string> GuiApp::changed_keys() const {
  auto as_map = [](const std::vector<std::string>& entries) {
    std::map<std::string, std::string> map;
    for (const std::string& entry : entries) {
      const auto equals = entry.find('=');
      map[entry.substr(0, equals)] = equals == std::string::npos ? "" : entry.substr(equals + 1);
    }
    return map;
  };
  const auto now = as_map(last_entries_), then = as_map(packing_entries_);
  std::vector<std::string> keys;
  for (const auto& [key, value] : now) {
    const auto found = then.find(key);
    if (found == then.end() || found->second != value) keys.push_back(key);
  }
  for (const auto& [key, value] : then) {
    if (now.count(key) == 0) keys.push_back(key);
  }
  return keys;
}

void GuiApp::update_field_errors() {
  std::vector<std::string> entries = fields_.set_entries();
  if (entries == last_entries_ && !last_entries_.empty()) return;
  last_entries_ = std::move(entries);
  field_errors_.clear();
  form_error_.clear();
  // Each shown number against its range, in plain words next to the field.
  const auto& schema = pack_schema();
  const auto views = key_views(schema);
  const PackConfig draft = fields_.draft();
  for (std::size_t i = 0; i < schema.keys.size(); ++i) {
    const auto& key = schema.keys[i];
    if (!ConfigFields::is_editable(key) || !key.scope(draft)) continue;
    if (key.presence == Presence::kOptional && !fields_.is_on(key.name)) continue;
    const Value& value = fields_.value(key.name);
    double number = 0.0;
    if (key.type == ValueType::kFloat) {
      number = std::get<double>(value);
    } else if (key.type == ValueType::kInteger) {
      number = static_cast<double>(std::get<std::int64_t>(value));
    } else {
      continue;
    }
    if (key.range.contains(number)) continue;
    const std::string unit = key.unit.empty() || key.unit == "-" ? "" : " " + key.unit;
    field_errors_[key.name] = fmt::format("{} is outside the allowed range {}{}.",
                                          format_value(number), allowed_text(views[i]), unit);
  }
  if (!field_errors_.empty()) return;
  // Then the rules between fields, with the configuration's own message for the field it names.
  try {
    (void)fields_.build();
  } catch (const ConfigError& error) {
    std::string message = plain_error(error.what());
    const std::string prefix = error.key() + ": ";
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    if (error.key().empty() || !fields_.has(error.key())) {
      form_error_ = plain_error(error.what());
    } else {
      field_errors_[error.key()] = message;
    }
  } catch (const Error& error) {
    form_error_ = plain_error(error.what());
  }
}

void GuiApp::apply_edits() {
  const auto& keys = pack_schema().keys;
  for (const std::string& edit : options_.edits) {
    const auto equals = edit.find('=');
    const std::string name = edit.substr(0, equals);
    const std::string text = equals == std::string::npos ? "" : edit.substr(equals + 1);
    const auto key =
        std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.name == name; });
    if (key == keys.end() || !fields_.has(name) || equals == std::string::npos) {
      std::fprintf(stderr, "aggpack-gui: error: --edit %s: no such field in the panel\n",
                   edit.c_str());
      exit_code_ = 2;
      continue;
    }
    Value& value = fields_.value(name);
    try {
      switch (key->type) {
        case ValueType::kFloat:
          value = std::stod(text);
          break;
        case ValueType::kInteger:
          value = static_cast<std::int64_t>(std::stoll(text));
          break;
        case ValueType::kBool:
          value = text == "true";
          break;
        case ValueType::kWord: {
          std::string word = text;
          if (word.size() >= 2 && word.front() == '"' && word.back() == '"') {
            word = word.substr(1, word.size() - 2);
          }
          value = word;
          break;
        }
        default:
          throw InvalidInput("--edit", edit, "a number, word or true/false field");
      }
      if (key->presence == Presence::kOptional) fields_.set_on(name, true);
    } catch (const std::exception&) {
      std::fprintf(stderr, "aggpack-gui: error: --edit %s: not a value for this field\n",
                   edit.c_str());
      exit_code_ = 2;
    }
  }
  update_field_errors();
}

void GuiApp::draw_panel() {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  ImGui::SetNextWindowPos(ImVec2(0, menu_height_));
  ImGui::SetNextWindowSize(
      ImVec2(static_cast<float>(panel_width()),
             std::max(1.0f, static_cast<float>(height) - menu_height_ - status_height_)));
  ImGui::Begin("aggpack", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings);
  // Pack / Cancel, the progress and the result's state first, in a fixed height: always in view
  // and never moving what is below; the sections scroll beneath it.
  draw_job_section();
  ImGui::BeginChild("##sections", ImVec2(0.0f, 0.0f), false);
  ImGui::PushItemWidth(-150.0f);
  draw_config_section("Container", {"container"});
  draw_config_section("Particle shape", {"particle"});
  draw_config_section("Packer and grading", {"packer", "grading", "densify"});
  ImGui::PopItemWidth();
  if (!form_error_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", form_error_.c_str());
    ImGui::PopStyleColor();
  }
  draw_file_section();
  draw_view_section();
  ImGui::EndChild();
  ImGui::End();
}

void GuiApp::draw_job_section() {
  const float line = ImGui::GetFrameHeightWithSpacing();
  ImGui::BeginChild("##job", ImVec2(0.0f, 3.0f * line + 4.0f), false, ImGuiWindowFlags_NoScrollbar);
  const bool is_running = job_.is_running();
  ImGui::BeginDisabled(is_running);
  if (ImGui::Button("Pack", ImVec2(120, 0))) start_pack();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Pack with the parameters below (Enter)");
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!is_running);
  if (ImGui::Button("Cancel", ImVec2(-1, 0))) job_.request_cancel();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Stop the job under way (Esc); a packing keeps what it placed");
  }
  // The progress bar line: the job, the scene upload, or empty.
  if (is_running) {
    const double fraction = job_.progress();
    const std::string overlay = fmt::format("{} {:.0f} %{}", job_.name(), 100.0 * fraction,
                                            eta_text(job_.elapsed_seconds(), fraction));
    ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1, 0), overlay.c_str());
    const std::string detail = job_.detail();
    ImGui::TextUnformatted(detail.c_str());
  } else if (renderer_->is_upload_pending()) {
    const std::string overlay =
        fmt::format("Showing the packing {:.0f} %", 100.0 * renderer_->upload_progress());
    ImGui::ProgressBar(static_cast<float>(renderer_->upload_progress()), ImVec2(-1, 0),
                       overlay.c_str());
  } else if (is_result_stale()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextUnformatted("Out of date: parameters changed.");
    ImGui::TextUnformatted("Pack again (Enter) to see them.");
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) {
      std::string keys;
      for (const std::string& key : changed_keys()) keys += "\n  " + key;
      ImGui::SetTooltip("The view shows a packing made before these changed:%s", keys.c_str());
    }
  } else if (packing_) {
    ImGui::TextDisabled("The view shows the panel's parameters.");
  }
  ImGui::EndChild();
  ImGui::Separator();
}

void GuiApp::draw_file_section() {
  if (!ImGui::CollapsingHeader("Open and export", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const bool is_idle = !job_.is_running();
  ImGui::BeginDisabled(!is_idle);
  if (ImGui::Button("Open...", ImVec2(110, 0))) open_dialog(FileDialog::Kind::kOpen);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Open a packing made by aggpack (.h5) (Ctrl+O)");
  const bool can_export = packing_ != nullptr && is_idle && !pending_packing_;
  ImGui::BeginDisabled(!can_export);
  ImGui::SameLine();
  if (ImGui::Button("Export...", ImVec2(110, 0))) open_dialog(FileDialog::Kind::kExport);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Write the shown packing in a chosen format (Ctrl+S)");
  }
  ImGui::SameLine();
  if (ImGui::Button("rock.dat...", ImVec2(-1, 0))) open_dialog(FileDialog::Kind::kExport, "dat");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("Write the paper's rock.dat (nodes and tetrahedra) (Ctrl+E)");
  }
  ImGui::EndDisabled();
  draw_mesomodel_export(can_export);
}

void GuiApp::draw_view_section() {
  if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
  bool is_changed = false;
  int color = static_cast<int>(style_.color);
  ImGui::Text("Colour by");
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("particle", &color, 0);
  item_tooltip("A colour of its own for each particle");
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("size", &color, 1);
  item_tooltip("Colour by volume-equivalent diameter (legend below)");
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton("alpha", &color, 2);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "Colour by the measured alpha of each particle (the paper's Eq. 2, sphericity^1.5).\n"
        "It is not the input alpha of the panel (Eq. 3, the growth's shape control): the\n"
        "grown particles are rounder than the control suggests, so measured alpha is usually\n"
        "higher (0.68-0.89 for input 0.3).");
  }
  style_.color = static_cast<ColorMode>(color);
  is_changed |= ImGui::Checkbox("wireframe", &style_.is_wireframe);
  item_tooltip("Draw the triangle edges only");
  ImGui::SameLine();
  is_changed |= ImGui::Checkbox("container", &style_.show_container);
  item_tooltip("Draw the container's outline");
  ImGui::SameLine();
  bool is_orthographic = camera_.is_orthographic();
  if (ImGui::Checkbox("ortho", &is_orthographic)) {
    camera_.set_orthographic(is_orthographic);
    reset_view();
  }
  item_tooltip("Orthographic projection (no perspective)");
  const ViewPreset presets[] = {ViewPreset::kIso, ViewPreset::kFront, ViewPreset::kSide,
                                ViewPreset::kTop};
  for (int k = 0; k < 4; ++k) {
    if (k > 0) ImGui::SameLine();
    if (ImGui::Button(view_preset_name(presets[k]))) {
      view_ = presets[k];
      reset_view();
    }
    item_tooltip("Look at the scene from this side");
  }
  ImGui::SameLine();
  if (ImGui::Button("Reset View (R)")) reset_view();
  item_tooltip("Fit the whole scene in the view again (R)");
  float coarse = static_cast<float>(style_.coarse_below_pixels);
  ImGui::SetNextItemWidth(-130.0f);
  if (ImGui::SliderFloat("coarse below", &coarse, 0.0f, 64.0f, "%.0f px",
                         ImGuiSliderFlags_AlwaysClamp)) {
    style_.coarse_below_pixels = coarse;
    is_changed = true;
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("Particles smaller than this on screen are drawn with a 24-triangle shape");
  }
  int budget = static_cast<int>(style_.triangle_budget / 1000);
  ImGui::SetNextItemWidth(-130.0f);
  if (ImGui::SliderInt("triangle budget", &budget, 0, 5000, budget == 0 ? "no limit" : "%d k",
                       ImGuiSliderFlags_AlwaysClamp)) {
    style_.triangle_budget = static_cast<std::size_t>(budget) * 1000;
    is_scene_dirty_ = true;
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "Most triangles per picture (thousands); beyond it the smallest particles are drawn as "
        "shaded discs. 0 = no limit");
  }
  if (style_.color != ColorMode::kParticle && renderer_->particle_count() > 0) {
    draw_legend(renderer_->colors(style_.color));
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("%zu particles, %zu distinct shapes (%zu drawn as scaled copies)",
                      renderer_->particle_count(), renderer_->shape_count(),
                      renderer_->merged_shape_count());
  ImGui::TextDisabled("in view %zu, drawn %zu (%zu coarse, %zu as discs), %.2f M triangles",
                      last_stats_.particles_in_frustum, last_stats_.particles_drawn,
                      last_stats_.coarse_particles, last_stats_.point_particles,
                      last_stats_.triangles / 1e6);
  if (needs_light_frames_) {
    const DetailLevel level = detail_.level();
    ImGui::TextDisabled(
        "While the view moves (a full picture takes %.0f ms): %zu k triangles, %.0f %% "
        "resolution, %s particles",
        1e3 * last_picture_latency_, level.triangle_budget / 1000, 100.0 * level.resolution_scale,
        level.max_particles == 0 ? "all" : fmt::format("{} k", level.max_particles / 1000).c_str());
  } else {
    ImGui::TextDisabled("Full detail while the view moves (a picture takes %.0f ms)",
                        1e3 * last_picture_latency_);
  }
  ImGui::PopTextWrapPos();
  if (is_changed) is_scene_dirty_ = true;
}

}  // namespace aggpack::gui
