// The mesomodel's phase image files read by their consumers: VTK's own XML image reader (.vti)
// and numpy (raw + JSON header) give the same voxels as the image in memory.

#include "aggpack/io/voxel_image.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

TEST(VoxelImageFiles, VtkAndNumpyReadTheSameVoxels) {
  AGGPACK_REQUIRE_READER("vtk");
  const Packing packing = test::grid_packing(3, 2, 2, 44);
  VoxelOptions options;
  options.resolution = 48;
  options.itz_thickness = 0.004;
  const VoxelImage image = voxelize(packing, options);
  const auto counts = image.phase_counts();
  ASSERT_GT(counts[1], 0U);
  ASSERT_GT(counts[2], 0U);
  test::ScratchFolder folder;
  const std::string vti = folder.file("image.vti");
  write_vti(vti, image, Overwrite::kForbid);
  write_voxel_raw(folder.file("image"), image, packing, options.itz_thickness, Overwrite::kForbid);
  const auto header = nlohmann::json::parse(test::read_text(folder.file("image.json")));
  EXPECT_EQ(header["dims"][0], image.dims[0]);
  EXPECT_EQ(header["voxels"]["itz"], counts[1]);
  EXPECT_EQ(header["voxels"]["aggregate"], counts[2]);
  EXPECT_EQ(header["files"]["phase"]["path"], "image.phase.raw");
  // In VTK: dims, spacing, origin, and per phase the voxel count and the particles it names; the
  // raw files (numpy, the header's order) hold the same arrays.
  const auto result = test::run_python(folder, R"(
import sys, json, numpy as np
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
folder = sys.argv[1]
reader = vtkXMLImageDataReader()
reader.SetFileName(folder + "/image.vti")
reader.Update()
data = reader.GetOutput()
dims = [d - 1 for d in data.GetDimensions()]
phase = vtk_to_numpy(data.GetCellData().GetArray("phase"))
particle = vtk_to_numpy(data.GetCellData().GetArray("particle"))
header = json.load(open(folder + "/image.json"))
raw_phase = np.fromfile(folder + "/" + header["files"]["phase"]["path"], dtype=np.uint8)
raw_particle = np.fromfile(folder + "/" + header["files"]["particle"]["path"], dtype="<u4")
assert dims == header["dims"], (dims, header["dims"])
assert (raw_phase == phase).all() and (raw_particle == particle).all()
grid = raw_phase.reshape(dims[2], dims[1], dims[0])
print(*dims, data.GetSpacing()[0], *data.GetOrigin(), phase.size,
      *[int((phase == k).sum()) for k in range(4)],
      int(particle[phase == 2].min()), int(particle[phase == 2].max()),
      int((particle[phase == 0] != 0).sum()), int(grid[0, 0, 1] == phase[1]))
)",
                                       folder.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::istringstream in(result.output);
  std::uint64_t nx = 0, ny = 0, nz = 0, total = 0, mortar = 0, itz = 0, aggregate = 0, outside = 0;
  double spacing = 0, ox = 0, oy = 0, oz = 0;
  std::uint32_t lowest = 0, highest = 0, mortar_with_particle = 0, x_fastest = 0;
  in >> nx >> ny >> nz >> spacing >> ox >> oy >> oz >> total >> mortar >> itz >> aggregate >>
      outside >> lowest >> highest >> mortar_with_particle >> x_fastest;
  ASSERT_FALSE(in.fail()) << result.output;
  EXPECT_EQ(nx, image.dims[0]);
  EXPECT_EQ(ny, image.dims[1]);
  EXPECT_EQ(nz, image.dims[2]);
  EXPECT_NEAR(spacing, image.spacing, 1e-15);
  EXPECT_NEAR(ox, image.origin.x(), 1e-15);
  EXPECT_EQ(total, image.count());
  EXPECT_EQ(mortar, counts[0]);
  EXPECT_EQ(itz, counts[1]);
  EXPECT_EQ(aggregate, counts[2]);
  EXPECT_EQ(outside, counts[3]);
  EXPECT_EQ(lowest, 1U);
  EXPECT_EQ(highest, packing.particles.size());
  EXPECT_EQ(mortar_with_particle, 0U);
  EXPECT_EQ(x_fastest, 1U);
}

}  // namespace
}  // namespace aggpack
