// Rendering benchmarks (bench/RESULTS.md, section "Rendering"): whole frames of the OpenGL
// renderer on the machine's driver (llvmpipe here), headless, with the camera turning a little
// every frame as a drag does, so every frame is a fresh redraw.
//
//   build-main/bench/render_bench [--benchmark_filter=<name>]
//
// The packing is the GUI benchmark's `dense.h5` made in-process: 100,000 random particles of
// radius 10 mm (alpha 0.5, L = r, 200 shapes) in a 0.85 m cube, 15 % solid. A frame is
// draw() + glFinish() into a 1040 x 900 framebuffer (the GUI's default view size; /2 = at half
// its width and height, as the GUI's light frames at 50 % resolution). Counters:
// particles drawn, impostors, mesh triangles, and the main-thread parts of the frame (ms).

#include <benchmark/benchmark.h>

#include <GL/gl.h>

#include <cstdio>
#include <memory>

#include "aggpack/pack/random_packer.h"
#include "aggpack/render/camera.h"
#include "aggpack/render/headless.h"
#include "aggpack/render/renderer.h"

namespace {

using namespace aggpack;

// The GUI's default view (a 1400 x 900 window less the 360 px panel).
constexpr int kWidth = 1040;
constexpr int kHeight = 900;

const Packing& dense_packing() {
  static const Packing packing = [] {
    RandomPackOptions options;
    options.container = {.shape = BoxContainer{.length = 0.85, .width = 0.85, .depth = 0.85}};
    options.grading = {.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.01};
    options.shape = {.alpha = 0.5, .edge_length_ratio = 1.0, .library_size = 200};
    options.target = PackTarget::kCount;
    options.count = 100000;
    options.seed = 1;
    PackResult result = pack_random(options);
    std::printf("  packing: %s\n", result.report.summary().c_str());
    return std::move(result.packing);
  }();
  return packing;
}

// One context, targets and renderer for the whole run (uploading 100k particles takes ~1 s).
struct Scene {
  HeadlessContext context;
  OffscreenTarget target{kWidth, kHeight, 0};
  OffscreenTarget half_target{kWidth / 2, kHeight / 2, 0};  // light frames at 50 % resolution
  PackingRenderer renderer;
  Scene() {
    std::printf("  renderer: %s\n", context.renderer_name().c_str());
    renderer.set_packing(dense_packing());
  }
};

Scene& scene() {
  static Scene instance;
  return instance;
}

// state.range(0): 1 = the full view, 2 = half its width and height (a light frame at 50 %).
void run_frames(benchmark::State& state, const RenderStyle& style) {
  Scene& s = scene();
  const OffscreenTarget& target = state.range(0) == 2 ? s.half_target : s.target;
  target.bind();
  const int width = target.width(), height = target.height();
  Camera camera = Camera::framing(s.renderer.scene_bounds(), ViewPreset::kIso,
                                  static_cast<double>(width) / height);
  DrawStats total;
  double frames = 0;
  // Two warm-up frames: the first compiles llvmpipe's shader variants and fills the visible set.
  for (int k = 0; k < 2; ++k) s.renderer.draw(camera, width, height, style);
  glFinish();
  for (auto _ : state) {
    camera.rotate_arcball(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.02, 0.0));
    total += s.renderer.draw(camera, width, height, style);
    glFinish();
    frames += 1;
  }
  state.counters["drawn"] = static_cast<double>(total.particles_drawn) / frames;
  state.counters["impostors"] = static_cast<double>(total.point_particles) / frames;
  state.counters["triangles"] = static_cast<double>(total.triangles) / frames;
  state.counters["sort_ms"] = 1e3 * total.frustum_sort_seconds / frames;
  state.counters["submit_ms"] = 1e3 * total.submit_seconds / frames;
  state.counters["readback_ms"] = 1e3 * total.depth_readback_seconds / frames;
  state.counters["occlusion_ms"] = 1e3 * total.occlusion_test_seconds / frames;
}

// The GUI's still (full-detail) frame: 250k mesh triangles at most, points below 3 px.
void BM_FullDetail(benchmark::State& state) {
  RenderStyle style;
  style.triangle_budget = 250000;
  style.point_below_pixels = 3.0;
  run_frames(state, style);
}
BENCHMARK(BM_FullDetail)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// Every visible particle as an impostor (the lightest frame that still draws them all).
void BM_AllImpostors(benchmark::State& state) {
  RenderStyle style;
  style.triangle_budget = 1;
  run_frames(state, style);
}
BENCHMARK(BM_AllImpostors)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// Every visible particle as its mesh (no budget): what the full-detail frame would cost.
void BM_AllMeshes(benchmark::State& state) {
  RenderStyle style;
  style.triangle_budget = 0;
  style.coarse_below_pixels = 0.0;
  run_frames(state, style);
}
BENCHMARK(BM_AllMeshes)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// Every visible particle as its coarse 24-triangle mesh.
void BM_AllCoarse(benchmark::State& state) {
  RenderStyle style;
  style.triangle_budget = 0;
  style.coarse_below_pixels = 1e9;
  run_frames(state, style);
}
BENCHMARK(BM_AllCoarse)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace

BENCHMARK_MAIN();
