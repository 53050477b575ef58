// YADE deck (--deck yade): the real YADE (Debian's yade, installed by scripts/install-deps.sh)
// runs the exported script headless, as written, on a small pile: the run call completes the
// whole test (settle, baffle, rest), the particles fall onto the floor and stay in the trough,
// nothing flies off, and the baffle reaches the trough's end.

#include <regex>

#include "aggpack/io/export.h"
#include "deck_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

TEST(YadeDeck, YadeRunsTheExportedScript) {
  // Fails (not skips) without YADE.
  AGGPACK_REQUIRE_READER("yade");
  // Two layers, the lower 5 cm above the floor.
  const Packing packing = test::pile_near_floor(3, 2, 2, 0.05, 101);
  ScratchFolder folder;
  ExportOptions options;
  // PolyhedraMat.young is YADE's volumetric contact stiffness (N/m^3); YADE's examples use
  // 1e7 .. 1e8. With 1e8 the deck's own time step is about 3e-4 s: a few hundred steps.
  options.material = {.density = 2600.0, .youngs_modulus = 1e8, .poisson_ratio = 0.2};
  options.deck = {.kind = DeckKind::kYade,
                  .friction = 0.5,
                  .trough_length = packing.container.get_if<BoxContainer>()->length + 0.05,
                  .baffle_speed = 1.0,
                  .settle_time = 0.1,
                  .rest_time = 0.02};
  write(packing, folder.file("trough.py"), options);
  const auto result = test::run_command("cd " + folder.path().string() +
                                        " && TMPDIR=. OMP_NUM_THREADS=1 yade -n -x trough.py");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(result.output, match,
                                std::regex("aggpack-yade: running (\\d+) steps of (\\S+) s")))
      << result.output;
  const long steps = std::stol(match[1]);
  const double dt = std::stod(match[2]);
  EXPECT_GE(steps, 100);
  EXPECT_LE(steps, 2000);
  ASSERT_TRUE(std::regex_search(
      result.output, match,
      std::regex("aggpack-yade: particles (\\d+) bodies (\\d+) iterations (\\d+) time (\\S+) "
                 "mean_z_start (\\S+) mean_z_end (\\S+) max_speed (\\S+) baffle_x (\\S+)")))
      << result.output;
  std::printf("%s\n", match[0].str().c_str());
  const std::size_t count = packing.particles.size();
  EXPECT_EQ(std::stoul(match[1]), count);
  EXPECT_EQ(std::stoul(match[2]), count + 6);  // floor, 4 walls, baffle
  EXPECT_EQ(std::stol(match[3]), steps);
  EXPECT_NEAR(std::stod(match[4]), steps * dt, 1e-5 * steps * dt);  // dt printed to 6 digits
  const double start = std::stod(match[5]);
  const double end = std::stod(match[6]);
  // The pile settled: the upper layer fell about a layer's spacing onto the lower one, which
  // fell 5 cm onto the floor; nobody went through the floor.
  EXPECT_LT(end, start - 0.03);
  EXPECT_GT(end, 0.0);
  EXPECT_LT(std::stod(match[7]), 4.0);  // free fall through 0.3 m reaches 2.4 m/s
  EXPECT_NEAR(std::stod(match[8]), packing.container.get_if<BoxContainer>()->length + 0.05, 0.01);
}

}  // namespace
}  // namespace aggpack
