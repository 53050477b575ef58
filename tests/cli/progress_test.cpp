// The CLI's progress display (app/cli/progress.cpp) with a hand-driven clock: what a terminal
// and a log see, and when.

#include "progress.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <string>

#include "aggpack/core/text.h"

namespace aggpack::cli {
namespace {

// The text written to a temporary stream.
std::string contents(std::FILE* stream) {
  std::fflush(stream);
  std::rewind(stream);
  std::string text;
  char buffer[4096];
  while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, stream)) text.append(buffer, n);
  return text;
}

TEST(FormatSeconds, TwoSignificantDigitsWithoutExponent) {
  EXPECT_EQ(format_seconds(0.0), "0");
  EXPECT_EQ(format_seconds(0.00123), "0.0012");
  EXPECT_EQ(format_seconds(0.04), "0.040");
  EXPECT_EQ(format_seconds(0.1), "0.10");
  EXPECT_EQ(format_seconds(0.1049), "0.10");
  EXPECT_EQ(format_seconds(3.14159), "3.1");
  EXPECT_EQ(format_seconds(9.96), "10");
  EXPECT_EQ(format_seconds(12.4), "12");
  EXPECT_EQ(format_seconds(99.4), "99");
  EXPECT_EQ(format_seconds(341.7), "342");
  EXPECT_EQ(format_seconds(-1.0), "-");
}

TEST(ProgressBar, LinesCarryRateAndEtaAndComeAtLeastEveryHeartbeat) {
  std::FILE* stream = std::tmpfile();
  ASSERT_NE(stream, nullptr);
  double now = 0.0;
  {
    ProgressBar bar("settling", "steps", ProgressStyle::kLines, stream, [&] { return now; });
    bar.update(0.0, 0, 1000);
    now = 1.0;
    bar.update(0.01, 10, 1000, "t = 0.01 s");  // < 10 % and < 2 s since the first update
    EXPECT_EQ(contents(stream), "");
    now = 2.5;
    bar.heartbeat();  // nothing new reported, but 2.5 s without a line: a line
    const std::string first = contents(stream);
    // 10 steps in 1 s; 1 % in 1 s leaves 99 s at the update, 97.5 s by now.
    EXPECT_EQ(first, "settling:   1.0%  10/1000 steps  10/s  ETA 1:38  t = 0.01 s\n");
    now = 3.0;
    bar.heartbeat();  // 0.5 s after the last line: none
    EXPECT_EQ(contents(stream), first);
    now = 4.5;
    bar.heartbeat();
    EXPECT_EQ(contents(stream),
              first + "settling:   1.0%  10/1000 steps  10/s  ETA 1:36  t = 0.01 s\n");
    bar.set_eta_is_bound(true);
    now = 5.0;
    bar.update(0.5, 500, 1000);  // a further 10 %: a line at once, ETA as an upper bound
    const std::string text = contents(stream);
    EXPECT_NE(text.find("settling:  50.0%  500/1000 steps  100/s  ETA <= 0:05\n"),
              std::string::npos)
        << text;
  }
  const std::string text = contents(stream);
  EXPECT_NE(text.find("settling: 50.0%  500/1000 steps in 5.0 s (100/s)\n"), std::string::npos)
      << text;
  std::fclose(stream);
}

TEST(ProgressBar, NoRateOrEtaBeforeTheyAreKnown) {
  std::FILE* stream = std::tmpfile();
  ASSERT_NE(stream, nullptr);
  double now = 0.0;
  {
    ProgressBar bar("placing", "particles", ProgressStyle::kLines, stream, [&] { return now; });
    bar.update(0.244, 256, 1050, "solid 5.1 %");  // the first update is a further 10 %: a line
    EXPECT_EQ(contents(stream), "placing:  24.4%  256/1050 particles  solid 5.1 %\n");
    EXPECT_EQ(contents(stream).find("-/s"), std::string::npos);
  }  // ends the display (its final line) before the stream closes
  std::fclose(stream);
}

TEST(ProgressBar, TerminalBarIsRedrawnBetweenSlowUpdates) {
  std::FILE* stream = std::tmpfile();
  ASSERT_NE(stream, nullptr);
  double now = 0.0;
  {
    ProgressBar bar("repose stage 1", "steps", ProgressStyle::kBar, stream, [&] { return now; });
    bar.update(0.0, 0, 100);
    const std::size_t drawn = contents(stream).size();
    now = 0.5;
    bar.heartbeat();
    EXPECT_EQ(contents(stream).size(), drawn);  // drawn 0.5 s ago
    now = 1.2;
    bar.heartbeat();
    const std::string text = contents(stream);
    EXPECT_GT(text.size(), drawn);
    EXPECT_EQ(text.rfind("\r\033[K"), drawn);  // a redraw in place
  }
  std::fclose(stream);
}

// A stage that reports nothing (TetGen, voxels): its line carries the estimate's ETA counted
// down, then "longer than the estimate", and the stage's and each item's time limits.
TEST(StageText, EtaByTheEstimateAndTheLimits) {
  EXPECT_EQ(stage_text("voxelising", 4.0, {.expected_seconds = 10.0}, false),
            "voxelising: 0:04 elapsed, ETA ~0:06 by the estimate");
  EXPECT_EQ(stage_text("voxelising", 12.0, {.expected_seconds = 10.0}, false),
            "voxelising: 0:12 elapsed, longer than the estimate of 0:10");
  EXPECT_EQ(stage_text("meshing (TetGen)", 4.0, {.limit_seconds = 3600.0}, false),
            "meshing (TetGen): 0:04 elapsed (stops at the time limit, 59:56 from now at most)");
  EXPECT_EQ(stage_text("meshing shapes (TetGen)", 2.0,
                       {.item_limit_seconds = 20.0, .expected_seconds = 5.0}, false),
            "meshing shapes (TetGen): 0:02 elapsed, ETA ~0:03 by the estimate (each shape stops "
            "at its time limit of 20 s)");
  EXPECT_EQ(stage_text("voxelising", 3.14159, {.expected_seconds = 10.0}, true),
            "voxelising: done in 3.1 s");
}

// A stage that counts its items (TetGen's shapes, one per worker result): the count from the
// start, then the measured rate and an ETA from it instead of the estimate's.
TEST(StageText, CountedItemsGiveRateAndMeasuredEta) {
  const StageTiming before{.item_limit_seconds = 20.0, .expected_seconds = 5.0, .items_total = 300};
  EXPECT_EQ(stage_text("meshing shapes (TetGen)", 0.0, before, false),
            "meshing shapes (TetGen): 0:00 elapsed, 0 of 300 shapes, ETA ~0:05 by the estimate "
            "(each shape stops at its time limit of 20 s)");
  StageTiming during = before;
  during.items_done = 100;
  // 100 shapes in 4 s: 25 shapes/s, 200 left: 8 s (the estimate said 1 s more is left).
  EXPECT_EQ(stage_text("meshing shapes (TetGen)", 4.0, during, false),
            "meshing shapes (TetGen): 0:04 elapsed, 100 of 300 shapes, 25 shapes/s, ETA 0:08 "
            "(each shape stops at its time limit of 20 s)");
  during.items_done = 300;
  EXPECT_EQ(stage_text("meshing shapes (TetGen)", 6.0, during, false),
            "meshing shapes (TetGen): 0:06 elapsed, 300 of 300 shapes, 50 shapes/s, ETA 0:00 "
            "(each shape stops at its time limit of 20 s)");
}

// A stage the estimate expects to take kProgressHeartbeat or more shows its line at once; a short
// one that ends at once shows nothing.
TEST(StageTimer, ShownAtOnceOnlyWhenExpectedToBeLong) {
  std::FILE* stream = std::tmpfile();
  ASSERT_NE(stream, nullptr);
  { StageTimer quick("quick", ProgressStyle::kLines, {.expected_seconds = 0.5}, stream); }
  EXPECT_EQ(contents(stream), "");
  {
    StageTimer slow("slow", ProgressStyle::kLines, {.expected_seconds = 30.0}, stream);
    const std::string text = contents(stream);
    EXPECT_EQ(text, "slow: 0:00 elapsed, ETA ~0:30 by the estimate\n");
    std::fseek(stream, 0, SEEK_END);
  }
  const std::string text = contents(stream);
  EXPECT_EQ(text.rfind("slow: 0:00 elapsed, ETA ~0:30 by the estimate\nslow: done in ", 0), 0U)
      << text;
  std::fclose(stream);
}

}  // namespace
}  // namespace aggpack::cli
