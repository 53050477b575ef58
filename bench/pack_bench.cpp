// Packing benchmarks (bench/RESULTS.md, section "Packing").
//
//   build-pack/bench/pack_bench --benchmark_filter=<name>
//
// Counters: particles placed, solid fraction reached, attempts, seconds spent growing shapes and
// placing them. Every random run here also passes aggpack::verify (grid broad phase + exact GJK),
// so a fast but wrong packing would abort the benchmark.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "aggpack/core/rng.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/pack/verify.h"
#include "aggpack/shape/generator.h"

namespace {

using namespace aggpack;

Grading fuller4() {
  // d_max / d_min = 4, exponent 0.5 (Fuller-Thompson), sizes = control diameters in metres.
  return {.kind = GradingKind::kFuller, .size_min = 0.005, .size_max = 0.02, .exponent = 0.5};
}

// A cube whose volume holds about `particles` particles of the grading at `fraction`, assuming
// a particle fills `kappa` of its control sphere (measured: ~0.22 for alpha 0.5, L = r).
Container cube_for(const Grading& grading, double particles, double fraction, double kappa = 0.22) {
  const double solid = particles * kappa * std::numbers::pi / 6.0 * mean_cubed_size(grading);
  const double side = std::cbrt(solid / fraction);
  return {.shape = BoxContainer{.length = side, .width = side, .depth = side}};
}

void record(benchmark::State& state, const PackResult& result) {
  state.counters["placed"] = static_cast<double>(result.report.placed);
  state.counters["requested"] = static_cast<double>(result.report.requested);
  state.counters["solid_fraction"] = result.report.solid_fraction;
  state.counters["attempts"] = static_cast<double>(result.report.attempts);
  state.counters["shape_s"] = result.report.shape_seconds;
  state.counters["place_s"] = result.report.placement_seconds;
  std::printf("  %s\n", result.report.summary().c_str());
}

void check(const PackResult& result, double gap) {
  const VerifyResult verified = verify(result.packing, {.gap = gap});
  if (!verified.is_ok) throw std::runtime_error("invalid packing: " + verified.message);
}

// The paper's case: 1,050 lattice sites, alpha 0.5, R = L = 0.1 m, box 3.0 x 1.0 x 2.8 m.
void BM_LatticePaperCase(benchmark::State& state) {
  PackResult result;
  for (auto _ : state) result = pack_lattice(LatticeOptions{});
  check(result, 0.0);
  record(state, result);
  state.counters["solid_m3"] = result.report.solid_volume;
}
BENCHMARK(BM_LatticePaperCase)->Unit(benchmark::kMillisecond)->Iterations(1);

// Fuller 4 to 35 % solid in a cube sized for `particles`; library_size 0 = unique shapes.
void run_fuller35(benchmark::State& state, double particles, std::uint32_t library_size) {
  const RandomPackOptions options{
      .container = cube_for(fuller4(), particles, 0.35),
      .grading = fuller4(),
      .shape = {.alpha = 0.5, .edge_length_ratio = 1.0, .library_size = library_size},
      .volume_fraction = 0.35,
      .seed = 1};
  PackResult result;
  for (auto _ : state) result = pack_random(options);
  check(result, 0.0);
  record(state, result);
}

// 100,000 graded particles (Fuller, d_max/d_min = 4, q = 0.5) to 35 % solid, unique shapes.
void BM_Random100kFuller35(benchmark::State& state) { run_fuller35(state, 1.0e5, 0); }
BENCHMARK(BM_Random100kFuller35)->Unit(benchmark::kSecond)->Iterations(1);

// 1,000,000 particles, same grading, shape library of 1,000 shapes.
void BM_Random1MFuller35Library(benchmark::State& state) { run_fuller35(state, 1.0e6, 1000); }
BENCHMARK(BM_Random1MFuller35Library)->Unit(benchmark::kSecond)->Iterations(1);

// Highest fraction: aim at 0.9 (unreachable) and let the failure rule stop the run. The size
// list is drawn for 0.9, so a graded run keeps offering smaller particles that still fit: its
// end is set by `attempts` per particle and `failures` rejections in a row.
void densest(benchmark::State& state, const Grading& grading, double particles,
             std::uint64_t attempts, std::uint64_t failures) {
  const RandomPackOptions options{.container = cube_for(grading, particles, 0.4),
                                  .grading = grading,
                                  .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
                                  .volume_fraction = 0.9,
                                  .max_attempts_per_particle = attempts,
                                  .max_total_attempts = 1000000000,
                                  .max_consecutive_failures = failures,
                                  .seed = 1};
  PackResult result;
  for (auto _ : state) result = pack_random(options);
  check(result, 0.0);
  record(state, result);
}
void BM_DensestSingleSize(benchmark::State& state) {
  densest(state, Grading{.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.01},
          static_cast<double>(state.range(0)), 20000, 200);
}
BENCHMARK(BM_DensestSingleSize)->Arg(5000)->Unit(benchmark::kSecond)->Iterations(1);
void BM_DensestFuller4(benchmark::State& state) {
  densest(state, fuller4(), static_cast<double>(state.range(0)), 2000, 200);
}
BENCHMARK(BM_DensestFuller4)->Arg(20000)->Unit(benchmark::kSecond)->Iterations(1);

// Scaling: the grid packer against the plain O(N^2) approach (every candidate tested against
// every placed particle: bounding spheres, then the exact test) on the same single-size problem
// at 25 % solid.
RandomPackOptions scaling_options(double particles) {
  const Grading grading{.kind = GradingKind::kUniform, .radius_min = 0.01, .radius_max = 0.01};
  return {.container = cube_for(grading, particles, 0.25),
          .grading = grading,
          .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
          .target = PackTarget::kCount,
          .count = static_cast<std::uint64_t>(particles),
          .seed = 1};
}

void BM_ScalingGrid(benchmark::State& state) {
  const RandomPackOptions options = scaling_options(static_cast<double>(state.range(0)));
  PackResult result;
  for (auto _ : state) result = pack_random(options);
  record(state, result);
}
BENCHMARK(BM_ScalingGrid)->RangeMultiplier(2)->Range(1000, 16000)->Unit(benchmark::kMillisecond);

void BM_ScalingBruteForce(benchmark::State& state) {
  const RandomPackOptions options = scaling_options(static_cast<double>(state.range(0)));
  const auto n = static_cast<std::size_t>(options.count);
  const Container& container = options.container;
  std::size_t placed_count = 0;
  for (auto _ : state) {
    // Same shapes and the same candidate rule as the packer, without any broad phase.
    std::vector<ConvexPolyhedron> bodies(n);
    std::vector<double> radius(n);
    for (std::size_t i = 0; i < n; ++i) {
      const GeneratedParticle particle = generate_particle(
          {.alpha = 0.5, .radius_min = 0.01, .radius_max = 0.01, .edge_length = 0.01, .seed = 1},
          i);
      bodies[i] = particle.body;
      radius[i] = bounding_radius(particle.body);
    }
    std::vector<Pose> poses;
    std::vector<std::size_t> placed;
    for (std::size_t i = 0; i < n; ++i) {
      // Centres drawn where the inscribed ball fits, then the exact containment test: the same
      // candidate rule as the packer.
      double inner = 1e300;
      for (std::size_t f = 0; f < bodies[i].triangle_count(); ++f) {
        inner = std::min(
            inner, bodies[i].face_normal(f).dot(bodies[i].vertices()[bodies[i].triangles()[f][0]]));
      }
      const Aabb region = centre_region(container, inner);
      Rng rng(7, i);
      for (int attempt = 0; attempt < 5000; ++attempt) {
        Pose pose;
        pose.position = region.lower + region.extent().cwiseProduct(
                                           Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        pose.rotation = Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized();
        bool is_free = contains(container, bodies[i], pose);
        for (std::size_t k = 0; k < placed.size() && is_free; ++k) {
          const std::size_t j = placed[k];
          is_free = is_separated(bodies[i], pose, radius[i], bodies[j], poses[k], radius[j], 0.0);
        }
        if (is_free) {
          placed.push_back(i);
          poses.push_back(pose);
          break;
        }
      }
    }
    placed_count = placed.size();
  }
  state.counters["placed"] = static_cast<double>(placed_count);
}
BENCHMARK(BM_ScalingBruteForce)
    ->RangeMultiplier(2)
    ->Range(1000, 8000)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
