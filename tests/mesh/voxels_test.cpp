// The mesomodel's phase image against exact answers: grid-aligned cubes (exact voxel counts),
// Steiner's offset formula (exact ITZ shell volumes), point-polyhedron distances, a cylinder's
// outside corners, thread-count independence and the voxel limit.

#include "aggpack/mesh/voxels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/halfspace.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"
#include "support/packings.h"

namespace aggpack {
namespace {

constexpr double kPi = std::numbers::pi;

using test::box_with;

TEST(OffsetShell, SteinerFormulaOfACubeAndATetrahedron) {
  const double a = 0.5;
  const double t = 0.1;
  const ConvexPolyhedron cube = make_box(Vec3::Constant(-a / 2), Vec3::Constant(a / 2));
  // Cube: S = 6 a^2, M = 1/2 x 12 edges x a x pi/2 (the triangulation's diagonals add 0).
  EXPECT_NEAR(offset_shell_volume(cube, t),
              6 * a * a * t + 3 * kPi * a * t * t + 4.0 / 3.0 * kPi * t * t * t, 1e-15);
  // Regular tetrahedron of edge e: S = sqrt 3 e^2, exterior angle pi - acos(1/3) at 6 edges.
  const ConvexPolyhedron tet = make_regular_tetrahedron(1.0);
  const double e = (tet.vertices()[0] - tet.vertices()[1]).norm();
  const double expected = std::sqrt(3.0) * e * e * t +
                          3.0 * e * (kPi - std::acos(1.0 / 3.0)) * t * t +
                          4.0 / 3.0 * kPi * t * t * t;
  EXPECT_NEAR(offset_shell_volume(tet, t), expected, 1e-14);
  EXPECT_EQ(offset_shell_volume(cube, 0.0), 0.0);
}

TEST(DistanceToBody, FaceEdgeCornerAndInside) {
  const ConvexPolyhedron cube = make_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_NEAR(distance_to_body(cube, Vec3(0.5, 0.5, 1.3)), 0.3, 1e-15);                 // face
  EXPECT_NEAR(distance_to_body(cube, Vec3(1.3, 0.5, 1.4)), 0.5, 1e-15);                 // edge
  EXPECT_NEAR(distance_to_body(cube, Vec3(-1, -2, 3)), std::sqrt(1 + 4 + 4.0), 1e-14);  // corner
  EXPECT_EQ(distance_to_body(cube, Vec3(0.2, 0.9, 0.5)), 0.0);
}

TEST(Voxelize, GridAlignedCubeGivesExactCounts) {
  // A 1 m box in 20^3 voxels of 5 cm; a cube [0.25, 0.75]^3 covers exactly 10^3 voxel centres.
  // Its 5 cm ITZ holds the voxels whose centres are 2.5 cm off a face (6 x 100), 3.54 cm off an
  // edge (12 x 10) and 4.33 cm off a corner (8); the next ones are 7.5 cm or more away.
  const ConvexPolyhedron cube = make_box(Vec3::Constant(-0.25), Vec3::Constant(0.25));
  const Packing packing = box_with(1.0, {cube}, {Vec3::Constant(0.5)});
  VoxelOptions options;
  options.resolution = 20;
  options.itz_thickness = 0.05;
  const VoxelImage image = voxelize(packing, options);
  ASSERT_EQ(image.dims, (std::array<std::uint32_t, 3>{20, 20, 20}));
  EXPECT_DOUBLE_EQ(image.spacing, 0.05);
  const auto counts = image.phase_counts();
  EXPECT_EQ(counts[2], 1000U);
  EXPECT_EQ(counts[1], 600U + 120U + 8U);
  EXPECT_EQ(counts[0], 8000U - 1000U - 728U);
  EXPECT_EQ(counts[3], 0U);
  for (std::size_t v = 0; v < image.count(); ++v) {
    EXPECT_EQ(image.particle[v] != 0, image.phase[v] == 1 || image.phase[v] == 2);
  }
}

TEST(Voxelize, RandomParticlesMatchExactVolumesToTheResolution) {
  // Four generated particles, turned, in a 0.1 m box: voxel volumes against the exact polyhedra
  // and Steiner shells; the error of a voxel count is bounded by the surface x the voxel size.
  std::vector<ConvexPolyhedron> shapes;
  std::vector<Vec3> at;
  const GeneratorOptions generator{
      .alpha = 0.5, .radius_min = 0.015, .radius_max = 0.015, .edge_length = 0.015, .seed = 4};
  double volume = 0.0;
  double shell = 0.0;
  double area = 0.0;
  const double t = 0.002;
  for (int i = 0; i < 4; ++i) {
    ConvexPolyhedron body = generate_particle(generator, static_cast<std::uint64_t>(i)).body;
    volume += mass_properties(body).volume;
    area += mass_properties(body).surface_area;
    shell += offset_shell_volume(body, t);
    shapes.push_back(std::move(body));
    at.emplace_back(0.025 + 0.05 * (i % 2), 0.025 + 0.05 * (i / 2), 0.05);
  }
  Packing packing = box_with(0.1, shapes, at);
  for (std::size_t i = 0; i < 4; ++i) {
    packing.particles[i].pose.rotation =
        Eigen::AngleAxisd(0.3 + i, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  }
  VoxelOptions options;
  options.resolution = 200;
  options.itz_thickness = t;
  const VoxelImage image = voxelize(packing, options);
  const auto counts = image.phase_counts();
  const double voxel = std::pow(image.spacing, 3);
  const double bound = area * image.spacing;  // a generous bound: surface x voxel side
  EXPECT_NEAR(counts[2] * voxel, volume, 0.2 * bound);
  EXPECT_NEAR(counts[1] * voxel, shell, 0.3 * bound);
  EXPECT_LT(std::abs(counts[2] * voxel - volume) / volume, 0.01);
  // Same image at one thread.
  const ThreadLimit one(1);
  const VoxelImage again = voxelize(packing, options);
  EXPECT_EQ(again.phase, image.phase);
  EXPECT_EQ(again.particle, image.particle);
}

TEST(Voxelize, CylinderCornersAreOutside) {
  Packing packing;
  packing.container.shape = CylinderContainer{.radius = 0.5, .height = 1.0};
  VoxelOptions options;
  options.resolution = 100;
  const VoxelImage image = voxelize(packing, options);
  const auto counts = image.phase_counts();
  const double inside = static_cast<double>(counts[0]) / static_cast<double>(image.count());
  EXPECT_NEAR(inside, kPi / 4.0, 2e-3);
  EXPECT_EQ(counts[0] + counts[3], image.count());
}

TEST(Voxelize, BadOptionsAndTheVoxelLimit) {
  const Packing packing = box_with(1.0, {}, {});
  VoxelOptions options;
  options.resolution = 1;
  EXPECT_THROW(voxelize(packing, options), InvalidInput);
  options.resolution = 64;
  options.itz_thickness = -1e-3;
  EXPECT_THROW(voxelize(packing, options), InvalidInput);
  options.itz_thickness = 0.6;  // more than half the box
  EXPECT_THROW(voxelize(packing, options), InvalidInput);
  options.itz_thickness = 0.0;
  options.resolution = 4096;
  options.max_voxels = 1000000;
  try {
    voxelize(packing, options);
    FAIL() << "no limit";
  } catch (const LimitExceeded& error) {
    EXPECT_NE(std::string(error.what()).find("voxels"), std::string::npos);
  }
}

}  // namespace
}  // namespace aggpack
