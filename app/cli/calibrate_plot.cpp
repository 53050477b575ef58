// PNG plot of a calibration search (on the plot raster of core/raster.h).

#include "calibrate_plot.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/raster.h"

namespace aggpack::cli {

void write_calibration_plot(const std::string& path, const CalibrationOptions& options,
                            const CalibrationResult& result) {
  constexpr int kWidth = 800;
  constexpr int kHeight = 560;
  constexpr int kLeft = 90;
  constexpr int kRight = 30;
  constexpr int kTop = 70;
  constexpr int kBottom = 70;
  const Rgb black{0, 0, 0};
  const Rgb grey{200, 200, 200};
  const Rgb blue{30, 90, 200};
  const Rgb red{210, 40, 40};
  const Rgb green{20, 150, 60};
  double lo = options.value;
  double hi = options.value;
  for (const auto& p : result.evaluated) {
    lo = std::min(lo, p.achieved.mean - p.achieved.standard_deviation);
    hi = std::max(hi, p.achieved.mean + p.achieved.standard_deviation);
  }
  const double pad = 0.05 * std::max(hi - lo, 1e-6);
  lo -= pad;
  hi += pad;
  const double plot_w = kWidth - kLeft - kRight;
  const double plot_h = kHeight - kTop - kBottom;
  auto px = [&](double alpha) { return kLeft + alpha * plot_w; };
  auto py = [&](double v) { return kTop + (hi - v) / (hi - lo) * plot_h; };

  Raster canvas(kWidth, kHeight);
  for (int k = 0; k <= 10; ++k) {  // grid and tick labels
    const double a = 0.1 * k;
    canvas.line(px(a), kTop, px(a), kTop + plot_h, 1, grey);
    canvas.text(fmt::format("{:.1f}", a), static_cast<int>(px(a)) - 8, kTop + plot_h + 8, 2, black);
    const double v = lo + (hi - lo) * k / 10.0;
    canvas.line(kLeft, py(v), kLeft + plot_w, py(v), 1, grey);
    canvas.text(fmt::format("{:.3f}", v), 10, static_cast<int>(py(v)) - 6, 2, black);
  }
  canvas.line(kLeft, kTop, kLeft, kTop + plot_h, 2, black);
  canvas.line(kLeft, kTop + plot_h, kLeft + plot_w, kTop + plot_h, 2, black);
  canvas.line(kLeft, py(options.value), kLeft + plot_w, py(options.value), 2, red);
  canvas.line(px(result.alpha), kTop, px(result.alpha), kTop + plot_h, 2, green);
  for (const auto& p : result.evaluated) {
    const double x = px(p.alpha);
    const double s = p.achieved.standard_deviation;
    canvas.line(x, py(p.achieved.mean - s), x, py(p.achieved.mean + s), 2, blue);
    canvas.fill_rect(static_cast<int>(x) - 4, static_cast<int>(py(p.achieved.mean)) - 4,
                     static_cast<int>(x) + 5, static_cast<int>(py(p.achieved.mean)) + 5, blue);
  }
  const std::string name = calibration_target_name(options.target);
  canvas.text(fmt::format("{} vs Eq. 3 alpha: mean +- sd (blue)", name), 20, 8, 2, black);
  canvas.text(
      fmt::format("target {:.4g} (red), found alpha {:.4f} (green)", options.value, result.alpha),
      20, 32, 2, black);
  canvas.text(fmt::format("Eq. 3 alpha (L/R {:.3g}, {} per point, seed {})", options.edge_ratio,
                          options.samples, options.seed),
              kLeft + 60, kHeight - 30, 2, black);

  write_png(path, canvas);
}

}  // namespace aggpack::cli
