#include "gui_app.h"

#define GLFW_INCLUDE_NONE
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/grading.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pipeline/pipeline.h"

namespace aggpack::gui {

namespace {

// A TOML float: fmt's shortest round-trip form, with ".0" added where it would read as integer.
std::string toml_float(double value) {
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

const char* kContainerKinds[] = {"box", "cylinder"};
const char* kPackers[] = {"lattice", "random"};
const char* kGradings[] = {"uniform", "fuller", "sieve"};
constexpr float kPanelWidth = 360.0f;
// Text and input background of a sieve table error.
const ImVec4 kErrorText(0.95f, 0.35f, 0.3f, 1.0f);
const ImVec4 kErrorFrame(0.55f, 0.15f, 0.12f, 1.0f);
// Full-detail pictures timed after the moving frames in --benchmark-frames.
constexpr int kBenchmarkStillFrames = 5;
// Time a frame may spend on steps of a full-detail picture before it shows what it has (s).
constexpr double kFullFrameStepSeconds = 0.025;

// Input for a length in metres with a sensible step; returns true when changed.
bool input_metres(const char* label, double* value, double step = 0.01) {
  return ImGui::InputDouble(label, value, step, step * 10.0, "%.4g m");
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

}  // namespace

Fields fields_from_config(const PackConfig& config) {
  Fields f;
  const bool is_random = config.packer == PackerKind::kRandom;
  const Container& c = config.container();
  f.container_kind = static_cast<int>(c.shape.index());
  if (const auto* box = c.get_if<BoxContainer>()) {
    f.length = box->length;
    f.width = box->width;
    f.depth = box->depth;
  }
  if (const auto* cylinder = c.get_if<CylinderContainer>()) {
    f.cylinder_radius = cylinder->radius;
    f.cylinder_height = cylinder->height;
  }
  f.wall_gap = c.wall_gap;
  f.packer = is_random ? 1 : 0;
  f.seed = config.seed();
  const LatticeOptions& l = config.lattice;
  f.alpha = l.alpha;
  f.radius = l.radius;
  f.radius_min = l.radius;
  f.radius_max = l.radius;
  f.edge_length = l.edge_length;
  f.spacing = l.spacing;
  f.gap = l.gap;
  if (is_random) {
    const RandomPackOptions& r = config.random;
    f.alpha = r.shape.alpha;
    f.edge_length = r.shape.edge_length;
    f.edge_length_ratio = r.shape.edge_length_ratio;
    f.gap = r.gap;
    f.grading = r.grading.kind == GradingKind::kFuller  ? 1
                : r.grading.kind == GradingKind::kSieve ? 2
                                                        : 0;
    if (r.grading.kind == GradingKind::kSieve) f.sieve = r.grading.sieve;
    f.radius_min = r.grading.radius_min;
    f.radius_max = r.grading.radius_max;
    f.radius = r.grading.radius_min;
    f.has_radius_range = r.grading.radius_min != r.grading.radius_max;
    f.size_min = r.grading.size_min;
    f.size_max = r.grading.size_max;
    f.exponent = r.grading.exponent;
    f.target = r.target == PackTarget::kCount ? 1 : 0;
    f.target_fraction = r.volume_fraction;
    f.target_count = static_cast<int>(std::min<std::uint64_t>(r.count, 100000000));
    f.shape_library = static_cast<int>(r.shape.library_size);
  }
  return f;
}

std::vector<std::string> overrides_from_fields(const Fields& f) {
  std::vector<std::string> set;
  auto add = [&set](const std::string& key, const std::string& value) {
    set.push_back(key + "=" + value);
  };
  const bool is_random = f.packer == 1;
  add("packer.kind", fmt::format("\"{}\"", kPackers[f.packer]));
  add("packer.seed", std::to_string(f.seed));
  add("container.kind", fmt::format("\"{}\"", kContainerKinds[f.container_kind]));
  if (f.container_kind == 0) {
    add("container.length", toml_float(f.length));
    add("container.width", toml_float(f.width));
    add("container.depth", toml_float(f.depth));
  } else {
    add("container.radius", toml_float(f.cylinder_radius));
    add("container.height", toml_float(f.cylinder_height));
  }
  add("container.wall_gap", toml_float(f.wall_gap));
  add("particle.alpha", toml_float(f.alpha));
  add("packer.gap", toml_float(f.gap));
  if (!is_random) {
    add("particle.radius", toml_float(f.radius));
    add("particle.edge_length", toml_float(f.edge_length));
    add("packer.spacing", toml_float(f.spacing));
    return set;
  }
  add("grading.kind", fmt::format("\"{}\"", kGradings[f.grading]));
  if (f.grading == 0) {
    add("particle.radius_min", toml_float(f.has_radius_range ? f.radius_min : f.radius));
    add("particle.radius_max", toml_float(f.has_radius_range ? f.radius_max : f.radius));
  } else if (f.grading == 1) {
    add("grading.size_min", toml_float(f.size_min));
    add("grading.size_max", toml_float(f.size_max));
    add("grading.exponent", toml_float(f.exponent));
  } else {
    // No spaces, so the printed `panel:` line stays one word per key.
    std::string rows;
    for (const SieveRow& row : f.sieve) {
      rows += fmt::format("{}[{},{}]", rows.empty() ? "" : ",", toml_float(row.size),
                          toml_float(row.percent_passing));
    }
    add("grading.sieve", "[" + rows + "]");
  }
  add("particle.edge_length", toml_float(f.edge_length));
  if (f.edge_length == 0.0) add("particle.edge_length_ratio", toml_float(f.edge_length_ratio));
  if (f.target == 0) {
    add("packer.target_fraction", toml_float(f.target_fraction));
  } else {
    add("packer.target_count", std::to_string(f.target_count));
  }
  add("packer.shape_library", std::to_string(f.shape_library));
  return set;
}

GuiApp::GuiApp(GLFWwindow* window, GuiOptions options)
    : window_(window), options_(std::move(options)) {
  // The configuration fills the fields (defaults: the paper's case); errors are the CLI's.
  const PackConfig config = options_.config_path
                                ? load_pack_config(*options_.config_path, options_.overrides)
                                : parse_pack_config("", "defaults", options_.overrides);
  fields_ = fields_from_config(config);
  style_ = options_.style;
  view_ = options_.view;
  export_base_ = options_.export_base;
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
    config = parse_pack_config("", "gui", overrides_from_fields(fields_));
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
      job.set_detail(fmt::format("placed {} of {}, solid fraction {:.1f} %", progress.placed,
                                 progress.total, 100.0 * progress.solid_fraction));
    };
    PipelineResult result = pack(config, control);
    JobResult out;
    const bool is_cancelled = result.report.stop_reason == StopReason::kCancelled;
    out.is_ok = true;
    out.message = fmt::format("{} {} particles, solid fraction {:.2f} %.\n{}",
                              is_cancelled ? "Cancelled:" : "Packing finished!",
                              result.packing.particles.size(), 100.0 * result.report.solid_fraction,
                              result.report.summary());
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
      fields_ = fields_from_config(parse_pack_config(result.config_toml, "stored config"));
      message += " The panel shows its configuration.";
    } catch (const Error&) {
      message += " Its stored configuration is not readable; the panel is unchanged.";
    }
  }
  set_status(message, !result.is_ok);
  if (result.packing) show_packing(result.packing);
  if (is_waiting_for_first_job_) {
    is_waiting_for_first_job_ = false;
    frames_since_job_ = 0;
    if (!result.is_ok) exit_code_ = 2;
    if (options_.benchmark_frames > 0) start_benchmark();
  }
}

void GuiApp::render_scene_if_needed(int width, int height) {
  is_picture_new_ = false;
  if (!scene_target_ || scene_target_->width() != width || scene_target_->height() != height) {
    scene_target_ = std::make_unique<OffscreenTarget>(width, height, 0);
    has_picture_ = false;
    is_scene_dirty_ = true;
  }
  const bool is_light = is_interacting();
  if (!is_scene_dirty_ && (is_light || !renderer_->is_frame_pending())) return;
  const double start = glfwGetTime();
  detail_.set_full_budget(style_.triangle_budget);
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
  // One step at least; more while this frame has time (all when there is nothing to show yet).
  bool is_done = false;
  do {
    is_done = renderer_->step_frame();
  } while (!is_done && (!has_picture_ || glfwGetTime() - start < kFullFrameStepSeconds));
  if (is_done) glFinish();  // so the time measures the scene
  full_frame_seconds_ += glfwGetTime() - start;
  if (!is_done) return;
  std::swap(scene_target_, full_target_);
  is_drawn_scaled_ = false;
  last_stats_ = renderer_->frame_stats();
  last_scene_seconds_ = full_frame_seconds_;
  last_picture_latency_ = glfwGetTime() - full_frame_start_;
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

void GuiApp::save_screenshot(const std::string& path) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  try {
    write_png(read_framebuffer(0, 0, width, height), path);
    std::printf("screenshot: wrote %s (%dx%d)\n", path.c_str(), width, height);
    std::fflush(stdout);
    set_status("Saved the window to " + path + ".", false);
  } catch (const Error& error) {
    std::fprintf(stderr, "aggpack-gui: error: %s\n", error.what());
    set_status(error.what(), true);
    exit_code_ = 3;
  }
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
  for (const auto& entry : overrides_from_fields(fields_)) panel += " " + entry;
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
  ImGui::PushItemWidth(-150.0f);
  draw_container_section();
  draw_shape_section();
  draw_packer_section();
  ImGui::PopItemWidth();
  draw_job_section();
  draw_file_section();
  draw_view_section();
  ImGui::End();
}

void GuiApp::draw_container_section() {
  if (!ImGui::CollapsingHeader("Container", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Combo("kind", &fields_.container_kind, kContainerKinds, 2);
  if (fields_.container_kind == 0) {
    input_metres("length (x)", &fields_.length, 0.1);
    input_metres("width (y)", &fields_.width, 0.1);
    input_metres("depth (z)", &fields_.depth, 0.1);
  } else {
    input_metres("radius", &fields_.cylinder_radius, 0.005);
    input_metres("height", &fields_.cylinder_height, 0.01);
  }
  input_metres("wall gap", &fields_.wall_gap, 0.001);
}

void GuiApp::draw_shape_section() {
  if (!ImGui::CollapsingHeader("Particle shape", ImGuiTreeNodeFlags_DefaultOpen)) return;
  float alpha = static_cast<float>(fields_.alpha);
  if (ImGui::SliderFloat("alpha (Eq. 3)", &alpha, 0.0f, 1.0f, "%.2f")) fields_.alpha = alpha;
  const bool is_random = fields_.packer == 1;
  if (is_random && fields_.grading == 0) {
    ImGui::Checkbox("radius range", &fields_.has_radius_range);
  }
  if (is_random && fields_.grading == 0 && fields_.has_radius_range) {
    input_metres("radius min", &fields_.radius_min);
    input_metres("radius max", &fields_.radius_max);
  } else if (!is_random || fields_.grading == 0) {
    input_metres("radius R", &fields_.radius);
  }
  input_metres(is_random ? "edge length L (0=rel.)" : "edge length L", &fields_.edge_length);
  if (is_random && fields_.edge_length == 0.0) {
    ImGui::InputDouble("L / r", &fields_.edge_length_ratio, 0.05, 0.25, "%.3g");
  }
}

void GuiApp::draw_packer_section() {
  if (!ImGui::CollapsingHeader("Grading and packer", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Combo("packer", &fields_.packer, kPackers, 2);
  if (fields_.packer == 0) {
    input_metres("spacing (0=2R+gap)", &fields_.spacing);
  } else {
    ImGui::Combo("grading", &fields_.grading, kGradings, 3);
    if (fields_.grading == 1) {
      input_metres("size min d", &fields_.size_min, 0.001);
      input_metres("size max d", &fields_.size_max, 0.001);
      ImGui::InputDouble("exponent q", &fields_.exponent, 0.05, 0.1, "%.3g");
    } else if (fields_.grading == 2) {
      draw_sieve_table();
    }
    ImGui::Combo("target", &fields_.target, "solid fraction\0count\0");
    if (fields_.target == 0) {
      ImGui::InputDouble("solid fraction", &fields_.target_fraction, 0.01, 0.05, "%.3g");
    } else {
      ImGui::InputInt("count", &fields_.target_count, 100, 10000);
    }
    ImGui::InputInt("shape library K", &fields_.shape_library, 10, 100);
  }
  input_metres("gap", &fields_.gap, 0.001);
  ImGui::InputScalar("seed", ImGuiDataType_U64, &fields_.seed);
}

void GuiApp::draw_sieve_table() {
  std::vector<SieveRow>& rows = fields_.sieve;
  // The library's own check, so the panel states the rule in the words Pack would use; the
  // field it names ("grading.sieve[2].size") marks the cell.
  std::string error, error_field;
  try {
    validate(Grading{.kind = GradingKind::kSieve, .sieve = rows});
  } catch (const InvalidInput& invalid) {
    error = invalid.what();
    error_field = invalid.field();
  } catch (const Error& other) {
    error = other.what();
  }
  ImGui::TextUnformatted("sieve table by volume; d = control diameter");
  int insert_after = -1, remove = -1;
  const float button_width = ImGui::GetFrameHeight();
  constexpr ImGuiTableFlags kTableFlags =
      ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("sieve", 4, kTableFlags)) {
    ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("size d", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("% passing", ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("##rows", ImGuiTableColumnFlags_WidthFixed,
                            2.0f * button_width + ImGui::GetStyle().ItemSpacing.x);
    ImGui::TableHeadersRow();
    for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
      SieveRow& row = rows[static_cast<std::size_t>(k)];
      const std::string field = fmt::format("grading.sieve[{}]", k);
      ImGui::PushID(k);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::AlignTextToFramePadding();
      ImGui::Text("%d", k);
      auto cell = [&error_field](const std::string& name, const char* id, double* value,
                                 const char* format) {
        ImGui::TableNextColumn();
        const bool is_bad = error_field == name;
        if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
        ImGui::SetNextItemWidth(-FLT_MIN);
        ImGui::InputDouble(id, value, 0.0, 0.0, format);
        if (is_bad) ImGui::PopStyleColor();
      };
      cell(field + ".size", "##size", &row.size, "%.4g m");
      cell(field + ".percent_passing", "##percent", &row.percent_passing, "%.4g");
      ImGui::TableNextColumn();
      if (ImGui::Button("+", ImVec2(button_width, 0))) insert_after = k;
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("Insert a row after this one (midway: the grading stays the same)");
      }
      ImGui::SameLine();
      ImGui::BeginDisabled(rows.size() <= 2);  // a table needs two sieves
      if (ImGui::Button("-", ImVec2(button_width, 0))) remove = k;
      ImGui::EndDisabled();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Remove this row");
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  if (insert_after >= 0) {
    const auto after = static_cast<std::size_t>(insert_after);
    const SieveRow& row = rows[after];
    // Midway in d with the percent interpolated (P is linear in d between sieves), or a larger
    // sieve passing 100 % after the last: either way the grading is unchanged until edited.
    const SieveRow added =
        after + 1 < rows.size()
            ? SieveRow{.size = 0.5 * (row.size + rows[after + 1].size),
                       .percent_passing =
                           0.5 * (row.percent_passing + rows[after + 1].percent_passing)}
            : SieveRow{.size = 1.25 * row.size, .percent_passing = 100.0};
    rows.insert(rows.begin() + insert_after + 1, added);
  } else if (remove >= 0) {
    rows.erase(rows.begin() + remove);
  }
  ImGui::PushTextWrapPos(0.0f);
  if (!error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorText);
    ImGui::TextUnformatted(error.c_str());
    ImGui::PopStyleColor();
  } else {
    const Grading grading{.kind = GradingKind::kSieve, .sieve = rows};
    const std::string fines =
        rows.front().percent_passing > 0.0
            ? fmt::format("; the {:.4g} % passing the smallest sieve (fines) is not packed",
                          rows.front().percent_passing)
            : std::string();
    ImGui::TextDisabled("d %.4g to %.4g m%s", smallest_size(grading), largest_size(grading),
                        fines.c_str());
  }
  ImGui::PopTextWrapPos();
}

void GuiApp::draw_job_section() {
  ImGui::Separator();
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

void GuiApp::on_key(int key, int action) {
  if (action != GLFW_PRESS || ImGui::GetIO().WantTextInput) return;
  if (key == GLFW_KEY_R) reset_view();
  if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) start_pack();
  if (key == GLFW_KEY_ESCAPE && job_.is_running()) job_.request_cancel();
  if (key == GLFW_KEY_F12) is_screenshot_requested_ = true;
}

}  // namespace aggpack::gui
