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
  constexpr double kClamp = 50.0;  // misses beyond +- 50 % are drawn at the edge
  const Rgb black{0, 0, 0};
  const Rgb grey{200, 200, 200};
  const Rgb band{225, 245, 225};
  const std::array<Rgb, 3> colours = {Rgb{30, 90, 200}, Rgb{210, 40, 40}, Rgb{20, 150, 60}};
  const std::size_t n = std::max<std::size_t>(result.evaluated.size(), 2);
  const double plot_w = kWidth - kLeft - kRight;
  const double plot_h = kHeight - kTop - kBottom;
  auto px = [&](double i) { return kLeft + i / static_cast<double>(n - 1) * plot_w; };
  auto py = [&](double miss) {
    return kTop + (kClamp - std::clamp(miss, -kClamp, kClamp)) / (2.0 * kClamp) * plot_h;
  };

  Raster canvas(kWidth, kHeight);
  const double tolerance = 100.0 * options.tolerance;
  canvas.fill_rect(kLeft, static_cast<int>(py(tolerance)), kLeft + static_cast<int>(plot_w),
                   static_cast<int>(py(-tolerance)), band);
  for (int k = 0; k <= 10; ++k) {  // grid and tick labels
    const double i = static_cast<double>(n - 1) * k / 10.0;
    canvas.line(px(i), kTop, px(i), kTop + plot_h, 1, grey);
    canvas.text(fmt::format("{:.0f}", i), static_cast<int>(px(i)) - 8, kTop + plot_h + 8, 2, black);
    const double miss = -kClamp + 2.0 * kClamp * k / 10.0;
    canvas.line(kLeft, py(miss), kLeft + plot_w, py(miss), 1, grey);
    canvas.text(fmt::format("{:+.0f}", miss), 30, static_cast<int>(py(miss)) - 6, 2, black);
  }
  canvas.line(kLeft, kTop, kLeft, kTop + plot_h, 2, black);
  canvas.line(kLeft, kTop + plot_h, kLeft + plot_w, kTop + plot_h, 2, black);
  std::string legend;
  for (std::size_t g = 0; g < options.goals.size(); ++g) {
    const CalibrationGoal& goal = options.goals[g];
    const Rgb& colour = colours[g % colours.size()];
    double last_x = 0.0;
    double last_y = 0.0;
    for (std::size_t i = 0; i < result.evaluated.size(); ++i) {
      const double miss =
          100.0 * (mean_of(result.evaluated[i], goal.target) - goal.value) / goal.value;
      const double x = px(static_cast<double>(i));
      const double y = py(miss);
      if (i > 0) canvas.line(last_x, last_y, x, y, 1, colour);
      canvas.fill_rect(static_cast<int>(x) - 3, static_cast<int>(y) - 3, static_cast<int>(x) + 4,
                       static_cast<int>(y) + 4, colour);
      last_x = x;
      last_y = y;
    }
    canvas.text(calibration_target_name(goal.target), 20 + static_cast<int>(g) * 250, 32, 2,
                colour);
  }
  canvas.text(
      fmt::format("miss (%) of each target per evaluation; green band +- {:.3g} %", tolerance), 20,
      8, 2, black);
  canvas.text(fmt::format("evaluation ({} particles each, seed {})", options.samples, options.seed),
              kLeft + 60, kHeight - 30, 2, black);

  write_png(path, canvas);
}

}  // namespace aggpack::cli
