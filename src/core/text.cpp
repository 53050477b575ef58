#include "aggpack/core/text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace aggpack {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(c));
          out += escape;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

namespace {

void append_escaped(std::string& out, std::string_view text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (byte < 0x20 || byte == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned>(byte));
      out += escape;
    } else {
      out += c;
    }
  }
}

// Moves a cut position off UTF-8 continuation bytes (towards `direction`).
std::size_t on_boundary(std::string_view text, std::size_t at, int direction) {
  while (at > 0 && at < text.size() && (static_cast<unsigned char>(text[at]) & 0xC0) == 0x80) {
    at = direction < 0 ? at - 1 : at + 1;
  }
  return at;
}

}  // namespace

std::string shortened(std::string_view text, std::size_t max_bytes) {
  if (text.size() <= max_bytes) return std::string(text);
  const std::size_t head = on_boundary(text, max_bytes * 2 / 3, -1);
  const std::size_t tail = on_boundary(text, text.size() - max_bytes / 3, +1);
  return std::string(text.substr(0, head)) + "..." + std::string(text.substr(tail));
}

std::string clipped(std::string_view text, std::size_t max_bytes) {
  std::string out;
  append_escaped(out, shortened(text, max_bytes));
  return out;
}

std::string format_seconds(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "-";
  if (seconds < 0.00005) return "0";
  char buffer[32];
  if (seconds >= 99.5) {
    std::snprintf(buffer, sizeof buffer, "%.0f", seconds);
    return buffer;
  }
  // Round to 2 significant digits first, then take the decimals from the rounded value (9.96
  // becomes 10, not 10.0).
  const double unit = std::pow(10.0, std::floor(std::log10(seconds)) - 1);
  const double rounded = std::round(seconds / unit) * unit;
  const int decimals =
      std::clamp(1 - static_cast<int>(std::floor(std::log10(rounded) + 1e-9)), 0, 4);
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, rounded);
  return buffer;
}

}  // namespace aggpack
