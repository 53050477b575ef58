// PNG plot of a calibration search (stb_image_write and stb_easy_font, as the repose side view).

#include "calibrate_plot.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"

#ifdef AGGPACK_HAS_STB
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wuseless-cast"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#endif
#include <stb_easy_font.h>
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#endif

namespace aggpack::cli {

#ifdef AGGPACK_HAS_STB

namespace {

using Rgb = std::array<std::uint8_t, 3>;

struct Canvas {
  int width;
  int height;
  std::vector<std::uint8_t> pixels;

  Canvas(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(3 * w * h), 255) {}

  void fill(int x0, int y0, int x1, int y1, const Rgb& c) {
    for (int y = std::max(0, y0); y < std::min(height, y1); ++y) {
      for (int x = std::max(0, x0); x < std::min(width, x1); ++x) {
        auto* p = &pixels[3 * (static_cast<std::size_t>(y) * width + x)];
        p[0] = c[0];
        p[1] = c[1];
        p[2] = c[2];
      }
    }
  }

  void line(double x0, double y0, double x1, double y1, int thickness, const Rgb& c) {
    const int steps = std::max(1, static_cast<int>(std::ceil(2.0 * std::hypot(x1 - x0, y1 - y0))));
    for (int k = 0; k <= steps; ++k) {
      const double t = static_cast<double>(k) / steps;
      const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0))) - thickness / 2;
      const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0))) - thickness / 2;
      fill(x, y, x + thickness, y + thickness, c);
    }
  }

  void text(const std::string& message, int x, int y, int scale, const Rgb& c) {
    std::vector<char> buffer(message.size() * 300 + 1000);
    std::string copy = message;
    const int quads = stb_easy_font_print(0.0F, 0.0F, copy.data(), nullptr, buffer.data(),
                                          static_cast<int>(buffer.size()));
    const auto* v = reinterpret_cast<const float*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
      const float* quad = v + static_cast<std::ptrdiff_t>(q) * 16;
      fill(x + scale * static_cast<int>(quad[0]), y + scale * static_cast<int>(quad[1]),
           x + scale * static_cast<int>(quad[8]), y + scale * static_cast<int>(quad[9]), c);
    }
  }
};

}  // namespace

void check_plot_available(const std::string& /*option*/) {}

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

  Canvas canvas(kWidth, kHeight);
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
    canvas.fill(static_cast<int>(x) - 4, static_cast<int>(py(p.achieved.mean)) - 4,
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

  AtomicFile file(path);
  auto writer = [](void* context, void* data, int size) {
    static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
  };
  if (stbi_write_png_to_func(writer, &file.stream(), kWidth, kHeight, 3, canvas.pixels.data(),
                             kWidth * 3) == 0) {
    throw IoError("cannot encode PNG " + path);
  }
  file.commit();
}

#else

void check_plot_available(const std::string& option) {
  throw InvalidInput(option, "PNG", "a build with stb_image_write (apt-get install libstb-dev)");
}

void write_calibration_plot(const std::string& path, const CalibrationOptions& /*options*/,
                            const CalibrationResult& /*result*/) {
  check_plot_available(path);
}

#endif

}  // namespace aggpack::cli
