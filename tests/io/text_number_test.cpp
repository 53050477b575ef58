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
#include "aggpack/io/export.h"
#include "export_fixture.h"
#include "support/paths.h"
#include "support/readers.h"

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
  AGGPACK_REQUIRE_READER("ccx");
  const std::string fixture =
      test::read_text(test::source_dir() + "/tests/io/fixtures/inp-long-numbers/single_tet.inp");
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

// rock.dat and the APDL macro (the paper's rock.dat -> ANSYS path) keep every number within 20
// characters and every APDL command line within ANSYS's 640; LS-DYNA's free-format material line
// keeps each field within its 10-column card width. The packing is shifted to negative
// coordinates and scaled so that every coordinate is tiny (~1e-5, up to 23 characters in the
// shortest form).
TEST(TextNumber, FiniteElementTextFormatsKeepTheirFieldWidths) {
  Packing packing = test::grid_packing(3, 2, 1, 38);
  for (auto& particle : packing.particles) particle.pose.position -= Vec3(0.4, 0.3, 0.15);
  const ExportOptions options{.scale = 1e-4,
                              .material = {.density = 2650.1234567890123,
                                           .youngs_modulus = 6.1234567890123456e10,
                                           .poisson_ratio = -0.012345678901234567}};
  test::ScratchFolder folder;
  write(packing, folder.file("rock.dat"), options);
  write(packing, folder.file("model.mac"), options);
  write(packing, folder.file("model.k"), options);
  for (const std::string name : {"rock.dat", "model.mac"}) {
    std::istringstream in(test::read_text(folder.file(name)));
    std::string line;
    std::size_t numbers = 0;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '!' || line[0] == '/') continue;
      EXPECT_LE(line.size(), 640U) << name << ": " << line;
      for (const std::string& field : test::split(line, ',')) {
        const std::string value = test::trim(field);
        EXPECT_LE(value.size(), 20U) << name << ": '" << value << "' in " << line;
        numbers += value.find("e-") != std::string::npos ? 1 : 0;
      }
    }
    EXPECT_GT(numbers, 300U) << name;  // the tiny coordinates were there
  }
  const std::string k = test::read_text(folder.file("model.k"));
  const auto material = k.find("\n1,");
  ASSERT_NE(material, std::string::npos);
  const std::string line = k.substr(material + 1, k.find('\n', material + 1) - material - 1);
  const auto fields = test::split(line, ',');
  ASSERT_EQ(fields.size(), 4U) << line;
  for (const std::string& field : fields) EXPECT_LE(field.size(), 10U) << line;
  EXPECT_NEAR(std::stod(fields[1]), 2650.1234567890123, 1e-4);
  EXPECT_NEAR(std::stod(fields[2]), 6.1234567890123456e10, 1e6);
  EXPECT_NEAR(std::stod(fields[3]), -0.012345678901234567, 1e-7);
}

}  // namespace
}  // namespace aggpack
