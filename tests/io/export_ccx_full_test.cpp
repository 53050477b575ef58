// CalculiX at full scale: the paper's default packing (`aggpack pack`, 1,050 particles) exported
// by `aggpack export` as .inp runs a static gravity step in ccx with every particle held at its
// base: exit 0, no *ERROR and no *WARNING, every node's displacement listed, and the total mass
// ccx computes equals density x the sum of the particle volumes. Before numbers were bounded to
// 20 characters, this packing's file held 24 longer coordinates and ccx stopped on it.

#include <map>
#include <utility>

#include "aggpack/io/native.h"
#include "ccx_fixture.h"
#include "export_fixture.h"
#include "support/paths.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

constexpr std::size_t kPaperParticles = 1050;
constexpr double kDensity = 2700.0;  // the export's default (kg/m^3)

class PaperPackingInCalculix : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { folder_ = new ScratchFolder; }
  static void TearDownTestSuite() {
    delete folder_;
    folder_ = nullptr;
  }

  // Packs the paper's default configuration with `pack_flags` (once per flags) and exports it
  // with `export_flags`, runs ccx and checks the run and the mass.
  static void run(const std::string& pack_flags, const std::string& export_flags,
                  const std::string& element_type) {
    AGGPACK_REQUIRE_READER("ccx");
    const std::string h5 = folder_->file("paper" + std::to_string(volumes_.size()) + ".h5");
    if (volumes_.count(pack_flags) == 0) {
      const auto pack =
          test::run_command(test::aggpack_binary() + " pack -o " + h5 + " " + pack_flags);
      ASSERT_EQ(pack.exit_code, 0) << pack.output;
      const Packing packing = read_packing(h5);
      ASSERT_EQ(packing.particles.size(), kPaperParticles);
      double volume = 0;
      for (std::size_t i = 0; i < packing.particles.size(); ++i) {
        volume += test::particle_volume(packing, i);
      }
      volumes_[pack_flags] = {h5, volume};
    }
    const auto& [packed, volume] = volumes_.at(pack_flags);
    ScratchFolder folder;
    const auto exported =
        test::run_command(test::aggpack_binary() + " export " + packed + " --format inp -o " +
                          folder.file("model.inp") + " " + export_flags);
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    EXPECT_NE(exported.output.find("tetrahedron quality: min dihedral angle"), std::string::npos)
        << exported.output;
    EXPECT_NE(test::read_text(folder.file("model.inp")).find("TYPE=" + element_type),
              std::string::npos);
    test::CcxGravity result;
    test::run_ccx_gravity(folder, "model.inp", kPaperParticles, &result);
    const double expected = kDensity * volume;
    // ccx prints the total with 7 significant digits.
    EXPECT_NEAR(result.total_mass, expected, 1e-6 * expected);
  }

  static ScratchFolder* folder_;
  static std::map<std::string, std::pair<std::string, double>> volumes_;  // flags -> h5, m^3
};

ScratchFolder* PaperPackingInCalculix::folder_ = nullptr;
std::map<std::string, std::pair<std::string, double>> PaperPackingInCalculix::volumes_;

TEST_F(PaperPackingInCalculix, FanC3D4) { run("", "", "C3D4"); }

TEST_F(PaperPackingInCalculix, FanC3D10) { run("", "--quadratic", "C3D10"); }

#ifdef AGGPACK_HAS_TETGEN
// The paper's configuration with seed 4, on whose 1,050 shapes Debian's TetGen 1.5 does not
// abort (it does on the default seed's, see below).
TEST_F(PaperPackingInCalculix, TetGenC3D4Seed4) { run("--seed 4", "--tet-method tetgen", "C3D4"); }

TEST_F(PaperPackingInCalculix, TetGenC3D10Seed4) {
  run("--seed 4", "--tet-method tetgen --quadratic", "C3D10");
}

// The default seed: Debian's TetGen 1.5 aborts on 4 of its shapes (in a worker process); those
// particles are cut as centroid fans, and ccx runs the mixed model as well.
TEST_F(PaperPackingInCalculix, TetGenC3D4) { run("", "--tet-method tetgen", "C3D4"); }
#endif

}  // namespace
}  // namespace aggpack
