#pragma once
// Comparisons for golden tests (tests/cli/golden_cli_test.cpp): text with numbers within a
// relative tolerance, everything else exact; images within a per-pixel tolerance; and the masks
// that hide what changes from run to run (timings, the scratch folder, the binary's path).

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

namespace aggpack::test {

/// Relative tolerance for numbers in golden text (absolute below 1e-15).
inline constexpr double kGoldenRelativeTolerance = 1e-9;
inline constexpr double kGoldenAbsoluteTolerance = 1e-15;

/// `text` with every occurrence of `from` replaced by `to`.
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

/// Hides what differs between two identical runs: wall-clock times become <T>, the scratch folder
/// <dir>, the binary's path `aggpack`. One table of patterns; add one here when a new timing is
/// printed.
inline std::string mask_volatile(std::string text, const std::string& scratch_folder,
                                 const std::string& binary) {
  text = replaced(std::move(text), scratch_folder, "<dir>");
  text = replaced(std::move(text), binary, "aggpack");
  static const std::vector<std::pair<std::regex, std::string>> masks = {
      // "0.2 s wall", "0.00 s shapes + 0.06 s placement"
      {std::regex(R"([0-9]+(\.[0-9]+)? s (wall|shapes|placement)\b)"), "<T> s $2"},
      // "1 file in 0.14 s", "in 0 sweeps (0.0 s)"
      {std::regex(R"(\bin [0-9]+(\.[0-9]+)? s\b)"), "in <T> s"},
      {std::regex(R"(\([0-9]+(\.[0-9]+)? s\))"), "(<T> s)"},
      // JSON: "placement_seconds": 0.041
      {std::regex(R"(("[a-z_]*seconds"): [-+0-9.eE]+)"), "$1: <T>"},
  };
  for (const auto& [pattern, replacement] : masks) {
    text = std::regex_replace(text, pattern, replacement);
  }
  return text;
}

/// One piece of golden text: a number, or the text between numbers.
struct GoldenToken {
  bool is_number = false;
  std::string text;
  double value = 0;
};

/// Splits text into numbers and the text between them. A number starts at a digit (or a sign or
/// point followed by one) that does not continue a word, so "P12", "C3D4" and "h5" stay text.
inline std::vector<GoldenToken> golden_tokens(const std::string& text) {
  std::vector<GoldenToken> tokens;
  const auto is_digit = [&](std::size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) != 0;
  };
  const auto continues_word = [&](std::size_t i) {
    if (i == 0) return false;
    const char before = text[i - 1];
    return std::isalnum(static_cast<unsigned char>(before)) != 0 || before == '_' || before == '.';
  };
  std::string pending;
  std::size_t i = 0;
  while (i < text.size()) {
    std::size_t start = i;
    std::size_t j = i;
    if ((text[j] == '-' || text[j] == '+') && !continues_word(j)) ++j;
    const bool starts = !continues_word(start) &&
                        (is_digit(j) || (j < text.size() && text[j] == '.' && is_digit(j + 1)));
    if (!starts) {
      pending += text[i++];
      continue;
    }
    while (is_digit(j)) ++j;
    if (j < text.size() && text[j] == '.') {
      ++j;
      while (is_digit(j)) ++j;
    }
    if (j < text.size() && (text[j] == 'e' || text[j] == 'E')) {
      std::size_t k = j + 1;
      if (k < text.size() && (text[k] == '-' || text[k] == '+')) ++k;
      if (is_digit(k)) {
        while (is_digit(k)) ++k;
        j = k;
      }
    }
    if (!pending.empty()) tokens.push_back({.is_number = false, .text = pending});
    pending.clear();
    const std::string number = text.substr(start, j - start);
    tokens.push_back(
        {.is_number = true, .text = number, .value = std::strtod(number.c_str(), nullptr)});
    i = j;
  }
  if (!pending.empty()) tokens.push_back({.is_number = false, .text = pending});
  return tokens;
}

/// 1-based line of `text` at `tokens[index]`.
inline std::size_t golden_line_of(const std::vector<GoldenToken>& tokens, std::size_t index) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < index && i < tokens.size(); ++i) {
    line +=
        static_cast<std::size_t>(std::count(tokens[i].text.begin(), tokens[i].text.end(), '\n'));
  }
  return line;
}

/// "" when `actual` matches `expected` (text exact, numbers within the tolerances), else where and
/// how they first differ.
inline std::string golden_difference(const std::string& expected, const std::string& actual) {
  const std::vector<GoldenToken> want = golden_tokens(expected);
  const std::vector<GoldenToken> got = golden_tokens(actual);
  const std::size_t count = std::min(want.size(), got.size());
  for (std::size_t i = 0; i < count; ++i) {
    const GoldenToken& a = want[i];
    const GoldenToken& b = got[i];
    const std::string where = "line " + std::to_string(golden_line_of(want, i)) + ": ";
    if (a.is_number != b.is_number || (!a.is_number && a.text != b.text)) {
      return where + "expected '" + a.text + "', got '" + b.text + "'";
    }
    if (a.is_number && a.text != b.text) {
      const double scale = std::max(std::abs(a.value), std::abs(b.value));
      const double difference = std::abs(a.value - b.value);
      if (!(difference <= kGoldenRelativeTolerance * scale ||
            difference <= kGoldenAbsoluteTolerance)) {
        return where + "expected number " + a.text + ", got " + b.text;
      }
    }
  }
  if (want.size() != got.size()) {
    return "line " + std::to_string(golden_line_of(want, count)) + ": " +
           (want.size() > got.size() ? "output ends early" : "output goes on longer");
  }
  return "";
}

/// A decoded picture: 8-bit RGB, rows top to bottom.
struct GoldenImage {
  int width = 0;
  int height = 0;
  std::vector<unsigned char> rgb;  ///< width * height * 3 bytes
};

/// Image tolerance: the mean absolute channel difference (of 255) may be at most
/// kGoldenImageMeanTolerance, and at most kGoldenImagePixelFraction of the pixels may differ by
/// more than kGoldenImagePixelTolerance in some channel (an edge drawn a pixel aside by another
/// rasteriser, not a changed colour, view or particle).
inline constexpr double kGoldenImageMeanTolerance = 2.0;
inline constexpr int kGoldenImagePixelTolerance = 32;
inline constexpr double kGoldenImagePixelFraction = 0.02;

/// "" when the images have the same size and match within the tolerances above, else how not.
inline std::string golden_image_difference(const GoldenImage& expected, const GoldenImage& actual) {
  if (expected.width != actual.width || expected.height != actual.height) {
    return "size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
           ", expected " + std::to_string(expected.width) + "x" + std::to_string(expected.height);
  }
  const std::size_t pixels =
      static_cast<std::size_t>(expected.width) * static_cast<std::size_t>(expected.height);
  if (expected.rgb.size() != pixels * 3 || actual.rgb.size() != pixels * 3) {
    return "pixel data of the wrong length";
  }
  double sum = 0.0;
  std::size_t far = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    int largest = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const int difference = std::abs(static_cast<int>(expected.rgb[3 * p + c]) -
                                      static_cast<int>(actual.rgb[3 * p + c]));
      sum += difference;
      largest = std::max(largest, difference);
    }
    if (largest > kGoldenImagePixelTolerance) ++far;
  }
  const double mean = pixels == 0 ? 0.0 : sum / (3.0 * static_cast<double>(pixels));
  const double far_fraction =
      pixels == 0 ? 0.0 : static_cast<double>(far) / static_cast<double>(pixels);
  if (mean > kGoldenImageMeanTolerance || far_fraction > kGoldenImagePixelFraction) {
    return "mean channel difference " + std::to_string(mean) + " (at most " +
           std::to_string(kGoldenImageMeanTolerance) + "), " + std::to_string(far) + " of " +
           std::to_string(pixels) + " pixels off by more than " +
           std::to_string(kGoldenImagePixelTolerance) + " (at most " +
           std::to_string(kGoldenImagePixelFraction * 100.0) + " %)";
  }
  return "";
}

}  // namespace aggpack::test
