#pragma once
// Small text helpers shared by the config readers and the CLI.

#include <cstddef>
#include <string>
#include <string_view>

namespace aggpack {

/// Levenshtein distance (insertions, deletions, substitutions), for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);

/// `text` as a double-quoted string literal that is valid both in JSON and as a TOML basic
/// string: quote, backslash and control characters escaped (\n, \r, \t, else \u00XX).
std::string quoted(std::string_view text);

/// Echoed input for a message: control characters escaped (\n, \r, \t, \xNN) so that it stays
/// on one line, and cut to about `max_bytes` with "..." in the middle (UTF-8 kept whole).
std::string clipped(std::string_view text, std::size_t max_bytes = 200);

/// `text` cut like clipped() but not escaped (for quoted(), which escapes).
std::string shortened(std::string_view text, std::size_t max_bytes = 200);

/// A wall-clock time in seconds to 2 significant digits, no exponent: "0.0012", "0.040", "3.1",
/// "12", "340" (whole seconds from 100 on; "0" below 0.00005, "-" if negative or not finite).
/// Every timing aggpack prints goes through it.
std::string format_seconds(double seconds);

}  // namespace aggpack
