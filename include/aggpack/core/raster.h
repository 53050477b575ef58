#pragma once
// A small RGB raster for the PNG plots the command-line tools write (repose side view, ensemble
// and calibration plots): filled rectangles, thick lines, convex polygons, bitmap text
// (stb_easy_font) and PNG output (stb_image_write) through an AtomicFile. Pixels outside the
// raster are clipped. Not a renderer: the 3D views are in render/.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/rgb.h"

namespace aggpack {

class Raster {
 public:
  /// A white raster of width x height pixels (both >= 1).
  Raster(int width, int height);

  void set(int x, int y, const Rgb& colour);
  /// Fills [x0, x1) x [y0, y1).
  void fill_rect(int x0, int y0, int x1, int y1, const Rgb& colour);
  /// A line `thickness` pixels wide from (x0, y0) to (x1, y1), by stamping squares along it.
  void line(double x0, double y0, double x1, double y1, int thickness, const Rgb& colour);
  /// Fills a convex polygon (either orientation) by scanlines.
  void fill_convex(const std::vector<std::array<double, 2>>& polygon, const Rgb& colour);
  /// Text with stb_easy_font magnified `scale` times; (x, y) is the top-left corner.
  void text(const std::string& message, int x, int y, int scale, const Rgb& colour);

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] const std::vector<std::uint8_t>& pixels() const { return pixels_; }

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> pixels_;
};

/// Writes the raster as an 8-bit RGB PNG, atomically (an existing regular file is replaced).
/// Throws IoError if it cannot be encoded or written.
void write_png(const std::string& path, const Raster& raster);

/// The one PNG encoder of the project (every plot, the raster above and the 3D renderer's
/// pictures): `rgb` holds width * height * 3 bytes, rows top to bottom; written atomically
/// through an AtomicFile with `overwrite`. \throw InvalidInput when the sizes do not match,
/// IoError if it cannot be encoded or written.
void write_png_rgb(const std::string& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb, Overwrite overwrite = Overwrite::kAllow);

}  // namespace aggpack
