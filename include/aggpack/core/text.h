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

}  // namespace aggpack
