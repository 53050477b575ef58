// Gmsh MSH 4.1: Gmsh itself reads the file and writes it again (gmsh FILE -0 -o OUT), and meshio
// reads both with the same counts and one physical group per particle.

#include "aggpack/io/export.h"
#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

constexpr const char* kMeshioScript = R"(
import sys, meshio
mesh = meshio.read(sys.argv[1], file_format="gmsh")
cells = sum(len(block.data) for block in mesh.cells)
groups = sorted(set(int(v) for block in mesh.cell_data["gmsh:physical"] for v in block))
names = len(mesh.field_data)
print(len(mesh.points), cells, mesh.cells[0].type, groups[0], groups[-1], len(groups), names)
)";

void check_round_trip(const Packing& packing, MeshCells cells, const std::string& name) {
  AGGPACK_REQUIRE_READER("meshio");
  AGGPACK_REQUIRE_READER("gmsh");
  ScratchFolder folder;
  const std::string path = folder.file(name);
  const ExportSummary summary = write(packing, path, {.cells = cells});
  const std::string n = std::to_string(packing.particles.size());
  const std::string expected =
      std::to_string(summary.nodes) + " " + std::to_string(summary.elements) + " " +
      (cells == MeshCells::kSurface ? "triangle" : "tetra") + " 1 " + n + " " + n + " " + n;
  const auto ours = test::run_python(folder, kMeshioScript, path);
  ASSERT_EQ(ours.exit_code, 0) << ours.output;
  EXPECT_EQ(test::trim(ours.output), expected);
  const std::string again = folder.file("again.msh");
  ASSERT_TRUE(test::gmsh_rewrites(path, again, /*allow_warnings=*/true));
  const auto theirs = test::run_python(folder, kMeshioScript, again);
  ASSERT_EQ(theirs.exit_code, 0) << theirs.output;
  EXPECT_EQ(test::trim(theirs.output), expected);
}

TEST(GmshExport, GmshReadsTetrahedraWithOneGroupPerParticle) {
  check_round_trip(test::grid_packing(3, 2, 1, 51), MeshCells::kDefault, "t.msh");
}

TEST(GmshExport, GmshReadsSurfaces) {
  check_round_trip(test::grid_packing(2, 2, 1, 52, /*share_shapes=*/true), MeshCells::kSurface,
                   "s.msh");
}

TEST(GmshExport, HeaderAndSectionsInOrder) {
  const Packing packing = test::grid_packing(1, 1, 1, 53);
  ScratchFolder folder;
  write(packing, folder.file("one.msh"));
  const std::string text = test::read_text(folder.file("one.msh"));
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"P1\"\n", 0),
            0U);
  std::size_t position = 0;
  for (const char* section :
       {"$Entities", "$EndEntities", "$Nodes", "$EndNodes", "$Elements", "$EndElements"}) {
    const std::size_t found = text.find(section, position);
    ASSERT_NE(found, std::string::npos) << section;
    position = found;
  }
}

}  // namespace
}  // namespace aggpack
