// aggpack-gui's catalogues (app/gui/i18n/): every text has Chinese words, with the English
// words' placeholders and widget ids; every configuration key and word the panel shows has its
// Chinese label, doc line and words; the locale picks the language.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/config/config.h"
#include "i18n.h"

namespace aggpack::gui {
namespace {

constexpr auto kTextCount = static_cast<int>(Text::kCount);

// The fmt placeholders ("{}", "{:.2f}") and printf conversions ("%.0f", "%d") in order.
std::vector<std::string> placeholders(const std::string& text) {
  static const std::regex pattern(R"(\{[^}]*\}|%[-+#0]*[0-9]*(?:\.[0-9]+)?[a-zA-Z])");
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    found.push_back(it->str());
  }
  return found;
}

// The widget id after "###" ("" without one).
std::string widget_id(const std::string& text) {
  const auto at = text.find("###");
  return at == std::string::npos ? "" : text.substr(at);
}

// The words a reader sees: without the "###" id and the placeholders.
std::string words_of(const std::string& text) {
  static const std::regex pattern(R"(\{[^}]*\}|%[-+#0]*[0-9]*(?:\.[0-9]+)?[a-zA-Z])");
  return std::regex_replace(text.substr(0, text.find("###")), pattern, "");
}

bool has_chinese(const std::string& text) {
  for (const char c : text) {
    if ((static_cast<unsigned char>(c) & 0xF0U) == 0xE0U) return true;  // a 3-byte UTF-8 lead
  }
  return false;
}

TEST(GuiCatalogue, EveryTextHasChineseWordsOnce) {
  EXPECT_EQ(catalogue_size(Language::kEnglish), static_cast<std::size_t>(kTextCount));
  EXPECT_EQ(catalogue_size(Language::kChinese), static_cast<std::size_t>(kTextCount))
      << "zh_CN.h lists an id twice or misses one";
  for (int k = 0; k < kTextCount; ++k) {
    const auto id = static_cast<Text>(k);
    const char* chinese = catalogue_text(Language::kChinese, id);
    ASSERT_NE(chinese, nullptr) << text_name(id) << " has no Chinese words (zh_CN.h)";
    EXPECT_STRNE(chinese, "") << text_name(id);
    EXPECT_STRNE(catalogue_text(Language::kEnglish, id), "") << text_name(id);
  }
}

TEST(GuiCatalogue, ChineseKeepsPlaceholdersAndWidgetIds) {
  for (int k = 0; k < kTextCount; ++k) {
    const auto id = static_cast<Text>(k);
    const std::string english = catalogue_text(Language::kEnglish, id);
    const std::string chinese = catalogue_text(Language::kChinese, id);
    EXPECT_EQ(placeholders(english), placeholders(chinese)) << text_name(id);
    EXPECT_EQ(widget_id(english), widget_id(chinese)) << text_name(id);
  }
}

TEST(GuiCatalogue, ChineseIsNotEnglishLeftOver) {
  // Words that are the same in both: names of things, file names, the language names.
  const std::vector<Text> same = {
      Text::kLanguageEnglish, Text::kLanguageChinese, Text::kProgressOverlay, Text::kStatsThousands,
      Text::kSieveCellFormat, Text::kMesomodelMsh,    Text::kMesomodelVtu};
  for (int k = 0; k < kTextCount; ++k) {
    const auto id = static_cast<Text>(k);
    if (std::find(same.begin(), same.end(), id) != same.end()) continue;
    const std::string chinese = words_of(catalogue_text(Language::kChinese, id));
    const bool has_letters = std::regex_search(words_of(catalogue_text(Language::kEnglish, id)),
                                               std::regex("[A-Za-z]{2}"));
    if (has_letters) {
      EXPECT_TRUE(has_chinese(chinese)) << text_name(id) << ": " << chinese;
    }
  }
}

TEST(GuiCatalogue, EveryPanelKeyAndWordHasChinese) {
  int keys = 0;
  for (const auto& key : pack_schema().keys) {
    const std::string table = key.name.substr(0, key.name.find('.'));
    if (table != "container" && table != "particle" && table != "packer" && table != "grading" &&
        table != "densify") {
      continue;
    }
    if (key.type == ValueType::kPath) continue;  // not in the panel (particle.library's list is)
    ++keys;
    const char* label = key_label_chinese(key.name);
    const char* doc = key_doc_chinese(key.name);
    ASSERT_NE(label, nullptr) << key.name << " has no Chinese label (keys_zh_CN.h)";
    ASSERT_NE(doc, nullptr) << key.name;
    EXPECT_TRUE(has_chinese(label)) << key.name;
    EXPECT_TRUE(has_chinese(doc)) << key.name;
    for (const std::string& word : key.words) {
      const char* words = word_chinese(word);
      ASSERT_NE(words, nullptr) << key.name << " = " << word << " has no Chinese words";
      EXPECT_TRUE(has_chinese(words)) << word;
    }
  }
  EXPECT_GE(keys, 40);  // the panel's tables are all there
}

TEST(GuiCatalogue, FormatsInEitherLanguage) {
  set_language(Language::kChinese);
  EXPECT_STREQ(trf(Text::kPackFinished, 1050, 84.0).c_str(),
               "颗粒生成与投放完成！共 1050 个颗粒，固体体积分数 84.00 %。");
  set_language(Language::kEnglish);
  EXPECT_EQ(trs(Text::kPackFinished, 1050, 84.0),
            "Packing finished! 1050 particles, solid fraction 84.00 %.");
}

TEST(GuiLanguage, FromTheLocale) {
  auto with = [](const char* all, const char* messages, const char* lang) {
    for (const auto& [name, value] :
         {std::pair{"LC_ALL", all}, std::pair{"LC_MESSAGES", messages}, std::pair{"LANG", lang}}) {
      if (value == nullptr) {
        unsetenv(name);
      } else {
        setenv(name, value, 1);
      }
    }
    return language_from_environment();
  };
  EXPECT_EQ(with(nullptr, nullptr, "zh_CN.UTF-8"), Language::kChinese);
  EXPECT_EQ(with(nullptr, nullptr, "en_GB.UTF-8"), Language::kEnglish);
  EXPECT_EQ(with(nullptr, nullptr, nullptr), Language::kEnglish);
  EXPECT_EQ(with(nullptr, "zh_CN.UTF-8", "en_US.UTF-8"), Language::kChinese);
  EXPECT_EQ(with("C", "zh_CN.UTF-8", "zh_CN.UTF-8"), Language::kEnglish);
  EXPECT_EQ(with("zh_TW.UTF-8", nullptr, "en_US.UTF-8"), Language::kChinese);
  EXPECT_EQ(with("", "", "zh_SG"), Language::kChinese);
  EXPECT_EQ(parse_language("zh_CN"), Language::kChinese);
  EXPECT_EQ(parse_language("en"), Language::kEnglish);
  EXPECT_EQ(parse_language("fr_FR"), std::nullopt);
  EXPECT_EQ(parse_language(""), std::nullopt);
}

}  // namespace
}  // namespace aggpack::gui
