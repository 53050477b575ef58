// CalculiX deck (--deck calculix): the real ccx runs the exported trough test on a small pile
// resting just above the floor to completion (exit 0, no *ERROR), the particles reach the floor
// (contact elements, floor reaction near the pile's weight), and the baffle moves.

#include <regex>

#include "aggpack/io/export.h"
#include "deck_fixture.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// The last "total force (fx,fy,fz) for set <set>" of a ccx .dat file.
Vec3 last_total_force(const std::string& dat, const std::string& set) {
  const std::regex pattern("total force \\(fx,fy,fz\\) for set " + set +
                           " and time +\\S+\\s+(\\S+) +(\\S+) +(\\S+)");
  Vec3 force(NAN, NAN, NAN);
  for (auto it = std::sregex_iterator(dat.begin(), dat.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    force = Vec3(std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]));
  }
  return force;
}

TEST(CalculixDeck, CcxRunsTheTroughTestOnASmallPile) {
  // Fails (not skips) without ccx: scripts/install-deps.sh installs calculix-ccx.
  ASSERT_TRUE(test::has_program("ccx")) << "ccx (calculix-ccx) is required for this test";
  const Packing packing = test::pile_near_floor(3, 2, 1, 0.0005, 71);
  ScratchFolder folder;
  ExportOptions options;
  options.material.density = 2500.0;
  options.deck = {.kind = DeckKind::kCalculix,
                  .friction = 0.4,
                  .trough_length = packing.container.length + 0.02,
                  .baffle_speed = 1.0,
                  .settle_time = 0.04,
                  .rest_time = 0.02,
                  .max_increment = 0.004};
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
  // Contact happened: ccx reports active contact elements, and at the end the floor carries
  // about the pile's weight (the particles rest on it; they may still rock a little).
  std::smatch match;
  std::size_t most_contacts = 0;
  const std::regex contacts("Number of contact spring elements=(\\d+)");
  for (auto it = std::sregex_iterator(result.output.begin(), result.output.end(), contacts);
       it != std::sregex_iterator(); ++it) {
    most_contacts = std::max<std::size_t>(most_contacts, std::stoul((*it)[1]));
  }
  EXPECT_GT(most_contacts, 0U);
  double weight = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    weight += 2500.0 * 9.81 * test::particle_volume(packing, i);
  }
  const std::string dat = test::read_text(folder.file("trough.dat"));
  const Vec3 floor = last_total_force(dat, "FLOOR_N");
  std::printf("floor reaction %g %g %g, weight %g, most contact elements %zu\n", floor.x(),
              floor.y(), floor.z(), weight, most_contacts);
  EXPECT_GT(std::abs(floor.z()), 0.3 * weight);
  EXPECT_LT(std::abs(floor.z()), 3.0 * weight);
}

}  // namespace
}  // namespace aggpack
