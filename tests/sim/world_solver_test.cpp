// The velocity solvers of src/sim/world_solver.cpp. The default sweeps Bullet's rows on compact
// copies; the cache-blocked solver (PhysicsOptions::solver = kBlocked) with one block calls
// Bullet's own row updates in Bullet's order, so the two must agree bit for bit. With many blocks
// (small blocks here, so that small piles have many) the blocked solver keeps the physics checks
// of world_test.cpp: incline, rest on a plane, energy, penetration and creep of a settled pile,
// determinism.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"
#include "aggpack/sim/world.h"
#include "support/packings.h"

namespace aggpack {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

PhysicsOptions blocked(int block_contacts, int block_sweeps = 4) {
  PhysicsOptions options;
  options.solver = SolverKind::kBlocked;
  options.solver_block_contacts = block_contacts;
  options.solver_block_sweeps = block_sweeps;
  return options;
}

using test::box_container;

// per_axis^3 aggregates on a lattice in a unit box, randomly turned.
Packing gas(std::uint64_t seed, int per_axis, double depth) {
  Packing packing = box_container(1.0, 1.0, depth);
  Rng rng(seed, 0);
  // aggpack 0.1's particles (midpoint growth), on which the solver checks below were set.
  const GeneratorOptions generator{.alpha = 0.4,
                                   .radius_min = 0.08,
                                   .radius_max = 0.08,
                                   .edge_length = 0.08,
                                   .seed = 7,
                                   .form = {.growth = Growth::kMidpoint}};
  const double spacing = 1.0 / per_axis;
  for (int index = 0; index < per_axis * per_axis * per_axis; ++index) {
    const ConvexPolyhedron body = generate_particle(generator, index).body;
    packing.shapes.push_back(body.translated(-mass_properties(body).centroid));
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(index);
    particle.pose.position =
        Vec3(spacing * (index % per_axis + 0.5), spacing * (index / per_axis % per_axis + 0.5),
             spacing * (index / (per_axis * per_axis) + 0.5));
    particle.pose.rotation =
        Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized();
    packing.particles.push_back(particle);
  }
  return packing;
}

bool same_poses(const World& a, const World& b) {
  for (std::size_t i = 0; i < a.particle_count(); ++i) {
    const Pose p = a.pose(i);
    const Pose q = b.pose(i);
    if (p.position != q.position || p.rotation.coeffs() != q.rotation.coeffs()) return false;
  }
  return true;
}

TEST(BlockedSolver, OneBlockIsBulletsGaussSeidelBitForBit) {
  const Packing packing = gas(5, 3, 1.0);
  World plain(packing, {});
  World one_block(packing, blocked(1000000, 3));  // 100 sweeps as 33 passes of 3 and one of 1
  World small_blocks(packing, blocked(8));
  plain.step(300);
  one_block.step(300);
  small_blocks.step(300);
  EXPECT_TRUE(same_poses(plain, one_block));
  EXPECT_FALSE(same_poses(plain, small_blocks));  // the blocks do change the rounding
  // With rolling friction (its own rows, found per contact).
  World rolling_plain(packing, {.rolling_friction = 0.1});
  PhysicsOptions options = blocked(1000000);
  options.rolling_friction = 0.1;
  World rolling_one_block(packing, options);
  rolling_plain.step(300);
  rolling_one_block.step(300);
  EXPECT_TRUE(same_poses(rolling_plain, rolling_one_block));
  EXPECT_FALSE(same_poses(plain, rolling_plain));
  EXPECT_EQ(to_string(SolverKind::kBlocked), std::string("blocked"));
  EXPECT_EQ(solver_kind_from_string("gauss-seidel"), SolverKind::kGaussSeidel);
  EXPECT_THROW((void)solver_kind_from_string("jacobi"), InvalidInput);
}

// The default's compact sweeps against Bullet's row updates (one block): particles against each
// other, the static container (Bullet's fixed body, whose rows have a zero side), a kinematic wall
// pushing into the pile (a body of zero inverse mass that Bullet does update), restitution.
TEST(BlockedSolver, DefaultSweepsAreBulletsBitForBitWithStaticAndKinematicWalls) {
  const Packing packing = gas(3, 3, 1.0);
  for (const double restitution : {0.1, 0.6}) {
    PhysicsOptions bullet = blocked(1000000, 1);
    bullet.restitution = restitution;
    World compact(packing, {.restitution = restitution});
    World reference(packing, bullet);
    for (World* world : {&compact, &reference}) {
      world->step(150);
      const std::size_t pusher = world->add_wall(
          {.box = {Vec3(-0.2, 0.0, 0.0), Vec3(0.0, 1.0, 1.0)}, .is_kinematic = true});
      world->set_wall_velocity(pusher, Vec3(0.5, 0.0, 0.0));
      world->step(150);
    }
    EXPECT_GT(compact.pose(0).position.x(), 0.25);  // pushed: it started at x = 1/6
    EXPECT_TRUE(same_poses(compact, reference)) << "restitution " << restitution;
    for (std::size_t i = 0; i < compact.particle_count(); ++i) {
      EXPECT_EQ(compact.linear_velocity(i), reference.linear_velocity(i));
      EXPECT_EQ(compact.angular_velocity(i), reference.angular_velocity(i));
    }
  }
}

TEST(BlockedSolver, SameInputGivesTheSameResult) {
  const Packing packing = gas(5, 3, 1.0);
  World first(packing, blocked(8));
  World second(packing, blocked(8));
  first.step(300);
  second.step(300);
  EXPECT_TRUE(same_poses(first, second));
}

// A cube on the floor with gravity tilted by theta (default solver options: every contact point
// its own block).
double slide_on_incline(double theta, double mu, PhysicsOptions options = blocked(1, 1)) {
  Packing packing = box_container(20.0, 1.0, 1.0);
  const double side = 0.1;
  packing.shapes.push_back(make_box(Vec3::Constant(-side / 2), Vec3::Constant(side / 2)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(1.0, 0.5, side / 2)}});
  options.friction = mu;
  options.wall_friction = mu;
  options.gravity = Vec3(9.81 * std::sin(theta), 0.0, -9.81 * std::cos(theta));
  World world(packing, options);
  world.step(static_cast<std::size_t>(std::round(1.0 / world.time_step())));
  return world.pose(0).position.x() - 1.0;
}

TEST(BlockedSolver, BlockOnAnInclineSlidesIffTanThetaExceedsMu) {
  for (const double mu : {0.2, 0.5, 0.8}) {
    const double critical = std::atan(mu);
    // world_test.cpp's bounds (Gauss-Seidel creeps up to 0.25 mm here, the blocks 0.28 mm).
    EXPECT_LT(std::abs(slide_on_incline(critical - 3.0 * kDegree, mu)), 1e-3) << "mu " << mu;
    EXPECT_GT(slide_on_incline(critical + 3.0 * kDegree, mu), 0.02) << "mu " << mu;
  }
}

// No gravity, a closed box, collisions with restitution 0.5, blocks of 2 contact points. (With
// blocks of 4, seed 1 has one step whose kinetic energy grows by 1e-4 of it: sequential impulses
// with restitution are not strictly dissipative in every order; bench/RESULTS.md.)
TEST(BlockedSolver, KineticEnergyNeverGrowsWithoutInput) {
  for (const std::uint64_t seed : {1u, 2u}) {
    Packing packing = gas(seed, 3, 1.0);
    PhysicsOptions options = blocked(2);
    options.restitution = 0.5;
    options.gravity = Vec3::Zero();
    World world(packing, options);
    Rng rng(seed, 99);
    for (std::size_t i = 0; i < world.particle_count(); ++i) {
      world.set_velocity(i, Vec3(rng.normal(), rng.normal(), rng.normal()),
                         Vec3(rng.normal(), rng.normal(), rng.normal()));
    }
    world.add_wall({.box = {Vec3(-0.5, -0.5, 1.0), Vec3(1.5, 1.5, 1.5)}});  // a lid
    double previous = world.kinetic_energy();
    const double initial = previous;
    for (int step = 0; step < 600; ++step) {
      world.step();
      const double energy = world.kinetic_energy();
      ASSERT_LE(energy, previous * (1.0 + 1e-9) + 1e-12) << "seed " << seed << " step " << step;
      previous = energy;
    }
    EXPECT_LT(previous, 0.9 * initial);
  }
}

// A pile of 64 aggregates settled with `options`: penetration below 1 % of d_min, mechanical
// energy never grows, and once at rest it does not creep. `contacts_at_rest`: its contact points.
void expect_settled_pile_rests(const PhysicsOptions& options, std::size_t& contacts_at_rest) {
  const Packing packing = gas(4, 4, 1.2);
  World world(packing, options);
  const double allowance = 1e-4 * world.total_mass() * 9.81 * world.smallest_size();
  double previous = world.kinetic_energy() + world.potential_energy();
  const auto steps = static_cast<std::size_t>(2.5 / world.time_step());
  for (std::size_t step = 0; step < steps; ++step) {
    world.step();
    const double energy = world.kinetic_energy() + world.potential_energy();
    ASSERT_LE(energy, previous + allowance) << "step " << step;
    previous = energy;
  }
  const ContactStatistics contacts = world.contact_statistics();
  contacts_at_rest = contacts.contact_count;
  EXPECT_LT(contacts.max_contact_penetration, 0.01 * world.smallest_size());
  EXPECT_LT(world.overlap_statistics().max_depth_fraction, 0.01);
  std::vector<Vec3> before;
  for (std::size_t i = 0; i < world.particle_count(); ++i) before.push_back(world.pose(i).position);
  world.step(static_cast<std::size_t>(0.5 / world.time_step()));
  double largest = 0.0;
  for (std::size_t i = 0; i < world.particle_count(); ++i) {
    largest = std::max(largest, (world.pose(i).position - before[i]).norm());
  }
  EXPECT_LT(largest, 0.01 * world.smallest_size());
}

// Many blocks of 16 contact points: as small a penetration as Gauss-Seidel's, and no creep.
TEST(BlockedSolver, SettledPileRestsWithoutPenetrationOrCreep) {
  std::size_t contacts = 0;
  expect_settled_pile_rests(blocked(16), contacts);
  EXPECT_GT(contacts, 100u);  // > 6 blocks
}

// The sweeps stop once no row changes its relative velocity by more than the tolerance: friction
// still holds a cube below its angle and lets it slide above, and a settled pile still rests.
// (The tolerance is 1e-4 m/s: 2.5e-3 of the speed gravity gives in one step of these piles.)
TEST(SolverTolerance, InclineAndSettledPileKeepTheirPhysics) {
  PhysicsOptions options;
  options.solver_tolerance = 1e-4;
  for (const double mu : {0.2, 0.5, 0.8}) {
    const double critical = std::atan(mu);
    EXPECT_LT(std::abs(slide_on_incline(critical - 3.0 * kDegree, mu, options)), 1e-3)
        << "mu " << mu;
    EXPECT_GT(slide_on_incline(critical + 3.0 * kDegree, mu, options), 0.02) << "mu " << mu;
  }
  std::size_t contacts = 0;
  expect_settled_pile_rests(options, contacts);
  EXPECT_GT(contacts, 50u);
}

// The tolerance reaches the sweeps: a coarse one stops them early and the pile moves otherwise.
TEST(SolverTolerance, ACoarseToleranceChangesTheTrajectory) {
  const Packing packing = gas(5, 3, 1.0);
  PhysicsOptions coarse;
  coarse.solver_tolerance = 0.1;
  World full(packing, PhysicsOptions{});
  World early(packing, coarse);
  full.step(300);
  early.step(300);
  EXPECT_FALSE(same_poses(full, early));
}

TEST(SolverTolerance, RejectsBadTolerances) {
  Packing packing = box_container(1.0, 1.0, 1.0);
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.5, 0.5, 0.5)}});
  for (const double tolerance : {-1e-9, 1.5, std::nan("")}) {
    PhysicsOptions options;
    options.solver_tolerance = tolerance;
    EXPECT_THROW(World(packing, options), InvalidInput) << tolerance;
  }
}

TEST(BlockedSolver, RejectsBadBlocks) {
  Packing packing = box_container(1.0, 1.0, 1.0);
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.5, 0.5, 0.5)}});
  EXPECT_THROW(World(packing, blocked(0)), InvalidInput);
  EXPECT_THROW(World(packing, blocked(10, 0)), InvalidInput);
  EXPECT_THROW(World(packing, blocked(10, 1001)), InvalidInput);
}

}  // namespace
}  // namespace aggpack
