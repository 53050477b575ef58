#include "script_driver.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include "gui_app.h"

namespace aggpack::gui {

void ScriptDriver::start(bool is_job_started, bool is_scripted) {
  if (is_job_started) {
    is_waiting_for_first_job_ = true;
  } else if (is_scripted) {
    frames_since_job_ = 0;  // nothing to wait for: screenshot / quit after two frames
  }
  is_timing_frames_ = is_waiting_for_first_job_;
}

bool ScriptDriver::is_busy() const {
  return is_waiting_for_first_job_ || (frames_since_job_ >= 0 && frames_since_job_ < 3);
}

void ScriptDriver::on_job_result(const JobResult& result) {
  GuiApp& app = app_;
  if (is_waiting_for_first_job_ && result.is_ok && app.options_.mesomodel_export &&
      !is_mesomodel_script_started_) {  // scripted: the mesomodel export follows, wait for it
    is_mesomodel_script_started_ = true;
    // Scripted: the packing is shown at once (its upload finished in this frame) to be meshed.
    while (app.upload_.is_pending()) {
      if (app.renderer_->upload_step(std::numeric_limits<std::size_t>::max())) {
        app.finish_upload_if_done();
      }
    }
    app.start_mesomodel_export(*app.options_.mesomodel_export);
    if (app.job_.is_running()) return;
    app.exit_code_ = 2;  // refused before it started (the status line says why)
  }
  if (is_waiting_for_first_job_) {
    is_waiting_for_first_job_ = false;
    frames_since_job_ = 0;
    if (!result.is_ok) app.exit_code_ = 2;
  }
}

void ScriptDriver::count_frame() {
  if (frames_since_job_ >= 0) ++frames_since_job_;
}

void ScriptDriver::after_render() {
  GuiApp& app = app_;
  // Act once the first job's result has been on screen for two frames (the status line and the
  // scene are then drawn) and any benchmark is over; then the --edit values, then the --export
  // dialog, answering its questions with --answer. A job that finished after this frame's
  // poll_job still holds its result (its status line is not shown yet): wait for the next frame.
  if (frames_since_job_ < 2 || app.benchmark_phase_ != GuiApp::BenchmarkPhase::kOff ||
      is_script_done_ || app.is_scene_dirty_ || app.renderer_->is_frame_pending() ||
      app.renderer_->is_upload_pending() || app.job_.is_running() || app.job_.has_result() ||
      is_waiting_for_first_job_) {
    return;
  }
  if (app.options_.benchmark_frames > 0 && !is_benchmark_started_) {
    // Once the packing is shown (uploaded, its first full-detail picture drawn).
    is_benchmark_started_ = true;
    app.start_benchmark();
    return;
  }
  if (!are_edits_applied_) {
    are_edits_applied_ = true;
    if (!app.options_.edits.empty()) {
      app.apply_edits();
      frames_since_job_ = 0;
      return;
    }
  }
  if (app.options_.library_folder && !is_library_script_started_) {
    is_library_script_started_ = true;
    app.open_library_dialog(*app.options_.library_folder);
    for (const std::string& name : app.options_.library_picks) {
      if (std::find(app.dialog_.files.begin(), app.dialog_.files.end(), name) !=
          app.dialog_.files.end()) {
        app.dialog_.picked.push_back(name);
      }
    }
    frames_since_job_ = 0;
    if (app.dialog_.kind != FileDialog::Kind::kNone) return;
  }
  if (app.dialog_.kind == FileDialog::Kind::kLibrary) {
    answer_library_dialog();
    return;
  }
  if (app.options_.export_format && !is_export_script_started_) {
    is_export_script_started_ = true;
    app.open_dialog(FileDialog::Kind::kExport, *app.options_.export_format,
                    app.options_.export_deck);
    frames_since_job_ = 0;
    if (app.dialog_.kind != FileDialog::Kind::kNone) return;
  }
  if (app.dialog_.kind != FileDialog::Kind::kNone) {
    answer_dialog();
    return;
  }
  is_script_done_ = true;
  print_outcome();
  if (app.options_.is_quit_when_done) app.should_quit_ = true;
}

// The library dialog, printed (a screenshot of it), answered with --answer.
void ScriptDriver::answer_library_dialog() {
  GuiApp& app = app_;
  FileDialog& dialog = app.dialog_;
  if (dialog.scripted != 0) return;  // the answer is not taken yet
  std::string picked;
  for (const std::string& name : dialog.picked) picked += " " + name;
  std::printf("dialog: library %s (%zu mesh files; picked:%s); answer %s\n", dialog.folder.c_str(),
              dialog.files.size(), picked.c_str(), app.options_.answer.c_str());
  take_screenshot_once();  // the dialog on screen
  std::fflush(stdout);
  dialog.scripted = app.options_.answer == "yes" ? 1 : 2;
  frames_since_job_ = 0;
}

// The export dialog's current step, printed, answered with --answer (a screenshot of the first
// question).
void ScriptDriver::answer_dialog() {
  GuiApp& app = app_;
  FileDialog& dialog = app.dialog_;
  if (dialog.scripted != 0) return;  // the last answer is not taken yet
  const bool is_yes = app.options_.answer == "yes";
  switch (dialog.stage) {
    case FileDialog::Stage::kAskStale: {
      std::string keys;
      for (const std::string& key : app.changed_keys()) keys += " " + key;
      std::printf("dialog: asks: export an out-of-date packing? (changed:%s)\n", keys.c_str());
      break;
    }
    case FileDialog::Stage::kAskOverwrite:
      std::printf("dialog: asks: replace %s?\n", dialog.path().c_str());
      break;
    case FileDialog::Stage::kBrowse:
      std::printf(
          "dialog: export %s to %s\n",
          dialog.deck == DeckKind::kNone ? dialog.format.c_str() : deck_title(dialog.deck).c_str(),
          dialog.path().c_str());
      break;
  }
  const bool is_question = dialog.stage != FileDialog::Stage::kBrowse;
  if (is_question) std::printf("dialog: answer %s\n", is_yes ? "yes" : "no");
  if (is_question) take_screenshot_once();  // the question on screen
  std::fflush(stdout);
  dialog.scripted = !is_question || is_yes ? 1 : 2;
  frames_since_job_ = 0;
}

// The status line of the finished job (a screenshot below replaces it on screen), the
// configuration the panel would pack next (the keys of `aggpack pack --set`), the field errors,
// the longest frame; then the --screenshot.
void ScriptDriver::print_outcome() {
  GuiApp& app = app_;
  std::printf("status: %s\n", app.status_.c_str());
  std::string panel;
  for (const auto& entry : app.fields_.set_entries()) panel += " " + entry;
  std::printf("panel:%s\n", panel.c_str());
  std::printf("result: %s\n", !app.packing_           ? "none"
                              : app.is_result_stale() ? "out of date"
                                                      : "current");
  for (const auto& [key, message] : app.field_errors_) {
    std::printf("field error: %s: %s\n", key.c_str(), message.c_str());
  }
  for (const auto& [field, message] : app.mesomodel_field_errors()) {
    std::printf("field error: %s: %s\n", field.c_str(), message.c_str());
  }
  if (!app.form_error_.empty()) std::printf("form error: %s\n", app.form_error_.c_str());
  if (is_timing_frames_) {
    std::printf(
        "longest frame: %.0f ms (of %d frames while packing/opening and showing %zu "
        "particles; the first frame, start-up, took %.0f ms)\n",
        1e3 * longest_frame_, timed_frames_, app.renderer_->particle_count(), 1e3 * first_frame_);
  }
  take_screenshot_once();
  std::fflush(stdout);
}

// --screenshot, written at the script's first chance only; the frame that wrote it is not timed.
void ScriptDriver::take_screenshot_once() {
  if (!app_.options_.screenshot_path || is_screenshot_taken_) return;
  app_.save_screenshot(*app_.options_.screenshot_path);
  is_screenshot_taken_ = true;
  is_frame_timing_skipped_ = true;
}

void ScriptDriver::note_frame_start() { frame_work_start_ = glfwGetTime(); }

void ScriptDriver::note_frame_end() {
  if (!is_timing_frames_ || is_script_done_) return;
  if (std::exchange(is_frame_timing_skipped_, false)) return;  // a screenshot was written
  const double seconds = glfwGetTime() - frame_work_start_;
  // The window's first frame compiles shaders and builds the font atlas (start-up, before the
  // window is shown): reported apart.
  if (timed_frames_ == 0 && first_frame_ < 0.0) {
    first_frame_ = seconds;
    return;
  }
  longest_frame_ = std::max(longest_frame_, seconds);
  if (app_.options_.is_frame_log) {
    std::printf("frame %d: %.1f ms%s%s\n", timed_frames_, 1e3 * seconds,
                app_.job_.is_running() ? " (job running)" : "",
                app_.renderer_->is_upload_pending() ? " (uploading)" : "");
  }
  ++timed_frames_;
}

}  // namespace aggpack::gui
