// The library's errors and reports in aggpack-gui's words (app/gui/library_words.h): every
// sentence of core/error_words.h has an entry in each catalogue (English: the library's own
// words), a Chinese window words a refused value, a rule between keys, a read error and the
// densifier's summary from their parts, with no English word of the library's sentence left.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <new>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/grading.h"
#include "gui/words.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {
namespace {

constexpr auto kSentenceCount = static_cast<int>(Sentence::kCount);

using test_words::english_words_of;
using test_words::has_chinese_text;
using test_words::is_kept_name;

// Runs `words` with the window in Chinese, then back in English.
template <typename F>
std::string in_chinese(F words) {
  set_language(Language::kChinese);
  std::string text = words();
  set_language(Language::kEnglish);
  return text;
}

TEST(LibraryWords, EverySentenceHasAnEntryInEachCatalogue) {
  for (int k = 0; k < kSentenceCount; ++k) {
    const auto sentence = static_cast<Sentence>(k);
    const Text id = sentence_text(sentence);
    EXPECT_STREQ(catalogue_text(Language::kEnglish, id), english_words(sentence))
        << text_name(id) << ": the English catalogue differs from the library's words";
    ASSERT_NE(catalogue_text(Language::kChinese, id), nullptr)
        << text_name(id) << " has no Chinese words (zh_CN.h)";
  }
}

TEST(LibraryWords, ChineseSentencesHaveNoEnglishWordOfTheLibrary) {
  // A configuration key ("shape.library_size") is a name too.
  static const std::regex key("[a-z_]+\\.[a-z_]+");
  for (int k = 0; k < kSentenceCount; ++k) {
    const auto sentence = static_cast<Sentence>(k);
    if (sentence == Sentence::kText) continue;  // free-form: its one value
    const std::string chinese = catalogue_text(Language::kChinese, sentence_text(sentence));
    const std::set<std::string> left = english_words_of(chinese);
    const std::string english = std::regex_replace(english_words(sentence), key, "");
    for (const std::string& word : english_words_of(english)) {
      if (is_kept_name(word)) continue;
      EXPECT_EQ(left.count(word), 0U)
          << text_name(sentence_text(sentence)) << " keeps the English word '" << word << "'";
    }
    if (!english_words_of(english_words(sentence)).empty()) {
      EXPECT_TRUE(has_chinese_text(chinese)) << text_name(sentence_text(sentence));
    }
  }
}

TEST(LibraryWords, RefusedValueInChinese) {
  try {
    validate(Grading{.kind = GradingKind::kUniform, .radius_min = 0.02, .radius_max = 0.01});
    FAIL() << "radius_max < radius_min was accepted";
  } catch (const InvalidInput& error) {
    ASSERT_TRUE(error.has_value());
    EXPECT_EQ(error.wording().sentence, Sentence::kAtLeastKey);
    EXPECT_STREQ(error.what(),
                 "invalid grading.radius_max = 0.01 (allowed: >= grading.radius_min = 0.02)");
    EXPECT_EQ(in_chinese([&] { return error_words(error); }),
              "grading.radius_max：不允许取值 0.01；允许范围：不小于 grading.radius_min = 0.02");
    EXPECT_EQ(error_words(error),
              "grading.radius_max: 0.01 is not allowed; allowed: >= grading.radius_min = 0.02");
  }
}

TEST(LibraryWords, RuleBetweenKeysInChinese) {
  // The configuration's own rule (as the panel's Pack meets it): a ConfigError with its parts.
  try {
    (void)parse_pack_config(
        "", "gui",
        {"packer.kind=\"random\"", "particle.radius_min=0.02", "particle.radius_max=0.01"});
    FAIL() << "radius_max < radius_min was accepted";
  } catch (const ConfigError& error) {
    ASSERT_TRUE(error.has_value()) << error.what();
    const std::string chinese = in_chinese([&] { return error_words(error); });
    EXPECT_TRUE(has_chinese_text(chinese)) << chinese;
    for (const char* english : {"invalid", "allowed", "gui"}) {
      EXPECT_EQ(chinese.find(english), std::string::npos) << chinese;
    }
    EXPECT_NE(chinese.find("particle.radius_min = 0.02 m"), std::string::npos) << chinese;
  }
}

TEST(LibraryWords, ReadErrorsInChinese) {
  const std::string missing = "/nonexistent-aggpack-folder/packing.h5";
  try {
    (void)read_packing(missing);
    FAIL() << "a missing file was read";
  } catch (const IoError& error) {
    EXPECT_EQ(error.wording().sentence, Sentence::kReadNoSuchFile);
    EXPECT_EQ(error_words(error), std::string(error.what()));  // English: the library's words
    EXPECT_EQ(in_chinese([&] { return error_words(error); }),
              "无法读取 " + missing + "：文件不存在");
  }
  const auto text_file = std::filesystem::temp_directory_path() / "aggpack-gui-not-hdf5.h5";
  std::ofstream(text_file) << "not a packing\n";
  try {
    (void)read_packing(text_file.string());
    FAIL() << "a text file was read as a packing";
  } catch (const FormatError& error) {
    EXPECT_EQ(error.wording().sentence, Sentence::kNotHdf5);
    EXPECT_EQ(
        in_chinese([&] { return error_words(error); }),
        text_file.string() + "：不是 HDF5 文件（应为 aggpack 堆积文件，格式 aggpack-packing）");
  }
  std::filesystem::remove(text_file);
}

TEST(LibraryWords, OtherErrorsAreNamedAsErrors) {
  // Not the library's: a bug (its what() a detail), out of memory, an operating-system failure.
  const std::runtime_error other("basic_string::_M_create");
  EXPECT_EQ(in_chinese([&] { return error_words(other); }),
            "内部错误（程序缺陷，请报告）：basic_string::_M_create");
  EXPECT_EQ(error_words(other),
            "Internal error (a bug, please report it): basic_string::_M_create");
  EXPECT_EQ(in_chinese([&] { return error_words(std::bad_alloc()); }), "错误：内存不足。");
  const std::system_error system(std::make_error_code(std::errc::no_space_on_device), "write");
  // Its reason in words (the caller's English label of the call, "write", is left out).
  EXPECT_EQ(in_chinese([&] { return error_words(system); }), "错误：设备上没有空间");
  EXPECT_EQ(error_words(system), "Error: " + std::string(system.what()));
}

// The panel's keys (config_panel.cpp draws these tables; particle.library's list included).
std::vector<std::size_t> panel_keys() {
  std::vector<std::size_t> indices;
  const auto& keys = pack_schema().keys;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string table = keys[i].name.substr(0, keys[i].name.find('.'));
    if ((table == "container" || table == "particle" || table == "packer" || table == "grading" ||
         table == "densify") &&
        keys[i].type != ValueType::kPath) {
      indices.push_back(i);
    }
  }
  return indices;
}

// What a text of a key says in English that is no name: a key ("packer.kind"), a number, a name
// with an underscore ("radius_max"), a configuration word ("random") or true | false stay.
std::set<std::string> english_prose(const std::string& text) {
  // Keys and numbers in exponent form ("1e12") are no words.
  static const std::regex names("[a-z_]+\\.[a-z_]+|[0-9.]+e[-+]?[0-9]+");
  std::set<std::string> prose;
  for (const std::string& word : english_words_of(std::regex_replace(text, names, ""))) {
    bool is_name = word == "true" || word == "false" || word.find('_') != std::string::npos;
    for (const auto& key : pack_schema().keys) {
      is_name = is_name || std::find(key.words.begin(), key.words.end(), word) != key.words.end();
    }
    if (!is_name) prose.insert(word);
  }
  return prose;
}

TEST(LibraryWords, EveryPanelKeyNoteAndDefaultHasChinese) {
  // The tooltip's allowed values and default, and a field's error, are worded from the key's
  // parts: a note or default words must be a sentence with Chinese words (error_words.h), and
  // the Chinese window shows no English prose of them.
  const auto& schema = pack_schema();
  const auto views = key_views(schema);
  std::size_t notes = 0;
  std::size_t defaults = 0;
  for (const std::size_t i : panel_keys()) {
    const Key<PackConfig>& key = schema.keys[i];
    for (const Wording* words : {&key.note, &key.default_text}) {
      if (!has_words(*words)) continue;
      ++(words == &key.note ? notes : defaults);
      EXPECT_NE(words->sentence, Sentence::kText) << key.name << ": free-form English words";
      const char* chinese = catalogue_text(Language::kChinese, sentence_text(words->sentence));
      ASSERT_NE(chinese, nullptr) << key.name << " has no Chinese words (zh_CN.h)";
    }
    const std::string default_english =
        default_text(views[i], *key.default_value, key.default_from, key.default_text);
    // English: the library's own words (docs/config.md, `aggpack config keys`).
    EXPECT_EQ(allowed_words(views[i]), allowed_text(views[i])) << key.name;
    EXPECT_EQ(default_words(views[i], *key.default_value, key.default_from, key.default_text),
              default_english)
        << key.name;
    const std::string allowed = in_chinese([&] { return allowed_words(views[i]); });
    const std::string shown = in_chinese([&] {
      return default_words(views[i], *key.default_value, key.default_from, key.default_text);
    });
    EXPECT_EQ(english_prose(allowed), std::set<std::string>()) << key.name << ": " << allowed;
    EXPECT_EQ(english_prose(shown), std::set<std::string>()) << key.name << ": " << shown;
    if (!english_prose(allowed_text(views[i])).empty()) {
      EXPECT_TRUE(has_chinese_text(allowed)) << key.name << ": " << allowed;
    }
    if (!english_prose(default_english).empty()) {
      EXPECT_TRUE(has_chinese_text(shown)) << key.name << ": " << shown;
    }
  }
  EXPECT_GE(notes, 9U);     // the panel's rules beside a range
  EXPECT_GE(defaults, 3U);  // grading.sieve, packer.target_count, particle.library
}

TEST(LibraryWords, KeyNotesInChinese) {
  const auto& schema = pack_schema();
  const auto views = key_views(schema);
  auto chinese_allowed = [&](const std::string& name) {
    const auto* key = schema.find(name);
    return in_chinese(
        [&] { return allowed_words(views[static_cast<std::size_t>(key - schema.keys.data())]); });
  };
  EXPECT_EQ(chinese_allowed("container.wall_gap"), "[0, 1e6]，小于容器最小尺寸的一半");
  EXPECT_EQ(chinese_allowed("particle.edge_length"),
            "[0, 1e6]，仅当 packer.kind = random 时可为 0");
  EXPECT_EQ(chinese_allowed("particle.library"), "非空路径，或由路径组成的数组");
}

TEST(LibraryWords, DensifySummaryFromTheReport) {
  DensifyReport report;
  report.stop = DensifyStop::kJammed;
  report.start_fraction = 0.41;
  report.solid_fraction = 0.6125;
  report.sweeps = 800;
  report.seconds = 12.1;
  EXPECT_EQ(densify_words(report), report.summary());  // English: the library's words
  EXPECT_EQ(in_chinese([&] { return densify_words(report); }),
            "固体体积分数 0.4100 -> 0.6125，800 轮（12 秒），已卡死（体积分数不再上升）");
}

}  // namespace
}  // namespace aggpack::gui
