// The cohesive ITZ in the mesomodel's files (io/mesomodel_files.h, mesh/mesomodel.h
// split_cohesive_interfaces): COH3D6 elements with a traction-separation section in the .inp
// (read by meshio's Abaqus reader), Gmsh prisms in the .msh (read by Gmsh and meshio), VTK wedges
// in the .vtu (read by VTK), each wedge's two triangles at the same points and facing the same way
// in every file. No solver here runs COH3D6 (CalculiX has no cohesive elements; Abaqus is not
// available), so the mechanics of the deck are checked only as text.

#include <gtest/gtest.h>

#include <regex>

#include "aggpack/core/error.h"
#include "aggpack/io/mesomodel_files.h"
#include "export_fixture.h"
#include "mesomodel_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// 4 x 4 x 4 cells of side 0.025 m (384 tetrahedra, 125 nodes): aggregate 1 the cell (1, 1, 1)
// (all six faces on mortar: 12 interface triangles, 8 shared nodes), aggregate 2 the corner cell
// (3, 3, 3) (three faces on mortar, three on walls: 6 triangles, 7 shared nodes), the rest
// mortar; split for a cohesive ITZ 5e-5 m thick.
MesoMesh bonded_specimen(int second_cell = 3) {
  return test::cube_mesomodel(4, 0.1, 2, [second_cell](int i, int j, int k) {
    if (i == 1 && j == 1 && k == 1) return std::pair(MesoPhase::kAggregate, 1U);
    if (i == second_cell && j == second_cell && k == second_cell) {
      return std::pair(MesoPhase::kAggregate, 2U);
    }
    return std::pair(MesoPhase::kMortar, 0U);
  });
}

MesoMesh cohesive_specimen() {
  MesoMesh mesh = bonded_specimen();
  split_cohesive_interfaces(mesh, 5e-5);
  return mesh;
}

TEST(MesomodelCohesiveFiles, SplitMeshHasOneWedgePerInterfaceTriangle) {
  const MesoMesh mesh = cohesive_specimen();
  EXPECT_EQ(mesh.nodes.size(), 125U + 8U + 7U);
  ASSERT_EQ(mesh.cohesive.size(), 18U);
  EXPECT_EQ(std::count(mesh.cohesive_particle.begin(), mesh.cohesive_particle.end(), 1U), 12);
  EXPECT_EQ(mesh.cohesive_particle.front(), 1U);  // particle by particle
  EXPECT_EQ(mesh.itz_thickness, 5e-5);
  const MesoReport report = measure_mesomodel(mesh);
  EXPECT_EQ(report.cohesive_elements, 18U);
  EXPECT_NEAR(report.interface_area, 9 * 0.025 * 0.025, 1e-15);
  EXPECT_EQ(report.phases[1].nodes, 2U * 15U);  // both sides of every shared node
  // Aggregates that touch (cells (1,1,1) and (2,2,2) share a corner) cannot be split.
  MesoMesh touching = bonded_specimen(2);
  try {
    split_cohesive_interfaces(touching, 5e-5);
    FAIL() << "touching aggregates split";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("aggregates 1 and 2 share node"), std::string::npos)
        << error.what();
  }
  MesoMesh bonded = bonded_specimen();
  EXPECT_THROW(split_cohesive_interfaces(bonded, 0.0), InvalidInput);
}

constexpr const char* kMeshioInpScript = R"(
import sys, collections, meshio
from meshio.abaqus import _abaqus
# meshio's Abaqus reader knows the solid wedge C3D6, not the cohesive COH3D6 of the same topology.
_abaqus.abaqus_to_meshio_type["COH3D6"] = "wedge"
mesh = meshio.read(sys.argv[1], file_format="abaqus")
print(len(mesh.points), *["%s:%d" % (b.type, len(b.data)) for b in mesh.cells])
sizes = {name: sum(len(ids) for ids in blocks) for name, blocks in mesh.cell_sets.items()}
print(*["%s=%d" % (name, sizes[name]) for name in sorted(sizes) if sizes[name] > 0])
pts = mesh.points
for block in mesh.cells:
    if block.type == "wedge":
        gap = max(abs(pts[c[k]] - pts[c[k + 3]]).max() for c in block.data for k in range(3))
        print("wedge sides apart by", gap)
)";

TEST(MesomodelCohesiveFiles, InpHasCohesiveElementsSectionAndTractionStiffness) {
  AGGPACK_REQUIRE_READER("meshio");
  ScratchFolder folder;
  const MesoMesh mesh = cohesive_specimen();
  const std::string path = folder.file("s.inp");
  MesoFileOptions options;
  options.units = MesoUnits::kMillimetre;
  options.step.strain = 1e-3;
  const MesoFileSummary summary = write_mesomodel(path, mesh, options);
  EXPECT_EQ(summary.elements, 402U);
  EXPECT_EQ(summary.nodes, 140U);
  const std::string text = test::read_text(path);
  // Elements: aggregates 1-12, the wedges 13-30 (ITZ1 then ITZ2), the mortar 31-402.
  EXPECT_NE(text.find("*ELEMENT, TYPE=COH3D6, ELSET=ITZ1\n13, "), std::string::npos);
  EXPECT_NE(text.find("*ELEMENT, TYPE=COH3D6, ELSET=ITZ2\n25, "), std::string::npos);
  EXPECT_NE(text.find("*ELSET, ELSET=ITZ, GENERATE\n13, 30, 1\n"), std::string::npos);
  // mm, N, MPa: K_nn = E = 15,000 MPa, K_ss = K_tt = G = E / 2.4 = 6,250 MPa over the
  // constitutive thickness 0.05 mm; density 2000 kg/m^3 = 2e-9 t/mm^3.
  EXPECT_NE(text.find("*MATERIAL, NAME=MAT_ITZ\n*ELASTIC, TYPE=TRACTION\n15000, 6250, 6250\n"
                      "*DENSITY\n2e-09,\n*COHESIVE SECTION, ELSET=ITZ, MATERIAL=MAT_ITZ, "
                      "RESPONSE=TRACTION SEPARATION, THICKNESS=SPECIFIED\n0.05,\n"),
            std::string::npos)
      << text.substr(text.find("*MATERIAL"));
  EXPECT_EQ(text.find("*SOLID SECTION, ELSET=ITZ"), std::string::npos);
  EXPECT_NE(text.find("*SOLID SECTION, ELSET=MORTAR, MATERIAL=MAT_MORTAR"), std::string::npos);
  // An independent reader of the format finds the nodes, both element kinds and the sets.
  const auto read = test::run_python(folder, kMeshioInpScript, path);
  ASSERT_EQ(read.exit_code, 0) << read.output;
  const auto lines = test::split(read.output, '\n');
  ASSERT_GE(lines.size(), 3U) << read.output;
  EXPECT_EQ(test::trim(lines[0]), "140 tetra:6 tetra:6 wedge:12 wedge:6 tetra:372");
  EXPECT_EQ(test::trim(lines[1]), "AGG1=6 AGG2=6 AGGREGATE=12 ITZ=18 ITZ1=12 ITZ2=6 MORTAR=372");
  EXPECT_EQ(test::trim(lines[2]), "wedge sides apart by 0.0");
  // C3D10 has no matching cohesive element: refused before anything is written.
  options.is_quadratic = true;
  try {
    write_mesomodel(folder.file("q.inp"), mesh, options);
    FAIL() << "C3D10 with COH3D6 accepted";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("quadratic"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder.file("q.inp")));
}

constexpr const char* kMeshioMshScript = R"(
import sys, collections, meshio
mesh = meshio.read(sys.argv[1], file_format="gmsh")
per_entity = collections.Counter()
for block, entity in zip(mesh.cells, mesh.cell_data["gmsh:geometrical"]):
    for e in entity:
        per_entity["%d:%s" % (int(e), block.type)] += 1
print(len(mesh.points), *sorted(per_entity.items()))
)";

TEST(MesomodelCohesiveFiles, GmshAndMeshioReadTheWedgesAsPrisms) {
  AGGPACK_REQUIRE_READER("gmsh");
  AGGPACK_REQUIRE_READER("meshio");
  ScratchFolder folder;
  const std::string path = folder.file("s.msh");
  write_mesomodel(path, cohesive_specimen(), {});
  // Entities: 1, 2 the aggregates; 3, 4 the ITZ of particles 1, 2 (prisms); 5 the mortar.
  const std::string expected =
      "140 ('1:tetra', 6) ('2:tetra', 6) ('3:wedge', 12) ('4:wedge', 6) ('5:tetra', 372)";
  test::expect_same_through_gmsh(folder, kMeshioMshScript, path, expected);
}

// VTK_WEDGE: the first triangle's right-hand normal points away from the second; for a wedge of
// zero thickness that means into the aggregate (towards its cell's centre).
constexpr const char* kCohesiveVtkScript = R"(
import sys
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy
reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(sys.argv[1])
reader.Update()
grid = reader.GetOutput()
particle = vtk_to_numpy(grid.GetCellData().GetArray("particle"))
phase = vtk_to_numpy(grid.GetCellData().GetArray("phase"))
centre = {1: np.full(3, 0.0375), 2: np.full(3, 0.0875)}
wedges = inward = coincident = 0
for i in range(grid.GetNumberOfCells()):
    if grid.GetCellType(i) != 13:
        continue
    wedges += 1
    ids = grid.GetCell(i).GetPointIds()
    p = [np.array(grid.GetPoint(ids.GetId(k))) for k in range(6)]
    coincident += all((p[k] == p[k + 3]).all() for k in range(3))
    normal = np.cross(p[1] - p[0], p[2] - p[0])
    inward += int(phase[i] == 1 and normal.dot(centre[int(particle[i])] - p[0]) > 0)
print(grid.GetNumberOfPoints(), grid.GetNumberOfCells(), wedges, coincident, inward)
)";

TEST(MesomodelCohesiveFiles, VtkReadsWedgesFacingIntoTheirAggregate) {
  AGGPACK_REQUIRE_READER("vtk");
  ScratchFolder folder;
  const std::string path = folder.file("s.vtu");
  write_mesomodel(path, cohesive_specimen(), {});
  const auto result = test::run_python(folder, kCohesiveVtkScript, path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_EQ(test::trim(result.output), "140 402 18 18 18");
}

TEST(MesomodelCohesiveFiles, InconsistentCohesiveMeshIsRefused) {
  ScratchFolder folder;
  MesoMesh mesh = cohesive_specimen();
  mesh.cohesive_particle.pop_back();
  EXPECT_THROW(write_mesomodel(folder.file("a.vtu"), mesh, {}), InvalidInput);
  mesh = cohesive_specimen();
  mesh.cohesive[3][4] = 1000;
  EXPECT_THROW(write_mesomodel(folder.file("a.msh"), mesh, {}), InvalidInput);
  mesh = cohesive_specimen();
  mesh.phase[0] = MesoPhase::kItz;  // a solid ITZ tetrahedron beside cohesive elements
  EXPECT_THROW(write_mesomodel(folder.file("a.inp"), mesh, {}), InvalidInput);
  EXPECT_TRUE(std::filesystem::is_empty(folder.path()));
}

}  // namespace
}  // namespace aggpack
