// Random aggregate generator throughput (issue 2 item 8): particles per second and time per final
// vertex for alpha in {0.2, 0.5, 0.9} x L/r in {1, 0.5, 0.25} x both growth rules, one thread.
// Target: >= 100,000 particles/s per core at L/r = 0.5. Also the cost of measuring a particle
// (describe) and of the two structural checks, so `aggpack shapes` timings can be split into their
// parts.
//
//   build-gen/generator_bench --benchmark_min_time=1

#include <benchmark/benchmark.h>

#include <cstdint>

#include "aggpack/core/rng.h"
#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"

namespace {

// Benchmark arguments are integers: alpha in percent, L/r in percent and the growth rule
// (0 = hull, the default; 1 = midpoint, aggpack 0.1's).
aggpack::GrowthParams params_from(const benchmark::State& state) {
  const double radius = 0.1;
  return {.alpha = static_cast<double>(state.range(0)) / 100.0,
          .radius = radius,
          .edge_length = radius * static_cast<double>(state.range(1)) / 100.0,
          .form = {.growth =
                       state.range(2) == 0 ? aggpack::Growth::kHull : aggpack::Growth::kMidpoint}};
}

void grid(benchmark::internal::Benchmark* bench) {
  bench->ArgNames({"alpha%", "L/r%", "midpoint"});
  for (const std::int64_t growth : {0, 1}) {
    for (const std::int64_t alpha : {20, 50, 90}) {
      for (const std::int64_t edge : {100, 50, 25}) bench->Args({alpha, edge, growth});
    }
  }
}

// One particle per iteration, each from its own stream as `aggpack shapes` does it.
void BM_GrowAggregate(benchmark::State& state) {
  const auto params = params_from(state);
  std::uint64_t index = 0;
  std::size_t vertices = 0;
  for (auto _ : state) {
    aggpack::Rng rng(1, index++);
    auto body = aggpack::grow_aggregate(params, rng);
    vertices += body.vertex_count();
    benchmark::DoNotOptimize(body);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["vertices/particle"] =
      static_cast<double>(vertices) / static_cast<double>(state.iterations());
  state.counters["s/vertex"] = benchmark::Counter(
      static_cast<double>(vertices), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GrowAggregate)->Apply(grid);

// generate_particle adds the radius draw and the options check on top of grow_aggregate.
void BM_GenerateParticle(benchmark::State& state) {
  const aggpack::GeneratorOptions options{
      .alpha = 0.5, .radius_min = 0.05, .radius_max = 0.1, .edge_length = 0.05, .seed = 7};
  std::uint64_t index = 0;
  for (auto _ : state) {
    auto particle = aggpack::generate_particle(options, index++);
    benchmark::DoNotOptimize(particle);
  }
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GenerateParticle);

// Measuring a particle: mass properties + principal axes (what `aggpack shapes` adds per particle).
void BM_Describe(benchmark::State& state) {
  aggpack::Rng rng(1, 0);
  const auto body =
      aggpack::grow_aggregate({.alpha = 0.5, .radius = 0.1, .edge_length = 0.05}, rng);
  for (auto _ : state) {
    auto descriptors = aggpack::describe(body);
    benchmark::DoNotOptimize(descriptors);
  }
  state.counters["vertices"] = static_cast<double>(body.vertex_count());
  state.counters["particles/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Describe);

void BM_MassProperties(benchmark::State& state) {
  aggpack::Rng rng(1, 0);
  const auto body =
      aggpack::grow_aggregate({.alpha = 0.5, .radius = 0.1, .edge_length = 0.05}, rng);
  for (auto _ : state) benchmark::DoNotOptimize(aggpack::mass_properties(body));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MassProperties);

// The structural checks used by the tests (O(V F) for convexity).
void BM_CheckClosedManifold(benchmark::State& state) {
  aggpack::Rng rng(1, 0);
  const auto body =
      aggpack::grow_aggregate({.alpha = 0.5, .radius = 0.1, .edge_length = 0.05}, rng);
  for (auto _ : state) benchmark::DoNotOptimize(aggpack::check_closed_manifold(body));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CheckClosedManifold);

void BM_CheckConvex(benchmark::State& state) {
  aggpack::Rng rng(1, 0);
  const auto body =
      aggpack::grow_aggregate({.alpha = 0.5, .radius = 0.1, .edge_length = 0.05}, rng);
  for (auto _ : state) benchmark::DoNotOptimize(aggpack::check_convex(body, 1e-10));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CheckConvex);

}  // namespace

BENCHMARK_MAIN();
