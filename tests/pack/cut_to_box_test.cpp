// A periodic packing cut to its box: clip_at_plane's exact answers, the pieces' volumes adding up
// to the particles' (images tile the box), every vertex inside the box, and the refusal of a
// walled box.

#include "aggpack/pack/cut_to_box.h"

#include <gtest/gtest.h>

#include <array>
#include <optional>

#include "aggpack/geom/clip.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/random_packer.h"
#include "pack/pack_test_util.h"
#include "support/periodic.h"

namespace aggpack {
namespace {

TEST(ClipAtPlane, KnownAnswers) {
  const ConvexPolyhedron cube = make_box(Vec3(0.0, 0.0, 0.0), Vec3(1.0, 2.0, 3.0));
  const std::optional<ConvexPolyhedron> below = clip_at_plane(cube, 2, 0.75, true);
  ASSERT_TRUE(below);
  EXPECT_NEAR(mass_properties(*below).volume, 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(below->bounds().upper.z(), 0.75);
  const std::optional<ConvexPolyhedron> above = clip_at_plane(cube, 0, 0.25, false);
  ASSERT_TRUE(above);
  EXPECT_NEAR(mass_properties(*above).volume, 4.5, 1e-12);
  EXPECT_DOUBLE_EQ(above->bounds().lower.x(), 0.25);
  // Wholly on the kept side: the body itself; wholly beyond: nothing.
  EXPECT_EQ(clip_at_plane(cube, 1, 5.0, true)->vertex_count(), cube.vertex_count());
  EXPECT_FALSE(clip_at_plane(cube, 1, 5.0, false));
  // An octahedron cut through its middle: half its volume, the cut exactly on the plane.
  const ConvexPolyhedron octahedron = make_octahedron({1.0, 1.0, 1.0, 1.0, 1.0, 1.0});
  const std::optional<ConvexPolyhedron> half = clip_at_plane(octahedron, 0, 0.0, true);
  ASSERT_TRUE(half);
  EXPECT_NEAR(mass_properties(*half).volume, mass_properties(octahedron).volume / 2.0, 1e-12);
  EXPECT_EQ(half->bounds().upper.x(), 0.0);
}

TEST(CutToBox, CubeAcrossOneFaceBecomesTwoPieces) {
  Packing packing;
  packing.container = test::periodic_box(1.0, 1.0, 1.0, {true, false, false});
  packing.shapes.push_back(make_box(Vec3(-0.1, -0.1, -0.1), Vec3(0.1, 0.1, 0.1)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.95, 0.5, 0.5)}});
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.5, 0.5, 0.5)}});
  const Packing pieces = cut_to_box(packing);
  ASSERT_EQ(pieces.particles.size(), 3u);
  // The image shifted by -1 period first, then the particle's own part, then the whole one.
  EXPECT_NEAR(mass_properties(pieces.placed(0)).volume, 0.05 * 0.04, 1e-15);
  EXPECT_NEAR(mass_properties(pieces.placed(1)).volume, 0.15 * 0.04, 1e-15);
  EXPECT_NEAR(mass_properties(pieces.placed(2)).volume, 0.008, 1e-15);
  EXPECT_EQ(pieces.placed(0).bounds().lower.x(), 0.0);
  EXPECT_EQ(pieces.placed(1).bounds().upper.x(), 1.0);
  EXPECT_EQ(periodic_axes(pieces.container), periodic_axes(packing.container));
}

TEST(CutToBox, PiecesOfAPeriodicPackingTileTheBox) {
  for (const std::array<bool, 3>& axes :
       {std::array<bool, 3>{true, true, true}, std::array<bool, 3>{true, false, true}}) {
    RandomPackOptions options;
    options.container = test::periodic_box(0.2, 0.15, 0.2, axes);
    options.grading.kind = GradingKind::kUniform;
    options.grading.radius_min = 0.012;
    options.grading.radius_max = 0.025;
    options.shape = {.alpha = 0.5, .edge_length_ratio = 1.0};
    options.target = PackTarget::kVolumeFraction;
    options.volume_fraction = 0.3;
    options.seed = 12;
    const Packing packing = pack_random(options).packing;
    const Packing pieces = cut_to_box(packing);
    ASSERT_GT(pieces.particles.size(), packing.particles.size() + 10);
    double whole = 0.0;
    for (std::size_t i = 0; i < packing.particles.size(); ++i) {
      whole += mass_properties(packing.placed(i)).volume;
    }
    double cut = 0.0;
    const Aabb box = packing.container.bounds();
    for (std::size_t i = 0; i < pieces.particles.size(); ++i) {
      const ConvexPolyhedron piece = pieces.placed(i);
      cut += mass_properties(piece).volume;
      for (const Vec3& vertex : piece.vertices()) {
        EXPECT_TRUE((vertex.array() >= box.lower.array()).all() &&
                    (vertex.array() <= box.upper.array()).all())
            << "piece " << i << " vertex " << vertex.transpose();
      }
    }
    EXPECT_NEAR(cut, whole, 1e-9 * whole);
  }
}

TEST(CutToBox, WalledBoxIsRefused) {
  Packing packing;
  packing.container = test::periodic_box(1.0, 1.0, 1.0, {});
  EXPECT_EQ(testing::invalid_field([&] { (void)cut_to_box(packing); }), "cut-to-box");
}

}  // namespace
}  // namespace aggpack
