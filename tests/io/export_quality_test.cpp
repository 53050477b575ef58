// The element quality an export reports (ExportSummary::quality, the CLI's "tetrahedron quality"
// line): every tetrahedron written is counted, and the figures equal a direct measurement of each
// particle's mesh in world coordinates.

#include <regex>

#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/mesh/quality.h"
#include "export_fixture.h"
#include "support/paths.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// Each particle's mesh measured one by one (meshes are made of the stored shape, which the export
// then places; placing moves, turns and scales, which leaves angles and ratios unchanged).
TetQuality direct_quality(const Packing& packing, const TetOptions& options) {
  TetQuality total;
  for (const Particle& particle : packing.particles) {
    const TetMesh mesh = tetrahedralize(packing.shapes[particle.shape], options);
    total.add(measure_quality(mesh.nodes, mesh.tetrahedra));
  }
  return total;
}

void expect_same(const TetQuality& reported, const TetQuality& direct) {
  EXPECT_EQ(reported.tetrahedra, direct.tetrahedra);
  EXPECT_EQ(reported.below_10_degrees, direct.below_10_degrees);
  EXPECT_NEAR(reported.min_dihedral_degrees, direct.min_dihedral_degrees, 1e-6);
  EXPECT_NEAR(reported.max_dihedral_degrees, direct.max_dihedral_degrees, 1e-6);
  EXPECT_NEAR(reported.max_aspect_ratio, direct.max_aspect_ratio, 1e-6 * direct.max_aspect_ratio);
}

TEST(ExportQuality, FanFiguresMatchEveryParticleMeasuredDirectly) {
  // Shared shapes (one measured mesh, counted per particle) and scaled particles.
  const Packing packing = test::grid_packing(3, 2, 1, 71, /*share_shapes=*/true);
  ScratchFolder folder;
  for (const bool is_quadratic : {false, true}) {
    const ExportSummary summary = write(packing, folder.file(is_quadratic ? "q.inp" : "l.inp"),
                                        {.scale = 1000, .is_quadratic = is_quadratic});
    EXPECT_EQ(summary.quality.tetrahedra, summary.elements);
    expect_same(summary.quality, direct_quality(packing, {}));
    EXPECT_GT(summary.quality.min_dihedral_degrees, 0.0);
    EXPECT_GE(summary.quality.max_aspect_ratio, 1.0);
  }
}

#ifdef AGGPACK_HAS_TETGEN
TEST(ExportQuality, TetGenFiguresMatchEveryParticleMeasuredDirectly) {
  const Packing packing = test::grid_packing(2, 2, 1, 72);
  const TetOptions options{.method = TetMethod::kTetGen, .max_volume = 5e-5};
  ScratchFolder folder;
  const ExportSummary summary = write(packing, folder.file("t.msh"), {.tetrahedra = options});
  EXPECT_EQ(summary.quality.tetrahedra, summary.elements);
  expect_same(summary.quality, direct_quality(packing, options));
}
#endif

TEST(ExportQuality, SurfaceFormatsReportNoTetrahedra) {
  const Packing packing = test::grid_packing(2, 1, 1, 73);
  ScratchFolder folder;
  EXPECT_EQ(write(packing, folder.file("s.stl")).quality.tetrahedra, 0U);
  EXPECT_EQ(write(packing, folder.file("s.vtu")).quality.tetrahedra, 0U);
  const ExportSummary cells =
      write(packing, folder.file("t.vtu"), {.cells = MeshCells::kTetrahedra});
  EXPECT_EQ(cells.quality.tetrahedra, cells.elements);
}

TEST(ExportQuality, CliPrintsOneQualityLineForTetrahedra) {
  const Packing packing = test::grid_packing(3, 1, 1, 74);
  ScratchFolder folder;
  write_packing(packing, folder.file("run.h5"));
  const std::string command = test::aggpack_binary() + " export " + folder.file("run.h5") + " -o ";
  const auto inp = test::run_command(command + folder.file("run.inp"));
  ASSERT_EQ(inp.exit_code, 0) << inp.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      inp.output, match,
      std::regex(R"(tetrahedron quality: min dihedral angle ([0-9.]+) deg, max aspect ratio )"
                 R"(([0-9.]+) \(circumradius / 3 inradius, 1 = regular\), (\d+) of (\d+) below )"
                 R"(10 deg)")))
      << inp.output;
  const TetQuality direct = direct_quality(packing, {});
  EXPECT_NEAR(std::stod(match[1]), direct.min_dihedral_degrees, 0.006);
  EXPECT_NEAR(std::stod(match[2]), direct.max_aspect_ratio, 0.01 * direct.max_aspect_ratio);
  EXPECT_EQ(std::stoull(match[3]), direct.below_10_degrees);
  EXPECT_EQ(std::stoull(match[4]), direct.tetrahedra);
  const auto stl = test::run_command(command + folder.file("run.stl"));
  ASSERT_EQ(stl.exit_code, 0) << stl.output;
  EXPECT_EQ(stl.output.find("tetrahedron quality"), std::string::npos) << stl.output;
}

}  // namespace
}  // namespace aggpack
