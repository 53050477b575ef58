// Headless rendering (EGL surfaceless + llvmpipe): render known packings and check the pixels.

#include <gtest/gtest.h>
#include <stb_image.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/convex_hull_2d.h"
#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/render/headless.h"
#include "test_packings.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

bool is_background(const Image& image, int x, int y, const Rgb& background) {
  return image.pixel(x, y) == background;
}

std::size_t covered_pixels(const Image& image, const Rgb& background) {
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) count += !is_background(image, x, y, background);
  }
  return count;
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  std::size_t count = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) count += !(a.pixel(x, y) == b.pixel(x, y));
  }
  return count;
}

// Pixel position (x right, y down) of a world point for the camera render_image uses.
Eigen::Vector2d project(const Camera& camera, int width, int height, const Vec3& point) {
  const Eigen::Vector4f clip =
      camera.projection_matrix(static_cast<double>(width) / height) * camera.view_matrix() *
      Eigen::Vector4f(static_cast<float>(point.x()), static_cast<float>(point.y()),
                      static_cast<float>(point.z()), 1.0f);
  return Eigen::Vector2d((clip.x() / clip.w() + 1.0) * 0.5 * width,
                         (1.0 - clip.y() / clip.w()) * 0.5 * height);
}

// A packing uploaded to a renderer that draws into a 320 x 240 target (no multisampling), as the
// culling and stepped-frame tests use it.
struct CullingScene {
  HeadlessContext context;  // first: the members below need its current context
  PackingRenderer renderer;
  OffscreenTarget target{320, 240};
  Camera camera;
  explicit CullingScene(const Packing& packing, ViewPreset view = ViewPreset::kIso) {
    renderer.set_packing(packing);
    camera = Camera::framing(renderer.scene_bounds(), view, 320.0 / 240.0);
  }
  // Binds the target and draws the whole frame into it.
  DrawStats draw(const RenderStyle& style) {
    target.bind();
    return renderer.draw(camera, 320, 240, style);
  }
};

RenderImageOptions small_options() {
  RenderImageOptions options;
  options.width = 320;
  options.height = 240;
  options.samples = 0;  // exact coverage: a pixel is covered iff its centre is inside
  return options;
}

// An empty packing in a 2 x 1 x 1 m box, the options that draw it from the top (orthographic,
// no container outline) and that view's camera: the pixel-exact coverage tests' set-up.
Packing two_by_one_box() {
  Packing packing;
  packing.container.get_if<BoxContainer>()->length = 2.0;
  packing.container.get_if<BoxContainer>()->width = 1.0;
  packing.container.get_if<BoxContainer>()->depth = 1.0;
  return packing;
}

RenderImageOptions top_orthographic_options() {
  RenderImageOptions options = small_options();
  options.view = ViewPreset::kTop;
  options.is_orthographic = true;
  options.style.show_container = false;
  return options;
}

Camera two_by_one_top_camera() {
  Aabb scene;
  scene.expand(Vec3::Zero());
  scene.expand(Vec3(2.0, 1.0, 1.0));
  return Camera::framing(scene, ViewPreset::kTop, 320.0 / 240.0, true);
}

TEST(Headless, EmptyPackingRendersOnlyBackground) {
  Packing packing;  // default container, no particles
  RenderImageOptions options = small_options();
  options.style.show_container = false;
  const Image image = render_image(packing, options);
  ASSERT_EQ(image.width, 320);
  ASSERT_EQ(image.height, 240);
  EXPECT_EQ(covered_pixels(image, options.style.background), 0u);

  // With the outline on, only outline-coloured pixels join the background.
  options.style.show_container = true;
  const Image outlined = render_image(packing, options);
  std::size_t outline = 0;
  for (int y = 0; y < outlined.height; ++y) {
    for (int x = 0; x < outlined.width; ++x) {
      const Rgb c = outlined.pixel(x, y);
      if (c == options.style.background) continue;
      EXPECT_EQ(c, options.style.container_color) << x << "," << y;
      ++outline;
    }
  }
  EXPECT_GT(outline, 300u);  // 12 edges of a box spanning most of the picture
}

TEST(Headless, CubeCoversExactlyItsProjectedSquare) {
  // One cube of side 0.4 m at (1.0, 0.5, 0.5) in a 2 x 1 x 1 box, seen from the top,
  // orthographic: it must cover the square its corners project to, and nothing else.
  Packing packing = two_by_one_box();
  packing.shapes.push_back(make_box(Vec3::Constant(-0.2), Vec3::Constant(0.2)));
  Particle particle;
  particle.pose.position = Vec3(1.0, 0.5, 0.5);
  packing.particles.push_back(particle);
  const RenderImageOptions options = top_orthographic_options();
  const Image image = render_image(packing, options);
  const Camera camera = two_by_one_top_camera();
  const Eigen::Vector2d a = project(camera, image.width, image.height, Vec3(0.8, 0.3, 0.7));
  const Eigen::Vector2d b = project(camera, image.width, image.height, Vec3(1.2, 0.7, 0.7));
  const double x0 = std::min(a.x(), b.x()), x1 = std::max(a.x(), b.x());
  const double y0 = std::min(a.y(), b.y()), y1 = std::max(a.y(), b.y());
  ASSERT_GT(x1 - x0, 20.0);  // the square is large enough for the test to mean something
  std::size_t inside = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;  // pixel centre
      const bool is_covered = !is_background(image, x, y, options.style.background);
      const bool is_in_square = cx > x0 && cx < x1 && cy > y0 && cy < y1;
      const bool is_near_edge = std::abs(cx - x0) < 1.0 || std::abs(cx - x1) < 1.0 ||
                                std::abs(cy - y0) < 1.0 || std::abs(cy - y1) < 1.0;
      if (!is_near_edge) {
        EXPECT_EQ(is_covered, is_in_square) << x << "," << y;
      }
      inside += is_covered;
    }
  }
  EXPECT_NEAR(static_cast<double>(inside), (x1 - x0) * (y1 - y0), 2.0 * (x1 - x0 + y1 - y0));
  // The top face faces the viewer: lit, so brighter than its unlit colour would be dark.
  const Rgb centre =
      image.pixel(static_cast<int>(0.5 * (x0 + x1)), static_cast<int>(0.5 * (y0 + y1)));
  EXPECT_GT(centre.r + centre.g + centre.b, 200);
}

// Whether point p is inside the convex hull of `points` by more than `margin` pixels from every
// hull edge (a negative margin: within -margin pixels outside it).
bool is_inside_hull(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p,
                    double margin) {
  std::vector<std::array<double, 2>> plane;
  for (const Eigen::Vector2d& point : points) plane.push_back({point.x(), point.y()});
  const auto hull = convex_hull_2d(std::move(plane));
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d a(hull[i][0], hull[i][1]);
    const Eigen::Vector2d b(hull[(i + 1) % hull.size()][0], hull[(i + 1) % hull.size()][1]);
    const Eigen::Vector2d edge = b - a;
    const double cross = edge.x() * (p.y() - a.y()) - edge.y() * (p.x() - a.x());
    if (cross / edge.norm() <= margin) return false;
  }
  return true;
}

TEST(Headless, RotatedScaledParticlesCoverTheirProjectedOutlines) {
  // Flat boxes (0.6 x 0.2 x 0.1 m) scaled and turned about skew axes, seen from the top,
  // orthographic: the pixels covered are the convex hulls of their projected corners (Eigen's
  // rotation on the CPU). One particle: its mesh is used once and drawn in world coordinates;
  // two particles of one shape: drawn instanced, the rotation and scale applied by the vertex
  // shader. A transposed rotation or a lost scale moves an outline by tens of pixels.
  for (const bool is_instanced : {false, true}) {
    SCOPED_TRACE(is_instanced ? "instanced" : "single-use mesh");
    Packing packing = two_by_one_box();
    packing.shapes.push_back(make_box(Vec3(-0.3, -0.1, -0.05), Vec3(0.3, 0.1, 0.05)));
    Particle particle;
    particle.pose.position = Vec3(0.6, 0.5, 0.5);
    particle.pose.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));
    particle.scale = 1.3;
    packing.particles.push_back(particle);
    if (is_instanced) {
      particle.pose.position = Vec3(1.45, 0.5, 0.5);
      particle.pose.rotation = Quat(Eigen::AngleAxisd(-1.1, Vec3(-2.0, 1.0, 0.5).normalized()));
      particle.scale = 0.9;
      packing.particles.push_back(particle);
    }
    const RenderImageOptions options = top_orthographic_options();
    const Image image = render_image(packing, options);
    const Camera camera = two_by_one_top_camera();
    std::vector<std::vector<Eigen::Vector2d>> outlines;
    for (const Particle& p : packing.particles) {
      auto& corners = outlines.emplace_back();
      for (const Vec3& vertex : packing.shapes[0].vertices()) {
        const Vec3 world = p.pose.position + p.pose.rotation * (p.scale * vertex);
        corners.push_back(project(camera, image.width, image.height, world));
      }
    }
    std::size_t inside = 0, outside = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const Eigen::Vector2d centre(x + 0.5, y + 0.5);
        const bool is_covered = !is_background(image, x, y, options.style.background);
        bool is_in = false, is_near = false;
        for (const auto& corners : outlines) {
          is_in = is_in || is_inside_hull(corners, centre, 1.0);
          is_near = is_near || is_inside_hull(corners, centre, -1.0);
        }
        if (is_in) {
          EXPECT_TRUE(is_covered) << x << "," << y;
          ++inside;
        } else if (!is_near) {
          EXPECT_FALSE(is_covered) << x << "," << y;
          ++outside;
        }
      }
    }
    EXPECT_GT(inside, 1000u * packing.particles.size());  // outlines large enough to mean much
    EXPECT_GT(outside, 40000u);
  }
}

TEST(Headless, ParticlesCoverTheRegionTheyOccupy) {
  // 6 x 3 x 3 particles on a grid; only the left half of a container twice as long holds them.
  Packing packing = test::grid_packing(6, 3, 3);
  const double filled_length = packing.container.get_if<BoxContainer>()->length;
  packing.container.get_if<BoxContainer>()->length = 2.0 * filled_length;
  RenderImageOptions options = small_options();
  options.view = ViewPreset::kFront;
  options.is_orthographic = true;
  options.style.show_container = false;
  const Image image = render_image(packing, options);

  Aabb scene = packing.container.bounds();
  const Camera camera = Camera::framing(scene, ViewPreset::kFront, 320.0 / 240.0, true);
  const double margin = 0.01;  // grid_packing's margin is 0.1 r = 0.01 m
  const Eigen::Vector2d low = project(camera, image.width, image.height, Vec3(margin, 0.0, margin));
  const Eigen::Vector2d high = project(
      camera, image.width, image.height,
      Vec3(filled_length - margin, 0.0, packing.container.get_if<BoxContainer>()->depth - margin));
  std::size_t covered_left = 0, pixels_left = 0, covered_right = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool is_covered = !is_background(image, x, y, options.style.background);
      const double cx = x + 0.5, cy = y + 0.5;
      if (cx > low.x() + 1 && cx < high.x() - 1 && cy > high.y() + 1 && cy < low.y() - 1) {
        ++pixels_left;
        covered_left += is_covered;
      } else if (cx > high.x() + 1 || cx < low.x() - 1 || cy < high.y() - 1 || cy > low.y() + 1) {
        covered_right += is_covered;  // outside the occupied block
      }
    }
  }
  ASSERT_GT(pixels_left, 1000u);
  EXPECT_EQ(covered_right, 0u);
  // Every particle contains its centre, so each projected centre is covered; the particles
  // (spacing 2.2 r, vertices between 0.6 r and r from the centre) cover a good part of the block.
  for (const Particle& particle : packing.particles) {
    const Eigen::Vector2d centre =
        project(camera, image.width, image.height, particle.pose.position);
    EXPECT_FALSE(is_background(image, static_cast<int>(centre.x()), static_cast<int>(centre.y()),
                               options.style.background));
  }
  EXPECT_GT(static_cast<double>(covered_left) / static_cast<double>(pixels_left), 0.3);
}

TEST(Headless, ColourModesGiveDifferentPictures) {
  Packing packing = test::grid_packing(5, 2, 2, 0.1, 3);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    packing.particles[i].scale = 0.6 + 0.02 * static_cast<double>(i);  // sizes differ
  }
  RenderImageOptions options = small_options();
  options.style.show_container = false;
  options.style.color = ColorMode::kParticle;
  const Image by_id = render_image(packing, options);
  options.style.color = ColorMode::kSize;
  const Image by_size = render_image(packing, options);
  options.style.color = ColorMode::kAlpha;
  const Image by_alpha = render_image(packing, options);
  const std::size_t covered = covered_pixels(by_id, options.style.background);
  ASSERT_GT(covered, 2000u);
  // Same geometry: the same pixels are covered in every mode ...
  EXPECT_EQ(covered_pixels(by_size, options.style.background), covered);
  EXPECT_EQ(covered_pixels(by_alpha, options.style.background), covered);
  // ... but most of them in other colours.
  EXPECT_GT(differing_pixels(by_id, by_size), covered / 2);
  EXPECT_GT(differing_pixels(by_id, by_alpha), covered / 2);
  EXPECT_GT(differing_pixels(by_size, by_alpha), covered / 2);

  // By id: many distinct hues; by size the colour follows the scale: the largest (last)
  // particle is the brightest yellow-green end, the smallest the dark blue end.
  std::set<std::tuple<int, int, int>> hues;
  for (int y = 0; y < by_id.height; ++y) {
    for (int x = 0; x < by_id.width; ++x) {
      const Rgb c = by_id.pixel(x, y);
      hues.insert({c.r / 32, c.g / 32, c.b / 32});
    }
  }
  EXPECT_GT(hues.size(), 15u);
}

TEST(Headless, InstancedAndSingleShapePathsDrawTheSamePicture) {
  const Packing library = test::grid_packing(4, 3, 2, 0.1, 2);  // 24 particles, 2 shapes
  const Packing unique = test::with_unique_shapes(library);
  ASSERT_EQ(unique.shapes.size(), 24u);
  RenderImageOptions options = small_options();
  options.style.coarse_below_pixels = 0.0;
  const Image a = render_image(library, options);
  const Image b = render_image(unique, options);
  const std::size_t covered = covered_pixels(a, options.style.background);
  ASSERT_GT(covered, 2000u);
  EXPECT_EQ(covered_pixels(b, options.style.background), covered);
  EXPECT_LE(differing_pixels(a, b), covered / 1000);
}

TEST(Headless, WireframeAndCoarseDetailChangeThePicture) {
  const Packing packing = test::grid_packing(4, 2, 2, 0.1, 0, 3);
  RenderImageOptions options = small_options();
  options.style.show_container = false;
  options.style.coarse_below_pixels = 0.0;
  const Image solid = render_image(packing, options);
  options.style.is_wireframe = true;
  const Image wire = render_image(packing, options);
  const std::size_t solid_covered = covered_pixels(solid, options.style.background);
  const std::size_t wire_covered = covered_pixels(wire, options.style.background);
  EXPECT_GT(wire_covered, solid_covered / 10);
  EXPECT_LT(wire_covered, solid_covered * 9 / 10);  // lines leave gaps between edges

  // All particles coarse: similar outline, different facets.
  options.style.is_wireframe = false;
  options.style.coarse_below_pixels = 1e6;
  const Image coarse = render_image(packing, options);
  const std::size_t coarse_covered = covered_pixels(coarse, options.style.background);
  EXPECT_GT(coarse_covered, solid_covered * 7 / 10);  // coarse hull lies inside the particle
  EXPECT_LE(coarse_covered, solid_covered);
  EXPECT_GT(differing_pixels(solid, coarse), solid_covered / 10);
}

TEST(Headless, RendererReportsCullingAndDetailLevels) {
  HeadlessContext context;
  EXPECT_FALSE(context.renderer_name().empty());
  const Packing packing = test::grid_packing(10, 10, 2, 0.1, 4);
  PackingRenderer renderer;
  renderer.set_packing(packing);
  EXPECT_EQ(renderer.particle_count(), 200u);
  EXPECT_EQ(renderer.shape_count(), 4u);
  OffscreenTarget target(200, 200);
  target.bind();
  Camera camera = Camera::framing(renderer.scene_bounds(), ViewPreset::kTop);
  RenderStyle style;
  style.coarse_below_pixels = 0.0;
  DrawStats stats = renderer.draw(camera, 200, 200, style);
  EXPECT_EQ(stats.particles_drawn, 200u);
  EXPECT_EQ(stats.coarse_particles, 0u);
  EXPECT_LE(stats.draw_calls, 4u * 2u + 1u);  // one instanced call per shape and level + outline
  std::size_t full_triangles = 0, coarse_triangles = 0;
  for (const Particle& particle : packing.particles) {
    const std::size_t count = packing.shapes[particle.shape].triangle_count();
    full_triangles += count;
    coarse_triangles += std::min<std::size_t>(count, 24);  // shapes at most that fine stay full
  }
  EXPECT_EQ(stats.triangles, full_triangles);
  style.coarse_below_pixels = 1e6;
  stats = renderer.draw(camera, 200, 200, style);
  EXPECT_EQ(stats.coarse_particles, 200u);
  EXPECT_EQ(stats.triangles, coarse_triangles);
  EXPECT_LT(coarse_triangles, full_triangles);
  // Zoomed far in on one corner: most particles are outside the view and skipped.
  camera.zoom(0.05);
  camera.pan(-90.0, -90.0, 200);
  stats = renderer.draw(camera, 200, 200, style);
  EXPECT_LT(stats.particles_drawn, 50u);
  EXPECT_GT(stats.particles_drawn, 0u);
}

TEST(Headless, TriangleBudgetTurnsTheSmallestParticlesIntoPoints) {
  Packing packing = test::grid_packing(6, 4, 3, 0.1, 3);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    packing.particles[i].scale = 0.5 + 0.01 * static_cast<double>(i);
  }
  HeadlessContext context;
  PackingRenderer renderer;
  renderer.set_packing(packing);
  OffscreenTarget target(320, 240);
  const Camera camera = Camera::framing(renderer.scene_bounds(), ViewPreset::kIso, 320.0 / 240.0);
  RenderStyle style;
  style.coarse_below_pixels = 0.0;
  style.show_container = false;
  target.bind();
  const DrawStats full = renderer.draw(camera, 320, 240, style);
  const std::size_t covered_full = covered_pixels(target.read(), style.background);
  EXPECT_EQ(full.point_particles, 0u);
  style.triangle_budget = full.triangles / 3;
  target.bind();
  const DrawStats budget = renderer.draw(camera, 320, 240, style);
  EXPECT_LE(budget.triangles, style.triangle_budget);
  EXPECT_GT(budget.point_particles, 0u);
  EXPECT_EQ(budget.particles_drawn, full.particles_drawn);
  // Everything as points: one shaded disc of the equal-volume size per particle, so about as
  // much of the picture is covered (a disc is rounder, not larger or smaller on average).
  style.triangle_budget = 0;
  style.point_below_pixels = 1e6;
  target.bind();
  const DrawStats points = renderer.draw(camera, 320, 240, style);
  const std::size_t covered_points = covered_pixels(target.read(), style.background);
  EXPECT_EQ(points.point_particles, packing.particles.size());
  EXPECT_EQ(points.triangles, 0u);
  EXPECT_GT(covered_points, covered_full / 2);
  EXPECT_LT(covered_points, covered_full * 2);
}

TEST(Headless, OcclusionCullingSkipsHiddenParticlesAndKeepsThePicture) {
  // 4,800 particles in a lattice block: from the iso view the inner ones hide behind the outer
  // layers (not all: there are lines of sight along the lattice gaps).
  CullingScene scene(test::grid_packing(20, 12, 20, 0.1, 4));
  PackingRenderer& renderer = scene.renderer;
  OffscreenTarget& target = scene.target;
  Camera& camera = scene.camera;
  RenderStyle style;
  style.is_occlusion_culled = false;
  target.bind();
  const DrawStats all = renderer.draw(camera, 320, 240, style);
  const Image expected = target.read();
  EXPECT_EQ(all.particles_drawn, all.particles_in_frustum);
  style.is_occlusion_culled = true;
  // The first frame learns what is visible, the next ones draw that first and test the rest;
  // every one must give the same picture.
  for (int frame = 0; frame < 3; ++frame) {
    target.bind();
    const DrawStats culled = renderer.draw(camera, 320, 240, style);
    EXPECT_EQ(culled.particles_in_frustum, all.particles_in_frustum);
    if (frame > 0) {
      EXPECT_LT(culled.particles_drawn, all.particles_drawn * 9 / 10) << "frame " << frame;
    }
    EXPECT_EQ(differing_pixels(target.read(), expected), 0u) << "frame " << frame;
  }
  // After the camera turns, last frame's visible set is stale: still the same picture as
  // drawing everything.
  camera.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.6, 0.2));
  target.bind();
  renderer.draw(camera, 320, 240, style);
  const Image turned = target.read();
  style.is_occlusion_culled = false;
  target.bind();
  renderer.draw(camera, 320, 240, style);
  EXPECT_EQ(differing_pixels(turned, target.read()), 0u);
}

TEST(Headless, ParticleCapAboveTheVisibleSetKeepsTheWholePicture) {
  CullingScene scene(test::grid_packing(20, 12, 20, 0.1, 4));
  RenderStyle style;
  scene.draw(style);  // learns the visible set
  const DrawStats culled = scene.draw(style);
  const Image expected = scene.target.read();
  ASSERT_LT(culled.particles_drawn, culled.particles_in_frustum * 9 / 10);
  // A cap under what is in view but over what shows: culled as before, nothing thinned.
  style.max_particles = culled.particles_drawn + 10;
  const DrawStats capped = scene.draw(style);
  EXPECT_EQ(capped.particles_drawn, culled.particles_drawn);
  EXPECT_EQ(differing_pixels(scene.target.read(), expected), 0u);
  // A cap under what shows: an even thinning, so fewer drawn and a different picture.
  style.max_particles = culled.particles_drawn / 2;
  const DrawStats thinned = scene.draw(style);
  // (a hash of the index keeps each particle with the fraction that fits: about the cap)
  EXPECT_LE(thinned.particles_drawn, style.max_particles * 11 / 10);
  EXPECT_GE(thinned.particles_drawn, style.max_particles * 9 / 10);
  EXPECT_GT(differing_pixels(scene.target.read(), expected), 0u);
}

TEST(Headless, LargeFirstPassIsDrawnInPiecesWithTheSamePicture) {
  CullingScene scene(test::grid_packing(40, 40, 20, 0.1, 4), ViewPreset::kTop);  // 32,000
  RenderStyle style;
  style.triangle_budget = 100000;  // binds: the halves share it, nearer half first
  scene.draw(style);               // learns the visible set (the top layers)
  const DrawStats whole = scene.draw(style);
  const Image expected = scene.target.read();
  ASSERT_GE(whole.particles_drawn, 8000u);  // enough to split the first pass
  EXPECT_LE(whole.triangles, 100000u);
  scene.target.bind();
  scene.renderer.begin_frame(scene.camera, 320, 240, style);
  // Two pieces at least for the first pass, none over 12,000 particles, then the read-back and
  // the rest.
  int steps = 1;
  std::size_t drawn = 0;
  bool is_done = false;
  while (!is_done) {
    is_done = scene.renderer.step_frame();
    EXPECT_LE(scene.renderer.frame_stats().particles_drawn - drawn, 12000u);
    drawn = scene.renderer.frame_stats().particles_drawn;
    if (!is_done) ++steps;
  }
  EXPECT_GE(steps, 4);
  EXPECT_EQ(scene.renderer.frame_stats().particles_drawn, whole.particles_drawn);
  EXPECT_EQ(scene.renderer.frame_stats().triangles, whole.triangles);
  EXPECT_EQ(differing_pixels(scene.target.read(), expected), 0u);
}

TEST(Headless, SteppedFrameDrawsTheSamePictureWithOtherDrawingBetweenSteps) {
  CullingScene scene(test::grid_packing(20, 12, 20, 0.1, 4));
  PackingRenderer& renderer = scene.renderer;
  OffscreenTarget& target = scene.target;
  Camera& camera = scene.camera;
  // Another renderer drawing elsewhere between the steps, with other GL state.
  OffscreenTarget other(64, 64);
  PackingRenderer other_renderer;
  other_renderer.set_packing(test::grid_packing(2, 2, 2, 0.1, 1));
  const Camera other_camera = Camera::framing(other_renderer.scene_bounds(), ViewPreset::kTop);
  RenderStyle other_style;
  other_style.is_wireframe = true;
  other_style.color = ColorMode::kSize;
  const RenderStyle style;  // occlusion culling on: three steps once the visible set is known
  target.bind();
  renderer.draw(camera, 320, 240, style);
  camera.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.3, 0.1));
  target.bind();
  const DrawStats whole = renderer.draw(camera, 320, 240, style);
  const Image expected = target.read();

  camera.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.3, 0.1));
  target.bind();
  renderer.draw(camera, 320, 240, style);  // another visible set, so the steps have work to do
  camera.rotate_arcball(Eigen::Vector2d(0.3, 0.1), Eigen::Vector2d(0.0, 0.0));
  target.bind();
  renderer.begin_frame(camera, 320, 240, style);
  int steps = 0;
  bool is_done = false;
  while (!is_done) {
    EXPECT_TRUE(renderer.is_frame_pending());
    // Something else drawn between the steps (as the GUI draws its panel).
    other.bind();
    other_renderer.draw(other_camera, 64, 64, other_style);
    target.bind();
    is_done = renderer.step_frame();
    ++steps;
  }
  EXPECT_GE(steps, 3);  // first pass (in pieces of at most 60,000 triangles), read-back, rest
  EXPECT_FALSE(renderer.is_frame_pending());
  EXPECT_TRUE(renderer.step_frame());  // nothing left to do
  EXPECT_EQ(renderer.frame_stats().particles_in_frustum, whole.particles_in_frustum);
  EXPECT_EQ(differing_pixels(target.read(), expected), 0u);

  // An abandoned frame leaves no trace: the next whole frame is the same picture.
  renderer.begin_frame(camera, 320, 240, style);
  renderer.step_frame();
  target.bind();
  renderer.draw(camera, 320, 240, style);
  EXPECT_EQ(differing_pixels(target.read(), expected), 0u);
}
TEST(Headless, PngRoundTripsThroughAnIndependentDecoder) {
  const Packing packing = test::grid_packing(3, 2, 2);
  RenderImageOptions options = small_options();
  options.samples = 4;
  const Image image = render_image(packing, options);
  const fs::path dir = fs::temp_directory_path() / "aggpack_render_test";
  fs::create_directories(dir);
  const std::string path = (dir / "grid.png").string();
  write_png(image, path);
  int width = 0, height = 0, channels = 0;
  unsigned char* decoded = stbi_load(path.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(decoded, nullptr);
  EXPECT_EQ(width, image.width);
  EXPECT_EQ(height, image.height);
  EXPECT_EQ(channels, 3);
  std::size_t mismatches = 0;
  for (int i = 0; i < width * height; ++i) {
    for (int c = 0; c < 3; ++c) mismatches += decoded[3 * i + c] != image.rgba[4 * i + c];
  }
  stbi_image_free(decoded);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_THROW(write_png(image, path, Overwrite::kForbid), IoError);
  EXPECT_THROW(write_png(image, (dir / "missing" / "x.png").string()), IoError);
  EXPECT_THROW(write_png(Image{}, (dir / "empty.png").string()), InvalidInput);
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  fs::remove_all(dir);
}

TEST(Headless, RejectsBadOptions) {
  const Packing packing;
  RenderImageOptions options;
  options.width = 8;
  EXPECT_THROW(render_image(packing, options), InvalidInput);
  options = {};
  options.samples = 32;
  EXPECT_THROW(render_image(packing, options), InvalidInput);
  options = {};
  options.style.coarse_below_pixels = -1.0;
  EXPECT_THROW(render_image(packing, options), InvalidInput);
  Packing broken = test::grid_packing(1, 1, 1);
  broken.particles[0].shape = 5;
  EXPECT_THROW(render_image(broken, small_options()), InvalidInput);
}

}  // namespace
}  // namespace aggpack

namespace aggpack {
namespace {

TEST(Headless, SceneUploadedInPiecesDrawsTheSamePicture) {
  const Packing packing = test::grid_packing(6, 5, 4, 0.1);
  CullingScene whole(packing);
  const RenderStyle style;
  whole.draw(style);
  const Image expected = whole.target.read();

  PackingRenderer& renderer = whole.renderer;
  // Prepared off the GL thread's work (no GL calls), then uploaded 4 kB at a time.
  std::vector<double> fractions;
  auto scene = prepare_scene(packing, [&](double f) { fractions.push_back(f); });
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  renderer.begin_upload(scene);
  EXPECT_TRUE(renderer.is_upload_pending());
  whole.target.bind();
  EXPECT_THROW(renderer.draw(whole.camera, 320, 240, style), Error);  // not while uploading
  int steps = 1;
  double last = 0.0;
  while (!renderer.upload_step(4096)) {
    EXPECT_GE(renderer.upload_progress(), last);
    last = renderer.upload_progress();
    ++steps;
  }
  EXPECT_GT(steps, 10);
  EXPECT_FALSE(renderer.is_upload_pending());
  EXPECT_EQ(renderer.particle_count(), packing.particles.size());
  whole.draw(style);
  EXPECT_EQ(differing_pixels(whole.target.read(), expected), 0u);

  // A smaller scene next goes into the storage the first one had: the same picture as a fresh
  // renderer draws.
  const Packing smaller = test::grid_packing(3, 4, 2, 0.1);
  CullingScene fresh(smaller);
  fresh.draw(style);
  renderer.begin_upload(prepare_scene(smaller));
  while (!renderer.upload_step(4096)) {
  }
  whole.target.bind();
  renderer.draw(fresh.camera, 320, 240, style);
  EXPECT_EQ(differing_pixels(whole.target.read(), fresh.target.read()), 0u);

  // Cancelled: no scene.
  const std::atomic<bool> cancel{true};
  EXPECT_EQ(prepare_scene(packing, {}, &cancel), nullptr);
}

TEST(Headless, ScaledCopiesOfAShapeShareItsMesh) {
  // One shape reused at three sizes through Particle::scale, and the same packing with each
  // particle given its own stored copy at its size: the renderer finds the copies and draws them
  // with one mesh, giving the same picture (float rounding aside).
  Packing shared = test::grid_packing(3, 2, 2, 0.1, 1);
  for (std::size_t i = 0; i < shared.particles.size(); ++i) {
    shared.particles[i].scale = 0.6 + 0.1 * static_cast<double>(i % 3);
  }
  Packing copies = shared;
  copies.shapes.clear();
  for (std::size_t i = 0; i < copies.particles.size(); ++i) {
    copies.shapes.push_back(shared.shapes[0].scaled(shared.particles[i].scale));
    copies.particles[i].shape = static_cast<std::uint32_t>(i);
    copies.particles[i].scale = 1.0;
  }
  const RenderStyle style;
  CullingScene a(shared);
  a.draw(style);
  const Image expected = a.target.read();
  CullingScene b(copies);
  EXPECT_EQ(b.renderer.merged_shape_count(), copies.shapes.size() - 1);
  b.draw(style);
  EXPECT_LE(differing_pixels(b.target.read(), expected), 40u);
  EXPECT_GT(covered_pixels(expected, style.background), 2000u);
}

TEST(Headless, MeshesSplitIntoSmallPagesDrawTheSamePicture) {
  // Pages of 4 kB hold a few shapes each: the meshes are spread over many buffers (one
  // multi-draw per page for single-use shapes, the page's vertex array for instanced ones), and
  // the picture is the one drawn from a single page (draw order within a step may differ between
  // pages, which only matters where two particles have the same depth at a pixel).
  for (const std::uint32_t library_size : {0u, 5u}) {
    const Packing packing = test::grid_packing(6, 5, 4, 0.1, library_size);
    CullingScene scene(packing);
    const RenderStyle style;
    const DrawStats one_page = scene.draw(style);
    const Image expected = scene.target.read();
    scene.renderer.begin_upload(prepare_scene(packing, {}, nullptr, 4096));
    int steps = 0;
    while (!scene.renderer.upload_step(1024)) ++steps;
    EXPECT_GT(steps, 3);
    const DrawStats paged = scene.draw(style);
    EXPECT_EQ(paged.particles_drawn, one_page.particles_drawn);
    EXPECT_EQ(paged.triangles, one_page.triangles);
    if (library_size == 0) {
      EXPECT_GT(paged.draw_calls, one_page.draw_calls + 5);
    }
    const Image image = scene.target.read();
    const std::size_t covered = covered_pixels(expected, style.background);
    EXPECT_GT(covered, 2000u);
    EXPECT_LE(differing_pixels(image, expected), covered / 1000);
  }
}

}  // namespace
}  // namespace aggpack
