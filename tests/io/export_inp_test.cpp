// Abaqus .inp: CalculiX (ccx, which reads the Abaqus format) runs a static gravity step on an
// exported packing with fixed base nodes; meshio reads it back with the same counts; the
// part/instance layout (which ccx does not read) is checked by a structural parser.

#include <map>
#include <regex>
#include <set>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "export_fixture.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

std::string upper(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// Node coordinates and the node range of every particle's generated node set, from a flat file.
struct FlatInp {
  std::map<std::uint64_t, Vec3> nodes;
  std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> node_sets;  // name -> [a, b]
  std::size_t elements = 0;
};

FlatInp parse_flat(const std::string& path) {
  FlatInp inp;
  std::istringstream in(test::read_text(path));
  std::string line;
  std::string block;
  std::string set_name;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind('*', 0) == 0) {
      const std::string keyword = upper(line);
      block = test::trim(test::split(keyword, ',')[0]);
      std::smatch found;
      if (block == "*NSET" && std::regex_search(keyword, found, std::regex("NSET=([A-Z0-9_]+)"))) {
        set_name = found[1];
      }
      continue;
    }
    const auto fields = test::split(line, ',');
    if (block == "*NODE") {
      inp.nodes[std::stoull(fields[0])] =
          Vec3(std::stod(fields[1]), std::stod(fields[2]), std::stod(fields[3]));
    } else if (block == "*ELEMENT") {
      ++inp.elements;
    } else if (block == "*NSET" && fields.size() == 3) {
      inp.node_sets[set_name] = {std::stoull(fields[0]), std::stoull(fields[1])};
    }
  }
  return inp;
}

// Runs ccx on `model` (an exported .inp in `folder`) with gravity and, per particle, the nodes in
// the lowest 30% of its height fixed. Returns ccx's output; expects success.
void run_ccx_gravity(const ScratchFolder& folder, const std::string& model, std::size_t particles) {
  const FlatInp inp = parse_flat(folder.file(model));
  ASSERT_EQ(inp.node_sets.size(), particles);
  std::string base;
  std::size_t fixed = 0;
  for (const auto& [name, range] : inp.node_sets) {
    if (name == "ALLNODES") continue;
    double low = 1e300;
    double high = -1e300;
    for (auto id = range.first; id <= range.second; ++id) {
      low = std::min(low, inp.nodes.at(id).z());
      high = std::max(high, inp.nodes.at(id).z());
    }
    for (auto id = range.first; id <= range.second; ++id) {
      if (inp.nodes.at(id).z() <= low + 0.3 * (high - low)) {
        base += std::to_string(id) + ",\n";
        ++fixed;
      }
    }
  }
  ASSERT_GE(fixed, 3 * particles);
  std::ofstream(folder.file("job.inp"))
      << "*INCLUDE, INPUT=" << model << "\n*NSET, NSET=BASE\n"
      << base
      << "*BOUNDARY\nBASE, 1, 3\n*STEP\n*STATIC\n*DLOAD\nAGGREGATES, GRAV, 9.81, 0., 0., -1.\n"
         "*NODE PRINT, NSET=ALLNODES\nU\n*END STEP\n";
  const auto result =
      test::run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i job");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("Job finished"), std::string::npos) << result.output;
  EXPECT_EQ(upper(result.output).find("*ERROR"), std::string::npos) << result.output;
  // Displacements: every node listed once; gravity pulls the free nodes down a little.
  std::istringstream dat(test::read_text(folder.file("job.dat")));
  std::string line;
  std::size_t listed = 0;
  double sum_z = 0;
  double largest = 0;
  while (std::getline(dat, line)) {
    std::istringstream fields(line);
    std::uint64_t id = 0;
    double ux = 0;
    double uy = 0;
    double uz = 0;
    if (fields >> id >> ux >> uy >> uz) {
      ++listed;
      sum_z += uz;
      largest = std::max(largest, std::abs(uz));
    }
  }
  EXPECT_EQ(listed, inp.nodes.size());
  EXPECT_LT(sum_z, 0.0);
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, 1e-3);  // stiff rock under its own weight: tiny displacements
}

TEST(AbaqusExport, CalculixRunsAGravityStepOnC3D4) {
  if (!test::has_program("ccx")) GTEST_SKIP() << "calculix-ccx not installed";
  const Packing packing = test::grid_packing(2, 2, 1, 31);
  ScratchFolder folder;
  write(packing, folder.file("packing.inp"));
  run_ccx_gravity(folder, "packing.inp", packing.particles.size());
}

TEST(AbaqusExport, CalculixRunsAGravityStepOnC3D10) {
  if (!test::has_program("ccx")) GTEST_SKIP() << "calculix-ccx not installed";
  const Packing packing = test::grid_packing(2, 1, 1, 32);
  ScratchFolder folder;
  write(packing, folder.file("packing.inp"), {.is_quadratic = true});
  EXPECT_NE(test::read_text(folder.file("packing.inp")).find("TYPE=C3D10"), std::string::npos);
  run_ccx_gravity(folder, "packing.inp", packing.particles.size());
}

#ifdef AGGPACK_HAS_TETGEN
TEST(AbaqusExport, CalculixRunsOnTetGenMeshWithFaceSurfaces) {
  if (!test::has_program("ccx")) GTEST_SKIP() << "calculix-ccx not installed";
  const Packing packing = test::grid_packing(2, 1, 1, 33);
  ScratchFolder folder;
  write(packing, folder.file("packing.inp"),
        {.tetrahedra = {.method = TetMethod::kTetGen, .max_volume = 5e-5}});
  const std::string text = test::read_text(folder.file("packing.inp"));
  EXPECT_NE(text.find("*ELSET, ELSET=P1_S"), std::string::npos);
  run_ccx_gravity(folder, "packing.inp", packing.particles.size());
}
#endif

TEST(AbaqusExport, MeshioReadsTheSameCountsAndSets) {
  if (!test::has_python_module("meshio")) GTEST_SKIP() << "python3-meshio not installed";
  const Packing packing = test::grid_packing(3, 2, 1, 34, /*share_shapes=*/true);
  ScratchFolder folder;
  for (bool is_quadratic : {false, true}) {
    const std::string path = folder.file(is_quadratic ? "c3d10.inp" : "c3d4.inp");
    const ExportSummary summary = write(packing, path, {.is_quadratic = is_quadratic});
    const auto result = test::run_python(folder, R"(
import sys, meshio
mesh = meshio.read(sys.argv[1], file_format="abaqus")
cells = sum(len(block.data) for block in mesh.cells)
types = sorted(set(block.type for block in mesh.cells))
sets = sorted(name for name in mesh.cell_sets if name.startswith("P"))
print(len(mesh.points), cells, ",".join(types), len(sets), len(mesh.point_sets))
)",
                                         path);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const std::string expected =
        std::to_string(summary.nodes) + " " + std::to_string(summary.elements) + " " +
        (is_quadratic ? "tetra10" : "tetra") + " " + std::to_string(packing.particles.size()) +
        " " + std::to_string(packing.particles.size());
    EXPECT_EQ(test::trim(result.output), expected);
  }
}

TEST(AbaqusExport, MaterialSectionAndSurfacesAreWritten) {
  const Packing packing = test::grid_packing(2, 1, 1, 35);
  ScratchFolder folder;
  write(
      packing, folder.file("m.inp"),
      {.material = {
           .name = "GRANITE", .density = 2650.0, .youngs_modulus = 6.5e10, .poisson_ratio = 0.25}});
  const std::string text = test::read_text(folder.file("m.inp"));
  EXPECT_NE(text.find("*MATERIAL, NAME=GRANITE\n*DENSITY\n2650,\n*ELASTIC\n6.5e+10, 0.25\n"),
            std::string::npos);
  EXPECT_NE(text.find("*SOLID SECTION, ELSET=AGGREGATES, MATERIAL=GRANITE\n"), std::string::npos);
  EXPECT_NE(text.find("*SURFACE, TYPE=ELEMENT, NAME=P1_SURFACE\nP1, S1\n"), std::string::npos);
  EXPECT_NE(text.find("*SURFACE, TYPE=ELEMENT, NAME=P2_SURFACE\nP2, S1\n"), std::string::npos);
}

// Structural check of the part/instance layout: every part has nodes numbered 1..n, elements that
// only use its own nodes, a node set, an element set, a section and a surface named after it, and
// exactly one instance of it in the assembly.
TEST(AbaqusExport, PartsAndInstancesAreWellFormed) {
  const Packing packing = test::grid_packing(2, 2, 1, 36);
  ScratchFolder folder;
  const ExportSummary summary =
      write(packing, folder.file("parts.inp"), {.abaqus_layout = AbaqusLayout::kPartsInstances});
  std::istringstream in(test::read_text(folder.file("parts.inp")));
  std::string line;
  std::string part;
  std::string block;
  std::set<std::string> parts;
  std::map<std::string, int> instances;
  std::size_t nodes = 0;
  std::size_t elements = 0;
  std::uint64_t part_nodes = 0;
  bool in_assembly = false;
  std::set<std::string> seen_in_part;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    const std::string keyword = upper(line);
    std::smatch match;
    if (keyword.rfind('*', 0) == 0) {
      block = test::trim(test::split(keyword, ',')[0]);
      if (block == "*PART" && std::regex_search(keyword, match, std::regex("NAME=(\\w+)"))) {
        part = match[1];
        EXPECT_TRUE(parts.insert(part).second);
        part_nodes = 0;
        seen_in_part.clear();
      } else if (block == "*END PART") {
        for (const std::string& expected : {"NSET=" + part, "ELSET=" + part, std::string("SECTION"),
                                            "SURFACE=" + part + "_SURFACE"}) {
          EXPECT_EQ(seen_in_part.count(expected), 1U) << part << " lacks " << expected;
        }
        part.clear();
      } else if (block == "*ASSEMBLY") {
        in_assembly = true;
      } else if (block == "*END ASSEMBLY") {
        in_assembly = false;
      } else if (block == "*INSTANCE") {
        EXPECT_TRUE(in_assembly);
        ASSERT_TRUE(std::regex_search(keyword, match, std::regex("PART=(\\w+)")));
        ++instances[match[1]];
      } else if (!part.empty()) {
        if (std::regex_search(keyword, match, std::regex("\\*NSET, NSET=(\\w+)"))) {
          seen_in_part.insert("NSET=" + std::string(match[1]));
        }
        if (std::regex_search(keyword, match, std::regex("\\*ELEMENT, .*ELSET=(\\w+)"))) {
          seen_in_part.insert("ELSET=" + std::string(match[1]));
        }
        if (block == "*SOLID SECTION") seen_in_part.insert("SECTION");
        if (std::regex_search(keyword, match, std::regex("\\*SURFACE, .*NAME=(\\w+)"))) {
          seen_in_part.insert("SURFACE=" + std::string(match[1]));
        }
      }
      continue;
    }
    if (part.empty()) continue;
    const auto fields = test::split(line, ',');
    if (block == "*NODE") {
      EXPECT_EQ(std::stoull(fields[0]), ++part_nodes);
      ++nodes;
    } else if (block == "*ELEMENT") {
      ASSERT_EQ(fields.size(), 5U);
      for (std::size_t k = 1; k < 5; ++k) {
        EXPECT_GE(std::stoull(fields[k]), 1U);
        EXPECT_LE(std::stoull(fields[k]), part_nodes);
      }
      ++elements;
    }
  }
  EXPECT_EQ(parts.size(), packing.particles.size());
  for (const auto& name : parts) EXPECT_EQ(instances[name], 1) << name;
  EXPECT_EQ(nodes, summary.nodes);
  EXPECT_EQ(elements, summary.elements);
  EXPECT_NE(test::read_text(folder.file("parts.inp")).find("*MATERIAL, NAME=AGGREGATE"),
            std::string::npos);
}

}  // namespace
}  // namespace aggpack
