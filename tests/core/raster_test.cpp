// The PNG plot raster: exact pixel coverage of rectangles and convex polygons, clipping, text,
// and a PNG that decodes back to the same pixels.

#include "aggpack/core/raster.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <stdlib.h>  // mkdtemp

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

namespace aggpack {
namespace {

std::size_t count(const Raster& raster, const Rgb& colour) {
  std::size_t n = 0;
  const auto& p = raster.pixels();
  for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
    n += static_cast<std::size_t>(p[i] == colour[0] && p[i + 1] == colour[1] &&
                                  p[i + 2] == colour[2]);
  }
  return n;
}

TEST(Raster, RectanglesAreHalfOpenAndClipped) {
  Raster raster(20, 10);
  EXPECT_EQ(raster.pixels().size(), 20U * 10U * 3U);
  EXPECT_EQ(count(raster, {255, 255, 255}), 200U);
  raster.fill_rect(2, 3, 7, 5, {1, 2, 3});  // 5 x 2
  EXPECT_EQ(count(raster, {1, 2, 3}), 10U);
  raster.fill_rect(-5, -5, 3, 2, {9, 9, 9});  // clipped to 3 x 2
  EXPECT_EQ(count(raster, {9, 9, 9}), 6U);
  raster.set(20, 0, {7, 7, 7});  // outside: ignored
  raster.set(-1, 3, {7, 7, 7});
  EXPECT_EQ(count(raster, {7, 7, 7}), 0U);
}

TEST(Raster, ConvexPolygonCoversItsArea) {
  Raster raster(200, 200);
  // A right triangle with legs of 100 pixels: area 5,000 pixels, to within its perimeter.
  raster.fill_convex({{{50.0, 50.0}, {150.0, 50.0}, {50.0, 150.0}}}, {0, 0, 0});
  const auto n = static_cast<double>(count(raster, {0, 0, 0}));
  EXPECT_NEAR(n, 5000.0, 150.0);
  // A square drawn clockwise or counter-clockwise covers exactly its 40 x 40 pixels.
  Raster square(100, 100);
  square.fill_convex({{{10.0, 10.0}, {50.0, 10.0}, {50.0, 50.0}, {10.0, 50.0}}}, {5, 5, 5});
  square.fill_convex({{{60.0, 60.0}, {60.0, 90.0}, {90.0, 90.0}, {90.0, 60.0}}}, {6, 6, 6});
  EXPECT_EQ(count(square, {5, 5, 5}), 1600U);
  EXPECT_EQ(count(square, {6, 6, 6}), 900U);
}

TEST(Raster, LinesAndTextMarkPixels) {
  Raster raster(100, 40);
  // Horizontal from x 10 to 89, 3 pixels thick: the square stamps reach one pixel past each end
  // (x 9 to 90), so 82 x 3 pixels.
  raster.line(10.0, 20.0, 89.0, 20.0, 3, {0, 0, 255});
  EXPECT_EQ(count(raster, {0, 0, 255}), 246U);
  raster.text("42", 0, 0, 2, {255, 0, 0});
  EXPECT_GT(count(raster, {255, 0, 0}), 20U);
}

TEST(Raster, PngDecodesToTheSamePixels) {
  std::string pattern = (std::filesystem::temp_directory_path() / "aggpack_raster_XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::filesystem::path folder = pattern;
  Raster raster(33, 17);  // odd sizes: no row padding assumptions
  raster.fill_rect(3, 4, 20, 11, {200, 10, 30});
  raster.line(0.0, 0.0, 32.0, 16.0, 1, {0, 120, 0});
  const std::string path = (folder / "plot.png").string();
  write_png(path, raster);
  int width = 0;
  int height = 0;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(width, 33);
  EXPECT_EQ(height, 17);
  const std::vector<std::uint8_t> decoded(data, data + static_cast<std::size_t>(33 * 17 * 3));
  stbi_image_free(data);
  EXPECT_EQ(decoded, raster.pixels());
  // No temporary file is left beside it.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) {
    ++files;
  }
  EXPECT_EQ(files, 1U);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace aggpack
