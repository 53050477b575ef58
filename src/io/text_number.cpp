// Bounded-width numbers for text formats (see aggpack/io/text_number.h).

#include "aggpack/io/text_number.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// Rewrites "d.ddd000e-05" as "d.ddde-5" in place: trailing zeros of the mantissa (and a bare
// point) go, the exponent loses its '+' and leading zeros. Returns the new length.
std::size_t compact(char* text, std::size_t length) {
  const std::string_view view(text, length);
  const std::size_t e = std::min(view.find('e'), length);
  std::size_t end = e;
  if (view.substr(0, e).find('.') != std::string_view::npos) {
    while (text[end - 1] == '0') --end;
    if (text[end - 1] == '.') --end;
  }
  if (e == length) return end;
  std::size_t digit = e + 1;
  const bool is_negative = text[digit] == '-';
  if (text[digit] == '-' || text[digit] == '+') ++digit;
  while (digit + 1 < length && text[digit] == '0') ++digit;
  if (digit + 1 == length && text[digit] == '0') return end;  // "e+00"
  text[end++] = 'e';
  if (is_negative) text[end++] = '-';
  while (digit < length) text[end++] = text[digit++];
  return end;
}

}  // namespace

void append_number_fitting(std::string& out, double value, int max_chars) {
  constexpr int kMinimum = 7;  // "-1e-308": sign, one digit, a three-digit exponent
  if (max_chars < kMinimum) {
    throw InvalidInput("number field width", std::to_string(max_chars),
                       ">= " + std::to_string(kMinimum));
  }
  const auto limit = static_cast<std::size_t>(max_chars);
  char text[64];
  const auto shortest = std::to_chars(text, text + sizeof text, value);
  if (static_cast<std::size_t>(shortest.ptr - text) <= limit || !std::isfinite(value)) {
    out.append(text, shortest.ptr);
    return;
  }
  // The shortest form needs more digits than fit, so every form that fits rounds: take the most
  // significant digits, and of the plain and scientific forms with that many the shorter.
  for (int digits = 16; digits >= 1; --digits) {
    char best[64];
    std::size_t best_length = 0;
    for (const auto format : {std::chars_format::general, std::chars_format::scientific}) {
      char candidate[64];
      const int precision = format == std::chars_format::general ? digits : digits - 1;
      const auto result =
          std::to_chars(candidate, candidate + sizeof candidate, value, format, precision);
      const std::size_t length =
          compact(candidate, static_cast<std::size_t>(result.ptr - candidate));
      if (best_length == 0 || length < best_length) {
        std::copy(candidate, candidate + length, best);
        best_length = length;
      }
    }
    if (best_length <= limit) {
      out.append(best, best_length);
      return;
    }
  }
  out.append(text, shortest.ptr);  // unreachable for limit >= kMinimum
}

}  // namespace aggpack
