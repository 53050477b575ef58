// CalculiX at full scale: the paper's default packing (`aggpack pack`, 1,050 particles) exported
// by `aggpack export` as .inp runs a static gravity step in ccx with every particle held at its
// base: exit 0, no *ERROR and no *WARNING, every node's displacement listed, and the total mass
// ccx computes equals density x the sum of the particle volumes. Before numbers were bounded to
// 20 characters, this packing's file held 24 longer coordinates and ccx stopped on it.

#include <numeric>

#include "aggpack/io/native.h"
#include "ccx_fixture.h"
#include "export_fixture.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

constexpr std::size_t kPaperParticles = 1050;
constexpr double kDensity = 2700.0;  // the export's default (kg/m^3)

class PaperPackingInCalculix : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new ScratchFolder;
    const auto pack =
        test::run_command(std::string(AGGPACK_BINARY) + " pack -o " + folder_->file("paper.h5"));
    ASSERT_EQ(pack.exit_code, 0) << pack.output;
    const Packing packing = read_packing(folder_->file("paper.h5"));
    particles_ = packing.particles.size();
    volume_ = 0;
    for (std::size_t i = 0; i < packing.particles.size(); ++i) {
      volume_ += test::particle_volume(packing, i);
    }
  }
  static void TearDownTestSuite() {
    delete folder_;
    folder_ = nullptr;
  }

  // Exports the paper's packing with `flags`, runs ccx and checks the run and the mass.
  static void run(const std::string& flags, const std::string& element_type) {
    ASSERT_TRUE(test::has_program("ccx")) << "calculix-ccx not installed (scripts/install-deps.sh)";
    ASSERT_EQ(particles_, kPaperParticles);
    ScratchFolder folder;
    const auto exported =
        test::run_command(std::string(AGGPACK_BINARY) + " export " + folder_->file("paper.h5") +
                          " --format inp -o " + folder.file("model.inp") + " " + flags);
    ASSERT_EQ(exported.exit_code, 0) << exported.output;
    EXPECT_NE(exported.output.find("tetrahedron quality: min dihedral angle"), std::string::npos)
        << exported.output;
    EXPECT_NE(test::read_text(folder.file("model.inp")).find("TYPE=" + element_type),
              std::string::npos);
    test::CcxGravity result;
    test::run_ccx_gravity(folder, "model.inp", kPaperParticles, &result);
    const double expected = kDensity * volume_;
    // ccx prints the total with 7 significant digits.
    EXPECT_NEAR(result.total_mass, expected, 1e-6 * expected);
  }

  static ScratchFolder* folder_;
  static std::size_t particles_;
  static double volume_;
};

ScratchFolder* PaperPackingInCalculix::folder_ = nullptr;
std::size_t PaperPackingInCalculix::particles_ = 0;
double PaperPackingInCalculix::volume_ = 0;

TEST_F(PaperPackingInCalculix, FanC3D4) { run("", "C3D4"); }

TEST_F(PaperPackingInCalculix, FanC3D10) { run("--quadratic", "C3D10"); }

#ifdef AGGPACK_HAS_TETGEN
// DISABLED until the TetGen isolation (branch `tetgen`) is merged: Debian's TetGen 1.5 aborts the
// whole process on ~0.3 % of generated shapes, some of them in this packing. Enable by removing
// the DISABLED_ prefix.
TEST_F(PaperPackingInCalculix, DISABLED_TetGenC3D4) { run("--tet-method tetgen", "C3D4"); }
#endif

}  // namespace
}  // namespace aggpack
