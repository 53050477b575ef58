#pragma once
// aggpack-gui: the paper's program (Section 5) done as a modern tool. Panels for the container,
// particle shape, grading and packer; Pack on a worker thread with progress and Cancel; a 3D
// view with arcball rotation, pan, zoom and colour modes; Open and Export.
// GuiApp owns the window's state and its parts: the job controller (job_controller.cpp: pack,
// open, export on the worker), the upload scheduler (upload_scheduler.h), the panels
// (gui_panel.cpp, config_panel.cpp, field_checks.cpp, file_dialog.cpp, deck_export.cpp,
// mesomodel_export.cpp, gui_layout.cpp), the 3D view (gui_view.cpp) and the scripted-test
// driver (script_driver.h).

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/io/export.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/render/camera.h"
#include "aggpack/render/detail_controller.h"
#include "aggpack/render/headless.h"
#include "aggpack/render/renderer.h"
#include "background_job.h"
#include "config_fields.h"
#include "file_dialog.h"
#include "gui_settings.h"
#include "i18n.h"
#include "script_driver.h"
#include "upload_scheduler.h"

struct GLFWwindow;

namespace aggpack::gui {

/// Start-up options (from the command line).
struct GuiOptions {
  std::optional<std::string> config_path;      ///< TOML configuration to fill the fields from
  std::vector<std::string> overrides;          ///< --set key=value, applied to the configuration
  std::optional<std::string> open_path;        ///< native packing to open at start
  bool is_pack_at_start = false;               ///< press Pack once at start
  std::optional<std::string> screenshot_path;  ///< save the window once the first job is done
  bool is_quit_when_done = false;              ///< exit after the screenshot / benchmark
  int benchmark_frames = 0;  ///< redraw the turning scene this many frames (moving), print fps
  ViewPreset view = ViewPreset::kIso;
  RenderStyle style;
  std::string export_base = "rock";  ///< export file name without extension
  /// Scripted runs: once the first pack/open is done, export the mesomodel with this extension
  /// (".inp", ".msh", ".vtu"), as the Mesomodel buttons do, before the screenshot / quit.
  std::optional<std::string> mesomodel_export;
  double mesomodel_itz_mm = 0.0;                 ///< the ITZ thickness field's start value (mm)
  ItzKind mesomodel_itz_kind = ItzKind::kSolid;  ///< the ITZ model combo's start value
  /// --edit KEY=VALUE: typed into the panel's field once the first pack/open is done (or at
  /// start without one), as a user would (values as `--set` takes them).
  std::vector<std::string> edits;
  bool is_frame_log = false;  ///< --frame-log: print every timed frame's time
  /// --export FORMAT: once the first job (and the edits) are done, press that export, as the
  /// Export menu does (the dialog's questions are printed and answered by --answer).
  std::optional<std::string> export_format;
  /// --export-deck NAME: as --export, the solver deck NAME (export_format is then its format).
  DeckKind export_deck = DeckKind::kNone;
  /// --answer yes|no: the scripted answer to the export dialog's question (stale, overwrite).
  std::string answer = "no";
  /// --library-dialog FOLDER: once the first job (and the edits) are done, open the shape
  /// library dialog in FOLDER, pick --library-pick's files and answer with --answer (yes: use
  /// the picked files, or the folder when none are picked).
  std::optional<std::string> library_folder;
  std::vector<std::string> library_picks;
  /// Settings folder (default $XDG_CONFIG_HOME/aggpack or ~/.config/aggpack).
  std::string settings_dir;
};

class GuiApp {
 public:
  /// Needs the window's OpenGL 3.3 core context current. \throw Error for a bad configuration.
  GuiApp(GLFWwindow* window, GuiOptions options);
  ~GuiApp();

  /// One frame: events already polled; draws scene + panels into the back buffer.
  void frame();
  /// After the frame (scene + panels) is drawn, before it is shown: takes the --screenshot and
  /// handles --quit.
  void after_render();
  /// True when the program should exit (window closed, or --quit finished its work).
  [[nodiscard]] bool should_quit() const { return should_quit_; }
  /// True while something changes on screen by itself (job running, benchmark), so the main
  /// loop polls instead of waiting for events.
  [[nodiscard]] bool is_busy() const;
  /// True during --benchmark-frames: main then finishes the GPU work after the panels and
  /// reports how long they and the buffer swap took (note_present_times).
  [[nodiscard]] bool is_timing_frames() const { return benchmark_phase_ != BenchmarkPhase::kOff; }
  /// Time (s) of drawing the panels (ImGui's draw data, finished) and of the buffer swap.
  void note_present_times(double ui_draw_seconds, double swap_seconds);
  /// Main calls these when a frame's work begins (events are in) and after its buffer swap:
  /// scripted runs print the longest such frame since the first job began.
  void note_frame_start() { script_.note_frame_start(); }
  void note_frame_end() { script_.note_frame_end(); }
  /// Exit code for main: non-zero when a --pack/--open/--screenshot step failed.
  [[nodiscard]] int exit_code() const { return exit_code_; }

  // Input from the GLFW callbacks (window coordinates).
  void on_mouse_button(int button, int action);
  void on_cursor(double x, double y);
  void on_scroll(double dy);
  void on_key(int key, int action, int mods);

 private:
  void draw_panel();
  // gui_layout.cpp: the menu bar, the status bar, the Help window, the view's overlays.
  void draw_menu_bar();
  void draw_status_bar();
  void draw_help_window();
  void draw_view_overlays();
  // View > Language; the language at start (the kept choice, else the locale's) and a change.
  void draw_language_menu();
  void choose_language();
  void set_gui_language(Language language);
  // file_dialog.cpp: the Open and Export dialogs (folder browsing, overwrite, stale result).
  void open_dialog(FileDialog::Kind kind, const std::string& format = "",
                   DeckKind deck = DeckKind::kNone);
  void draw_file_dialog();
  // library_dialog.cpp: particle.library's folder or files (in `folder`, else where the field's
  // library or the kept folder is); use_library sets the field and closes the dialog.
  void open_library_dialog(const std::string& folder = "");
  void draw_library_dialog();
  void use_library(std::vector<std::string> paths);
  // deck_export.cpp: a solver deck's fields in the Export dialog; returns their error in plain
  // words ("" = the library's check passes).
  std::string draw_deck_fields(DeckKind deck);
  // Whether the shown packing was made with other parameters than the panel shows now.
  [[nodiscard]] bool is_result_stale() const;
  // The keys whose panel value differs from the shown packing's.
  [[nodiscard]] std::vector<std::string> changed_keys() const;
  // Field checks: field_errors_ from the panel's values (each frame the values changed).
  void update_field_errors();
  void apply_edits();
  void finish_upload_if_done();
  // config_panel.cpp: the configuration sections, one widget per schema key.
  void draw_config_section(const char* title, const std::vector<std::string>& tables);
  void draw_key(const Key<PackConfig>& key, const KeyView& view);
  void draw_key_input(const Key<PackConfig>& key, const KeyView& view, const std::string& label,
                      Value& value);
  void draw_sieve_table(std::vector<SieveRow>& rows);
  void draw_job_section();
  void draw_file_section();
  void draw_view_section();
  void start_pack();
  void start_open(const std::string& path);
  void start_export(const std::string& format, DeckKind deck, const std::string& path);
  // mesomodel_export.cpp: the concrete mesomodel (.inp, .msh, .vtu) of the shown packing.
  void draw_mesomodel_export(bool can_export);
  void start_mesomodel_export(const std::string& extension);
  // The mesomodel fields' errors in plain words, by field label ("" key: none).
  [[nodiscard]] std::map<std::string, std::string> mesomodel_field_errors() const;
  void poll_job();
  void warm_up_renderer();
  void show_packing(std::shared_ptr<const Packing> packing, std::shared_ptr<SceneData> scene,
                    std::vector<std::string> entries);
  void render_scene_if_needed(int width, int height);
  void reset_view();
  void set_status(std::string text, bool is_error);
  void save_screenshot(const std::string& path);
  [[nodiscard]] int panel_width() const;
  [[nodiscard]] bool is_in_view(double x, double y) const;
  [[nodiscard]] bool is_interacting() const;

  GLFWwindow* window_;
  GuiOptions options_;
  ConfigFields fields_;
  BackgroundJob job_;
  std::shared_ptr<const Packing> packing_;
  std::vector<std::string> packing_entries_;
  std::vector<std::string> job_entries_;  // set_entries() of the pack job under way
  std::string job_kind_;                  // "pack", "open" (the job that gives a packing)
  Aabb last_bounds_;                      // scene bounds of packing_
  // A finished job's packing whose scene is being uploaded (a bounded piece per frame).
  UploadScheduler upload_;
  std::vector<std::string> last_entries_;            // set_entries() when field_errors_ were made
  std::map<std::string, std::string> field_errors_;  // key -> plain-words message
  std::string form_error_;                           // an error no field is named for
  GuiSettings settings_;
  FileDialog dialog_;
  bool show_help_ = false;
  bool show_fps_ = false;
  float menu_height_ = 0.0f;    // window pixels taken by the menu bar (top)
  float status_height_ = 0.0f;  // ... and by the status bar (bottom)
  // Whether frames drawn while the view moves must be light: the last full-detail picture took
  // longer than the detail controller's target (else they stay in full detail).
  bool needs_light_frames_ = false;
  bool is_upload_finished_now_ = false;  // this frame finished an upload: no drawing in it
  std::unique_ptr<PackingRenderer> renderer_;
  std::unique_ptr<OffscreenTarget> scene_target_;
  // Light frames drawn at a lower resolution (DetailLevel::resolution_scale) go here.
  std::unique_ptr<OffscreenTarget> light_target_;
  bool is_drawn_scaled_ = false;  // the current scene is in light_target_
  // The full-detail picture being drawn in steps (PackingRenderer::step_frame) goes here; it
  // replaces scene_target_ when finished.
  std::unique_ptr<OffscreenTarget> full_target_;
  double full_frame_start_ = 0.0;      // when the pending full-detail picture was begun
  double full_frame_seconds_ = 0.0;    // time spent in its steps so far
  double last_picture_latency_ = 0.0;  // begun to finished, last full-detail picture (s)
  bool has_picture_ = false;           // scene_target_ (or light_target_) holds a picture
  bool is_picture_new_ = false;        // this frame finished a picture (light or full)
  Camera camera_;
  RenderStyle style_;
  ViewPreset view_ = ViewPreset::kIso;
  bool is_scene_dirty_ = true;
  DrawStats last_stats_;
  double last_scene_seconds_ = 0.0;
  // Light frames while the view moves: their detail follows the frame time.
  DetailController detail_;
  double last_frame_start_ = -1.0;
  bool was_light_frame_ = false;  // the last frame redrew the scene as a light frame

  std::string status_;  // set by choose_language() (the start's words in its language)
  // The panel's field labels ("radius##particle.radius") by schema key, in the current language:
  // made once when it is empty (at start and after a language change), not per frame.
  std::vector<std::string> key_labels_;
  bool is_status_error_ = false;
  std::string open_path_ = "run.h5";
  std::string export_base_;
  double mesomodel_itz_mm_ = 0.0;                 // ITZ thickness of the mesomodel export (mm)
  double mesomodel_mortar_size_mm_ = 0.0;         // target mortar element edge (mm), 0 = no bound
  ItzKind mesomodel_itz_kind_ = ItzKind::kSolid;  // solid layer or cohesive elements
  DeckOptions deck_options_;                      // the Export dialog's solver deck fields
  MaterialOptions deck_material_;                 // ... and the deck's material

  // Mouse state.
  int dragging_button_ = -1;
  double last_scroll_time_ = -1.0;
  bool is_preview_ = false;  // the cached scene is a light in-motion frame
  double cursor_x_ = 0.0, cursor_y_ = 0.0;

  // Scripted runs (--pack/--open, --edit, --export, --screenshot, --benchmark-frames, --quit).
  friend class ScriptDriver;
  ScriptDriver script_{*this};
  // --benchmark-frames: first the camera turns as if dragged (light frames, adaptive detail),
  // then a few full-detail frames (the scene as it is drawn once the view rests).
  enum class BenchmarkPhase { kOff, kMoving, kStill };
  struct FrameTimes {  // sums over a phase's frames (s)
    int frames = 0;
    double wall = 0.0, scene = 0.0, blit = 0.0, panel = 0.0, ui_draw = 0.0, swap = 0.0;
    DrawStats drawn;            // summed over the pictures finished (a stepped one counts once)
    int scenes = 0;             // pictures finished (light frames and full-detail pictures)
    double settled_wall = 0.0;  // over the second half of the frames
    int settled_frames = 0;
    double longest = 0.0;          // longest frame
    double picture_latency = 0.0;  // still: from beginning each picture to finishing it
  };
  void start_benchmark();
  void print_benchmark(const char* label, const FrameTimes& times) const;
  BenchmarkPhase benchmark_phase_ = BenchmarkPhase::kOff;
  int benchmark_left_ = 0;
  double benchmark_frame_start_ = 0.0;
  FrameTimes moving_times_, still_times_;
  bool is_screenshot_requested_ = false;  // F12
  bool should_quit_ = false;
  int exit_code_ = 0;
};

}  // namespace aggpack::gui
