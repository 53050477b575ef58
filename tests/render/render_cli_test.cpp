// `aggpack render`: a saved packing to PNG through the real command line.

#include <gtest/gtest.h>
#include <stb_image.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

#include "aggpack/io/native.h"
#include "support/paths.h"
#include "test_packings.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

int run(const std::string& arguments) {
  const std::string command = test::aggpack_binary() + " " + arguments + " > /dev/null 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("aggpack_render_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    input_ = (dir_ / "run.h5").string();
    write_packing(test::grid_packing(4, 2, 3), input_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string input_;
};

TEST_F(RenderCli, WritesAPngOfTheRequestedSize) {
  const std::string output = (dir_ / "view.png").string();
  ASSERT_EQ(run("render " + input_ + " -o " + output +
                " --size 320x200 --view front --color size --samples 0"),
            0);
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load(output.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr);
  EXPECT_EQ(width, 320);
  EXPECT_EQ(height, 200);
  // Not a blank picture: some pixels differ from the background of the top-left corner.
  std::size_t other = 0;
  for (int i = 0; i < width * height; ++i) {
    other += pixels[3 * i] != pixels[0] || pixels[3 * i + 1] != pixels[1] ||
             pixels[3 * i + 2] != pixels[2];
  }
  stbi_image_free(pixels);
  EXPECT_GT(other, 1000u);
  // The default output name is the input's with .png; an existing file needs --force.
  EXPECT_EQ(run("render " + input_ + " --size 64x64"), 0);
  EXPECT_TRUE(fs::exists(dir_ / "run.png"));
  EXPECT_EQ(run("render " + input_ + " --size 64x64"), 3);
  EXPECT_EQ(run("render " + input_ + " --size 64x64 --force --wireframe --ortho --no-container"),
            0);
}

TEST_F(RenderCli, RejectsBadOptionsWithoutWritingAFile) {
  const std::string output = (dir_ / "bad.png").string();
  EXPECT_EQ(run("render " + input_ + " -o " + output + " --size 10x10"), 2);
  EXPECT_EQ(run("render " + input_ + " -o " + output + " --size 300"), 2);
  EXPECT_EQ(run("render " + input_ + " -o " + output + " --view back"), 2);
  EXPECT_EQ(run("render " + input_ + " -o " + output + " --color red"), 2);
  EXPECT_EQ(run("render " + input_ + " -o " + output + " --samples 99"), 2);
  EXPECT_EQ(run("render " + (dir_ / "missing.h5").string() + " -o " + output), 3);
  EXPECT_FALSE(fs::exists(output));
}

}  // namespace
}  // namespace aggpack
