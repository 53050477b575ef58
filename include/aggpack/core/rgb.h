#pragma once
// The one colour type: the 3D views' particle colours (render/colors.h), the headless renderer's
// pixels and the PNG plots' raster (core/raster.h) all use it.

#include <compare>
#include <cstddef>
#include <cstdint>

namespace aggpack {

/// An 8-bit sRGB colour. Channels by name (r, g, b) or by index (0, 1, 2) for loops over them.
struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;

  /// Channel 0 (r), 1 (g) or 2 (b); any larger index is b.
  [[nodiscard]] std::uint8_t& operator[](std::size_t channel) {
    return channel == 0 ? r : (channel == 1 ? g : b);
  }
  [[nodiscard]] std::uint8_t operator[](std::size_t channel) const {
    return channel == 0 ? r : (channel == 1 ? g : b);
  }
  friend bool operator==(const Rgb&, const Rgb&) = default;
  /// Ordered by r, then g, then b (for sorting and sets of colours).
  friend auto operator<=>(const Rgb&, const Rgb&) = default;
};

}  // namespace aggpack
