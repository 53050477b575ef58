// The phase image of a periodic box (mesh/voxels.h): it tiles without seams (the image of the
// packing moved by whole voxels and wrapped into the box is the first image rolled), particles
// crossing a face are counted on both sides, and the refusal of a grid that cannot tile.

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/mesh/voxels.h"
#include "aggpack/pack/random_packer.h"

namespace aggpack {
namespace {

Packing periodic_voxel_packing(std::array<bool, 3> axes) {
  const RandomPackOptions options{
      .container = {.shape =
                        BoxContainer{
                            .length = 0.06, .width = 0.06, .depth = 0.06, .periodic = axes}},
      .grading = {.kind = GradingKind::kUniform, .radius_min = 0.008, .radius_max = 0.014},
      .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
      .target = PackTarget::kVolumeFraction,
      .volume_fraction = 0.3,
      .gap = 0.0005,
      .seed = 12};
  return pack_random(options).packing;
}

TEST(VoxelizePeriodic, ImageOfTheWrappedShiftedPackingIsTheImageRolled) {
  const Packing packing = periodic_voxel_packing({true, true, true});
  const VoxelOptions options{.resolution = 40, .itz_thickness = 0.0008};
  const VoxelImage image = voxelize(packing, options);
  const double spacing = image.spacing;
  const std::array<int, 3> roll{7, 3, 11};  // voxels
  Packing moved = packing;
  for (Particle& particle : moved.particles) {
    for (int axis = 0; axis < 3; ++axis) {
      double& x = particle.pose.position[axis];
      x += roll[static_cast<std::size_t>(axis)] * spacing;
      if (x >= 0.06) x -= 0.06;  // wrapped: the same periodic packing
    }
  }
  const VoxelImage rolled = voxelize(moved, options);
  const auto n = static_cast<int>(image.dims[0]);
  ASSERT_EQ(n, 40);
  std::size_t differ = 0;
  std::size_t particle_differ = 0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const std::size_t from = (static_cast<std::size_t>(k) * n + j) * n + i;
        const std::size_t to =
            (static_cast<std::size_t>((k + roll[2]) % n) * n + (j + roll[1]) % n) * n +
            (i + roll[0]) % n;
        differ += image.phase[from] != rolled.phase[to];
        particle_differ += image.particle[from] != rolled.particle[to];
      }
    }
  }
  // A seam would differ on whole slabs (1 / 40 of the voxels); rounding may flip a voxel centre
  // that lies on a face to within 1e-16.
  EXPECT_LE(differ, 5U);
  EXPECT_LE(particle_differ, 5U);
  // The image's aggregate share is the particles' whole volume over the box's (images count).
  double solid = 0.0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    solid += mass_properties(packing.placed(i)).volume;
  }
  const auto counts = image.phase_counts();
  const double share = static_cast<double>(counts[static_cast<int>(VoxelPhase::kAggregate)]) /
                       static_cast<double>(image.phase.size());
  EXPECT_NEAR(share, solid / (0.06 * 0.06 * 0.06), 0.01);
  EXPECT_EQ(counts[static_cast<int>(VoxelPhase::kOutside)], 0U);
}

TEST(VoxelizePeriodic, RefusesAGridThatCannotTile) {
  Packing packing = periodic_voxel_packing({true, false, false});
  std::get<BoxContainer>(packing.container.shape).width = 0.05;
  try {
    (void)voxelize(packing, {.resolution = 7});  // x is the longest side: 7 voxels along it
    SUCCEED();
  } catch (const InvalidInput&) {
    ADD_FAILURE() << "the periodic x extent is the longest side: 7 voxels tile it";
  }
  std::get<BoxContainer>(packing.container.shape).periodic = {false, true, false};
  try {
    (void)voxelize(packing, {.resolution = 7});
    ADD_FAILURE() << "0.05 m in voxels of 0.06 / 7 m was accepted for a periodic y";
  } catch (const InvalidInput& error) {
    EXPECT_NE(std::string(error.what()).find("voxels = 7"), std::string::npos) << error.what();
  }
  EXPECT_NO_THROW((void)voxelize(packing, {.resolution = 12}));  // 0.005 m voxels: 10 along y
}

}  // namespace
}  // namespace aggpack
