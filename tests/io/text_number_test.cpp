// Bounded-width numbers (aggpack/io/text_number.h): the shortest form when it fits, else the most
// digits that fit; and the CalculiX rule they serve, checked with ccx on the fixture that shows
// what a 23-character coordinate does (tests/io/fixtures/inp-long-numbers).

#include "aggpack/io/text_number.h"

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <random>
#include <regex>

#include "aggpack/core/error.h"
#include "export_fixture.h"

namespace aggpack {
namespace {

std::string fitted(double value, int max_chars) {
  std::string text;
  append_number_fitting(text, value, max_chars);
  return text;
}

// Significant digits a 20-character field keeps (aggpack/io/text_number.h).
double documented_relative_error(double value) {
  const double magnitude = std::abs(value);
  if (magnitude >= 1e-9 && magnitude < 1e100) return 5e-15;
  if (magnitude >= 1e-99) return 5e-14;
  return 5e-13;
}

TEST(TextNumber, ShortestFormWhenItFits) {
  EXPECT_EQ(fitted(0.25, 20), "0.25");
  EXPECT_EQ(fitted(5e10, 20), "5e+10");
  EXPECT_EQ(fitted(-0.0, 20), "-0");
  EXPECT_EQ(fitted(2700, 10), "2700");
  EXPECT_EQ(fitted(0.1 + 0.2, 20), "0.30000000000000004");
  EXPECT_EQ(fitted(-0.12345678901234566, 20), "-0.12345678901234566");
}

TEST(TextNumber, LongNumbersLoseTheLeastDigits) {
  // The issue's numbers: 23 and 21 characters in the shortest form.
  EXPECT_EQ(fitted(-1.1006292118507371e-05, 20), "-1.10062921185074e-5");
  EXPECT_EQ(fitted(6.566569607759087e-05, 20), "6.566569607759087e-5");  // still exact
  EXPECT_EQ(std::strtod("6.566569607759087e-5", nullptr), 6.566569607759087e-05);
  EXPECT_EQ(fitted(-0.012345678901234567, 20), "-0.01234567890123457");
  EXPECT_EQ(fitted(-1.2345678901234567e-100, 20), "-1.234567890123e-100");
  EXPECT_EQ(fitted(2650.123456789, 10), "2650.12346");
  EXPECT_EQ(fitted(6.5e10 + 1, 10), "6.5e10");
  EXPECT_EQ(fitted(-DBL_MAX, 7), "-2e308");
  EXPECT_EQ(fitted(-DBL_TRUE_MIN, 7), "-5e-324");
  EXPECT_EQ(fitted(-9.99999999999999999e-6, 20), "-1e-05");  // shortest form fits
  EXPECT_EQ(fitted(-9.999999999999999e-6, 20), "-1e-5");     // 15 digits round up
}

TEST(TextNumber, RandomDoublesFitAndReadBackWithinTheDocumentedPrecision) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> mantissa(1.0, 10.0);
  std::uniform_int_distribution<int> exponent(-320, 300);
  std::size_t rounded = 0;
  for (int i = 0; i < 50000; ++i) {
    double value = mantissa(random) * std::pow(10.0, exponent(random));
    if (i % 2 == 1) value = -value;
    if (!std::isfinite(value) || value == 0) continue;
    const std::string text = fitted(value, 20);
    ASSERT_LE(text.size(), 20U) << text;
    const double back = std::strtod(text.c_str(), nullptr);
    if (back != value) ++rounded;
    ASSERT_LE(std::abs(back - value), documented_relative_error(value) * std::abs(value))
        << value << " -> " << text;
    ASSERT_LE(fitted(value, 10).size(), 10U);
  }
  EXPECT_GT(rounded, 0U);  // the sweep reached the rounding branch
}

TEST(TextNumber, RejectsFieldsTooNarrowForAnyDouble) { EXPECT_THROW(fitted(1.0, 6), InvalidInput); }

// The fixture as aggpack 0.1.0 wrote it stops ccx; the same coordinate in 20 characters runs.
TEST(TextNumber, CalculixReadsTwentyCharactersAndNoMore) {
  ASSERT_TRUE(test::has_program("ccx")) << "calculix-ccx not installed (scripts/install-deps.sh)";
  const std::string fixture = test::read_text(std::string(AGGPACK_SOURCE_DIR) +
                                              "/tests/io/fixtures/inp-long-numbers/single_tet.inp");
  const std::string long_number = "-1.1006292118507371e-05";
  ASSERT_NE(fixture.find(long_number), std::string::npos);
  test::ScratchFolder folder;
  std::ofstream(folder.file("long.inp")) << fixture;
  const auto failed =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i long");
  EXPECT_NE(failed.output.find("*ERROR reading *NODE"), std::string::npos) << failed.output;

  const std::string short_number = fitted(-1.1006292118507371e-05, kFeNumberWidth);
  std::ofstream(folder.file("short.inp")) << std::regex_replace(
      fixture, std::regex(std::regex_replace(long_number, std::regex(R"([.+-])"), R"(\$&)")),
      short_number);
  const auto passed =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i short");
  EXPECT_EQ(passed.exit_code, 0) << passed.output;
  EXPECT_EQ(passed.output.find("*ERROR"), std::string::npos) << passed.output;
  EXPECT_NE(passed.output.find("Job finished"), std::string::npos) << passed.output;
}

}  // namespace
}  // namespace aggpack
