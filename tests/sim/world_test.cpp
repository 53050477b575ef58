// The Bullet bridge: mass properties, poses, friction rules, energy, penetration, determinism.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"
#include "aggpack/sim/world.h"
#include "support/packings.h"
#include "support/random_rotation.h"

namespace aggpack {
namespace {

constexpr double kOneDegree = std::numbers::pi / 180.0;

using test::box_container;

// A shape stored with its centroid at the origin (the Packing convention).
ConvexPolyhedron centred(const ConvexPolyhedron& body) {
  return body.translated(-mass_properties(body).centroid);
}

// aggpack 0.1's particles (midpoint growth), on which the physics checks below were set.
ConvexPolyhedron aggregate(std::uint64_t index, double alpha = 0.5, double radius = 0.1) {
  const GeneratorOptions options{.alpha = alpha,
                                 .radius_min = radius,
                                 .radius_max = radius,
                                 .edge_length = radius,
                                 .seed = 7,
                                 .form = {.growth = Growth::kMidpoint}};
  return centred(generate_particle(options, index).body);
}

// A cube of side `side` resting on the floor of a long box, with gravity tilted by `theta` about
// y: the same as a cube on an incline of angle theta.
struct Incline {
  double slide = 0.0;  // m travelled down the slope in `time`
  double time = 0.0;
};

Incline cube_on_incline(double theta, double particle_friction, double wall_friction,
                        double time = 1.0) {
  Packing packing = box_container(20.0, 1.0, 1.0);
  const double side = 0.1;
  packing.shapes.push_back(make_box(Vec3::Constant(-side / 2), Vec3::Constant(side / 2)));
  Particle particle;
  particle.pose.position = Vec3(1.0, 0.5, side / 2);
  packing.particles.push_back(particle);
  World world(packing, {.friction = particle_friction,
                        .wall_friction = wall_friction,
                        .gravity = Vec3(9.81 * std::sin(theta), 0.0, -9.81 * std::cos(theta))});
  world.step(static_cast<std::size_t>(std::round(time / world.time_step())));
  return {.slide = world.pose(0).position.x() - 1.0, .time = world.time()};
}

TEST(World, MassAndInertiaComeFromTheExactPolyhedron) {
  Packing packing = box_container(2.0, 2.0, 2.0);
  Rng rng(3, 0);
  for (std::uint64_t i = 0; i < 4; ++i) {
    packing.shapes.push_back(aggregate(i));
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(i);
    particle.pose.position = Vec3(0.3 + 0.4 * static_cast<double>(i), 1.0, 1.0);
    particle.pose.rotation = test::random_rotation(rng);
    packing.particles.push_back(particle);
  }
  const double density = 2000.0;
  World world(packing, {.density = density, .gravity = Vec3::Zero()});
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const MassProperties mass = mass_properties(packing.shapes[i]);
    EXPECT_NEAR(world.mass(i), density * mass.volume, 1e-12 * world.mass(i));
    // Rotational energy 1/2 w^T I w with I the world inertia of the rotated polyhedron checks
    // that the principal frame is composed with the pose correctly.
    const Vec3 omega(0.3, -1.1, 0.7);
    world.set_velocity(i, Vec3::Zero(), omega);
    const Mat3 rotation = packing.particles[i].pose.rotation.toRotationMatrix();
    const Mat3 inertia = density * rotation * mass.inertia * rotation.transpose();
    const double expected = 0.5 * omega.dot(inertia * omega);
    World single(Packing{.container = packing.container,
                         .shapes = {packing.shapes[i]},
                         .particles = {{.pose = packing.particles[i].pose}},
                         .provenance = {}},
                 {.density = density, .gravity = Vec3::Zero()});
    single.set_velocity(0, Vec3::Zero(), omega);
    EXPECT_NEAR(single.kinetic_energy(), expected, 1e-9 * expected);
  }
}

TEST(World, PosesRoundTripThroughThePrincipalFrame) {
  Packing packing = box_container(2.0, 2.0, 2.0);
  Rng rng(5, 0);
  for (std::uint64_t i = 0; i < 6; ++i) {
    packing.shapes.push_back(aggregate(i, 0.3));
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(i);
    particle.pose.position = Vec3(0.2 + 0.3 * static_cast<double>(i), 1.0, 1.0);
    particle.pose.rotation = test::random_rotation(rng);
    particle.scale = 0.5 + 0.1 * static_cast<double>(i);
    packing.particles.push_back(particle);
  }
  World world(packing, {.gravity = Vec3::Zero()});
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Pose pose = world.pose(i);
    EXPECT_LT((pose.position - packing.particles[i].pose.position).norm(), 1e-12);
    EXPECT_GT(std::abs(pose.rotation.dot(packing.particles[i].pose.rotation)), 1.0 - 1e-12);
  }
}

TEST(World, ParticleAtRestOnAPlaneStaysPut) {
  // A cube placed on the floor, and an aggregate dropped onto it and left to settle: neither may
  // drift afterwards.
  Packing packing = box_container(1.0, 1.0, 1.0);
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.shapes.push_back(aggregate(11));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.25, 0.5, 0.05)}});
  packing.particles.push_back({.shape = 1, .pose = {.position = Vec3(0.7, 0.5, 0.15)}});
  World world(packing, {});
  world.step(static_cast<std::size_t>(1.5 / world.time_step()));
  const Pose cube = world.pose(0);
  const Pose rock = world.pose(1);
  EXPECT_LT((cube.position - packing.particles[0].pose.position).norm(), 1e-4 * 0.1);
  world.step(static_cast<std::size_t>(3.0 / world.time_step()));
  const double size = world.smallest_size();
  EXPECT_LT((world.pose(0).position - cube.position).norm(), 1e-5 * size);
  EXPECT_LT((world.pose(1).position - rock.position).norm(), 1e-3 * size);
  EXPECT_GT(std::abs(world.pose(1).rotation.dot(rock.rotation)), 1.0 - 1e-6);
  EXPECT_LT(world.kinetic_energy(), 1e-9);
  // Resting contact: the cube's face on the floor, penetration far below 1% of the size.
  EXPECT_NEAR(world.pose(0).position.z(), 0.05, 1e-3 * size);
  EXPECT_LT(world.contact_statistics().max_contact_penetration, 1e-3 * size);
}

TEST(World, BlockOnAnInclineSlidesIffTanThetaExceedsMu) {
  for (const double mu : {0.2, 0.5, 0.8}) {
    const double critical = std::atan(mu);
    // Below the friction angle: sticks (any creep far below the block size).
    const Incline below = cube_on_incline(critical - 3.0 * kOneDegree, mu, mu);
    EXPECT_LT(std::abs(below.slide), 1e-3) << "mu " << mu;
    // Above: slides.
    const Incline above = cube_on_incline(critical + 3.0 * kOneDegree, mu, mu);
    EXPECT_GT(above.slide, 0.02) << "mu " << mu;
  }
}

TEST(World, SlidingAccelerationIsCoulombs) {
  // Well above the friction angle the block slides with a = g (sin theta - mu cos theta).
  for (const double mu : {0.0, 0.3, 0.6}) {
    const double theta = std::atan(mu) + 12.0 * kOneDegree;
    const Incline run = cube_on_incline(theta, mu, mu);
    const double expected =
        0.5 * 9.81 * (std::sin(theta) - mu * std::cos(theta)) * run.time * run.time;
    EXPECT_NEAR(run.slide, expected, 0.03 * expected) << "mu " << mu;
  }
}

TEST(World, ParticleAndWallFrictionAreSeparate) {
  const double theta = 25.0 * kOneDegree;  // tan = 0.466
  // The floor is a wall: only the wall coefficient counts for a block on it.
  EXPECT_GT(cube_on_incline(theta, 0.9, 0.3).slide, 0.05);
  EXPECT_LT(std::abs(cube_on_incline(theta, 0.1, 0.8).slide), 1e-3);

  // A small cube on a heavy slab that grips the floor (wall mu 1): particle-particle friction
  // alone decides whether the cube slides on the slab.
  for (const double mu_particle : {0.3, 0.8}) {
    Packing packing = box_container(20.0, 2.0, 1.0);
    packing.shapes.push_back(make_box(Vec3(-0.5, -0.5, -0.05), Vec3(0.5, 0.5, 0.05)));
    packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
    packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(2.0, 1.0, 0.05)}});
    packing.particles.push_back({.shape = 1, .pose = {.position = Vec3(1.7, 1.0, 0.15)}});
    World world(packing, {.friction = mu_particle,
                          .wall_friction = 1.0,
                          .gravity = Vec3(9.81 * std::sin(theta), 0.0, -9.81 * std::cos(theta))});
    world.step(static_cast<std::size_t>(0.5 / world.time_step()));
    const double slab = world.pose(0).position.x() - 2.0;
    const double cube = world.pose(1).position.x() - 1.7;
    EXPECT_LT(std::abs(slab), 1e-3) << "mu " << mu_particle;
    if (mu_particle < std::tan(theta)) {
      EXPECT_GT(cube - slab, 0.05) << "mu " << mu_particle;
    } else {
      EXPECT_LT(std::abs(cube - slab), 1e-3) << "mu " << mu_particle;
    }
  }
}

Packing gas(std::uint64_t seed, int per_axis) {
  Packing packing = box_container(1.0, 1.0, 1.0);
  Rng rng(seed, 0);
  int index = 0;
  for (int k = 0; k < per_axis; ++k) {
    for (int j = 0; j < per_axis; ++j) {
      for (int i = 0; i < per_axis; ++i) {
        packing.shapes.push_back(aggregate(static_cast<std::uint64_t>(index), 0.4, 0.08));
        Particle particle;
        particle.shape = static_cast<std::uint32_t>(index++);
        const double spacing = 1.0 / per_axis;
        particle.pose.position =
            Vec3(spacing * (i + 0.5), spacing * (j + 0.5), spacing * (k + 0.5));
        particle.pose.rotation = test::random_rotation(rng);
        packing.particles.push_back(particle);
      }
    }
  }
  return packing;
}

TEST(World, KineticEnergyNeverGrowsWithoutInput) {
  // No gravity: particles fly around a closed box and collide; every collision may only lose
  // energy (restitution <= 1, Coulomb friction, split-impulse position correction).
  for (const std::uint64_t seed : {1u, 2u}) {
    Packing packing = gas(seed, 3);
    packing.container.get_if<BoxContainer>()->depth = 1.0;
    World world(packing, {.restitution = 0.5, .gravity = Vec3::Zero()});
    Rng rng(seed, 99);
    for (std::size_t i = 0; i < world.particle_count(); ++i) {
      world.set_velocity(i, Vec3(rng.normal(), rng.normal(), rng.normal()),
                         Vec3(rng.normal(), rng.normal(), rng.normal()));
    }
    // The lid: the container's top is open, close it for the test.
    world.add_wall({.box = {Vec3(-0.5, -0.5, 1.0), Vec3(1.5, 1.5, 1.5)}});
    double previous = world.kinetic_energy();
    const double initial = previous;
    int collisions = 0;
    for (int step = 0; step < 600; ++step) {
      world.step();
      const double energy = world.kinetic_energy();
      ASSERT_LE(energy, previous * (1.0 + 1e-9) + 1e-12) << "seed " << seed << " step " << step;
      if (energy < previous * (1.0 - 1e-6)) ++collisions;
      previous = energy;
    }
    EXPECT_GT(collisions, 10);  // the test did exercise collisions
    EXPECT_LT(previous, 0.9 * initial);
  }
}

TEST(World, MechanicalEnergyNeverGrowsUnderGravity) {
  Packing packing = gas(3, 3);
  packing.container.get_if<BoxContainer>()->depth = 1.5;
  World world(packing, {.restitution = 0.3});
  const double initial = world.kinetic_energy() + world.potential_energy();
  double previous = initial;
  // Split-impulse position correction lifts a particle out of a penetration without touching its
  // velocity, so the potential energy may rise by m g x (the correction, a small fraction of the
  // penetration) in a step: allow the work of lifting every particle by 1e-4 of its size.
  const double allowance = 1e-4 * world.total_mass() * 9.81 * world.smallest_size();
  for (int step = 0; step < 600; ++step) {
    world.step();
    const double energy = world.kinetic_energy() + world.potential_energy();
    ASSERT_LE(energy, previous + allowance) << "step " << step;
    previous = energy;
  }
  EXPECT_LT(previous, initial - 0.1 * (initial - world.potential_energy()));
}

TEST(World, PenetrationInASettledPileStaysBelowOnePercent) {
  Packing packing = gas(4, 4);
  packing.container.get_if<BoxContainer>()->depth = 1.2;
  World world(packing, {});
  world.step(static_cast<std::size_t>(2.5 / world.time_step()));
  const ContactStatistics contacts = world.contact_statistics();
  const OverlapStatistics overlap = world.overlap_statistics();
  EXPECT_GT(contacts.contact_count, 50u);
  EXPECT_LT(contacts.max_contact_penetration, 0.01 * world.smallest_size());
  EXPECT_GT(overlap.overlapping_pairs, 0u);  // resting neighbours touch
  EXPECT_LT(overlap.max_depth_fraction, 0.01);
}

TEST(World, SameInputGivesTheSameResult) {
  const Packing packing = gas(5, 3);
  World first(packing, {});
  World second(packing, {});
  first.step(300);
  second.step(300);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Pose a = first.pose(i);
    const Pose b = second.pose(i);
    EXPECT_EQ(a.position.x(), b.position.x());
    EXPECT_EQ(a.position.y(), b.position.y());
    EXPECT_EQ(a.position.z(), b.position.z());
    EXPECT_EQ(a.rotation.coeffs(), b.rotation.coeffs());
  }
}

TEST(World, KinematicWallPushesParticles) {
  Packing packing = box_container(4.0, 1.0, 1.0);
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(1.0, 0.5, 0.05)}});
  World world(packing, {.friction = 0.2, .wall_friction = 0.2});
  const std::size_t pusher =
      world.add_wall({.box = {Vec3(0.5, 0.0, 0.0), Vec3(0.6, 1.0, 0.5)}, .is_kinematic = true});
  world.set_wall_velocity(pusher, Vec3(0.5, 0.0, 0.0));
  world.step(static_cast<std::size_t>(2.0 / world.time_step()));
  EXPECT_NEAR(world.wall_box(pusher).lower.x(), 1.5, 0.01);
  // The cube was pushed: its back face stays in front of the wall's face.
  EXPECT_NEAR(world.pose(0).position.x() - 0.05, world.wall_box(pusher).upper.x(), 0.01);
  EXPECT_TRUE(world.is_wall_touched(pusher, 0.001));
  world.remove_wall(pusher);
  EXPECT_THROW(world.remove_wall(pusher), InvalidInput);
}

TEST(World, RejectsBadInput) {
  Packing packing = box_container(1.0, 1.0, 1.0);
  EXPECT_THROW(World(packing, {}), InvalidInput);  // no particles
  packing.shapes.push_back(make_box(Vec3::Constant(-0.05), Vec3::Constant(0.05)));
  packing.particles.push_back({.shape = 0, .pose = {.position = Vec3(0.5, 0.5, 0.5)}});
  try {
    World world(packing, {.friction = -0.1});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "friction");
  }
  EXPECT_THROW(World(packing, {.density = 0.0}), InvalidInput);
  EXPECT_THROW(World(packing, {.restitution = 1.5}), InvalidInput);
  EXPECT_THROW(World(packing, {.solver_iterations = 0}), InvalidInput);
  packing.particles[0].shape = 3;
  EXPECT_THROW(World(packing, {}), InvalidInput);
}

}  // namespace
}  // namespace aggpack
