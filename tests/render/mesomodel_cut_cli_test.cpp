// `aggpack render --mesomodel-cut`: a packing meshed into aggregate, ITZ and mortar
// (build_mesomodel) and its section drawn in software, through the real command line.

#include <gtest/gtest.h>
#include <stb_image.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "aggpack/io/native.h"
#include "aggpack/mesh/mesomodel_cut.h"
#include "support/cli_test.h"
#include "test_packings.h"

namespace aggpack {
namespace {

class MesomodelCutCli : public test::CliTest {
 protected:
  MesomodelCutCli() : CliTest("aggpack_cut_cli_") {}
};

TEST_F(MesomodelCutCli, DrawsThePhasesOfTheSection) {
  // 3 x 2 x 2 particles of radius 0.1 m, 0.22 m apart (gaps >= 0.02 m), walls 0.01 m away.
  write_packing(test::grid_packing(3, 2, 2), (folder_ / "run.h5").string());
  const test::CliRun ok =
      run("render run.h5 --mesomodel-cut z=0.12 --itz 0.004 --size 600x400 -o cut.png");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("wrote cut.png (600x"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("mesomodel cut z=0.12"), std::string::npos) << ok.out;
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels =
      stbi_load((folder_ / "cut.png").string().c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr);
  EXPECT_EQ(width, 600);
  std::size_t mortar = 0, itz = 0, stone = 0;
  const Rgb mortar_colour = mesomodel_cut_colour(MesoPhase::kMortar, 0, false);
  const Rgb itz_colour = mesomodel_cut_colour(MesoPhase::kItz, 0, false);
  const Rgb stone_colour = mesomodel_cut_colour(MesoPhase::kAggregate, 0, false);
  for (int i = 0; i < width * height; ++i) {
    const Rgb p{pixels[3 * i], pixels[3 * i + 1], pixels[3 * i + 2]};
    mortar += p == mortar_colour;
    itz += p == itz_colour;
    // Tinted aggregate greys: the stone colour shifted by -24..24 levels on every channel.
    stone += p[0] == p[1] && p[2] - p[0] == stone_colour[2] - stone_colour[0] &&
             p[0] >= stone_colour[0] - 24 && p[0] <= stone_colour[0] + 24;
  }
  stbi_image_free(pixels);
  // The section (520 pixels wide) is mostly aggregate and mortar, with a thin ITZ ring (0.004 m
  // is about 3 pixels) round each of the 6 aggregates it cuts.
  EXPECT_GT(mortar, 10000U);
  EXPECT_GT(stone, 10000U);
  EXPECT_GT(itz, 300U);

  // A plane outside the container: one line naming the flag and the range, no file.
  const test::CliRun bad = run("render run.h5 --mesomodel-cut z=0.9 -o bad.png");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--mesomodel-cut = z=0.9"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("z in [0, 0.46]"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(folder_ / "bad.png"));
}

}  // namespace
}  // namespace aggpack
