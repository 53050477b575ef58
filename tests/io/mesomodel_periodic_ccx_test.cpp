// The periodic mesomodel's .inp (io/mesomodel_files.h): its *EQUATION ties (every node on an
// upper periodic face dependent exactly once, on its image and the reference nodes), and
// CalculiX's run of its six load cases: the homogenised stiffness of a mortar-only box is the
// mortar's isotropic one, a packed box's lies between the Reuss and Voigt tensors.

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "aggpack/core/error.h"
#include "aggpack/io/homogenize.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "ccx_fixture.h"
#include "support/periodic.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

MesoMesh small_periodic_mesh(double fraction) {
  return build_mesomodel(test::small_periodic_packing(fraction), {.mortar_size = 0.004});
}

// CalculiX's stiffness of the mesh's six load cases (the .inp in mm), after a clean run.
VoigtStiffness ccx_stiffness(const MesoMesh& mesh, const MesoMaterials& materials) {
  MesoFileOptions options;
  options.materials = materials;
  options.units = MesoUnits::kMillimetre;
  const Homogenized h = homogenize_with_calculix(mesh, options, {.threads = 1, .progress = {}});
  EXPECT_TRUE(h.warnings.empty()) << h.warnings.front();
  return h.stiffness;
}

TEST(PeriodicInp, EveryUpperFaceNodeIsTiedOnceToItsImage) {
  const ScratchFolder folder;
  const MesoMesh mesh = small_periodic_mesh(0.2);
  write_mesomodel(folder.file("rve.inp"), mesh, {});
  std::istringstream in(test::read_text(folder.file("rve.inp")));
  std::string line;
  bool is_equation = false;
  std::size_t terms_left = 0;
  std::vector<std::vector<std::uint64_t>> equations;
  std::vector<std::string> steps;
  while (std::getline(in, line)) {
    if (line.rfind('*', 0) == 0 && line.rfind("**", 0) != 0) {
      is_equation = line == "*EQUATION";
      if (line == "*STEP") steps.push_back(line);
      continue;
    }
    if (!is_equation) continue;
    const auto fields = test::split(line, ',');
    if (terms_left == 0) {
      terms_left = std::stoull(fields[0]);
      equations.emplace_back();
      continue;
    }
    for (std::size_t f = 0; f + 2 < fields.size(); f += 3) {
      equations.back().push_back(std::stoull(fields[f]));
      --terms_left;
    }
  }
  const std::vector<PeriodicPair> pairs = periodic_pairs(mesh);
  ASSERT_EQ(equations.size(), 3 * pairs.size());
  std::map<std::uint64_t, int> dependent;
  std::set<std::uint64_t> independent;
  const auto references = mesh.nodes.size() + 1;  // REF_X, REF_Y, REF_Z follow the mesh's nodes
  std::size_t corners = 0;
  for (const auto& terms : equations) {
    ASSERT_GE(terms.size(), 3U);
    ++dependent[terms[0]];
    for (std::size_t t = 1; t < terms.size(); ++t) {
      if (terms[t] < references) independent.insert(terms[t]);
    }
    corners += terms.size() == 5;
    const Vec3& p = mesh.nodes[terms[0] - 1];
    const Vec3& q = mesh.nodes[terms[1] - 1];
    int moved = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (p[axis] != q[axis]) {
        ++moved;
        EXPECT_EQ(p[axis], mesh.bounds.upper[axis]);
        EXPECT_EQ(q[axis], mesh.bounds.lower[axis]);
      }
    }
    EXPECT_EQ(moved + 2, static_cast<int>(terms.size())) << "one reference node per face crossed";
  }
  EXPECT_EQ(corners, 3U) << "the corner opposite the origin, three dofs";
  std::size_t upper = 0;
  for (const Vec3& p : mesh.nodes) {
    upper += (p.array() == mesh.bounds.upper.array()).any();
  }
  EXPECT_EQ(dependent.size(), upper);
  for (const auto& [node, count] : dependent) {
    EXPECT_EQ(count, 3) << "node " << node;
    EXPECT_EQ(independent.count(node), 0U) << "node " << node << " dependent and independent";
  }
  EXPECT_EQ(steps.size(), 6U);
}

TEST(PeriodicInp, StiffnessFromADatText) {
  // A 2 x 4 x 5 mm box in mm: step k's totals on XMAX, YMAX, ZMAX (areas 20, 10, 8 mm^2).
  MesoMesh mesh;
  mesh.container.shape = BoxContainer{.length = 0.002, .width = 0.004, .depth = 0.005};
  mesh.bounds = mesh.container.bounds();
  mesh.periodic = {true, true, true};
  std::string dat;
  for (int k = 0; k < 6; ++k) {
    const double time = k + 1.0;
    char text[512];
    // sigma_11 = 100 (k + 1) MPa from XMAX's fx; shear sigma_12 from XMAX's fy (20 MPa) and YMAX's
    // fx (22 MPa): their mean, 21 MPa.
    std::snprintf(text, sizeof text,
                  " total force (fx,fy,fz) for set XMAX and time  %.7E\n\n        %.6E  %.6E  "
                  "0.000000E+00\n\n total force (fx,fy,fz) for set YMAX and time  %.7E\n\n"
                  "        %.6E  0.000000E+00  0.000000E+00\n\n total force (fx,fy,fz) for set "
                  "ZMAX and time  %.7E\n\n        0.000000E+00  0.000000E+00  0.000000E+00\n\n",
                  time, 2000.0 * (k + 1), 400.0, time, 220.0, time);
    dat += text;
  }
  MesoFileOptions options;
  options.units = MesoUnits::kMillimetre;
  options.step.strain = 0.002;
  const VoigtStiffness c = periodic_stiffness_from_dat(dat, mesh, options);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(c[0][k], 100e6 * (k + 1) / 0.002, 1e3) << k;
    EXPECT_NEAR(c[5][k], 21e6 / 0.002, 1e3) << k;
    EXPECT_NEAR(c[1][k], 0.0, 1e-6) << k;
  }
  EXPECT_THROW((void)periodic_stiffness_from_dat(dat.substr(0, dat.size() / 2), mesh, options),
               InvalidInput);
}

TEST(PeriodicCcx, MortarEverywhereGivesTheMortarsIsotropicStiffness) {
  AGGPACK_REQUIRE_READER("ccx");
  MesoMaterials materials;
  materials.aggregate = materials.mortar;
  const VoigtStiffness c = ccx_stiffness(small_periodic_mesh(0.2), materials);
  const VoigtStiffness expected = isotropic_stiffness(25e9, 0.2);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(c[i][j], expected[i][j], 1e-5 * expected[0][0]) << i << ", " << j;
    }
  }
}

TEST(PeriodicCcx, PackedBoxLiesBetweenTheReussAndVoigtTensors) {
  AGGPACK_REQUIRE_READER("ccx");
  const MesoMesh mesh = small_periodic_mesh(0.3);
  const MesoMaterials materials;
  const VoigtStiffness c = ccx_stiffness(mesh, materials);
  // With one Poisson ratio the Voigt and Reuss tensors are isotropic with E_Voigt and E_Reuss.
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, materials);
  const VoigtStiffness voigt = isotropic_stiffness(bounds.voigt, 0.2);
  const VoigtStiffness reuss = isotropic_stiffness(bounds.reuss, 0.2);
  for (int i = 0; i < 6; ++i) {
    EXPECT_GT(c[i][i], reuss[i][i]) << i;
    EXPECT_LT(c[i][i], voigt[i][i]) << i;
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(c[i][j], c[j][i], 1e-4 * c[0][0]) << i << ", " << j;
    }
  }
  EXPECT_GT(c[0][1], 0.0);
}

}  // namespace
}  // namespace aggpack
