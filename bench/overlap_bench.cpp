// Overlap tests per second (GJK, aggpack/geom/overlap.h), single thread.
//
// Pair sets (4096 pairs each, particles from generate_particle, alpha 0.2/0.5/0.9, radius
// 0.5..1 m, L = 0.5 m, i.e. L/r = 0.5..1; random orientations):
//   sphere_overlap  centre distance uniform in [0, Ra+Rb): every bounding-sphere pair overlaps;
//   narrow          centre distance uniform in [ra+rb, Ra+Rb) (r = inner radius): no cheap
//                   answer exists, every is_separated call runs GJK;
//   packing_mix     centre uniform in the ball of radius 1.5 (Ra+Rb) (what a grid broad phase
//                   hands over: ~30% of the pairs have overlapping bounding spheres).
// Run: build/bench/overlap_bench --benchmark_min_time=0.5 --benchmark_repetitions=5
//        --benchmark_report_aggregates_only=true
// and read the CPU column of the _min rows (the min aggregate also takes the minimum of the
// items_per_second counter, i.e. the slowest rate; tests/s = 1e9 / min CPU ns).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "aggpack/core/rng.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/shape/generator.h"
#include "support/ellipsoid.h"

namespace {

using namespace aggpack;

struct Pair {
  std::uint32_t a;
  std::uint32_t b;
  Pose pose_a;
  Pose pose_b;
};

struct Pool {
  std::vector<ConvexPolyhedron> bodies;
  std::vector<SupportShape> shapes;
  std::vector<double> radii;
};

Quat random_rotation(Rng& rng) {
  Quat q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
  q.normalize();
  return q;
}

Vec3 random_unit(Rng& rng) { return Vec3(rng.normal(), rng.normal(), rng.normal()).normalized(); }

const Pool& particle_pool() {
  static const Pool pool = [] {
    Pool p;
    for (double alpha : {0.2, 0.5, 0.9}) {
      const GeneratorOptions options{
          .alpha = alpha, .radius_min = 0.5, .radius_max = 1.0, .edge_length = 0.5, .seed = 3};
      for (std::uint64_t i = 0; i < 32; ++i) {
        p.bodies.push_back(generate_particle(options, i).body);
        p.shapes.emplace_back(p.bodies.back());
        p.radii.push_back(bounding_radius(p.bodies.back()));
      }
    }
    return p;
  }();
  return pool;
}

enum class PairSet { kSphereOverlap, kNarrow, kPackingMix };

std::vector<Pair> make_pairs(const Pool& pool, PairSet set) {
  Rng rng(17, static_cast<std::uint64_t>(set));
  std::vector<Pair> pairs;
  const auto count = static_cast<double>(pool.bodies.size());
  while (pairs.size() < 4096) {
    Pair pair;
    pair.a = static_cast<std::uint32_t>(rng.uniform() * count);
    pair.b = static_cast<std::uint32_t>(rng.uniform() * count);
    const double outer = pool.radii[pair.a] + pool.radii[pair.b];
    const double inner = pool.shapes[pair.a].inner_radius() + pool.shapes[pair.b].inner_radius();
    double distance = 0.0;
    switch (set) {
      case PairSet::kSphereOverlap:
        distance = rng.uniform(0.0, outer);
        break;
      case PairSet::kNarrow:
        distance = rng.uniform(inner, outer);
        break;
      case PairSet::kPackingMix:
        distance = 1.5 * outer * std::cbrt(rng.uniform());
        break;
    }
    pair.pose_a = {Vec3(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)),
                   random_rotation(rng)};
    pair.pose_b = {pair.pose_a.position + distance * random_unit(rng), random_rotation(rng)};
    pairs.push_back(pair);
  }
  return pairs;
}

const std::vector<Pair>& pairs_for(PairSet set) {
  static const std::vector<Pair> sets[3] = {make_pairs(particle_pool(), PairSet::kSphereOverlap),
                                            make_pairs(particle_pool(), PairSet::kNarrow),
                                            make_pairs(particle_pool(), PairSet::kPackingMix)};
  return sets[static_cast<int>(set)];
}

void report(benchmark::State& state, std::size_t positives, std::size_t calls) {
  state.SetItemsProcessed(static_cast<std::int64_t>(calls));
  state.counters["separated"] = static_cast<double>(positives) / static_cast<double>(calls);
}

void BM_IsSeparated_Shape(benchmark::State& state) {
  const Pool& pool = particle_pool();
  const auto& pairs = pairs_for(static_cast<PairSet>(state.range(0)));
  std::size_t i = 0, positives = 0, calls = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const bool separated =
        is_separated(pool.shapes[p.a], p.pose_a, pool.shapes[p.b], p.pose_b, 0.0);
    benchmark::DoNotOptimize(separated);
    positives += separated ? 1 : 0;
    ++calls;
    i = (i + 1) & 4095;
  }
  report(state, positives, calls);
}

void BM_IsSeparated_Polyhedron(benchmark::State& state) {
  const Pool& pool = particle_pool();
  const auto& pairs = pairs_for(static_cast<PairSet>(state.range(0)));
  std::size_t i = 0, positives = 0, calls = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const bool separated = is_separated(pool.bodies[p.a], p.pose_a, pool.radii[p.a],
                                        pool.bodies[p.b], p.pose_b, pool.radii[p.b], 0.0);
    benchmark::DoNotOptimize(separated);
    positives += separated ? 1 : 0;
    ++calls;
    i = (i + 1) & 4095;
  }
  report(state, positives, calls);
}

void BM_GjkDistance_Shape(benchmark::State& state) {
  const Pool& pool = particle_pool();
  const auto& pairs = pairs_for(static_cast<PairSet>(state.range(0)));
  std::size_t i = 0, positives = 0, calls = 0, iterations = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const DistanceResult r = gjk_distance(pool.shapes[p.a], p.pose_a, pool.shapes[p.b], p.pose_b);
    benchmark::DoNotOptimize(r);
    positives += r.is_intersecting ? 0 : 1;
    iterations += static_cast<std::size_t>(r.iterations);
    ++calls;
    i = (i + 1) & 4095;
  }
  report(state, positives, calls);
  state.counters["gjk_iterations"] = static_cast<double>(iterations) / static_cast<double>(calls);
}

void BM_GjkDistance_Polyhedron(benchmark::State& state) {
  const Pool& pool = particle_pool();
  const auto& pairs = pairs_for(static_cast<PairSet>(state.range(0)));
  std::size_t i = 0, positives = 0, calls = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const DistanceResult r = gjk_distance(pool.bodies[p.a], p.pose_a, pool.bodies[p.b], p.pose_b);
    benchmark::DoNotOptimize(r);
    positives += r.is_intersecting ? 0 : 1;
    ++calls;
    i = (i + 1) & 4095;
  }
  report(state, positives, calls);
}

// On a shared machine other jobs only ever add time, so the minimum over repetitions is the
// best estimate of the cost (run with --benchmark_repetitions=N).
double minimum(const std::vector<double>& values) {
  return *std::min_element(values.begin(), values.end());
}

void pair_set_args(benchmark::internal::Benchmark* b) {
  b->ArgName("set");  // 0 = sphere_overlap, 1 = narrow, 2 = packing_mix
  for (int set = 0; set < 3; ++set) b->Arg(set);
  b->ComputeStatistics("min", minimum);
}

BENCHMARK(BM_IsSeparated_Shape)->Apply(pair_set_args);
BENCHMARK(BM_IsSeparated_Polyhedron)->Apply(pair_set_args);
BENCHMARK(BM_GjkDistance_Shape)->Apply(pair_set_args);
BENCHMARK(BM_GjkDistance_Polyhedron)->Apply(pair_set_args);

// --- scan vs hill-climbing, on polyhedral ellipsoids (every vertex a hull vertex) -----------

// GJK (is_separated) between two ellipsoids of 2 + 2 r (r - 1) vertices, r = range(1), with the
// support search forced to scan (range(0) = 0) or hill-climb (1).
void BM_EllipsoidIsSeparated(benchmark::State& state) {
  const auto search = state.range(0) == 0 ? SupportSearch::kScan : SupportSearch::kHillClimb;
  const auto rings = static_cast<int>(state.range(1));
  const ConvexPolyhedron body = test::make_ellipsoid(rings, 2 * rings, Vec3(1, 0.7, 0.5));
  const SupportShape shape(body, search);
  Rng rng(23, 0);
  std::vector<Pair> pairs;
  for (int k = 0; k < 4096; ++k) {
    pairs.push_back({0,
                     0,
                     {Vec3::Zero(), random_rotation(rng)},
                     {rng.uniform(0.5, 2.0) * random_unit(rng), random_rotation(rng)}});
  }
  std::size_t i = 0, positives = 0, calls = 0;
  for (auto _ : state) {
    const bool separated = is_separated(shape, pairs[i].pose_a, shape, pairs[i].pose_b, 0.0);
    benchmark::DoNotOptimize(separated);
    positives += separated ? 1 : 0;
    ++calls;
    i = (i + 1) & 4095;
  }
  report(state, positives, calls);
  state.counters["vertices"] = static_cast<double>(shape.vertex_count());
}

BENCHMARK(BM_EllipsoidIsSeparated)
    ->ArgNames({"climb", "rings"})
    ->ArgsProduct({{0, 1}, {3, 4, 5, 6, 8, 12, 20}})
    ->ComputeStatistics("min", minimum);

}  // namespace

BENCHMARK_MAIN();
