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
#include "i18n.h"

namespace aggpack::gui {

namespace {

constexpr float kPanelWidth = 360.0f;

// Builds the job's packing's scene on the worker (the window uploads it in pieces).
void build_scene(BackgroundJob& job, JobResult& out) {
  job.set_name(tr(Text::kJobBuildingScene));
  job.set_progress(0.0);
  job.set_detail(trs(Text::kJobParticles, out.packing->particles.size()));
  out.scene = prepare_scene(*out.packing, [&job](double fraction) { job.set_progress(fraction); });
}

// The packer's report line in the window's language (in English, PackReport::summary()'s).
std::string report_summary(const PackReport& report) {
  Text reason = Text::kStopTarget;
  switch (report.stop_reason) {
    case StopReason::kTargetReached:
      break;
    case StopReason::kAttemptBudget:
      reason = Text::kStopBudget;
      break;
    case StopReason::kConsecutiveFailures:
      reason = Text::kStopFailures;
      break;
    case StopReason::kSizeListExhausted:
      reason = Text::kStopSizeList;
      break;
    case StopReason::kCancelled:
      reason = Text::kStopCancelled;
      break;
  }
  return trs(Text::kReportSummary, report.placed, report.requested, report.rejected,
             report.solid_volume, report.container_volume, 100.0 * report.solid_fraction,
             tr(reason));
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
    return trs(Text::kNotAllowed, key, value, rest);
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
  set_status(tr(Text::kStatusPacking), false);
  job_entries_ = fields_.set_entries();
  job_kind_ = "pack";
  job_.start(tr(Text::kJobPacking), [config](BackgroundJob& job) {
    PackControl control;
    control.cancel = job.cancel_flag();
    control.progress_interval = 0.05;
    control.on_progress = [&job](const PackProgress& progress) {
      job.set_progress(progress.fraction);
      // The lattice kind measures the volume at the end only: no live solid fraction.
      const std::string solid = progress.solid_fraction > 0.0
                                    ? trs(Text::kProgressSolid, 100.0 * progress.solid_fraction)
                                    : std::string();
      job.set_detail(
          trs(progress.stage == PackStage::kDensify ? Text::kProgressSweep : Text::kProgressPlaced,
              progress.placed, progress.total, solid));
    };
    PipelineResult result = pack(config, control);
    JobResult out;
    const bool is_cancelled = result.report.stop_reason == StopReason::kCancelled;
    out.is_ok = true;
    // The densifier's summary and the shortfall warnings are the library's words (English).
    out.message = trs(is_cancelled ? Text::kPackCancelled : Text::kPackFinished,
                      result.packing.particles.size(), 100.0 * result.report.solid_fraction) +
                  "\n" +
                  (result.fill ? tr(Text::kFillPrefix) + report_summary(result.fill->report)
                               : report_summary(result.report));
    // The dense kind: the densifier, the asked fraction, and what fell short of it.
    if (result.densify)
      out.message += "\n" + (tr(Text::kDensifyPrefix) + result.densify->summary());
    if (result.fill && result.fill->asked_fraction > 0) {
      out.message += trs(Text::kAskedFraction, 100.0 * result.fill->asked_fraction);
    }
    for (const std::string& line : dense_shortfalls(result)) {
      out.message += "\n" + (tr(Text::kWarningPrefix) + line);
    }
    out.packing = std::make_shared<const Packing>(std::move(result.packing));
    build_scene(job, out);
    return out;
  });
}

void GuiApp::start_open(const std::string& path) {
  if (job_.is_running()) return;
  set_status(trs(Text::kStatusOpening, path), false);
  job_kind_ = "open";
  job_.start(tr(Text::kJobOpening), [path](BackgroundJob& job) {
    JobResult out;
    auto packing = std::make_shared<const Packing>(read_packing(path));
    out.is_ok = true;
    double solid = 0.0;
    for (std::size_t i = 0; i < packing->particles.size(); ++i) {
      solid += mass_properties(packing->local_body(i)).volume;
    }
    const double volume = packing->container.volume();
    out.message = trs(Text::kOpened, path, packing->particles.size(),
                      volume > 0 ? 100.0 * solid / volume : 0.0);
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
  set_status(trs(Text::kStatusWriting, path), false);
  const std::string what =
      deck == DeckKind::kNone ? std::string() : deck_title(deck) + tr(Text::kListSeparator);
  job_.start(tr(Text::kJobExporting), [packing = packing_, options, path, what](BackgroundJob&) {
    JobResult out;
    const ExportSummary summary = write(*packing, path, options);
    out.message = trs(Text::kWrote, path, what, summary.particles, summary.nodes, summary.elements);
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
      message += tr(Text::kOpenedConfig);
    } catch (const Error&) {
      message += tr(Text::kOpenedConfigBad);
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
  if (options_.library_folder && !is_library_script_started_) {
    is_library_script_started_ = true;
    open_library_dialog(*options_.library_folder);
    for (const std::string& name : options_.library_picks) {
      if (std::find(dialog_.files.begin(), dialog_.files.end(), name) != dialog_.files.end()) {
        dialog_.picked.push_back(name);
      }
    }
    frames_since_job_ = 0;
    if (dialog_.kind != FileDialog::Kind::kNone) return;
  }
  if (dialog_.kind == FileDialog::Kind::kLibrary) {
    if (dialog_.scripted != 0) return;  // the answer is not taken yet
    std::string picked;
    for (const std::string& name : dialog_.picked) picked += " " + name;
    std::printf("dialog: library %s (%zu mesh files; picked:%s); answer %s\n",
                dialog_.folder.c_str(), dialog_.files.size(), picked.c_str(),
                options_.answer.c_str());
    if (options_.screenshot_path && !is_screenshot_taken_) {
      save_screenshot(*options_.screenshot_path);  // the dialog on screen
      is_screenshot_taken_ = true;
      is_frame_timing_skipped_ = true;
    }
    std::fflush(stdout);
    dialog_.scripted = options_.answer == "yes" ? 1 : 2;
    frames_since_job_ = 0;
    return;
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

}  // namespace aggpack::gui
