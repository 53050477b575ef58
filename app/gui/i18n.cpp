#include "i18n.h"

#include <atomic>
#include <cstdlib>
#include <iterator>

namespace aggpack::gui {

namespace {

constexpr std::size_t kCount = static_cast<std::size_t>(Text::kCount);

constexpr std::array<const char*, kCount> kEnglish = {{
#define AGGPACK_TEXT(id, words) words,
#include "i18n/en.h"
#undef AGGPACK_TEXT
}};

constexpr std::array<const char*, kCount> kNames = {{
#define AGGPACK_TEXT(id, words) #id,
#include "i18n/en.h"
#undef AGGPACK_TEXT
}};

struct Entry {
  Text id;
  const char* words;
};

constexpr Entry kChineseEntries[] = {
#define AGGPACK_TEXT(id, words) {Text::id, words},
#include "i18n/zh_CN.h"
#undef AGGPACK_TEXT
};

// The Chinese catalogue in id order (a missing id stays nullptr: tr() then shows the English
// words, and the catalogue test fails).
constexpr std::array<const char*, kCount> chinese_table() {
  std::array<const char*, kCount> table{};
  for (const Entry& entry : kChineseEntries)
    table[static_cast<std::size_t>(entry.id)] = entry.words;
  return table;
}
constexpr std::array<const char*, kCount> kChinese = chinese_table();

struct KeyEntry {
  std::string_view key;
  const char* label;
  const char* doc;
};

constexpr KeyEntry kChineseKeys[] = {
#define AGGPACK_KEY(key, label, doc) {key, label, doc},
#define AGGPACK_WORD(word, words)
#include "i18n/keys_zh_CN.h"
#undef AGGPACK_KEY
#undef AGGPACK_WORD
};

struct WordEntry {
  std::string_view word;
  const char* words;
};

constexpr WordEntry kChineseWords[] = {
#define AGGPACK_KEY(key, label, doc)
#define AGGPACK_WORD(word, words) {word, words},
#include "i18n/keys_zh_CN.h"
#undef AGGPACK_KEY
#undef AGGPACK_WORD
};

std::atomic<Language> g_language{Language::kEnglish};

const KeyEntry* find_key(std::string_view key) {
  for (const KeyEntry& entry : kChineseKeys) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

}  // namespace

const char* catalogue_text(Language language, Text id) {
  const auto index = static_cast<std::size_t>(id);
  if (index >= kCount) return nullptr;
  return language == Language::kChinese ? kChinese[index] : kEnglish[index];
}

const char* tr(Text id) {
  const char* words = catalogue_text(g_language.load(std::memory_order_relaxed), id);
  return words != nullptr ? words : kEnglish[static_cast<std::size_t>(id)];
}

const char* text_name(Text id) { return kNames[static_cast<std::size_t>(id)]; }

std::size_t catalogue_size(Language language) {
  return language == Language::kChinese ? std::size(kChineseEntries) : kEnglish.size();
}

Language language() { return g_language.load(std::memory_order_relaxed); }

void set_language(Language language) { g_language.store(language, std::memory_order_relaxed); }

const char* language_code(Language language) {
  return language == Language::kChinese ? "zh_CN" : "en";
}

std::optional<Language> parse_language(std::string_view code) {
  if (code.rfind("zh", 0) == 0) return Language::kChinese;
  if (code.rfind("en", 0) == 0 || code == "C" || code.rfind("C.", 0) == 0 || code == "POSIX") {
    return Language::kEnglish;
  }
  return std::nullopt;
}

Language language_from_environment() {
  for (const char* name : {"LC_ALL", "LC_MESSAGES", "LANG"}) {
    const char* value = std::getenv(name);
    if (value == nullptr || *value == '\0') continue;
    return std::string_view(value).rfind("zh", 0) == 0 ? Language::kChinese : Language::kEnglish;
  }
  return Language::kEnglish;
}

const char* key_label_chinese(std::string_view key) {
  const KeyEntry* entry = find_key(key);
  return entry != nullptr ? entry->label : nullptr;
}

const char* key_doc_chinese(std::string_view key) {
  const KeyEntry* entry = find_key(key);
  return entry != nullptr ? entry->doc : nullptr;
}

const char* word_chinese(std::string_view word) {
  for (const WordEntry& entry : kChineseWords) {
    if (entry.word == word) return entry.words;
  }
  return nullptr;
}

void for_each_chinese_text(void (*visit)(const char* text, void* context), void* context) {
  for (const Entry& entry : kChineseEntries) visit(entry.words, context);
  for (const KeyEntry& entry : kChineseKeys) {
    visit(entry.label, context);
    visit(entry.doc, context);
  }
  for (const WordEntry& entry : kChineseWords) visit(entry.words, context);
}

}  // namespace aggpack::gui
