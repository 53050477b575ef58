#pragma once
// aggpack-gui's words in English and Simplified Chinese. Every text the window shows is a Text
// id whose words live in one catalogue per language, app/gui/i18n/en.h and zh_CN.h (one
// AGGPACK_TEXT(id, "words") line each); the configuration keys' labels and docs in Chinese are
// in app/gui/i18n/keys_zh_CN.h (in English they are the schema's own key names and doc lines).
// Words with placeholders are fmt format strings ("{}"); tests/gui/i18n_test.cpp checks that
// every id has Chinese words with the same placeholders and "###" ids.
//
// The language is one process-wide setting (as ImGui's own context is): the panel, the menus
// and the worker thread's job messages all read it, so it is an atomic.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace aggpack::gui {

enum class Language { kEnglish, kChinese };

enum class Text : int {
#define AGGPACK_TEXT(id, words) id,
#include "i18n/en.h"
#undef AGGPACK_TEXT
  kCount
};

/// The words of `id` in the current language (static storage: no allocation, O(1)).
const char* tr(Text id);
/// The words of `id` in `language` (nullptr: that catalogue has no entry, a test failure).
const char* catalogue_text(Language language, Text id);
/// The id's name in the catalogues ("kPackButton").
const char* text_name(Text id);
/// How many entries `language`'s catalogue lists (Text::kCount for each when none is missing or
/// listed twice).
std::size_t catalogue_size(Language language);

Language language();
void set_language(Language language);
/// "en" or "zh_CN" (the settings file's and --language's words).
const char* language_code(Language language);
/// "en..." / "C" / "POSIX" -> English, "zh..." -> Chinese; nullopt for anything else.
std::optional<Language> parse_language(std::string_view code);
/// The language of the locale: the first set of LC_ALL, LC_MESSAGES, LANG (POSIX order);
/// Chinese for zh_*, else English.
Language language_from_environment();

/// A configuration key's label and doc line in Chinese (nullptr when the catalogue has none).
const char* key_label_chinese(std::string_view key);
const char* key_doc_chinese(std::string_view key);
/// A configuration word ("box", "lattice") in Chinese (nullptr when the catalogue has none).
const char* word_chinese(std::string_view word);
/// Every Chinese catalogue entry in turn (the font's glyph ranges are built from them).
void for_each_chinese_text(void (*visit)(const char* text, void* context), void* context);

/// Formatted words held on the stack: no allocation per frame (truncated past 1 KiB).
struct Formatted {
  std::array<char, 1024> buffer{};
  [[nodiscard]] const char* c_str() const { return buffer.data(); }
};

/// `id`'s words in the current language with its placeholders filled, for a widget.
template <typename... Args>
Formatted trf(Text id, const Args&... args) {
  Formatted out;
  const auto result =
      fmt::format_to_n(out.buffer.data(), out.buffer.size() - 1, fmt::runtime(tr(id)), args...);
  out.buffer[std::min(result.size, out.buffer.size() - 1)] = '\0';
  return out;
}

/// As trf, as a string (status and job messages).
template <typename... Args>
std::string trs(Text id, const Args&... args) {
  return fmt::format(fmt::runtime(tr(id)), args...);
}

}  // namespace aggpack::gui
