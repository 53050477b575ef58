// CalculiX deck (--deck calculix): the real ccx runs the exported trough test on a small pile
// resting just above the floor to completion (exit 0, no *ERROR or *WARNING), and the particles
// land on the floor (its reaction grows from 0 to about the pile's weight).

#include <regex>
#include <vector>

#include "aggpack/io/export.h"
#include "deck_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// Every "total force (fx,fy,fz) for set <set>" of a ccx .dat file, in order.
std::vector<Vec3> total_forces(const std::string& dat, const std::string& set) {
  const std::regex pattern("total force \\(fx,fy,fz\\) for set " + set +
                           " and time +\\S+\\s+(\\S+) +(\\S+) +(\\S+)");
  std::vector<Vec3> forces;
  for (auto it = std::sregex_iterator(dat.begin(), dat.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    forces.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]));
  }
  return forces;
}

TEST(CalculixDeck, CcxRunsTheTroughTestOnASmallPile) {
  // Fails (not skips) without ccx: scripts/install-deps.sh installs calculix-ccx.
  AGGPACK_REQUIRE_READER("ccx");
  const Packing packing = test::pile_near_floor(3, 2, 1, 0.0005, 71);
  ScratchFolder folder;
  ExportOptions options;
  // A soft material keeps ccx's stable explicit increment large (2.5e-5 s): about 2,000
  // increments. The rock default (50 GPa) needs about 70 times as many.
  options.material.density = 2500.0;
  options.material.youngs_modulus = 1e7;
  options.deck = {.kind = DeckKind::kCalculix,
                  .friction = 0.4,
                  .trough_length = packing.container.get_if<BoxContainer>()->length + 0.01,
                  .baffle_speed = 1.0,
                  .settle_time = 0.03,
                  .rest_time = 0.01,
                  .contact_distance = 0.1};  // neighbours along x and y too
  const ExportSummary summary = write(packing, folder.file("trough.inp"), options);
  EXPECT_EQ(summary.format, ExportFormat::kAbaqus);
  const std::string deck = test::read_text(folder.file("trough.inp"));
  for (const char* expected :
       {"*CONTACT PAIR, INTERACTION=ROUGH", "P1_SURFACE, FLOOR_SURFACE", "*FRICTION\n0.4,",
        "*DLOAD\nAGGREGATES, GRAV, 9.81, 0, 0, -1\n", "*BOUNDARY, AMPLITUDE=BAFFLE_MOVE\n"}) {
    EXPECT_NE(deck.find(expected), std::string::npos) << expected;
  }
  const auto result =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i trough");
  ASSERT_EQ(result.exit_code, 0) << result.output.substr(result.output.size() - 2000);
  EXPECT_EQ(result.output.find("*ERROR"), std::string::npos);
  EXPECT_EQ(result.output.find("*WARNING"), std::string::npos);
  EXPECT_NE(result.output.find("Job finished"), std::string::npos);
  // Contact happened: the particles start 0.5 mm above the floor, which carries nothing at
  // first and about the pile's weight at the end (the particles may still rock a little).
  double weight = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    weight += 2500.0 * 9.81 * test::particle_volume(packing, i);
  }
  const std::string dat = test::read_text(folder.file("trough.dat"));
  const std::vector<Vec3> floor_forces = total_forces(dat, "FLOOR_N");
  ASSERT_GE(floor_forces.size(), 3U);
  EXPECT_EQ(floor_forces.front().norm(), 0.0);
  const Vec3 floor = floor_forces.back();
  std::printf("floor reaction %g %g %g at the end, pile weight %g\n", floor.x(), floor.y(),
              floor.z(), weight);
  EXPECT_GT(std::abs(floor.z()), 0.3 * weight);
  EXPECT_LT(std::abs(floor.z()), 3.0 * weight);
}

}  // namespace
}  // namespace aggpack
