#pragma once
// Progress display for long CLI runs: a redrawn bar with rate and ETA when the stream is a
// terminal, plain periodic lines otherwise (logs, CI, pipes).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "aggpack/pack/resources.h"

namespace aggpack::cli {

/// How progress is shown. kAuto = kBar when the stream is a terminal (isatty), else kLines.
enum class ProgressStyle { kAuto, kBar, kLines, kNone };

/// Parses "auto", "bar", "lines", "none". \throw InvalidInput naming `field`.
ProgressStyle parse_progress_style(const std::string& field, const std::string& text);

/// Prints heavy_run_note(estimate) to stderr as "aggpack: a large run: ..." when the run is
/// heavy (aggpack/pack/resources.h), whatever --progress says; nothing otherwise.
void announce_heavy_run(const RunEstimate& estimate);

/// Formats a duration in seconds as "0:07", "12:34" or "1:02:03" ("--:--" if not finite or < 0).
std::string format_duration(double seconds);

/// Longest gap (s) between two outputs of a running display: a bar is redrawn and a plain line
/// printed at least this often, with fresh figures when the work reported some and a count-down
/// ETA when it did not (a stage whose callbacks are slower than this still shows it is alive).
inline constexpr double kProgressHeartbeat = 2.0;

/// Seconds a step whose length is estimated (shapes -n, a timed stage) may run before its display
/// appears, so that a short step prints nothing: kProgressHeartbeat, or the environment variable
/// AGGPACK_PROGRESS_DELAY (seconds in [0, 3600]; 0 = every display from the start, e.g. for a
/// log that must show each step). \throw InvalidInput naming the variable.
double progress_delay();

/// One progress display. update() and finish() may be called from one thread at a time; a
/// heartbeat thread of its own redraws between updates (kProgressHeartbeat).
class ProgressBar {
 public:
  /// Seconds on a steady clock; replaceable for tests.
  using Clock = std::function<double()>;

  /// `label` starts every line ("placing"); `unit` names the counted items ("particles").
  /// `clock` = the steady clock and a heartbeat thread; a given clock means no thread (tests
  /// call heartbeat() themselves).
  ProgressBar(std::string label, std::string unit, ProgressStyle style = ProgressStyle::kAuto,
              std::FILE* stream = stderr, Clock clock = {});
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar();

  /// Counts the display's time (its final "in T s") from `start` instead of its construction: a
  /// stage's display is made at the stage's first report, its work began before.
  void set_start(std::chrono::steady_clock::time_point start);
  /// Reports progress: `fraction` of the work in [0, 1] (drives the bar and the ETA), `done` of
  /// `total` items (drives the rate, items per second; total 0 = unknown), `extra` appended
  /// ("solid 31.2 %"). Rate and ETA are measured from the first update, so a display created
  /// late (at a stage's first callback) still shows true figures; until they are known (0.2 s
  /// after the first update) they are left out rather than shown as "-/s ETA --:--".
  /// Bars redraw at most 10 times a second; plain lines appear at every further 10 % of the work
  /// and at least every kProgressHeartbeat seconds.
  void update(double fraction, std::uint64_t done, std::uint64_t total,
              const std::string& extra = {});
  /// The ETA is an upper bound ("ETA <= 1:23"): the work may end sooner (a settling run stops
  /// when the packing is at rest, its fraction is simulated time / the time limit).
  void set_eta_is_bound(bool is_bound);
  /// Redraws (bar) or prints a line if nothing was shown for kProgressHeartbeat seconds; called
  /// by the heartbeat thread, or by tests with their own clock.
  void heartbeat();
  /// Ends the display with a final line (elapsed time, mean rate). Called by the destructor.
  /// `seconds` >= 0: the line shows this duration instead of the display's clock, so that a
  /// summary printing the work's own measurement afterwards shows the same number.
  void finish(double seconds = -1.0);
  /// The duration the final line showed, once finished; nullopt when it showed none (kNone, or
  /// no update): a summary prints this number, so the two agree.
  [[nodiscard]] std::optional<double> shown_seconds() const { return shown_seconds_; }

  [[nodiscard]] bool is_bar() const { return style_ == ProgressStyle::kBar; }

 private:
  [[nodiscard]] double now() const;
  [[nodiscard]] std::string status_text(double elapsed) const;
  [[nodiscard]] std::string count_text() const;
  void draw(double elapsed);  // with mutex_ held
  void stop_thread();

  std::string label_;
  std::string unit_;
  ProgressStyle style_;
  std::FILE* stream_;
  Clock clock_;
  std::chrono::steady_clock::time_point start_;
  double last_output_ = -1.0;  // seconds since start of the last bar draw / line
  double next_line_fraction_ = 0.1;
  double first_time_ = -1.0;  // seconds since start of the first update
  double first_fraction_ = 0.0;
  std::uint64_t first_done_ = 0;
  double last_update_ = 0.0;  // seconds since start of the latest update
  double fraction_ = 0.0;
  std::uint64_t done_ = 0;
  std::uint64_t total_ = 0;
  std::string extra_;
  bool has_update_ = false;
  bool is_finished_ = false;
  bool is_eta_bound_ = false;
  std::optional<double> shown_seconds_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool is_stopping_ = false;
  std::thread ticker_;
};

/// What a StageTimer knows of its stage's duration besides the clock (all in seconds; <= 0 =
/// not known).
struct StageTiming {
  double limit_seconds = 0.0;       ///< the whole stage stops at this (mesomodel's --time-limit)
  double item_limit_seconds = 0.0;  ///< each item stops at this (export's --tet-time-limit)
  std::string item = "shape";       ///< what item_limit_seconds is per
  /// The estimate of aggpack/pack/resources.h (the heads-up's): gives an ETA ("ETA ~0:12 by the
  /// estimate"), and a stage expected to take kProgressHeartbeat or more shows its line at once.
  double expected_seconds = 0.0;
  /// Items settled so far of items_total (0 = not counted): once one is done, the line shows
  /// the count, the rate and an ETA measured from them instead of the estimate's.
  std::uint64_t items_done = 0;
  std::uint64_t items_total = 0;
};

/// A StageTimer's line after `elapsed` seconds: "meshing (TetGen): 0:04 elapsed, ETA ~0:06 by
/// the estimate (stops at the time limit, 59:56 from now at most)"; `is_final`: "LABEL: done in
/// T s".
std::string stage_text(const std::string& label, double elapsed, const StageTiming& timing,
                       bool is_final);

/// A step that reports nothing while it runs (TetGen meshing in a worker process, voxelisation):
/// shows the elapsed time every kProgressHeartbeat seconds (a bar is redrawn every second) so the
/// user sees it is alive, with the step's ETA by the estimate and its time limits when it has
/// them (stage_text), and a final line with its duration.
class StageTimer {
 public:
  StageTimer(std::string label, ProgressStyle style, StageTiming timing = {},
             std::FILE* stream = stderr);
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer();
  /// Stops the display with "label: done in T s" (when anything was shown). Called by the
  /// destructor.
  void finish();
  /// Counts the stage's items (StageTiming::items_done, items_total); any thread.
  void set_items(std::uint64_t done, std::uint64_t total);

 private:
  void draw(double elapsed, bool is_final);

  std::string label_;
  ProgressStyle style_;
  StageTiming timing_;
  std::FILE* stream_;
  std::chrono::steady_clock::time_point start_;
  bool has_output_ = false;
  bool is_finished_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool is_stopping_ = false;
  std::thread ticker_;
};

}  // namespace aggpack::cli
