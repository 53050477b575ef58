#pragma once
// Progress display for long CLI runs: a redrawn bar with rate and ETA when the stream is a
// terminal, plain periodic lines otherwise (logs, CI, pipes).

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>

namespace aggpack::cli {

/// How progress is shown. kAuto = kBar when the stream is a terminal (isatty), else kLines.
enum class ProgressStyle { kAuto, kBar, kLines, kNone };

/// Parses "auto", "bar", "lines", "none". \throw InvalidInput naming `field`.
ProgressStyle parse_progress_style(const std::string& field, const std::string& text);

/// Formats a duration in seconds as "0:07", "12:34" or "1:02:03" ("--:--" if not finite or < 0).
std::string format_duration(double seconds);

/// One progress display. Not thread-safe: call it from one thread (the packers call their
/// progress callback from the packing thread).
class ProgressBar {
 public:
  /// `label` starts every line ("placing"); `unit` names the counted items ("particles").
  ProgressBar(std::string label, std::string unit, ProgressStyle style = ProgressStyle::kAuto,
              std::FILE* stream = stderr);
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar();

  /// Reports progress: `fraction` of the work in [0, 1] (drives the bar and the ETA), `done` of
  /// `total` items (drives the rate, items per second; total 0 = unknown), `extra` appended
  /// ("solid 31.2 %"). Rate and ETA are measured from the first update, so a display created
  /// late (at a stage's first callback) still shows true figures.
  /// Bars redraw at most 10 times a second; plain lines appear at every further 10 % and at
  /// least every 10 s.
  void update(double fraction, std::uint64_t done, std::uint64_t total,
              const std::string& extra = {});
  /// Ends the display with a final line (elapsed time, mean rate). Called by the destructor.
  void finish();

  [[nodiscard]] bool is_bar() const { return style_ == ProgressStyle::kBar; }

 private:
  [[nodiscard]] std::string status_text(double elapsed) const;
  [[nodiscard]] std::string count_text() const;

  std::string label_;
  std::string unit_;
  ProgressStyle style_;
  std::FILE* stream_;
  std::chrono::steady_clock::time_point start_;
  double last_output_ = -1.0;  // seconds since start of the last bar draw / line
  double next_line_fraction_ = 0.1;
  double first_time_ = -1.0;  // seconds since start of the first update
  double first_fraction_ = 0.0;
  std::uint64_t first_done_ = 0;
  double fraction_ = 0.0;
  std::uint64_t done_ = 0;
  std::uint64_t total_ = 0;
  std::string extra_;
  bool has_update_ = false;
  bool is_finished_ = false;
};

}  // namespace aggpack::cli
