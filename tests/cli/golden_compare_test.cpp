// The comparison behind the golden CLI tests (tests/support/golden.h).
#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace aggpack
