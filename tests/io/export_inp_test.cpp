// Abaqus .inp: CalculiX (ccx, which reads the Abaqus format) runs a static gravity step on an
// exported packing with fixed base nodes; meshio reads it back with the same counts; the
// part/instance layout (which ccx does not read) is checked by a structural parser.

#include <map>
#include <regex>
#include <set>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "ccx_fixture.h"
#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::FlatInp;
using test::parse_flat;
using test::run_ccx_gravity;
using test::ScratchFolder;
using test::upper;

TEST(AbaqusExport, CalculixRunsAGravityStepOnC3D4) {
  AGGPACK_REQUIRE_READER("ccx");
  const Packing packing = test::grid_packing(2, 2, 1, 31);
  ScratchFolder folder;
  write(packing, folder.file("packing.inp"));
  run_ccx_gravity(folder, "packing.inp", packing.particles.size());
}

TEST(AbaqusExport, CalculixRunsAGravityStepOnC3D10) {
  AGGPACK_REQUIRE_READER("ccx");
  const Packing packing = test::grid_packing(2, 1, 1, 32);
  ScratchFolder folder;
  write(packing, folder.file("packing.inp"), {.is_quadratic = true});
  EXPECT_NE(test::read_text(folder.file("packing.inp")).find("TYPE=C3D10"), std::string::npos);
  run_ccx_gravity(folder, "packing.inp", packing.particles.size());
}

#ifdef AGGPACK_HAS_TETGEN
TEST(AbaqusExport, CalculixRunsOnTetGenMeshWithFaceSurfaces) {
  AGGPACK_REQUIRE_READER("ccx");
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
  AGGPACK_REQUIRE_READER("meshio");
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

// Node coordinates of a .msh file (written in the shortest round-trip form), by node tag.
std::map<std::uint64_t, Vec3> read_msh_nodes(const std::string& path) {
  std::istringstream in(test::read_text(path));
  std::string line;
  while (std::getline(in, line) && line != "$Nodes") {
  }
  std::map<std::uint64_t, Vec3> nodes;
  std::size_t blocks = 0;
  std::size_t total = 0;
  std::size_t lowest = 0;
  std::size_t highest = 0;
  in >> blocks >> total >> lowest >> highest;
  for (std::size_t b = 0; b < blocks; ++b) {
    int dimension = 0;
    int tag = 0;
    int parametric = 0;
    std::size_t count = 0;
    in >> dimension >> tag >> parametric >> count;
    std::vector<std::uint64_t> tags(count);
    for (auto& t : tags) in >> t;
    for (const auto t : tags) {
      Vec3 p;
      in >> p.x() >> p.y() >> p.z();
      nodes[t] = p;
    }
  }
  EXPECT_EQ(nodes.size(), total);
  return nodes;
}

// CalculiX and Abaqus read at most 20 characters per number. On a packing with negative
// coordinates, at scale 1 and at a scale that makes every coordinate tiny (~1e-5, where the
// shortest form has up to 23 characters), every field of every data line fits, each coordinate
// reads back within the documented precision (>= 15 significant digits) of the exact value (the
// same packing's .msh, in the shortest round-trip form), and ccx runs the tiny model.
TEST(AbaqusExport, EveryNumberFitsTwentyCharacters) {
  AGGPACK_REQUIRE_READER("ccx");
  Packing packing = test::grid_packing(3, 2, 1, 37);
  for (auto& particle : packing.particles) particle.pose.position -= Vec3(0.4, 0.3, 0.15);
  for (const double scale : {1.0, 1e-4}) {
    ScratchFolder folder;
    const ExportOptions options{.scale = scale,
                                .material = {.density = 2650.1234567890123,
                                             .youngs_modulus = 6.1234567890123456e10,
                                             .poisson_ratio = -0.012345678901234567}};
    write(packing, folder.file("model.inp"), options);
    write(packing, folder.file("model.msh"), options);
    const std::string text = test::read_text(folder.file("model.inp"));
    std::istringstream in(text);
    std::string line;
    std::size_t fields = 0;
    std::size_t negative = 0;
    std::size_t tiny = 0;
    bool is_title = false;
    while (std::getline(in, line)) {
      if (is_title || line.rfind('*', 0) == 0 || line.empty()) {  // title, keywords, comments
        is_title = line == "*HEADING";
        continue;
      }
      for (const std::string& field : test::split(line, ',')) {
        const std::string value = test::trim(field);
        EXPECT_LE(value.size(), 20U) << "'" << value << "' in: " << line;
        ++fields;
        negative += value.rfind('-', 0) == 0 ? 1 : 0;
        tiny += value.find("e-") != std::string::npos ? 1 : 0;
      }
    }
    EXPECT_GT(fields, 1000U);
    EXPECT_GT(negative, 100U);
    if (scale < 1) {
      EXPECT_GE(tiny, 300U);  // every coordinate
    }
    EXPECT_NE(text.find(", -0.01234567890123457\n"), std::string::npos);  // Poisson ratio

    const FlatInp inp = parse_flat(folder.file("model.inp"));
    const auto exact = read_msh_nodes(folder.file("model.msh"));
    ASSERT_EQ(inp.nodes.size(), exact.size());
    std::size_t rounded = 0;
    for (const auto& [id, node] : inp.nodes) {
      const Vec3& expected = exact.at(id);
      for (int axis = 0; axis < 3; ++axis) {
        // >= 15 significant digits, >= 14 for 1e-99 <= |x| < 1e-9 (aggpack/io/text_number.h).
        const double magnitude = std::abs(expected[axis]);
        const double precision = magnitude >= 1e-9 ? 5e-15 : 5e-14;
        EXPECT_LE(std::abs(node[axis] - expected[axis]), precision * magnitude)
            << "node " << id << " axis " << axis;
        rounded += node[axis] != expected[axis] ? 1 : 0;
      }
    }
    if (scale < 1) {
      EXPECT_GT(rounded, 100U);  // the tiny model needed rounding
    }
    run_ccx_gravity(folder, "model.inp", packing.particles.size());
  }
}

}  // namespace
}  // namespace aggpack
