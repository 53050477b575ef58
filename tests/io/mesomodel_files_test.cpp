// The mesomodel's files (io/mesomodel_files.h) read by their consumers - Gmsh and meshio (.msh),
// VTK (.vtu) - and parsed here (.inp: sets, materials, numbers within 20 characters); bad input
// refused with one-line errors and nothing left behind.

#include "aggpack/io/mesomodel_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "ccx_fixture.h"
#include "mesomodel_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// 3 x 3 x 3 cells: column (i, j) = (0, 0) and (2, 2) hold aggregates 1 and 2 with an ITZ cell on
// top of each (except at the top), the rest is mortar; particle 3 has no elements. The size makes
// coordinates such as 7e-5 / 3 whose shortest form is longer than 20 characters.
MesoMesh specimen(double size = 7e-5) {
  return test::cube_mesomodel(3, size, 3, [](int i, int j, int k) {
    const std::uint32_t particle = i == 0 && j == 0 ? 1 : (i == 2 && j == 2 ? 2 : 0);
    if (particle == 0) return std::pair(MesoPhase::kMortar, 0U);
    if (k == 0) return std::pair(MesoPhase::kAggregate, particle);
    if (k == 1) return std::pair(MesoPhase::kItz, particle);
    return std::pair(MesoPhase::kMortar, 0U);
  });
}

// "phase:particle" of every tetrahedron in file order (aggregates, ITZ shells, mortar).
std::vector<std::string> expected_order(const MesoMesh& mesh) {
  std::vector<std::string> order;
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    for (std::uint32_t p = 0; p <= mesh.particle_count; ++p) {
      for (std::size_t i = 0; i < mesh.tetrahedra.size(); ++i) {
        if (mesh.phase[i] == phase && mesh.particle[i] == p) {
          order.push_back(std::to_string(static_cast<int>(phase)) + ":" + std::to_string(p));
        }
      }
    }
  }
  return order;
}

TEST(MesomodelFiles, InpHasSetsMaterialsAndShortNumbers) {
  ScratchFolder folder;
  const MesoMesh mesh = specimen();
  const std::string path = folder.file("s.inp");
  MesoFileOptions options;
  options.step.strain = 2e-3;
  const MesoFileSummary summary = write_mesomodel(path, mesh, options);
  EXPECT_EQ(summary.format, ExportFormat::kAbaqus);
  EXPECT_EQ(summary.nodes, 64U);
  EXPECT_EQ(summary.elements, 162U);
  const std::string text = test::read_text(path);
  // Element sets: per block of *ELEMENT and GENERATE ranges; node sets listed.
  std::map<std::string, std::vector<std::uint64_t>> element_sets;
  std::map<std::string, std::vector<std::uint64_t>> node_sets;
  std::istringstream in(text);
  std::string line;
  std::string block;
  std::string name;
  bool is_generate = false;
  std::size_t nodes = 0;
  std::size_t longest = 0;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind('*', 0) == 0) {
      block = test::trim(test::split(line, ',')[0]);
      std::smatch found;
      name.clear();
      if (std::regex_search(line, found, std::regex("(?:ELSET|NSET)=([A-Z0-9_]+)")))
        name = found[1];
      is_generate = line.find("GENERATE") != std::string::npos;
      continue;
    }
    if (block == "*HEADING") continue;  // the title line: text, not numbers
    const auto fields = test::split(line, ',');
    for (const auto& field : fields) longest = std::max(longest, test::trim(field).size());
    if (block == "*NODE") {
      ++nodes;
      for (int axis = 0; axis < 3; ++axis) {
        const double value = std::stod(fields[1 + axis]);
        EXPECT_NEAR(value, mesh.nodes[nodes - 1][axis], 1e-14 * 7e-5) << line;
      }
    } else if (block == "*ELEMENT") {
      element_sets[name].push_back(std::stoull(fields[0]));
    } else if (block == "*ELSET" && is_generate) {
      for (auto id = std::stoull(fields[0]); id <= std::stoull(fields[1]); ++id) {
        element_sets[name].push_back(id);
      }
    } else if (block == "*NSET") {
      for (const auto& field : fields) {
        if (!test::trim(field).empty()) node_sets[name].push_back(std::stoull(field));
      }
    }
  }
  EXPECT_EQ(nodes, 64U);
  EXPECT_LE(longest, 20U);  // CalculiX reads at most 20 characters a number
  // The test means something: 7e-5 / 3 needs 22 characters in its shortest exact form.
  char shortest[32];
  EXPECT_GT(std::to_chars(shortest, shortest + 32, mesh.nodes[1].x()).ptr - shortest, 20);
  // Sets: 6 tetrahedra per cell; aggregates 1 and 2 one cell each, ITZ one cell each.
  EXPECT_EQ(element_sets["AGG1"], (std::vector<std::uint64_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(element_sets["AGG2"], (std::vector<std::uint64_t>{7, 8, 9, 10, 11, 12}));
  EXPECT_EQ(element_sets["AGGREGATE"].size(), 12U);
  EXPECT_EQ(element_sets["ITZ1"].front(), 13U);
  EXPECT_EQ(element_sets["ITZ"].size(), 12U);
  EXPECT_EQ(element_sets["MORTAR"].size(), 162U - 24U);
  EXPECT_EQ(element_sets["MORTAR"].front(), 25U);
  EXPECT_EQ(element_sets.count("AGG3"), 0U);    // particle 3 has no elements
  EXPECT_EQ(node_sets["ALLNODES"].size(), 0U);  // ALLNODES is the *NODE block's own set
  EXPECT_EQ(node_sets["BOTTOM"].size(), 16U);
  EXPECT_EQ(node_sets["TOP"].size(), 16U);
  EXPECT_EQ(node_sets["SIDES"].size(), 64U - 16U);  // all but the 2 x 2 inner columns of 4
  for (const char* material : {"MAT_AGGREGATE", "MAT_ITZ", "MAT_MORTAR"}) {
    EXPECT_NE(text.find(std::string("*MATERIAL, NAME=") + material), std::string::npos);
  }
  EXPECT_NE(text.find("*MATERIAL, NAME=MAT_AGGREGATE\n*ELASTIC\n6e+10, 0.2\n*DENSITY\n2700,\n"),
            std::string::npos);
  EXPECT_NE(text.find("*SOLID SECTION, ELSET=ITZ, MATERIAL=MAT_ITZ\n"), std::string::npos);
  std::smatch top;  // the top moves by -strain x height
  ASSERT_TRUE(std::regex_search(text, top, std::regex("\nTOP, 3, 3, (\\S+)\n")));
  EXPECT_NEAR(std::stod(top[1]), -2e-3 * 7e-5, 1e-22);
  EXPECT_NE(text.find("*NODE PRINT, NSET=TOP, TOTALS=YES\nRF\n"), std::string::npos);
}

TEST(MesomodelFiles, InpWithoutParticleSetsOrStep) {
  ScratchFolder folder;
  const std::string path = folder.file("plain.inp");
  MesoFileOptions options;
  options.has_particle_sets = false;
  write_mesomodel(path, specimen(), options);
  const std::string text = test::read_text(path);
  EXPECT_EQ(text.find("AGG1"), std::string::npos);
  EXPECT_EQ(text.find("*STEP"), std::string::npos);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D4, ELSET=AGGREGATE\n"), std::string::npos);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D4, ELSET=ITZ\n"), std::string::npos);
  // A mesh without ITZ has no ITZ set, material or section.
  MesoMesh no_itz = specimen();
  for (auto& phase : no_itz.phase) {
    if (phase == MesoPhase::kItz) phase = MesoPhase::kAggregate;
  }
  options = {};
  options.step.strain = 1e-3;
  write_mesomodel(folder.file("no_itz.inp"), no_itz, options);
  const std::string without = test::read_text(folder.file("no_itz.inp"));
  EXPECT_EQ(without.find("ELSET=ITZ"), std::string::npos);
  EXPECT_EQ(without.find("NAME=MAT_ITZ"), std::string::npos);
}

TEST(MesomodelFiles, QuadraticInpFaceSetsHoldExactlyTheNodesOnEachFace) {
  ScratchFolder folder;
  const std::string path = folder.file("q.inp");
  MesoFileOptions options;
  options.is_quadratic = true;
  options.step.strain = 1e-3;
  const MesoFileSummary summary = write_mesomodel(path, specimen(0.3), options);
  EXPECT_GT(summary.nodes, 64U);  // the corners and a node on every edge
  const std::string text = test::read_text(path);
  EXPECT_NE(text.find("*ELEMENT, TYPE=C3D10, ELSET=AGG1\n"), std::string::npos);
  std::map<std::uint64_t, Vec3> nodes;
  std::map<std::string, std::set<std::uint64_t>> sets;
  std::istringstream in(text);
  std::string line;
  std::string block;
  std::string name;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind('*', 0) == 0) {
      block = test::trim(test::split(line, ',')[0]);
      std::smatch found;
      name = std::regex_search(line, found, std::regex("NSET=([A-Z]+)")) ? found[1].str() : "";
      continue;
    }
    const auto fields = test::split(line, ',');
    if (block == "*NODE") {
      nodes[std::stoull(fields[0])] =
          Vec3(std::stod(fields[1]), std::stod(fields[2]), std::stod(fields[3]));
    } else if (block == "*NSET") {
      for (const auto& field : fields) {
        if (!test::trim(field).empty()) sets[name].insert(std::stoull(field));
      }
    }
  }
  EXPECT_EQ(nodes.size(), summary.nodes);
  std::map<std::string, std::set<std::uint64_t>> expected;
  for (const auto& [id, p] : nodes) {
    if (std::abs(p.z()) < 1e-12) expected["BOTTOM"].insert(id);
    if (std::abs(p.z() - 0.3) < 1e-12) expected["TOP"].insert(id);
    for (int axis = 0; axis < 2; ++axis) {
      if (std::abs(p[axis]) < 1e-12 || std::abs(p[axis] - 0.3) < 1e-12) {
        expected["SIDES"].insert(id);
      }
    }
  }
  // The step's anchors: A at the bottom's smallest (y, x), B farthest from it in x.
  std::smatch anchors;
  ASSERT_TRUE(
      std::regex_search(text, anchors, std::regex("\n(\\d+), 1, 2, 0\\.\n(\\d+), 2, 2, 0\\.\n")));
  EXPECT_EQ(nodes[std::stoull(anchors[1])], Vec3(0, 0, 0));
  EXPECT_EQ(nodes[std::stoull(anchors[2])], Vec3(0.3, 0, 0));
  for (const char* face : {"BOTTOM", "TOP", "SIDES"}) {
    std::string difference;
    for (const auto id : sets[face]) {
      if (expected[face].count(id) == 0) difference += " +" + std::to_string(id);
    }
    for (const auto id : expected[face]) {
      if (sets[face].count(id) == 0) {
        difference += " -" + std::to_string(id) + "(" + std::to_string(nodes[id].x()) + "," +
                      std::to_string(nodes[id].y()) + "," + std::to_string(nodes[id].z()) + ")";
      }
    }
    EXPECT_EQ(difference, "") << face << " in the set (+) or on the face (-) only";
    EXPECT_GT(sets[face].size(), 16U) << face;  // mid-side nodes included
  }
}

constexpr const char* kMeshioScript = R"(
import sys, meshio, collections
mesh = meshio.read(sys.argv[1], file_format="gmsh")
cells = sum(len(block.data) for block in mesh.cells)
types = sorted(set(block.type for block in mesh.cells))
per_entity = collections.Counter()
phys = {}
for block, physical, entity in zip(mesh.cells, mesh.cell_data["gmsh:physical"],
                                   mesh.cell_data["gmsh:geometrical"]):
    for p, e in zip(physical, entity):
        per_entity[int(e)] += 1
        phys[int(e)] = int(p)
names = sorted((name, int(v[0])) for name, v in mesh.field_data.items())
print(len(mesh.points), cells, *types)
print(*["%d:%d:%d" % (e, phys[e], per_entity[e]) for e in sorted(per_entity)])
print(*["%s=%d" % n for n in names])
)";

TEST(MesomodelFiles, GmshAndMeshioReadTheMshWithPhaseGroups) {
  AGGPACK_REQUIRE_READER("gmsh");
  AGGPACK_REQUIRE_READER("meshio");
  ScratchFolder folder;
  const std::string path = folder.file("s.msh");
  write_mesomodel(path, specimen(0.1), {});
  // Entity = group: 1, 2 aggregates; 4, 5 their ITZ shells (3 + k); 7 the mortar (2 * 3 + 1).
  // Physical = MesoPhase code + 1: 3 aggregate, 2 ITZ, 1 mortar.
  const std::string expected =
      "64 162 tetra\n1:3:6 2:3:6 4:2:6 5:2:6 7:1:138\nAGGREGATE=3 ITZ=2 MORTAR=1";
  test::expect_same_through_gmsh(folder, kMeshioScript, path, expected);
}

constexpr const char* kVtkScript = R"(
import sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter
from vtkmodules.util.numpy_support import vtk_to_numpy
reader = vtkXMLUnstructuredGridReader()
reader.SetFileName(sys.argv[1])
reader.Update()
grid = reader.GetOutput()
data = grid.GetCellData()
phase = vtk_to_numpy(data.GetArray("phase"))
particle = vtk_to_numpy(data.GetArray("particle"))
sizes = vtkCellSizeFilter()
sizes.SetInputData(grid)
sizes.Update()
volume = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
types = set(grid.GetCellType(i) for i in range(grid.GetNumberOfCells()))
print(grid.GetNumberOfPoints(), grid.GetNumberOfCells(), *sorted(types),
      data.GetArray("phase").GetDataTypeAsString(), data.GetArray("particle").GetDataTypeAsString(),
      "%.12g" % volume.sum(), int((volume > 0).all()))
print(*["%d:%d" % (p, q) for p, q in zip(phase, particle)])
)";

TEST(MesomodelFiles, VtkReadsTheVtuWithPhaseAndParticle) {
  AGGPACK_REQUIRE_READER("vtk");
  ScratchFolder folder;
  const MesoMesh mesh = specimen(0.1);
  const std::string path = folder.file("s.vtu");
  const MesoFileSummary summary = write_mesomodel(path, mesh, {});
  EXPECT_EQ(summary.format, ExportFormat::kVtu);
  const auto result = test::run_python(folder, kVtkScript, path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = test::split(result.output, '\n');
  ASSERT_GE(lines.size(), 2U) << result.output;
  EXPECT_EQ(test::trim(lines[0]), "64 162 10 unsigned char unsigned int 0.001 1");
  std::string order;
  for (const auto& cell : expected_order(mesh)) order += (order.empty() ? "" : " ") + cell;
  EXPECT_EQ(test::trim(lines[1]), order);
  // In millimetres: the same cells, the volume 1e9 times larger.
  MesoFileOptions millimetres;
  millimetres.units = MesoUnits::kMillimetre;
  write_mesomodel(folder.file("mm.vtu"), mesh, millimetres);
  const auto scaled = test::run_python(folder, kVtkScript, folder.file("mm.vtu"));
  ASSERT_EQ(scaled.exit_code, 0) << scaled.output;
  EXPECT_EQ(test::trim(test::split(scaled.output, '\n')[0]),
            "64 162 10 unsigned char unsigned int 1000000 1");
}

// ---- bad input -------------------------------------------------------------------------------

template <class Exception>
std::string message_of(const std::function<void()>& run) {
  try {
    run();
  } catch (const Exception& error) {
    return error.what();
  }
  return "(no exception)";
}

TEST(MesomodelFiles, UnknownExtensionIsRefusedNamingTheAllowedOnes) {
  ScratchFolder folder;
  const std::string path = folder.file("s.stl");
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(path, specimen()); }),
            "invalid output = '" + path + "' (allowed: .inp, .msh, .vtu)");
  EXPECT_EQ(mesomodel_format(folder.file("S.INP")), ExportFormat::kAbaqus);
  EXPECT_TRUE(folder.entries().empty());
}

TEST(MesomodelFiles, EveryRowWithAMesomodelWriterWritesItsFormat) {
  ScratchFolder folder;
  std::vector<std::string> names;
  for (const FormatInfo& info : export_formats()) {
    if (info.write_mesomodel == nullptr) continue;
    names.emplace_back(info.name);
    const std::string path = folder.file("s." + std::string(info.name));
    EXPECT_EQ(mesomodel_format(path), info.format);
    const MesoFileSummary summary = write_mesomodel(path, specimen());
    EXPECT_EQ(summary.format, info.format);
    EXPECT_EQ(summary.elements, specimen().tetrahedra.size()) << info.name;
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"inp", "msh", "vtu"}));
}

TEST(MesomodelFiles, BadMaterialsAndOptionsNameTheField) {
  ScratchFolder folder;
  const std::string path = folder.file("s.inp");
  const MesoMesh mesh = specimen();
  auto refused = [&](const MesoFileOptions& options) {
    return message_of<InvalidInput>([&] { write_mesomodel(path, mesh, options); });
  };
  MesoFileOptions options;
  options.materials.itz.youngs_modulus = -1;
  EXPECT_EQ(refused(options), "invalid materials.itz.youngs_modulus = -1 (allowed: (0, 1e13] Pa)");
  options = {};
  options.materials.mortar.poisson_ratio = 0.5;
  EXPECT_EQ(refused(options), "invalid materials.mortar.poisson_ratio = 0.5 (allowed: (-1, 0.5))");
  options = {};
  options.materials.aggregate.density = 0;
  EXPECT_EQ(refused(options), "invalid materials.aggregate.density = 0 (allowed: (0, 1e5] kg/m^3)");
  options = {};
  options.step.strain = 0.2;
  EXPECT_EQ(refused(options), "invalid step.strain = 0.2 (allowed: [0, 0.1]; 0 = no step)");
  options = {};
  options.is_quadratic = true;
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(folder.file("q.vtu"), mesh, options); }),
            "invalid quadratic = true for .vtu (allowed: .inp only (C3D10))");
  EXPECT_TRUE(folder.entries().empty());
}

TEST(MesomodelFiles, InconsistentMeshIsRefused) {
  ScratchFolder folder;
  const std::string path = folder.file("s.msh");
  MesoMesh mesh = specimen();
  mesh.phase.pop_back();
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(path, mesh); }),
            "invalid mesh.phase size = 161 (allowed: 162 (one per tetrahedron))");
  mesh = specimen();
  mesh.particle[0] = 4;  // an aggregate tetrahedron of a particle that does not exist
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(path, mesh); }),
            "invalid mesh.particle[0] = 4 (allowed: 1..3 for an aggregate or ITZ tetrahedron)");
  mesh = specimen();
  mesh.tetrahedra[5][2] = 64;
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(path, mesh); }),
            "invalid mesh.tetrahedra[5] node = 64 (allowed: 0..63 (0-based))");
  mesh = specimen();
  mesh.container = Container{};  // made by hand without its container: the face sets need it
  EXPECT_EQ(message_of<InvalidInput>([&] { write_mesomodel(path, mesh); }),
            "invalid mesh.container = box (allowed: the container whose prism "
            "(mesh.prism_sides) has the mesh's bounds)");
  EXPECT_TRUE(folder.entries().empty());
}

TEST(MesomodelFiles, ExistingAndNonRegularOutputsAreRefused) {
  ScratchFolder folder;
  const MesoMesh mesh = specimen();
  MesoFileOptions force;
  force.overwrite = Overwrite::kAllow;
  for (const char* name : {"s.inp", "s.msh", "s.vtu"}) {
    const std::string path = folder.file(name);
    std::ofstream(path) << "old";
    EXPECT_EQ(message_of<IoError>([&] { write_mesomodel(path, mesh); }),
              "cannot write " + path + ": file exists (use --force to replace it)");
    EXPECT_EQ(test::read_text(path), "old");
    write_mesomodel(path, mesh, force);
    EXPECT_NE(test::read_text(path), "old");
  }
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"s.inp", "s.msh", "s.vtu"}));
  // /dev/null under another name: a symbolic link s2.inp -> /dev/null, and /dev/null itself
  // through a writer called directly (its extension is not one of ours).
  const std::string link = folder.file("s2.inp");
  std::filesystem::create_symlink("/dev/null", link);
  const std::string refused = message_of<IoError>([&] { write_mesomodel(link, mesh, force); });
  EXPECT_NE(refused.find("not a regular file"), std::string::npos) << refused;
  const std::string device =
      message_of<IoError>([&] { write_mesomodel_inp("/dev/null", mesh, force); });
  EXPECT_NE(device.find("refusing to replace /dev/null: not a regular file"), std::string::npos)
      << device;
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"s.inp", "s.msh", "s.vtu", "s2.inp"}));
  const std::string missing = folder.file("no/such/folder/s.inp");
  EXPECT_NE(message_of<IoError>([&] { write_mesomodel(missing, mesh); }).find(missing),
            std::string::npos);
}

}  // namespace
}  // namespace aggpack
