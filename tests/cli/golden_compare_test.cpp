// The comparison behind the golden CLI tests (tests/support/golden.h).
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "support/golden.h"

namespace aggpack {
namespace {

using test::golden_difference;

TEST(GoldenCompare, NumbersMatchWithinTheRelativeTolerance) {
  EXPECT_EQ(golden_difference("volume 0.1 m^3\n", "volume 0.1 m^3\n"), "");
  EXPECT_EQ(golden_difference("volume 0.1 m^3\n", "volume 0.10000000000000001 m^3\n"), "");
  EXPECT_EQ(golden_difference("x = 1e6\n", "x = 1000000.0005\n"), "");
  EXPECT_EQ(golden_difference("[-2.5e-3, 7]", "[-0.0025, 7.0]"), "");
  EXPECT_NE(golden_difference("volume 0.1 m^3\n", "volume 0.1000001 m^3\n"), "");
  EXPECT_NE(golden_difference("x = 1e6\n", "x = 1000001\n"), "");
  EXPECT_NE(golden_difference("n 5\n", "n -5\n"), "");
}

TEST(GoldenCompare, TextMustMatchExactly) {
  EXPECT_NE(golden_difference("placed 16 particles\n", "placed 16 particle\n"), "");
  EXPECT_NE(golden_difference("a\n", "a\nb\n"), "");
  EXPECT_NE(golden_difference("a 1 2\n", "a 1\n"), "");
  // Digits inside words are text: P12 is not P12.0000000001.
  EXPECT_NE(golden_difference("P12 C3D4\n", "P13 C3D4\n"), "");
  EXPECT_NE(golden_difference("C3D4\n", "C3D10\n"), "");
}

TEST(GoldenCompare, TheFirstDifferenceNamesItsLine) {
  const std::string difference = golden_difference("a 1\nb 2\nc 3\n", "a 1\nb 2\nc 4\n");
  EXPECT_NE(difference.find("line 3"), std::string::npos) << difference;
  EXPECT_NE(difference.find("expected number 3, got 4"), std::string::npos) << difference;
}

TEST(GoldenCompare, TimingsFoldersAndTheBinaryAreMasked) {
  const std::string text =
      "time 0.00 s shapes + 0.06 s placement\nstage 1 0.02 s simulated, 3.1 s wall\n"
      "wrote /tmp/x/a.stl in 0.14 s; 0 sweeps (0.0 s)\n\"placement_seconds\": 0.041,\n"
      "Usage: /build/aggpack pack\n";
  EXPECT_EQ(test::mask_volatile(text, "/tmp/x", "/build/aggpack"),
            "time <T> s shapes + <T> s placement\nstage 1 0.02 s simulated, <T> s wall\n"
            "wrote <dir>/a.stl in <T> s; 0 sweeps (<T> s)\n\"placement_seconds\": <T>,\n"
            "Usage: aggpack pack\n");
}

// A w x h picture of one colour, with `changed` pixels (from the first) set to another.
test::GoldenImage flat_image(int width, int height, unsigned char value, std::size_t changed = 0,
                             unsigned char other = 0) {
  test::GoldenImage image{
      .width = width,
      .height = height,
      .rgb = std::vector<unsigned char>(
          static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3, value)};
  for (std::size_t p = 0; p < changed; ++p) image.rgb[3 * p + 1] = other;
  return image;
}

TEST(GoldenCompare, ImagesMatchWithinThePixelTolerance) {
  using test::golden_image_difference;
  const test::GoldenImage reference = flat_image(20, 10, 100);
  EXPECT_EQ(golden_image_difference(reference, reference), "");
  // Every channel off by 1: mean 1 <= 2.
  EXPECT_EQ(golden_image_difference(reference, flat_image(20, 10, 101)), "");
  // Every channel off by 3: mean 3 > 2.
  EXPECT_NE(golden_image_difference(reference, flat_image(20, 10, 103)), "");
  // 4 of 200 pixels (2 %) far off in one channel: mean (4 * 100) / 600 < 2, allowed.
  EXPECT_EQ(golden_image_difference(reference, flat_image(20, 10, 100, 4, 200)), "");
  // 5 of 200 (2.5 %) far off: refused, though the mean is still below 2.
  const std::string five = golden_image_difference(reference, flat_image(20, 10, 100, 5, 140));
  EXPECT_NE(five.find("5 of 200 pixels"), std::string::npos) << five;
  // Another size never matches.
  const std::string size = golden_image_difference(reference, flat_image(10, 20, 100));
  EXPECT_NE(size.find("size 10x20, expected 20x10"), std::string::npos) << size;
}

}  // namespace
}  // namespace aggpack
