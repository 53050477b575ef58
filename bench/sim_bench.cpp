// Physics benchmarks (bench/RESULTS.md, section "Physics"): Bullet steps per second of a settling
// pile of the paper's particles (alpha 0.5, R = L = 0.1 m, density 2650 kg/m^3, mu_s 0.5, the
// World defaults: automatic time step 0.004 s, 100 solver iterations).
//
//   build-main/bench/sim_bench --benchmark_filter=SettlingPile
//
// A lattice of 10 layers (2 m high) is released in a box whose footprint holds it; the first
// 0.6 s (free fall of the top layer onto the pile forming below, untimed) brings it into contact,
// then the next 0.4 s of settling (100 steps) are timed: every particle is in contact then, which
// is the state that dominates a settle or repose run. Counters: steps per second (wall clock, and
// per CPU second of this process: the machine is often shared, and a loaded machine stretches the
// wall time but hardly the CPU time), particle-steps per second, and contacts per particle at the
// end. Instruction counts per step: bench/sim_profile.cpp. The third argument selects the velocity
// solver: 0 = Bullet's Gauss-Seidel (the default), k > 0 = the cache-blocked solver with k sweeps
// per block (PhysicsOptions::solver = kBlocked, 1,000 contacts per block):
//
//   build/bench/sim_bench --benchmark_filter=SettlingPile/50/20/4

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <ctime>

#include "aggpack/pack/lattice_packer.h"
#include "aggpack/sim/world.h"

namespace {

using namespace aggpack;

constexpr double kWarmUp = 0.6;  // s simulated, untimed
constexpr std::size_t kTimedSteps = 100;

// `nx` x `ny` x 10 lattice sites of the paper's particles, spacing 2R = 0.2 m.
Packing lattice(int nx, int ny) {
  LatticeOptions options;
  options.container.get_if<BoxContainer>()->length = 0.2 * nx;
  options.container.get_if<BoxContainer>()->width = 0.2 * ny;
  options.container.get_if<BoxContainer>()->depth = 2.0;
  options.container.wall_gap = 0.0;
  return pack_lattice(options).packing;
}

void BM_SettlingPile(benchmark::State& state) {
  const int nx = static_cast<int>(state.range(0));
  const int ny = static_cast<int>(state.range(1));
  const int block_sweeps = static_cast<int>(state.range(2));
  const Packing packing = lattice(nx, ny);
  PhysicsOptions options;
  if (block_sweeps > 0) {
    options.solver = SolverKind::kBlocked;
    options.solver_block_sweeps = block_sweeps;
  }
  for (auto _ : state) {
    state.PauseTiming();
    World world(packing, options);
    world.step(static_cast<std::size_t>(kWarmUp / world.time_step() + 0.5));
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    world.step(kTimedSteps);
    const double cpu_seconds =
        static_cast<double>(std::clock() - cpu_start) / static_cast<double>(CLOCKS_PER_SEC);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.PauseTiming();
    const auto contacts = world.contact_statistics();
    const double particles = static_cast<double>(world.particle_count());
    state.counters["particles"] = particles;
    state.counters["steps_per_s"] = static_cast<double>(kTimedSteps) / seconds;
    state.counters["steps_per_cpu_s"] = static_cast<double>(kTimedSteps) / cpu_seconds;
    state.counters["particle_steps_per_s"] = particles * static_cast<double>(kTimedSteps) / seconds;
    state.counters["contacts_per_particle"] =
        static_cast<double>(contacts.contact_count) / particles;
    std::printf(
        "  %zu particles: %zu steps of %.4g s in %.2f s wall (%.2f s CPU), %.2f steps/s wall, %.2f "
        "steps per CPU s, max speed %.3g m/s\n",
        world.particle_count(), kTimedSteps, world.time_step(), seconds, cpu_seconds,
        static_cast<double>(kTimedSteps) / seconds, static_cast<double>(kTimedSteps) / cpu_seconds,
        world.max_speed());
    state.ResumeTiming();
  }
}
// 10 x 10 x 10 = 1,000 and 50 x 20 x 10 = 10,000 particles; Gauss-Seidel, then blocked.
BENCHMARK(BM_SettlingPile)
    ->Args({10, 10, 0})
    ->Args({50, 20, 0})
    ->Args({10, 10, 4})
    ->Args({50, 20, 4})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
