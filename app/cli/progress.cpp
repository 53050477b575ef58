#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "aggpack/core/error.h"

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

ProgressBar::ProgressBar(std::string label, std::string unit, ProgressStyle style,
                         std::FILE* stream)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      style_(style),
      stream_(stream),
      start_(std::chrono::steady_clock::now()) {
  if (style_ == ProgressStyle::kAuto) {
    style_ = ::isatty(::fileno(stream_)) != 0 ? ProgressStyle::kBar : ProgressStyle::kLines;
  }
}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::count_text() const {
  if (total_ == 0) return fmt::format("{} {}", done_, unit_);
  return fmt::format("{}/{} {}", done_, total_, unit_);
}

std::string ProgressBar::status_text(double elapsed) const {
  const double span = first_time_ >= 0 ? elapsed - first_time_ : 0.0;
  // Below 0.2 s a rate is noise (one callback may cover a large jump).
  const double rate = span > 0.2 ? static_cast<double>(done_ - first_done_) / span : 0.0;
  double eta = -1;
  if (fraction_ >= 1) {
    eta = 0;
  } else if (span > 0.2 && fraction_ > first_fraction_) {
    eta = span * (1 - fraction_) / (fraction_ - first_fraction_);
  }
  std::string text = fmt::format("{:5.1f}%  {}  {}/s  ETA {}", 100.0 * fraction_, count_text(),
                                 format_rate(rate), format_duration(eta));
  if (!extra_.empty()) text += "  " + extra_;
  return text;
}

void ProgressBar::update(double fraction, std::uint64_t done, std::uint64_t total,
                         const std::string& extra) {
  if (style_ == ProgressStyle::kNone || is_finished_) return;
  fraction_ = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  done_ = done;
  total_ = total;
  extra_ = extra;
  has_update_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (first_time_ < 0) {
    first_time_ = elapsed;
    first_fraction_ = fraction_;
    first_done_ = done_;
  }
  if (style_ == ProgressStyle::kBar) {
    if (last_output_ >= 0 && elapsed - last_output_ < 0.1 && fraction_ < 1) return;
    last_output_ = elapsed;
    const std::string status = status_text(elapsed);
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
    return;
  }
  // Plain lines: one per further 10 % of the work, and at least every 10 s.
  const bool is_step = fraction_ >= next_line_fraction_ && fraction_ < 1;
  const bool is_due = last_output_ < 0 ? elapsed >= 10 : elapsed - last_output_ >= 10;
  if (!is_step && !is_due) return;
  while (next_line_fraction_ <= fraction_) next_line_fraction_ += 0.1;
  last_output_ = elapsed;
  std::fprintf(stream_, "%s: %s\n", label_.c_str(), status_text(elapsed).c_str());
  std::fflush(stream_);
}

void ProgressBar::finish() {
  if (is_finished_) return;
  is_finished_ = true;
  if (style_ == ProgressStyle::kNone || !has_update_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double span = elapsed - first_time_;
  std::string line =
      fmt::format("{}: {:.1f}%  {} in {:.2f} s", label_, 100.0 * fraction_, count_text(), elapsed);
  if (span > 0.2) {
    line += fmt::format(" ({}/s)", format_rate(static_cast<double>(done_ - first_done_) / span));
  }
  if (!extra_.empty()) line += "  " + extra_;
  if (style_ == ProgressStyle::kBar) std::fprintf(stream_, "\r\033[K");
  std::fprintf(stream_, "%s\n", line.c_str());
  std::fflush(stream_);
}

}  // namespace aggpack::cli
