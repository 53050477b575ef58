// The PNG plot raster (core/raster.h): stb_easy_font for text, stb_image_write for PNG.

#include "aggpack/core/raster.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_easy_font.h>
#include <stb_image_write.h>  // a SYSTEM include folder: its warnings are not ours

namespace aggpack {

Raster::Raster(int width, int height)
    : width_(std::max(1, width)),
      height_(std::max(1, height)),
      pixels_(3 * static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 255) {}

void Raster::set(int x, int y, const Rgb& colour) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  auto* p = &pixels_[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                          static_cast<std::size_t>(x))];
  p[0] = colour[0];
  p[1] = colour[1];
  p[2] = colour[2];
}

void Raster::fill_rect(int x0, int y0, int x1, int y1, const Rgb& colour) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) set(x, y, colour);
  }
}

void Raster::line(double x0, double y0, double x1, double y1, int thickness, const Rgb& colour) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, static_cast<int>(std::ceil(length * 2.0)));
  const int half = thickness / 2;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    fill_rect(x - half, y - half, x - half + thickness, y - half + thickness, colour);
  }
}

void Raster::fill_convex(const std::vector<std::array<double, 2>>& polygon, const Rgb& colour) {
  if (polygon.size() < 3) return;
  double top = polygon[0][1];
  double bottom = polygon[0][1];
  for (const auto& p : polygon) {
    top = std::min(top, p[1]);
    bottom = std::max(bottom, p[1]);
  }
  for (int y = std::max(0, static_cast<int>(std::floor(top)));
       y <= std::min(height_ - 1, static_cast<int>(std::ceil(bottom))); ++y) {
    const double yc = y + 0.5;
    double left = 1e300;
    double right = -1e300;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const auto& a = polygon[i];
      const auto& b = polygon[(i + 1) % polygon.size()];
      if ((a[1] <= yc && b[1] > yc) || (b[1] <= yc && a[1] > yc)) {
        const double x = a[0] + (yc - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
        left = std::min(left, x);
        right = std::max(right, x);
      }
    }
    if (left > right) continue;
    for (int x = std::max(0, static_cast<int>(std::lround(left)));
         x < std::min(width_, static_cast<int>(std::lround(right))); ++x) {
      set(x, y, colour);
    }
  }
}

void Raster::text(const std::string& message, int x, int y, int scale, const Rgb& colour) {
  std::vector<char> buffer(message.size() * 300 + 1000);
  std::string copy = message;
  const int quads = stb_easy_font_print(0.0F, 0.0F, copy.data(), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size()));
  const auto* vertices = reinterpret_cast<const float*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const float* v = vertices + static_cast<std::ptrdiff_t>(q) * 4 * 4;  // 4 vertices x 16 bytes
    const int qx0 = static_cast<int>(v[0]);
    const int qy0 = static_cast<int>(v[1]);
    const int qx1 = static_cast<int>(v[8]);
    const int qy1 = static_cast<int>(v[9]);
    fill_rect(x + scale * qx0, y + scale * qy0, x + scale * qx1, y + scale * qy1, colour);
  }
}

void write_png(const std::string& path, const Raster& raster) {
  write_png_rgb(path, raster.width(), raster.height(), raster.pixels());
}

void write_png_rgb(const std::string& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb, Overwrite overwrite) {
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw InvalidInput("image", std::to_string(width) + "x" + std::to_string(height),
                       "a non-empty RGB image");
  }
  AtomicFile file(path, overwrite);
  auto writer = [](void* context, void* data, int size) {
    static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
  };
  if (stbi_write_png_to_func(writer, &file.stream(), width, height, 3, rgb.data(), width * 3) ==
      0) {
    throw IoError(Wording{Sentence::kPngEncode, {path}});
  }
  file.commit();
}

}  // namespace aggpack
