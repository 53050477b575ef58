#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "aggpack/core/error.h"
#include "aggpack/core/isolated.h"
#include "aggpack/core/text.h"

namespace aggpack::cli {

namespace {

int terminal_width(std::FILE* stream) {
  winsize size{};
  if (::ioctl(::fileno(stream), TIOCGWINSZ, &size) == 0 && size.ws_col >= 20) return size.ws_col;
  return 80;
}

std::string format_rate(double rate) {
  if (!std::isfinite(rate) || rate <= 0) return "-";
  if (rate >= 1e6) return fmt::format("{:.2f}M", rate / 1e6);
  if (rate >= 1e4) return fmt::format("{:.1f}k", rate / 1e3);
  if (rate >= 10) return fmt::format("{:.0f}", rate);
  return fmt::format("{:.2f}", rate);
}

}  // namespace

void announce_heavy_run(const RunEstimate& estimate) {
  if (const std::string note = heavy_run_note(estimate); !note.empty()) {
    std::fprintf(stderr, "aggpack: %s\n", note.c_str());
    std::fflush(stderr);
  }
}

ProgressStyle parse_progress_style(const std::string& field, const std::string& text) {
  if (text == "auto") return ProgressStyle::kAuto;
  if (text == "bar") return ProgressStyle::kBar;
  if (text == "lines") return ProgressStyle::kLines;
  if (text == "none") return ProgressStyle::kNone;
  throw InvalidInput(field, text, "auto | bar | lines | none");
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--";
  const auto total = static_cast<long long>(std::llround(seconds));
  const long long hours = total / 3600;
  const long long minutes = (total / 60) % 60;
  const long long secs = total % 60;
  if (hours > 0) return fmt::format("{}:{:02}:{:02}", hours, minutes, secs);
  return fmt::format("{}:{:02}", minutes, secs);
}

double progress_delay() {
  const char* text = std::getenv("AGGPACK_PROGRESS_DELAY");
  if (text == nullptr) return kProgressHeartbeat;
  const std::string typed = text;
  char* end = nullptr;
  const double seconds = std::strtod(typed.c_str(), &end);
  if (typed.empty() || end != typed.c_str() + typed.size() || !(seconds >= 0 && seconds <= 3600)) {
    throw InvalidInput("AGGPACK_PROGRESS_DELAY", "\"" + clipped(typed, 40) + "\"",
                       "seconds in [0, 3600] (unset: 2)");
  }
  return seconds;
}

ProgressBar::ProgressBar(std::string label, std::string unit, ProgressStyle style,
                         std::FILE* stream, Clock clock)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      style_(style),
      stream_(stream),
      clock_(std::move(clock)),
      start_(std::chrono::steady_clock::now()) {
  if (style_ == ProgressStyle::kAuto) {
    style_ = ::isatty(::fileno(stream_)) != 0 ? ProgressStyle::kBar : ProgressStyle::kLines;
  }
  if (style_ == ProgressStyle::kNone || clock_) return;
  ticker_ = start_thread_before_forks([this] {
    std::unique_lock lock(mutex_);
    while (!is_stopping_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (is_stopping_) break;
      lock.unlock();
      {
        const auto no_fork = section_without_fork();
        heartbeat();
      }
      lock.lock();
    }
  });
}

ProgressBar::~ProgressBar() { finish(); }

double ProgressBar::now() const {
  if (clock_) return clock_();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::stop_thread() {
  {
    const std::lock_guard lock(mutex_);
    is_stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void ProgressBar::set_start(std::chrono::steady_clock::time_point start) {
  const std::lock_guard lock(mutex_);
  start_ = start;
}

void ProgressBar::set_eta_is_bound(bool is_bound) {
  const std::lock_guard lock(mutex_);
  is_eta_bound_ = is_bound;
}

std::string ProgressBar::count_text() const {
  if (total_ == 0) return fmt::format("{} {}", done_, unit_);
  return fmt::format("{}/{} {}", done_, total_, unit_);
}

std::string ProgressBar::status_text(double elapsed) const {
  const double span = first_time_ >= 0 ? last_update_ - first_time_ : 0.0;
  std::string text = fmt::format("{:5.1f}%  {}", 100.0 * fraction_, count_text());
  // Below 0.2 s a rate is noise (one callback may cover a large jump): left out until known.
  if (span > 0.2) {
    text += fmt::format("  {}/s", format_rate(static_cast<double>(done_ - first_done_) / span));
    if (fraction_ > first_fraction_ && fraction_ < 1) {
      // The estimate at the latest update, counted down since (a heartbeat between updates).
      const double at_update = span * (1 - fraction_) / (fraction_ - first_fraction_);
      const double eta = std::max(0.0, at_update - (elapsed - last_update_));
      text += fmt::format("  ETA {}{}", is_eta_bound_ ? "<= " : "", format_duration(eta));
    }
  }
  if (!extra_.empty()) text += "  " + extra_;
  return text;
}

void ProgressBar::draw(double elapsed) {
  last_output_ = elapsed;
  const std::string status = status_text(elapsed);
  if (style_ == ProgressStyle::kLines) {
    std::fprintf(stream_, "%s: %s\n", label_.c_str(), status.c_str());
    std::fflush(stream_);
    return;
  }
  const int width = terminal_width(stream_);
  // A fixed bar width (a quarter of the terminal) so the bar does not jump as the text changes;
  // the status text is cut at the right edge instead.
  const int bar_width = std::clamp(width / 4, 10, 30);
  const int filled = static_cast<int>(std::floor(fraction_ * bar_width));
  const std::string bar = "[" + std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(bar_width - filled), '.') + "] ";
  std::string line = label_ + " " + bar + status;
  if (static_cast<int>(line.size()) > width - 1) line.resize(static_cast<std::size_t>(width - 1));
  // \r + erase-line: redraw in place.
  std::fprintf(stream_, "\r\033[K%s", line.c_str());
  std::fflush(stream_);
}

void ProgressBar::update(double fraction, std::uint64_t done, std::uint64_t total,
                         const std::string& extra) {
  if (style_ == ProgressStyle::kNone) return;
  const std::lock_guard lock(mutex_);
  if (is_finished_) return;
  fraction_ = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  done_ = done;
  total_ = total;
  extra_ = extra;
  has_update_ = true;
  const double elapsed = now();
  last_update_ = elapsed;
  if (first_time_ < 0) {
    first_time_ = elapsed;
    first_fraction_ = fraction_;
    first_done_ = done_;
  }
  if (style_ == ProgressStyle::kBar) {
    if (last_output_ >= 0 && elapsed - last_output_ < 0.1 && fraction_ < 1) return;
    draw(elapsed);
    return;
  }
  // Plain lines: one per further 10 % of the work, and at least every kProgressHeartbeat s.
  const bool is_step = fraction_ >= next_line_fraction_ && fraction_ < 1;
  const bool is_due =
      (last_output_ < 0 ? elapsed - first_time_ : elapsed - last_output_) >= kProgressHeartbeat;
  if (!is_step && !is_due) return;
  while (next_line_fraction_ <= fraction_) next_line_fraction_ += 0.1;
  draw(elapsed);
}

void ProgressBar::heartbeat() {
  if (style_ == ProgressStyle::kNone) return;
  const std::lock_guard lock(mutex_);
  if (is_finished_ || !has_update_) return;
  const double elapsed = now();
  const double since = last_output_ < 0 ? elapsed - first_time_ : elapsed - last_output_;
  if (since >= (style_ == ProgressStyle::kBar ? 1.0 : kProgressHeartbeat)) draw(elapsed);
}

void ProgressBar::finish(double seconds) {
  if (style_ != ProgressStyle::kNone && !clock_) stop_thread();
  const std::lock_guard lock(mutex_);
  if (is_finished_) return;
  is_finished_ = true;
  if (style_ == ProgressStyle::kNone || !has_update_) return;
  // A finished display reports the time to its last update: it may be ended later (a stage's
  // display ends when the next stage first reports).
  const double clock_elapsed = fraction_ >= 1 ? last_update_ : now();
  const double elapsed = seconds >= 0 ? seconds : clock_elapsed;
  shown_seconds_ = elapsed;
  const double span = clock_elapsed - first_time_;  // the rate: the display's own updates
  std::string line = fmt::format("{}: {:.1f}%  {} in {} s", label_, 100.0 * fraction_, count_text(),
                                 format_seconds(elapsed));
  if (span > 0.2) {
    line += fmt::format(" ({}/s)", format_rate(static_cast<double>(done_ - first_done_) / span));
  }
  if (!extra_.empty()) line += "  " + extra_;
  if (style_ == ProgressStyle::kBar) std::fprintf(stream_, "\r\033[K");
  std::fprintf(stream_, "%s\n", line.c_str());
  std::fflush(stream_);
}

std::string stage_text(const std::string& label, double elapsed, const StageTiming& timing,
                       bool is_final) {
  if (is_final) return fmt::format("{}: done in {} s", label, format_seconds(elapsed));
  std::string text = fmt::format("{}: {} elapsed", label, format_duration(elapsed));
  if (timing.items_total > 0) {
    text += fmt::format(", {} of {} {}s", timing.items_done, timing.items_total, timing.item);
  }
  if (timing.items_done > 0 && elapsed > 0) {
    // Measured: the items settled so far at their mean rate.
    const double rate = static_cast<double>(timing.items_done) / elapsed;
    const double left =
        static_cast<double>(timing.items_total - std::min(timing.items_done, timing.items_total));
    text += fmt::format(", {} {}s/s, ETA {}", format_rate(rate), timing.item,
                        format_duration(left / rate));
  } else if (timing.expected_seconds > 0) {
    text += elapsed < timing.expected_seconds
                ? fmt::format(", ETA ~{} by the estimate",
                              format_duration(timing.expected_seconds - elapsed))
                : fmt::format(", longer than the estimate of {}",
                              format_duration(timing.expected_seconds));
  }
  if (timing.limit_seconds > 0) {
    text += fmt::format(" (stops at the time limit, {} from now at most)",
                        format_duration(std::max(0.0, timing.limit_seconds - elapsed)));
  }
  if (timing.item_limit_seconds > 0) {
    text += fmt::format(" (each {} stops at its time limit of {} s)", timing.item,
                        format_seconds(timing.item_limit_seconds));
  }
  return text;
}

StageTimer::StageTimer(std::string label, ProgressStyle style, StageTiming timing,
                       std::FILE* stream)
    : label_(std::move(label)),
      style_(style),
      timing_(std::move(timing)),
      stream_(stream),
      start_(std::chrono::steady_clock::now()) {
  if (style_ == ProgressStyle::kAuto) {
    style_ = ::isatty(::fileno(stream_)) != 0 ? ProgressStyle::kBar : ProgressStyle::kLines;
  }
  if (style_ == ProgressStyle::kNone) return;
  // A stage the estimate expects to be long is shown at once, with its ETA.
  const bool is_shown_at_once = timing_.expected_seconds >= progress_delay();
  if (is_shown_at_once) draw(0.0, false);
  ticker_ = start_thread_before_forks([this] {
    const double interval = style_ == ProgressStyle::kBar ? 1.0 : kProgressHeartbeat;
    std::unique_lock lock(mutex_);
    for (int tick = 1; !is_stopping_; ++tick) {
      // Quiet for the first interval (unless shown at once): a step that ends at once prints
      // nothing.
      wake_.wait_until(lock, start_ + std::chrono::duration<double>(tick * interval));
      if (is_stopping_) break;
      const auto no_fork = section_without_fork();
      draw(tick * interval, false);
    }
  });
}

StageTimer::~StageTimer() { finish(); }

void StageTimer::set_items(std::uint64_t done, std::uint64_t total) {
  const std::lock_guard lock(mutex_);
  timing_.items_done = done;
  timing_.items_total = total;
}

void StageTimer::draw(double elapsed, bool is_final) {
  const std::string text = stage_text(label_, elapsed, timing_, is_final);
  if (style_ == ProgressStyle::kBar) {
    std::fprintf(stream_, "\r\033[K%s%s", text.c_str(), is_final ? "\n" : "");
  } else {
    std::fprintf(stream_, "%s\n", text.c_str());
  }
  std::fflush(stream_);
  has_output_ = true;
}

void StageTimer::finish() {
  {
    const std::lock_guard lock(mutex_);
    if (is_finished_) return;
    is_finished_ = true;
    is_stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  const std::lock_guard lock(mutex_);
  if (!has_output_) return;
  draw(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(), true);
}

}  // namespace aggpack::cli
