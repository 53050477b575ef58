// Every library error the window can meet, driven through the library as the window drives it
// (Pack's configuration and run, particle.library, Open, Export, the solver decks, the
// mesomodel), worded in Chinese from its parts: each part is a sentence of core/error_words.h or a
// name or number, and no English word of the library's message is left but names and values.
// A message that reaches the window as free-form English text fails here.

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/io/export.h"
#include "aggpack/io/shape_library_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "gui/words.h"
#include "i18n.h"
#include "library_words.h"
#include "support/packings.h"

namespace aggpack::gui {
namespace {

namespace fs = std::filesystem;

// A word kept in every language, or a name with an underscore (a key's part, "library_size").
bool is_name(const std::string& word) {
  return test_words::is_kept_name(word) || word.find('_') != std::string::npos;
}

// The error in the Chinese window (then back to English).
std::string chinese_words(const Error& error) {
  set_language(Language::kChinese);
  std::string text = error_words(error);
  set_language(Language::kEnglish);
  return text;
}

// What is wrong with the error's words in Chinese ("" when nothing): they must carry no English
// word of its message but names and values, and its whole message (or the allowed part of a
// refused value) must be a sentence unless it has no words. `chinese` gets the words.
std::string problems_in_chinese(const Error& error, std::string& chinese) {
  std::string problems;
  std::vector<const Wording*> parts = {&error.wording()};
  if (error.has_value()) {
    parts.push_back(&error.value_wording());
    parts.push_back(&error.field_wording());  // last: a field's name is a name
  }
  std::set<std::string> value_words;
  for (const Wording* part : parts) {
    for (const std::string& value : part->values) {
      // Words in a value (a path, a number with its unit) are names; English words in a value
      // with spaces are prose, unless the window words it (a Phrase* sentence).
      const std::set<std::string> words = test_words::english_words_of(value);
      value_words.insert(words.begin(), words.end());
      if (part == &error.field_wording() || value.find(' ') == std::string::npos) continue;
      std::size_t english = 0;
      for (const std::string& word : words) english += is_name(word) ? 0 : 1;
      const std::string worded =
          chinese_words(LimitExceeded("x", "1", Wording{Sentence::kAtMost, {value}}));
      if (english >= 2 && worded.find(value) != std::string::npos) {
        problems += " English value '" + value + "';";
      }
    }
  }
  if (error.wording().sentence == Sentence::kText) {
    for (const std::string& word : test_words::english_words_of(english(error.wording()))) {
      if (!is_name(word)) problems += " free-form English word '" + word + "';";
    }
  }
  chinese = chinese_words(error);
  if (!test_words::has_chinese_text(chinese)) problems += " no Chinese;";
  const std::set<std::string> left = test_words::english_words_of(chinese);
  for (const std::string& word : test_words::english_words_of(error.what())) {
    if (value_words.count(word) > 0 || is_name(word)) continue;
    if (left.count(word) > 0) problems += " '" + word + "' left;";
  }
  return problems;
}

// Checks the error's Chinese words (AGGPACK_SHOW_WORDS=1 prints both languages).
std::string expect_worded(const Error& error) {
  std::string chinese;
  const std::string problems = problems_in_chinese(error, chinese);
  if (std::getenv("AGGPACK_SHOW_WORDS") != nullptr) {
    std::printf("%s\n%s\n\n", error.what(), chinese.c_str());
  }
  EXPECT_EQ(problems, "") << chinese << "\n(English: " << error.what() << ")";
  return chinese;
}

// Runs `run`, which must throw an aggpack Error, and checks its Chinese words.
std::string expect_chinese_error(const std::function<void()>& run) {
  try {
    run();
  } catch (const Error& error) {
    return expect_worded(error);
  }
  ADD_FAILURE() << "no error thrown";
  return "";
}

// A scratch folder of its own, removed afterwards.
struct ErrorsScratch {
  fs::path folder =
      fs::temp_directory_path() / ("aggpack-gui-errors-" + std::to_string(::getpid()));
  ErrorsScratch() { fs::create_directories(folder); }
  ~ErrorsScratch() { fs::remove_all(folder); }
  [[nodiscard]] std::string path(const std::string& name) const { return (folder / name).string(); }
};

Packing two_cubes(double first_x, double second_x) {
  const ConvexPolyhedron cube = make_box(Vec3::Constant(-0.1), Vec3::Constant(0.1));
  return test::box_with(1.0, {cube, cube}, {Vec3(first_x, 0.5, 0.5), Vec3(second_x, 0.5, 0.5)});
}

TEST(LibraryErrors, FreeFormEnglishFails) {
  // The check itself: a message without a sentence of its own is caught.
  std::string chinese;
  const std::string problems =
      problems_in_chinese(FormatError("x.ply: PLY header has no format line"), chinese);
  EXPECT_NE(problems.find("free-form English word 'header'"), std::string::npos) << problems;
  EXPECT_NE(problems.find("no Chinese"), std::string::npos) << problems;
  // A value in English words is caught too, unless it is a phrase the window words.
  const LimitExceeded prose(Wording{Sentence::kText, {"grading"}},
                            Wording{Sentence::kText, {"sizes out of range"}},
                            Wording{Sentence::kAtMost, {"1"}});
  EXPECT_NE(problems_in_chinese(prose, chinese).find("English value"), std::string::npos);
  const LimitExceeded phrase(
      Wording{Sentence::kText, {"grading"}}, Wording{Sentence::kText, {"1"}},
      Wording{Sentence::kMemorySize, {english_words(Sentence::kPhraseUseLargerParticles)}});
  EXPECT_EQ(problems_in_chinese(phrase, chinese), "") << chinese;
}

TEST(LibraryErrors, WritingAFile) {
  const ErrorsScratch scratch;
  const Packing packing = two_cubes(0.3, 0.7);
  const ExportOptions stl{.format = parse_export_format("stl"), .overwrite = Overwrite::kAllow};
  expect_chinese_error([&] { (void)write(packing, "/nonexistent-aggpack-folder/rock.stl", stl); });
  fs::create_directories(scratch.path("rock.stl"));
  const std::string folder =
      expect_chinese_error([&] { (void)write(packing, scratch.path("rock.stl"), stl); });
  EXPECT_NE(folder.find("文件夹"), std::string::npos) << folder;  // "directory", a phrase
  expect_chinese_error([] { check_writable("", Overwrite::kAllow); });
  expect_chinese_error(
      [&] { check_writable(scratch.path(std::string(300, 'a')), Overwrite::kAllow); });
}

TEST(LibraryErrors, LimitsCheckedBeforeAPack) {
  const std::vector<std::string> random = {"packer.kind=\"random\""};
  auto config_with = [&](std::vector<std::string> sets) {
    sets.insert(sets.begin(), random.begin(), random.end());
    return [sets] { (void)parse_pack_config("", "gui", sets); };
  };
  expect_chinese_error(config_with({"packer.target_count=100000000"}));
  expect_chinese_error(config_with({"packer.target_count=10", "packer.shape_library=1000000"}));
  ::setenv("AGGPACK_MEMORY_LIMIT", "1K", 1);
  expect_chinese_error(config_with({"packer.target_count=1000"}));
  ::setenv("AGGPACK_MEMORY_LIMIT", "lots", 1);
  expect_chinese_error(config_with({"packer.target_count=1000"}));
  ::unsetenv("AGGPACK_MEMORY_LIMIT");
}

TEST(LibraryErrors, ShapeLibraryFiles) {
  const ErrorsScratch scratch;
  auto load = [](const std::string& path) {
    return [path] {
      ShapeLibraryOptions options;
      options.paths = {path};
      (void)load_shape_library(options);
    };
  };
  expect_chinese_error(load(scratch.path("missing")));
  expect_chinese_error(load(""));
  fs::create_directories(scratch.path("empty"));
  expect_chinese_error(load(scratch.path("empty")));
  std::ofstream(scratch.path("notes.txt")) << "not a mesh\n";
  expect_chinese_error(load(scratch.path("notes.txt")));
  // Damaged mesh files: each reader's sentence, the file named first.
  std::ofstream(scratch.path("bad.stl")) << "solid x\nfacet normal 0 0 1\nouter loop\n";
  expect_chinese_error(load(scratch.path("bad.stl")));
  std::ofstream(scratch.path("bad.obj")) << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
  expect_chinese_error(load(scratch.path("bad.obj")));
  std::ofstream(scratch.path("junk.stl")) << "junk\n";
  expect_chinese_error(load(scratch.path("junk.stl")));
}

TEST(LibraryErrors, Mesomodel) {
  MesoOptions options;
  options.itz_thickness = 0.03;  // two cubes 0.05 apart: their layers meet
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.3, 0.55), options); });
  options.itz_thickness = 0.0;  // touching cubes
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.3, 0.5), options); });
  expect_chinese_error([&] { (void)build_mesomodel(two_cubes(0.1, 0.5), options); });  // a wall
}

TEST(LibraryErrors, SolverDeckFields) {
  const ErrorsScratch scratch;
  ExportOptions options{.overwrite = Overwrite::kAllow};
  options.deck.kind = DeckKind::kAbaqus;
  for (const DeckInfo& deck : deck_kinds()) {
    if (deck.kind == DeckKind::kAbaqus) options.format = deck.format;
  }
  options.material.poisson_ratio = 0.7;
  const std::string poisson = expect_chinese_error([&] { validate(options, options.format); });
  EXPECT_NE(poisson.find("泊松比"), std::string::npos) << poisson;  // the field's label
  options.material.poisson_ratio = 0.2;
  options.deck.baffle_position = 0.01;  // in front of the particles
  expect_chinese_error(
      [&] { (void)write(two_cubes(0.3, 0.7), scratch.path("trough.inp"), options); });
}

}  // namespace
}  // namespace aggpack::gui
