#include "aggpack/sim/world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "world_impl.h"

namespace aggpack {

namespace {

constexpr double kStandardGravity = 9.81;  // m/s^2, only to turn d_min into a time scale

// Bullet's default combiners multiply the two bodies' coefficients, which cannot give
// particle-particle and particle-wall friction independently (a particle-wall pair would get
// mu_particle * mu_wall). These rules make the coefficient of a pair explicit: a wall (static or
// kinematic body) against a particle uses the wall's value, two particles use the geometric mean
// (every particle carries the same value, so that is exactly mu). The callbacks are pure functions
// of the two bodies and are installed once per process, before any world exists.
btScalar combine_friction(const btCollisionObject* a, const btCollisionObject* b) {
  const bool is_wall_a = a->isStaticOrKinematicObject();
  const bool is_wall_b = b->isStaticOrKinematicObject();
  if (is_wall_a != is_wall_b) return is_wall_a ? a->getFriction() : b->getFriction();
  return std::sqrt(a->getFriction() * b->getFriction());
}

btScalar combine_restitution(const btCollisionObject* a, const btCollisionObject* b) {
  const bool is_wall_a = a->isStaticOrKinematicObject();
  const bool is_wall_b = b->isStaticOrKinematicObject();
  if (is_wall_a != is_wall_b) return is_wall_a ? a->getRestitution() : b->getRestitution();
  return std::sqrt(a->getRestitution() * b->getRestitution());
}

// Rolling friction carries a length (mu_r times the particle's radius, set per body): a wall takes
// the particle's, two particles the mean of theirs.
btScalar combine_rolling_friction(const btCollisionObject* a, const btCollisionObject* b) {
  const bool is_wall_a = a->isStaticOrKinematicObject();
  const bool is_wall_b = b->isStaticOrKinematicObject();
  if (is_wall_a != is_wall_b) return is_wall_a ? b->getRollingFriction() : a->getRollingFriction();
  return 0.5 * (a->getRollingFriction() + b->getRollingFriction());
}

btScalar no_spinning_friction(const btCollisionObject*, const btCollisionObject*) { return 0.0; }

void install_combiners() {
  static std::once_flag flag;
  std::call_once(flag, [] {
    gCalculateCombinedFrictionCallback = &combine_friction;
    gCalculateCombinedRestitutionCallback = &combine_restitution;
    gCalculateCombinedRollingFrictionCallback = &combine_rolling_friction;
    gCalculateCombinedSpinningFrictionCallback = &no_spinning_friction;
  });
}

}  // namespace

using detail::from_bt;
using detail::to_bt;

void validate(const PhysicsOptions& options) {
  require_positive("density", options.density);
  require_in_range("friction", options.friction, 0.0, 10.0);
  if (options.wall_friction) require_in_range("wall_friction", *options.wall_friction, 0.0, 10.0);
  require_in_range("restitution", options.restitution, 0.0, 1.0);
  require_in_range("rolling_friction", options.rolling_friction, 0.0, 1.0);
  for (int axis = 0; axis < 3; ++axis) {
    require_in_range("gravity", options.gravity[axis], -1000.0, 1000.0);
  }
  require_in_range("time_step", options.time_step, 0.0, 1.0);
  require_in_range("time_step_factor", options.time_step_factor, 1e-6, 1.0);
  if (options.solver_iterations < 1 || options.solver_iterations > 1000) {
    throw InvalidInput("solver_iterations", std::to_string(options.solver_iterations), "[1, 1000]");
  }
  require_in_range("solver_tolerance", options.solver_tolerance, 0.0, 1.0);
  require_in_range("margin_fraction", options.margin_fraction, 1e-4, 0.1);
  if (options.solver_block_contacts < 1 || options.solver_block_contacts > 1000000) {
    throw InvalidInput("solver_block_contacts", std::to_string(options.solver_block_contacts),
                       "[1, 1000000]");
  }
  if (options.solver_block_sweeps < 1 || options.solver_block_sweeps > 1000) {
    throw InvalidInput("solver_block_sweeps", std::to_string(options.solver_block_sweeps),
                       "[1, 1000]");
  }
}

World::Impl::~Impl() {
  if (!world) return;
  // Empty the pair cache first, newest pair first (O(1) each). Removing a body scans every
  // pair for its proxy, so with the pairs still there tearing down 10,000 particles cost
  // O(particles x pairs), seconds at 10,000.
  btOverlappingPairCache* cache = world->getPairCache();
  btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
  while (pairs.size() > 0) {
    const btBroadphasePair& last = pairs[pairs.size() - 1];
    cache->removeOverlappingPair(last.m_pProxy0, last.m_pProxy1, dispatcher.get());
  }
  for (auto& wall : walls) {
    if (!wall.is_removed) world->removeRigidBody(wall.body.get());
  }
  for (auto& body : bodies) world->removeRigidBody(body.get());
  world.reset();
}

void World::Impl::build_world() {
  configuration = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
  dispatcher->setNearCallback(&Impl::near_callback);

  broadphase = std::make_unique<btDbvtBroadphase>();
  const bool is_blocked = options.solver == SolverKind::kBlocked;
  solver = std::make_unique<detail::OrderedSolver>(is_blocked ? options.solver_block_contacts : 0,
                                                   options.solver_block_sweeps);
  world = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), broadphase.get(),
                                                    solver.get(), configuration.get());
  world->setGravity(to_bt(scale * options.gravity));
  auto& info = world->getSolverInfo();
  info.m_numIterations = options.solver_iterations;
  // The solver's residual is a row's change of relative velocity in sim units, squared.
  info.m_leastSquaresResidualThreshold =
      static_cast<btScalar>(scale * options.solver_tolerance * scale * options.solver_tolerance);
  // Two friction directions with Bullet's implicit cone: static friction holds in every tangential
  // direction (one direction lets a resting particle drift sideways). No SOLVER_RANDMIZE_ORDER:
  // a fixed constraint order keeps runs bit-identical.
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_USE_2_FRICTION_DIRECTIONS;
  // Correct every penetration with split impulses (position only): Baumgarte correction feeds
  // the positional error into the velocity and so adds kinetic energy that was never put in.
  info.m_splitImpulse = 1;
  info.m_splitImpulsePenetrationThreshold = BT_LARGE_FLOAT;
  info.m_erp2 = 0.4;

  info.m_timeStep = time_step;
}

void World::Impl::add_particles() {
  bodies.reserve(packing.particles.size());
  bounding_radius.reserve(packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const auto& particle = packing.particles[i];
    const auto& shape = shapes[body_shape[i]];
    const double mass = options.density * shape.volume;
    // Bullet's body works in sim lengths; its inertia must be too (I scales with length^2).
    const Vec3 inertia = options.density * shape.unit_inertia * scale * scale;
    btRigidBody::btRigidBodyConstructionInfo construction(mass, nullptr, shape.hull.get(),
                                                          to_bt(inertia));
    construction.m_friction = options.friction;
    construction.m_restitution = options.restitution;
    construction.m_rollingFriction = options.rolling_friction * 0.5 * shape.size * scale;
    construction.m_linearSleepingThreshold = 0.0;
    construction.m_angularSleepingThreshold = 0.0;
    auto body = std::make_unique<btRigidBody>(construction);
    const Quat rotation = (particle.pose.rotation * shape.principal).normalized();
    const Vec3 centre = particle.pose.apply(shape.centroid);
    btTransform transform;
    transform.setOrigin(to_bt(scale * centre));
    transform.setRotation(to_bt(rotation));
    body->setWorldTransform(transform);
    body->setInterpolationWorldTransform(transform);
    body->setActivationState(DISABLE_DEACTIVATION);
    body->setUserIndex(static_cast<int>(i));
    body->setUserPointer(this);
    double radius = 0.0;
    for (int v = 0; v < shape.hull->getNumPoints(); ++v) {
      radius = std::max(radius, static_cast<double>(shape.hull->getUnscaledPoints()[v].length()));
    }
    bounding_radius.push_back(radius + margin);
    breaking_threshold = std::max(
        breaking_threshold,
        static_cast<double>(shape.hull->getContactBreakingThreshold(gContactBreakingThreshold)));
    world->addRigidBody(body.get());
    bodies.push_back(std::move(body));
  }
}

World::World(const Packing& packing, const PhysicsOptions& options, double wall_height)
    : impl_(std::make_unique<Impl>()) {
  validate(options);
  if (packing.particles.empty()) throw InvalidInput("particles", "0", ">= 1 particle");
  require_in_range("wall_height", wall_height, 0.0, 1e6);
  install_combiners();
  auto& impl = *impl_;
  impl.packing = packing;
  impl.options = options;
  impl.build_shapes();
  double largest = 0.0;
  for (const auto index : impl.body_shape) {
    largest = std::max(largest, impl.shapes[index].size);
  }
  impl.wall_thickness = 2.0 * largest;
  impl.time_step = options.time_step > 0.0 ? options.time_step
                                           : options.time_step_factor *
                                                 std::sqrt(impl.smallest_size / kStandardGravity);
  impl.build_world();
  impl.add_container_walls(wall_height);
  impl.add_particles();
}

World::~World() = default;

void World::step(std::size_t count) {
  auto& impl = *impl_;
  for (std::size_t n = 0; n < count; ++n) {
    // Kinematic walls: Bullet reads the new transform from the motion state and derives the
    // velocity the contacts see from the motion over the step.
    for (auto& wall : impl.walls) {
      if (!wall.is_kinematic || wall.is_removed) continue;
      btTransform transform;
      wall.motion->getWorldTransform(transform);
      transform.setOrigin(transform.getOrigin() +
                          to_bt(impl.scale * impl.time_step * wall.velocity));
      wall.motion->setWorldTransform(transform);
    }
    // maxSubSteps = 0: exactly one internal step of time_step, no interpolation.
    impl.world->stepSimulation(impl.time_step, 0, impl.time_step);
    ++impl.steps;
    impl.time = static_cast<double>(impl.steps) * impl.time_step;
  }
}

double World::time() const { return impl_->time; }
double World::time_step() const { return impl_->time_step; }
std::size_t World::step_count() const { return impl_->steps; }
std::size_t World::particle_count() const { return impl_->bodies.size(); }
double World::smallest_size() const { return impl_->smallest_size; }
double World::median_size() const { return impl_->median_size; }
double World::margin() const { return impl_->margin / impl_->scale; }

double World::kinetic_energy() const {
  double energy = 0.0;
  for (const auto& body : impl_->bodies) {
    const btVector3 v = body->getLinearVelocity();
    const btVector3 w = body->getAngularVelocity();
    // Angular part in the body (principal) frame where the inertia is diagonal.
    const btVector3 local_w = body->getWorldTransform().getBasis().transpose() * w;
    const btVector3 inverse = body->getInvInertiaDiagLocal();
    double rotational = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      if (inverse[axis] > 0.0) rotational += local_w[axis] * local_w[axis] / inverse[axis];
    }
    energy += 0.5 * v.length2() / body->getInvMass() + 0.5 * rotational;
  }
  return energy / (impl_->scale * impl_->scale);
}

double World::potential_energy() const {
  double energy = 0.0;
  for (const auto& body : impl_->bodies) {
    const Vec3 x = from_bt(body->getWorldTransform().getOrigin()) / impl_->scale;
    energy -= x.dot(impl_->options.gravity) / body->getInvMass();
  }
  return energy;
}

double World::total_mass() const {
  double mass = 0.0;
  for (const auto& body : impl_->bodies) mass += 1.0 / body->getInvMass();
  return mass;
}

double World::max_speed() const {
  double speed = 0.0;
  for (const auto& body : impl_->bodies) {
    speed = std::max(speed, static_cast<double>(body->getLinearVelocity().length()));
  }
  return speed / impl_->scale;
}

bool World::is_finite() const {
  for (const auto& body : impl_->bodies) {
    const btTransform& transform = body->getWorldTransform();
    const btQuaternion rotation = transform.getRotation();
    const btVector3 values[] = {transform.getOrigin(), body->getLinearVelocity(),
                                body->getAngularVelocity(),
                                btVector3(rotation.x(), rotation.y(), rotation.z())};
    for (const auto& v : values) {
      if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) return false;
    }
    if (!std::isfinite(rotation.w())) return false;
  }
  return true;
}

Pose World::pose(std::size_t i) const {
  const auto& impl = *impl_;
  const auto& shape = impl.shapes[impl.body_shape.at(i)];
  const btTransform& transform = impl.bodies[i]->getWorldTransform();
  Pose pose;
  pose.rotation = (from_bt(transform.getRotation()) * shape.principal.conjugate()).normalized();
  pose.position = from_bt(transform.getOrigin()) / impl.scale - pose.rotation * shape.centroid;
  return pose;
}

Vec3 World::linear_velocity(std::size_t i) const {
  return from_bt(impl_->bodies.at(i)->getLinearVelocity()) / impl_->scale;
}

Vec3 World::angular_velocity(std::size_t i) const {
  return from_bt(impl_->bodies.at(i)->getAngularVelocity());
}

void World::set_velocity(std::size_t i, const Vec3& linear, const Vec3& angular) {
  auto& body = *impl_->bodies.at(i);
  body.setLinearVelocity(to_bt(impl_->scale * linear));
  body.setAngularVelocity(to_bt(angular));
}

double World::mass(std::size_t i) const { return 1.0 / impl_->bodies.at(i)->getInvMass(); }

Packing World::packing() const {
  Packing result = impl_->packing;
  for (std::size_t i = 0; i < result.particles.size(); ++i) result.particles[i].pose = pose(i);
  return result;
}

}  // namespace aggpack
