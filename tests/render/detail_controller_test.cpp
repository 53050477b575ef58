// Adaptive level of detail for moving views: the controller given made-up frame times.

#include "aggpack/render/detail_controller.h"

#include <gtest/gtest.h>

#include "aggpack/core/error.h"

namespace aggpack {
namespace {

// A made-up frame: 5 ms fixed, 0.2 us per mesh triangle, 2 us per particle drawn, plus pixel
// work of `full_pixels` seconds at full resolution (falling with the square of the scale); a
// view of 50,000 particles that would use 400,000 triangles without a budget.
struct FakeScene {
  std::size_t particles_in_view = 50000;
  std::size_t triangles_wanted = 400000;
  double fixed = 0.005, per_triangle = 0.2e-6, per_particle = 2e-6, full_pixels = 0.0;
  std::size_t triangles = 0, particles = 0;
  double draw(const DetailLevel& level) {
    particles = level.max_particles == 0 ? particles_in_view
                                         : std::min(level.max_particles, particles_in_view);
    triangles = triangles_wanted * particles / particles_in_view;
    if (level.triangle_budget > 0) triangles = std::min(triangles, level.triangle_budget);
    return fixed + per_triangle * static_cast<double>(triangles) +
           per_particle * static_cast<double>(particles) +
           full_pixels * level.resolution_scale * level.resolution_scale;
  }
};

TEST(DetailController, StartsAtFullDetail) {
  const DetailController controller(0.045, 250000);
  EXPECT_EQ(controller.level().triangle_budget, 250000u);
  EXPECT_EQ(controller.level().max_particles, 0u);
  EXPECT_EQ(controller.level().resolution_scale, 1.0);
  EXPECT_THROW(DetailController(0.0, 1000), InvalidInput);
}

TEST(DetailController, LowersTheBudgetUntilFramesFitTheTarget) {
  // Affordable by triangles alone: 50k particles cost 105 ms without triangles, so the target
  // of 150 ms leaves 45 ms for about 225k triangles.
  DetailController controller(0.150, 0);
  FakeScene scene;
  double seconds = 0.0;
  for (int frame = 0; frame < 30; ++frame) {
    seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
  }
  EXPECT_LE(seconds, 0.150 * 1.0001);
  EXPECT_GE(seconds, 0.75 * 0.150 * 0.5);  // not needlessly light
  EXPECT_EQ(controller.level().max_particles, 0u);
  EXPECT_GT(controller.level().triangle_budget, 1u);
}

TEST(DetailController, DrawsFewerParticlesOnlyWhenAllImpostorsAreTooSlow) {
  DetailController controller(0.045, 250000, 5000);
  FakeScene scene;  // all impostors: 105 ms, over the target
  double seconds = 0.0;
  for (int frame = 0; frame < 30; ++frame) {
    seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
  }
  EXPECT_EQ(controller.level().triangle_budget, 1u);
  EXPECT_EQ(controller.level().resolution_scale, kMinResolutionScale);  // tried first
  EXPECT_GT(controller.level().max_particles, 5000u);
  EXPECT_LT(controller.level().max_particles, 50000u);
  EXPECT_LE(seconds, 0.045);
  EXPECT_GE(seconds, 0.045 * 0.5);

  // The scene becomes cheap (say the user zoomed in on a few particles): back to all particles,
  // then the budget rises to the ceiling and stays there.
  scene.particles_in_view = 2000;
  scene.triangles_wanted = 60000;
  for (int frame = 0; frame < 40; ++frame) {
    seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
  }
  EXPECT_EQ(controller.level().max_particles, 0u);
  EXPECT_EQ(controller.level().resolution_scale, 1.0);
  EXPECT_EQ(scene.triangles, 60000u);
  EXPECT_LE(controller.level().triangle_budget, 250000u);
}

TEST(DetailController, LowersTheResolutionBeforeDrawingFewerParticles) {
  DetailController controller(0.045, 250000, 5000);
  FakeScene scene;
  scene.per_particle = 0.5e-6;  // all impostors: 30 ms of geometry
  scene.full_pixels = 0.040;    // + 40 ms of pixels at full resolution, 10 ms at half
  double seconds = 0.0;
  for (int frame = 0; frame < 40; ++frame) {
    seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
  }
  EXPECT_EQ(controller.level().triangle_budget, 1u);
  EXPECT_EQ(controller.level().max_particles, 0u);  // every particle still drawn
  EXPECT_LT(controller.level().resolution_scale, 0.9);
  EXPECT_GE(controller.level().resolution_scale, kMinResolutionScale);
  EXPECT_LE(seconds, 0.045);

  // Cheap again: full resolution comes back before triangles do.
  scene.full_pixels = 0.0;
  scene.per_particle = 0.1e-6;
  for (int frame = 0; frame < 40; ++frame) {
    seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
  }
  EXPECT_EQ(controller.level().resolution_scale, 1.0);
  EXPECT_GT(controller.level().triangle_budget, 1u);
}

TEST(DetailController, SettlesInsteadOfOscillating) {
  DetailController controller(0.045, 250000);
  FakeScene scene;
  scene.per_particle = 0.5e-6;  // all impostors: 30 ms, so some triangles fit
  std::vector<std::size_t> budgets;
  for (int frame = 0; frame < 60; ++frame) {
    const double seconds = scene.draw(controller.level());
    controller.update(seconds, scene.triangles, scene.particles);
    budgets.push_back(controller.level().triangle_budget);
  }
  // The last 20 frames keep one level.
  for (std::size_t k = 40; k < budgets.size(); ++k) EXPECT_EQ(budgets[k], budgets[39]);
  const double seconds = scene.draw(controller.level());
  EXPECT_LE(seconds, 0.045);
  EXPECT_GE(seconds, 0.75 * 0.045 * 0.5);
}

TEST(DetailController, IgnoresBadFrameTimesAndResets) {
  DetailController controller(0.045, 100000);
  controller.update(0.0, 100000, 1000);
  controller.update(-1.0, 100000, 1000);
  EXPECT_EQ(controller.level().triangle_budget, 100000u);
  controller.update(0.2, 100000, 1000);
  EXPECT_EQ(controller.level().triangle_budget, 50000u);  // at most halved per frame
  controller.set_full_budget(20000);
  EXPECT_EQ(controller.level().triangle_budget, 20000u);
  controller.reset();
  EXPECT_EQ(controller.level().triangle_budget, 20000u);
  EXPECT_EQ(controller.level().max_particles, 0u);
}

}  // namespace
}  // namespace aggpack
