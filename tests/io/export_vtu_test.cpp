// VTK .vtu: read back by VTK itself (python3-vtk9's vtkXMLUnstructuredGridReader) and by meshio,
// surfaces and tetrahedra, with the per-particle cell data.

#include <map>

#include "aggpack/io/export.h"
#include "aggpack/shape/descriptors.h"
#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// Prints, per particle id: number of cells, summed cell volume (VTK's own vtkMeshQuality /
// triangle areas are not needed: we sum tetra volumes for tetrahedra), and the cell data values.
constexpr const char* kVtkScript = R"(
import sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
reader = vtk.vtkXMLUnstructuredGridReader()
reader.SetFileName(sys.argv[1])
reader.Update()
if reader.GetErrorCode() != 0:
    sys.exit("reader error %d" % reader.GetErrorCode())
grid = reader.GetOutput()
print("points", grid.GetNumberOfPoints())
print("cells", grid.GetNumberOfCells())
types = sorted(set(grid.GetCellType(i) for i in range(grid.GetNumberOfCells())))
print("types", " ".join(str(t) for t in types))
data = grid.GetCellData()
names = sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))
print("arrays", " ".join(names))
ids = vtk_to_numpy(data.GetArray("particle_id"))
volume = vtk_to_numpy(data.GetArray("volume"))
sphericity = vtk_to_numpy(data.GetArray("sphericity"))
alpha = vtk_to_numpy(data.GetArray("alpha"))
size_class = vtk_to_numpy(data.GetArray("size_class"))
tet_sum = {}
negative = 0
for i in range(grid.GetNumberOfCells()):
    cell = grid.GetCell(i)
    if grid.GetCellType(i) == vtk.VTK_TETRA:
        p = [grid.GetPoint(cell.GetPointId(k)) for k in range(4)]
        v = vtk.vtkTetra.ComputeVolume(p[0], p[1], p[2], p[3])
        if v <= 0:
            negative += 1
        tet_sum[int(ids[i])] = tet_sum.get(int(ids[i]), 0.0) + v
print("negative", negative)
first = {}
for i in range(len(ids)):
    first.setdefault(int(ids[i]), i)
for pid in sorted(first):
    i = first[pid]
    print("particle %d %.17g %.17g %.17g %d %.17g" % (pid, volume[i], sphericity[i], alpha[i],
          size_class[i], tet_sum.get(pid, 0.0)))
)";

struct VtkParticle {
  double volume = 0;
  double sphericity = 0;
  double alpha = 0;
  int size_class = 0;
  double tet_volume = 0;
};

void check_with_vtk(const Packing& packing, const ScratchFolder& folder, const std::string& path,
                    const ExportSummary& summary, bool is_tetra) {
  const auto result = test::run_python(folder, kVtkScript, path);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::istringstream lines(result.output);
  std::string line;
  std::map<std::string, std::string> header;
  std::map<int, VtkParticle> particles;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key == "particle") {
      int id = 0;
      VtkParticle p;
      fields >> id >> p.volume >> p.sphericity >> p.alpha >> p.size_class >> p.tet_volume;
      particles[id] = p;
    } else {
      std::string rest;
      std::getline(fields, rest);
      header[key] = test::trim(rest);
    }
  }
  EXPECT_EQ(header["points"], std::to_string(summary.nodes));
  EXPECT_EQ(header["cells"], std::to_string(summary.elements));
  EXPECT_EQ(header["types"], is_tetra ? "10" : "5");
  EXPECT_EQ(header["arrays"], "alpha control_radius particle_id size_class sphericity volume");
  EXPECT_EQ(header["negative"], "0");
  ASSERT_EQ(particles.size(), packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const VtkParticle& p = particles[static_cast<int>(i + 1)];
    const ShapeDescriptors d = describe(packing.placed(i));
    EXPECT_NEAR(p.volume, d.volume, 1e-12 * d.volume);
    EXPECT_NEAR(p.sphericity, d.sphericity, 1e-12);
    EXPECT_NEAR(p.alpha, d.measured_alpha, 1e-12);
    EXPECT_EQ(p.size_class, static_cast<int>(packing.particles[i].size_class));
    if (is_tetra) {
      EXPECT_NEAR(p.tet_volume, d.volume, 1e-12 * d.volume);
    }
  }
}

TEST(VtuExport, VtkReadsSurfacesWithParticleData) {
  AGGPACK_REQUIRE_READER("vtk");
  const Packing packing = test::grid_packing(3, 2, 2, 41, /*share_shapes=*/true);
  ScratchFolder folder;
  const std::string path = folder.file("surface.vtu");
  const ExportSummary summary = write(packing, path);
  check_with_vtk(packing, folder, path, summary, false);
}

TEST(VtuExport, VtkReadsPositiveTetrahedraThatSumToTheParticleVolume) {
  AGGPACK_REQUIRE_READER("vtk");
  const Packing packing = test::grid_packing(2, 2, 2, 42);
  ScratchFolder folder;
  const std::string path = folder.file("tetra.vtu");
  const ExportSummary summary = write(packing, path, {.cells = MeshCells::kTetrahedra});
  check_with_vtk(packing, folder, path, summary, true);
#ifdef AGGPACK_HAS_TETGEN
  const std::string quality = folder.file("tetgen.vtu");
  const ExportSummary tetgen_summary =
      write(packing, quality,
            {.cells = MeshCells::kTetrahedra,
             .tetrahedra = {.method = TetMethod::kTetGen, .max_volume = 5e-5}});
  // TetGen's own mesh for every particle (not the fan it falls back to on failure): with the
  // surface kept it may have fewer tetrahedra than the fan, but never the same ones.
  EXPECT_EQ(tetgen_summary.tetgen_shapes, 8U);
  EXPECT_TRUE(tetgen_summary.tetgen_fallbacks.empty());
  EXPECT_NE(tetgen_summary.elements, summary.elements);
  check_with_vtk(packing, folder, quality, tetgen_summary, true);
#endif
}

TEST(VtuExport, MeshioReadsTheSameCountsAndData) {
  AGGPACK_REQUIRE_READER("meshio");
  const Packing packing = test::grid_packing(2, 2, 1, 43);
  ScratchFolder folder;
  for (auto cells : {MeshCells::kSurface, MeshCells::kTetrahedra}) {
    const std::string path = folder.file("m.vtu");
    const ExportSummary summary =
        write(packing, path, {.overwrite = Overwrite::kAllow, .cells = cells});
    const auto result = test::run_python(folder, R"(
import sys, meshio
mesh = meshio.read(sys.argv[1])
cells = sum(len(block.data) for block in mesh.cells)
ids = sorted(set(int(v) for block in mesh.cell_data["particle_id"] for v in block))
print(len(mesh.points), cells, mesh.cells[0].type, ids[0], ids[-1], len(ids))
)",
                                         path);
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_EQ(test::trim(result.output),
              std::to_string(summary.nodes) + " " + std::to_string(summary.elements) + " " +
                  (cells == MeshCells::kSurface ? "triangle" : "tetra") + " 1 4 4");
  }
}

}  // namespace
}  // namespace aggpack
