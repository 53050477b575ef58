// CalculiX runs the mesomodel's uniaxial compression step (io/mesomodel_files.h) on synthetic
// specimens whose effective Young's modulus is known: laminates and a random mix of the phases.
//
// Why the tolerances hold (all phases share one Poisson ratio nu):
//  - Layers parallel to the load (Voigt): every layer in uniaxial stress at the same strain has the
//    same lateral strain -nu e, so the homogeneous strain field is the exact solution; linear
//    tetrahedra represent it exactly, and E = sum f_i E_i to the 7 digits ccx prints.
//  - Layers across the load (Reuss): the uniform uniaxial stress is statically admissible, so
//    E >= 1 / sum f_i / E_i (complementary energy). The layers' lateral strains differ and their
//    bond stiffens the stack, at most as much as in infinitely wide bonded layers, whose field
//    (uniform lateral strain -nu sigma / E_V, piecewise uniform in z) is kinematically admissible
//    here and exactly representable on this mesh (its interfaces are mesh planes): so the finite
//    element answer lies in [E_R, E_bonded], 1 / E_bonded = (1 - c) / E_R + c / E_V with
//    c = 2 nu^2 / (1 - nu) (0.1 for nu = 0.2; 2.9 % above E_R here).
//  - Any mix lies between the Reuss and Voigt moduli (the mesh's Voigt/Reuss stiffness tensors are
//    isotropic with these moduli and nu); a random mix lies strictly inside.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "aggpack/io/mesomodel_files.h"
#include "aggpack/shape/generator.h"
#include "ccx_fixture.h"
#include "mesomodel_fixture.h"
#include "support/packings.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

constexpr double kSize = 0.1;      // m
constexpr double kStrain = 1e-3;   // nominal compressive strain of the step
constexpr double kPrinted = 1e-5;  // relative: ccx prints forces with 7 significant digits

// Runs `name`.inp through ccx and returns E = (sum of RF_z over TOP / area) / strain, in the
// file's units (Pa, or MPa with MesoUnits::kMillimetre).
double effective_modulus(const ScratchFolder& folder, const MesoMesh& mesh, const std::string& name,
                         MesoFileOptions options = {}) {
  options.step.strain = kStrain;
  write_mesomodel(folder.file(name + ".inp"), mesh, options);
  const auto run =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i " + name);
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("Job finished"), std::string::npos) << run.output;
  EXPECT_EQ(test::upper(run.output).find("*ERROR"), std::string::npos) << run.output;
  EXPECT_EQ(test::upper(run.output).find("*WARNING"), std::string::npos) << run.output;
  std::istringstream dat(test::read_text(folder.file(name + ".dat")));
  std::string line;
  bool is_total = false;
  while (std::getline(dat, line)) {
    if (line.find("total force (fx,fy,fz) for set TOP") != std::string::npos) {
      is_total = true;
      continue;
    }
    double fx = 0;
    double fy = 0;
    double fz = 0;
    if (is_total && (std::istringstream(line) >> fx >> fy >> fz)) {
      const Vec3 extent = mesh.bounds.extent() * length_scale(options.units);
      EXPECT_LT(std::abs(fx), 1e-6 * std::abs(fz)) << line;  // no net shear on the top
      EXPECT_LT(std::abs(fy), 1e-6 * std::abs(fz)) << line;
      return -fz / (extent.x() * extent.y()) / kStrain;
    }
  }
  ADD_FAILURE() << "no total force for set TOP in " << name << ".dat";
  return 0.0;
}

// Four layers of cells along `axis`: aggregate (particle 1), ITZ (particle 1), mortar, aggregate
// (particle 2): fractions 1/2, 1/4, 1/4.
MesoMesh laminate(int axis, double size = kSize) {
  return test::cube_mesomodel(4, size, 2, [axis](int i, int j, int k) {
    const int layer = axis == 0 ? i : (axis == 1 ? j : k);
    switch (layer) {
      case 0:
        return std::pair(MesoPhase::kAggregate, 1U);
      case 1:
        return std::pair(MesoPhase::kItz, 1U);
      case 2:
        return std::pair(MesoPhase::kMortar, 0U);
      default:
        return std::pair(MesoPhase::kAggregate, 2U);
    }
  });
}

TEST(MesomodelCcx, LayersAlongTheLoadGiveTheVoigtModulus) {
  AGGPACK_REQUIRE_READER("ccx");
  ScratchFolder folder;
  const MesoMesh mesh = laminate(0);
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, {});
  EXPECT_NEAR(bounds.fractions[2], 0.5, 1e-12);
  EXPECT_NEAR(bounds.voigt, 0.5 * 60e9 + 0.25 * 15e9 + 0.25 * 25e9, 1e-3);
  const double modulus = effective_modulus(folder, mesh, "voigt");
  EXPECT_NEAR(modulus / bounds.voigt, 1.0, kPrinted) << modulus;
  // C3D10: the mid-side nodes of TOP and BOTTOM must be in their sets, or the answer is off.
  MesoFileOptions quadratic_options;
  quadratic_options.is_quadratic = true;
  const double quadratic = effective_modulus(folder, mesh, "voigt10", quadratic_options);
  EXPECT_NEAR(quadratic / bounds.voigt, 1.0, kPrinted) << quadratic;
  std::printf("Voigt laminate: E = %.7g Pa (C3D4), %.7g Pa (C3D10), Voigt %.7g\n", modulus,
              quadratic, bounds.voigt);
}

// ccx refuses a tetrahedron whose Jacobian determinant (6 x volume) is below 1e-20 in the file's
// units. A 0.5 um cube of 4^3 cells has 6 V = (0.125 um)^3 = 1.95e-21 m^3: refused in metres,
// fine in millimetres (1.95e-12 mm^3), where the Voigt laminate gives E_Voigt in MPa.
TEST(MesomodelCcx, MillimetresRunWhereMetresHitCcxsJacobianFloor) {
  AGGPACK_REQUIRE_READER("ccx");
  ScratchFolder folder;
  const MesoMesh mesh = laminate(0, 5e-7);
  MesoFileOptions metres;
  metres.step.strain = kStrain;
  write_mesomodel(folder.file("tiny_m.inp"), mesh, metres);
  const auto run =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i tiny_m");
  EXPECT_NE(run.output.find("nonpositive jacobian"), std::string::npos) << run.output;
  MesoFileOptions millimetres;
  millimetres.units = MesoUnits::kMillimetre;
  const double modulus = effective_modulus(folder, mesh, "tiny_mm", millimetres);
  EXPECT_NEAR(modulus / (voigt_reuss_bounds(mesh, {}).voigt * 1e-6), 1.0, kPrinted) << modulus;
  const std::string text = test::read_text(folder.file("tiny_mm.inp"));
  EXPECT_NE(text.find("*ELASTIC\n60000, 0.2\n*DENSITY\n2.7e-09,\n"), std::string::npos);
  EXPECT_NE(text.find("Units: mm, N, t, s, MPa"), std::string::npos);
}

TEST(MesomodelCcx, LayersAcrossTheLoadGiveTheReussModulus) {
  AGGPACK_REQUIRE_READER("ccx");
  ScratchFolder folder;
  const MesoMesh mesh = laminate(2);
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, {});
  const double nu = MesoMaterials{}.mortar.poisson_ratio;
  const double c = 2 * nu * nu / (1 - nu);
  const double bonded = 1.0 / ((1 - c) / bounds.reuss + c / bounds.voigt);
  const double modulus = effective_modulus(folder, mesh, "reuss");
  EXPECT_GE(modulus, bounds.reuss * (1 - kPrinted)) << modulus;
  EXPECT_LE(modulus, bonded * (1 + kPrinted)) << modulus << " bonded " << bonded;
  EXPECT_LT(bonded / bounds.reuss, 1.03);  // so the checks above pin E to within 3 % of Reuss
  std::printf("Reuss laminate: E = %.6g Pa, Reuss %.6g, bonded layers %.6g\n", modulus,
              bounds.reuss, bonded);
}

TEST(MesomodelCcx, RandomMixLiesStrictlyBetweenReussAndVoigt) {
  AGGPACK_REQUIRE_READER("ccx");
  ScratchFolder folder;
  std::mt19937 random(16);  // fixed: the same specimen on every run
  const MesoMesh mesh = test::cube_mesomodel(5, kSize, 3, [&](int, int, int) {
    switch (random() % 3) {
      case 0:
        return std::pair(MesoPhase::kMortar, 0U);
      case 1:
        return std::pair(MesoPhase::kItz, static_cast<std::uint32_t>(1 + random() % 3));
      default:
        return std::pair(MesoPhase::kAggregate, static_cast<std::uint32_t>(1 + random() % 3));
    }
  });
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, {});
  for (const double fraction : bounds.fractions) EXPECT_GT(fraction, 0.2);
  const double modulus = effective_modulus(folder, mesh, "random");
  // Strictly inside, by more than ccx's printing and the solver's rounding.
  EXPECT_GT(modulus, bounds.reuss * 1.01) << modulus << " reuss " << bounds.reuss;
  EXPECT_LT(modulus, bounds.voigt * 0.99) << modulus << " voigt " << bounds.voigt;
  std::printf("random mix: E = %.6g Pa, Reuss %.6g, Voigt %.6g\n", modulus, bounds.reuss,
              bounds.voigt);
}

// Issue 16, item 4: a packed specimen meshed by build_mesomodel - 20 generated aggregates with a
// 0.3 mm ITZ in a 40 mm cube - runs through the compression step; its modulus lies strictly
// between the Reuss and Voigt moduli of its phases.
TEST(MesomodelCcx, PackedSpecimenLiesBetweenReussAndVoigt) {
  AGGPACK_REQUIRE_READER("ccx");
  const double side = 0.04;
  const GeneratorOptions generator{
      .alpha = 0.5, .radius_min = 0.005, .radius_max = 0.005, .edge_length = 0.005, .seed = 16};
  std::vector<ConvexPolyhedron> shapes;
  std::vector<Vec3> at;
  const double pitch = side / 3;
  for (int i = 0; i < 20; ++i) {
    shapes.push_back(generate_particle(generator, static_cast<std::uint64_t>(i)).body);
    at.emplace_back((i % 3 + 0.5) * pitch, (i / 3 % 3 + 0.5) * pitch, (i / 9 + 0.5) * pitch);
  }
  MesoOptions meso;
  meso.itz_thickness = 3e-4;
  const MesoMesh mesh = build_mesomodel(test::box_with(side, shapes, at), meso);
  ASSERT_EQ(mesh.particle_count, 20U);
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, {});
  for (const double fraction : bounds.fractions) EXPECT_GT(fraction, 0.0);
  ScratchFolder folder;
  const double modulus = effective_modulus(folder, mesh, "packed");
  EXPECT_GT(modulus, bounds.reuss * 1.01) << modulus << " reuss " << bounds.reuss;
  EXPECT_LT(modulus, bounds.voigt * 0.99) << modulus << " voigt " << bounds.voigt;
  std::printf(
      "packed: %zu tetrahedra, fractions %.4f %.4f %.4f, E = %.6g Pa, Reuss %.6g, "
      "Voigt %.6g\n",
      mesh.tetrahedra.size(), bounds.fractions[0], bounds.fractions[1], bounds.fractions[2],
      modulus, bounds.reuss, bounds.voigt);
}

}  // namespace
}  // namespace aggpack
