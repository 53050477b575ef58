#pragma once
// The scripted-test driver of aggpack-gui: what --pack/--open, --mesomodel-export, --edit,
// --library-dialog with --library-pick, --export with --answer, --screenshot, --benchmark-frames,
// --frame-log and --quit do, step by step, once the first job's result is on screen; and the frame
// timing those runs print
// ("longest frame: ..."). The GUI tests (tests/gui/*.sh) drive the window through it.

namespace aggpack::gui {

class GuiApp;
struct JobResult;

class ScriptDriver {
 public:
  explicit ScriptDriver(GuiApp& app) : app_(app) {}

  /// At start: `is_job_started` when --open or --pack started the first job (the script waits
  /// for it), else `is_scripted` (a screenshot or quit without a job) acts after two frames.
  void start(bool is_job_started, bool is_scripted);
  /// Whether the script still waits for the first job's result.
  [[nodiscard]] bool is_waiting_for_first_job() const { return is_waiting_for_first_job_; }
  /// True while the script needs frames drawn (waiting, or the first frames after a step).
  [[nodiscard]] bool is_busy() const;
  /// A job result was taken (GuiApp::poll_job): starts --mesomodel-export after the first job,
  /// then counts frames from the result.
  void on_job_result(const JobResult& result);
  /// One frame was drawn.
  void count_frame();
  /// After the frame is drawn: the script's next step (see the file comment).
  void after_render();
  /// Frame timing of scripted runs: main calls these around each frame's work.
  void note_frame_start();
  void note_frame_end();

 private:
  void answer_dialog();
  void answer_library_dialog();
  void take_screenshot_once();
  void print_outcome();

  GuiApp& app_;
  bool is_waiting_for_first_job_ = false;
  bool is_mesomodel_script_started_ = false;  // --mesomodel-export's job was started
  int frames_since_job_ = -1;
  bool are_edits_applied_ = false;
  bool is_export_script_started_ = false;
  bool is_library_script_started_ = false;
  bool is_screenshot_taken_ = false;   // the scripted screenshot was written
  bool is_benchmark_started_ = false;  // --benchmark-frames began
  bool is_script_done_ = false;
  // Longest wall time between two frames since the first job started (scripted runs print it).
  bool is_timing_frames_ = false;
  bool is_frame_timing_skipped_ = false;  // this frame wrote a screenshot: not timed
  double frame_work_start_ = 0.0;
  double longest_frame_ = 0.0;
  double first_frame_ = -1.0;  // the window's first frame (start-up), not in longest_frame_
  int timed_frames_ = 0;
};

}  // namespace aggpack::gui
