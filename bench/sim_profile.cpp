// Per-step profile of the Bullet bridge (bench/RESULTS.md, "Physics speed"): callgrind counts
// instructions, which a loaded machine does not change, but the settling pile of sim_bench needs
// 150 steps to reach contact, far too slow under valgrind at 10,000 particles. So the state is
// prepared natively once, and the profiled run reloads it (poses and velocities; contact
// manifolds and warm-start impulses are rebuilt during the untimed settle steps):
//
//   build/bench/sim_profile prepare NX NY STATE TIME    lattice NX x NY x 10, TIME s simulated
//   valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no
//            build/bench/sim_profile run NX NY STATE SETTLE MEASURE
//
// `run` steps SETTLE times uninstrumented, then MEASURE times with callgrind collecting (the
// counts are per MEASURE steps), and prints wall and CPU seconds per step when run natively.
// The lattice and settings are sim_bench's (World defaults); an optional last argument SWEEPS > 0
// runs `run` with the cache-blocked solver (PhysicsOptions::solver = kBlocked, SWEEPS per block).
//
//   build/bench/sim_profile check NX NY SWEEPS TIME CREEP [ITERATIONS [TOLERANCE]]
//
// validates a solver on a large pile: the lattice settles TIME s from rest (SWEEPS 0 =
// Gauss-Seidel), then prints the state (contacts, deepest contact and exact overlap relative to
// d_min, mean height, kinetic energy) and how far the particles move during CREEP more seconds
// (mean and largest displacement, sinking of the mean height): a pile at rest should not creep.
// ITERATIONS sets PhysicsOptions::solver_iterations (default 100), TOLERANCE
// PhysicsOptions::solver_tolerance (m/s, default 0).

#include <valgrind/callgrind.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "aggpack/pack/lattice_packer.h"
#include "aggpack/sim/world.h"

namespace {

using namespace aggpack;

Packing lattice(int nx, int ny) {
  LatticeOptions options;
  options.container.get_if<BoxContainer>()->length = 0.2 * nx;
  options.container.get_if<BoxContainer>()->width = 0.2 * ny;
  options.container.get_if<BoxContainer>()->depth = 2.0;
  options.container.wall_gap = 0.0;
  return pack_lattice(options).packing;
}

using State = std::array<double, 13>;  // position, quaternion (w x y z), linear, angular velocity

int prepare(int nx, int ny, const char* path, double time) {
  World world(lattice(nx, ny), {});
  world.step(static_cast<std::size_t>(time / world.time_step() + 0.5));
  std::ofstream out(path, std::ios::binary);
  for (std::size_t i = 0; i < world.particle_count(); ++i) {
    const Pose p = world.pose(i);
    const Vec3 v = world.linear_velocity(i);
    const Vec3 w = world.angular_velocity(i);
    const State s = {p.position.x(), p.position.y(), p.position.z(), p.rotation.w(), p.rotation.x(),
                     p.rotation.y(), p.rotation.z(), v.x(),          v.y(),          v.z(),
                     w.x(),          w.y(),          w.z()};
    out.write(reinterpret_cast<const char*>(s.data()), sizeof(State));
  }
  return out ? 0 : 1;
}

PhysicsOptions solver_options(int block_sweeps) {
  PhysicsOptions options;
  if (block_sweeps > 0) {
    options.solver = SolverKind::kBlocked;
    options.solver_block_sweeps = block_sweeps;
  }
  return options;
}

double mean_height(const World& world) {
  return world.potential_energy() / (world.total_mass() * 9.81);
}

int check(int nx, int ny, int block_sweeps, double time, double creep, int iterations,
          double tolerance) {
  PhysicsOptions options = solver_options(block_sweeps);
  options.solver_iterations = iterations;
  options.solver_tolerance = tolerance;
  World world(lattice(nx, ny), options);
  const double d = world.smallest_size();
  const std::clock_t cpu_start = std::clock();
  world.step(static_cast<std::size_t>(time / world.time_step() + 0.5));
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const auto contacts = world.contact_statistics();
  const auto overlaps = world.overlap_statistics();
  const double particles = static_cast<double>(world.particle_count());
  std::printf(
      "%s, %d iterations, tolerance %g m/s, %zu particles, %.2f s settled (%zu steps, %.1f s CPU): "
      "contacts per "
      "particle %.3f, "
      "deepest contact %.3f%% of d_min, deepest exact overlap %.3f%% of d_min, mean height %.5f m, "
      "kinetic energy %.4g J, max speed %.3g m/s\n",
      block_sweeps > 0 ? "blocked" : "gauss-seidel", iterations, tolerance, world.particle_count(),
      world.time(), world.step_count(), cpu,
      static_cast<double>(contacts.contact_count) / particles,
      100.0 * contacts.max_contact_penetration / d, 100.0 * overlaps.max_depth_fraction,
      mean_height(world), world.kinetic_energy(), world.max_speed());
  std::vector<Vec3> before(world.particle_count());
  for (std::size_t i = 0; i < before.size(); ++i) before[i] = world.pose(i).position;
  const double height = mean_height(world);
  const std::clock_t creep_start = std::clock();
  world.step(static_cast<std::size_t>(creep / world.time_step() + 0.5));
  const double creep_cpu = static_cast<double>(std::clock() - creep_start) / CLOCKS_PER_SEC;
  double sum = 0.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const double moved = (world.pose(i).position - before[i]).norm();
    sum += moved;
    largest = std::max(largest, moved);
  }
  std::printf(
      "  creep over %.2f s (%.1f s CPU): mean displacement %.4f%% of d_min, largest %.3f%% of "
      "d_min, mean "
      "height %+.4f%% of d_min; then kinetic energy %.4g J, deepest contact %.3f%% of d_min\n",
      creep, creep_cpu, 100.0 * sum / particles / d, 100.0 * largest / d,
      100.0 * (mean_height(world) - height) / d, world.kinetic_energy(),
      100.0 * world.contact_statistics().max_contact_penetration / d);
  return 0;
}

int run(int nx, int ny, const char* path, int settle, int measure, int block_sweeps) {
  Packing packing = lattice(nx, ny);
  std::ifstream in(path, std::ios::binary);
  std::vector<State> states(packing.particles.size());
  for (auto& s : states) in.read(reinterpret_cast<char*>(s.data()), sizeof(State));
  if (!in) {
    std::fprintf(stderr, "sim_profile: %s does not hold %zu particles\n", path, states.size());
    return 1;
  }
  for (std::size_t i = 0; i < states.size(); ++i) {
    const State& s = states[i];
    packing.particles[i].pose.position = Vec3(s[0], s[1], s[2]);
    packing.particles[i].pose.rotation = Quat(s[3], s[4], s[5], s[6]).normalized();
  }
  World world(packing, solver_options(block_sweeps));
  for (std::size_t i = 0; i < states.size(); ++i) {
    const State& s = states[i];
    world.set_velocity(i, Vec3(s[7], s[8], s[9]), Vec3(s[10], s[11], s[12]));
  }
  world.step(static_cast<std::size_t>(settle));
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_TOGGLE_COLLECT;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  world.step(static_cast<std::size_t>(measure));
  const std::clock_t cpu_end = std::clock();
  const auto end = std::chrono::steady_clock::now();
  CALLGRIND_TOGGLE_COLLECT;
  CALLGRIND_STOP_INSTRUMENTATION;
  const auto contacts = world.contact_statistics();
  const double particles = static_cast<double>(world.particle_count());
  std::printf(
      "%zu particles, %d steps: %.4f s wall, %.4f s CPU per step; contacts per particle %.2f, "
      "max speed %.3g m/s, kinetic energy %.6g J\n",
      world.particle_count(), measure, std::chrono::duration<double>(end - start).count() / measure,
      static_cast<double>(cpu_end - cpu_start) / CLOCKS_PER_SEC / measure,
      static_cast<double>(contacts.contact_count) / particles, world.max_speed(),
      world.kinetic_energy());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "prepare" && argc == 6) {
    return prepare(std::atoi(argv[2]), std::atoi(argv[3]), argv[4], std::atof(argv[5]));
  }
  if (mode == "run" && (argc == 7 || argc == 8)) {
    return run(std::atoi(argv[2]), std::atoi(argv[3]), argv[4], std::atoi(argv[5]),
               std::atoi(argv[6]), argc == 8 ? std::atoi(argv[7]) : 0);
  }
  if (mode == "check" && argc >= 7 && argc <= 9) {
    return check(std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]), std::atof(argv[5]),
                 std::atof(argv[6]), argc >= 8 ? std::atoi(argv[7]) : 100,
                 argc == 9 ? std::atof(argv[8]) : 0.0);
  }
  std::fprintf(stderr,
               "usage: sim_profile prepare NX NY STATE TIME | run NX NY STATE SETTLE MEASURE "
               "[SWEEPS] | check NX NY SWEEPS TIME CREEP [ITERATIONS [TOLERANCE]]\n");
  return 2;
}
