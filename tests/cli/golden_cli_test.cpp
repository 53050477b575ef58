// Golden CLI tests: every folder of tests/cli/cases/ is one test, GoldenCli/Case.Matches/<name>.
// Its commands run in a scratch folder and their printed text (and the output files it lists) must
// match the references in its expected/ folder: text exactly, numbers within a relative 1e-9,
// timings and paths masked; the files listed in `exact` byte for byte, the PNGs listed in
// `images` within a pixel tolerance. Layout and the regenerate mode: tests/cli/cases/README.md.
//
//   AGGPACK_REGENERATE_GOLDEN=1 ctest --test-dir build -R GoldenCli   rewrites every expected/

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include "support/cli_test.h"
#include "support/golden.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

const fs::path kCases = fs::path(test::source_dir()) / "tests" / "cli" / "cases";

bool is_regenerating() {
  const char* value = std::getenv("AGGPACK_REGENERATE_GOLDEN");
  return value != nullptr && std::string(value) == "1";
}

// Non-empty lines of a case file, without `#` comment lines.
std::vector<std::string> lines_of(const fs::path& path) {
  std::vector<std::string> lines;
  std::istringstream in(test::file_text(path));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> case_names() {
  std::vector<std::string> names;
  if (!fs::is_directory(kCases)) return names;
  for (const auto& entry : fs::directory_iterator(kCases)) {
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A PNG's pixels as RGB (an empty image when the bytes are no PNG).
test::GoldenImage decode_png(const std::string& bytes) {
  test::GoldenImage image;
  int channels = 0;
  unsigned char* pixels = stbi_load_from_memory(
      reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<int>(bytes.size()),
      &image.width, &image.height, &channels, 3);
  if (pixels == nullptr) return {};
  image.rgb.assign(pixels, pixels + static_cast<std::size_t>(image.width) *
                                        static_cast<std::size_t>(image.height) * 3);
  stbi_image_free(pixels);
  return image;
}

// How an output file is compared with its reference.
enum class Comparison { kText, kBytes, kImage };

// The case's control files; every other file of a case folder is an input.
const std::vector<std::string> kControlFiles = {"cmd",    "outputs",  "exact",
                                                "images", "requires", "expected"};

class Case : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    source_ = kCases / GetParam();
    scratch_ = fs::temp_directory_path() /
               ("aggpack_golden_" + GetParam() + "_" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  // Runs one command line inside scratch_; returns its transcript block.
  [[nodiscard]] std::string run(const std::string& arguments) const {
    const std::string out = scratch_.string() + ".stdout";
    const std::string err = scratch_.string() + ".stderr";
    const std::string command = "cd '" + scratch_.string() + "' && '" + test::aggpack_binary() +
                                "' " + arguments + " >'" + out + "' 2>'" + err + "' </dev/null";
    const int status = std::system(command.c_str());
    const int exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::string block = "$ aggpack " + arguments + "\n" + test::file_text(out);
    const std::string error_text = test::file_text(err);
    if (!error_text.empty()) block += "[stderr]\n" + error_text;
    block += "[exit " + std::to_string(exit_code) + "]\n";
    fs::remove(out);
    fs::remove(err);
    return test::mask_volatile(block, scratch_.string(), test::aggpack_binary());
  }

  fs::path source_;
  fs::path scratch_;
};

TEST_P(Case, Matches) {
  for (const std::string& subcommand : lines_of(source_ / "requires")) {
    if (!test::has_subcommand(subcommand)) {
      GTEST_SKIP() << "this aggpack has no '" << subcommand << "' subcommand";
    }
  }
  const std::vector<std::string> commands = lines_of(source_ / "cmd");
  ASSERT_FALSE(commands.empty()) << source_ / "cmd"
                                 << " has no command";
  // Every file of the case folder except its own control files is an input.
  for (const auto& entry : fs::directory_iterator(source_)) {
    const std::string name = entry.path().filename().string();
    if (std::find(kControlFiles.begin(), kControlFiles.end(), name) != kControlFiles.end()) {
      continue;
    }
    fs::copy(entry.path(), scratch_ / name, fs::copy_options::recursive);
  }
  std::string transcript;
  for (const std::string& command : commands) transcript += run(command);

  struct Result {
    std::string name;
    std::string content;
    Comparison comparison = Comparison::kText;
  };
  std::vector<Result> results = {{"transcript.txt", transcript, Comparison::kText}};
  for (const auto& [list, comparison] :
       {std::pair{"outputs", Comparison::kText}, std::pair{"exact", Comparison::kBytes},
        std::pair{"images", Comparison::kImage}}) {
    for (const std::string& output : lines_of(source_ / list)) {
      ASSERT_TRUE(fs::exists(scratch_ / output)) << "the case lists output " << output << " (in "
                                                 << list << ") but the commands did not write it\n"
                                                 << transcript;
      std::string content = test::file_text(scratch_ / output);
      if (comparison == Comparison::kText) {
        content = test::mask_volatile(content, scratch_.string(), test::aggpack_binary());
      }
      results.push_back({output, std::move(content), comparison});
    }
  }

  const fs::path expected = source_ / "expected";
  if (is_regenerating()) {
    fs::remove_all(expected);
    for (const Result& result : results) write_file(expected / result.name, result.content);
    std::cout << "[golden] regenerated " << expected.string() << "\n";
    return;
  }
  for (const Result& result : results) {
    const fs::path reference = expected / result.name;
    ASSERT_TRUE(fs::exists(reference))
        << reference << " is missing; write it with AGGPACK_REGENERATE_GOLDEN=1 ctest -R GoldenCli";
    const std::string want = test::file_text(reference);
    std::string difference;
    switch (result.comparison) {
      case Comparison::kText:
        difference = test::golden_difference(want, result.content);
        break;
      case Comparison::kBytes:
        if (want != result.content) {
          const auto mismatch =
              std::mismatch(want.begin(), want.end(), result.content.begin(), result.content.end());
          difference = "bytes differ from offset " + std::to_string(mismatch.first - want.begin()) +
                       " (" + std::to_string(result.content.size()) + " bytes, expected " +
                       std::to_string(want.size()) + ")";
        }
        break;
      case Comparison::kImage: {
        const test::GoldenImage got = decode_png(result.content);
        difference =
            got.rgb.empty() ? "not a PNG" : test::golden_image_difference(decode_png(want), got);
        break;
      }
    }
    EXPECT_TRUE(difference.empty())
        << GetParam() << "/expected/" << result.name << " differs (" << difference
        << ").\nIf the change is intended: AGGPACK_REGENERATE_GOLDEN=1 ctest --test-dir build -R "
           "GoldenCli, then review `git diff tests/cli/cases`."
        << (result.comparison == Comparison::kText ? "\n--- got:\n" + result.content : "");
  }
}

// gtest names allow letters, digits and '_' only.
std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  std::replace_if(
      name.begin(), name.end(),
      [](char c) { return std::isalnum(static_cast<unsigned char>(c)) == 0; }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(GoldenCli, Case, ::testing::ValuesIn(case_names()), test_name);

TEST(GoldenCli, EveryCaseHasACommandAndReferences) {
  const std::vector<std::string> names = case_names();
  ASSERT_FALSE(names.empty()) << kCases << " has no cases";
  for (const std::string& name : names) {
    EXPECT_TRUE(fs::exists(kCases / name / "cmd")) << name;
    EXPECT_TRUE(fs::exists(kCases / name / "expected" / "transcript.txt")) << name;
  }
}

// A new subcommand needs a golden case: every name under "Subcommands:" in `aggpack --help` is the
// first word of some case's command.
TEST(GoldenCli, EverySubcommandHasACase) {
  const std::string help_path =
      (fs::temp_directory_path() / ("aggpack_golden_help_" + std::to_string(::getpid()))).string();
  const std::string command = "'" + test::aggpack_binary() + "' --help >'" + help_path + "' 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::istringstream help(test::file_text(help_path));
  fs::remove(help_path);
  std::vector<std::string> subcommands;
  bool is_listing = false;
  for (std::string line; std::getline(help, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      is_listing = true;
    } else if (is_listing && line.size() > 2 && line[0] == ' ' && line[2] != ' ') {
      subcommands.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  ASSERT_FALSE(subcommands.empty());
  std::vector<std::string> covered;
  for (const std::string& name : case_names()) {
    for (const std::string& line : lines_of(kCases / name / "cmd")) {
      covered.push_back(line.substr(0, line.find(' ')));
    }
  }
  for (const std::string& subcommand : subcommands) {
    EXPECT_NE(std::find(covered.begin(), covered.end(), subcommand), covered.end())
        << "no golden case runs `aggpack " << subcommand << "` (add tests/cli/cases/" << subcommand
        << "/)";
  }
}

}  // namespace
}  // namespace aggpack
