#include "aggpack/sim/world.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/geom/overlap.h"

namespace aggpack {

namespace {

constexpr double kStandardGravity = 9.81;  // m/s^2, only to turn d_min into a time scale
constexpr int kCylinderSegments = 64;
constexpr double kMinSize = 1e-9;      // m, smallest equivalent diameter simulated
constexpr double kMaxSize = 1e6;       // m, largest
constexpr double kMaxSizeRatio = 1e6;  // largest / smallest in one world

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

btVector3 to_bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btQuaternion to_bt(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }
Quat from_bt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

double equivalent_diameter(double volume) { return std::cbrt(6.0 * volume / std::numbers::pi); }

// One Bullet hull per distinct shape, in the shape's principal frame: Bullet wants a diagonal
// local inertia, so the body frame is the principal frame and the pose is composed with it.
struct ShapeData {
  std::unique_ptr<btConvexHullShape> hull;        // principal frame, sim units, with margin
  std::unique_ptr<btConvexHullShape> exact_hull;  // same, margin 0 (overlap measurement)
  Vec3 centroid = Vec3::Zero();                   // of the shape in its local frame (m)
  Quat principal = Quat::Identity();              // principal frame -> local frame
  double volume = 0.0;                            // m^3
  Vec3 unit_inertia = Vec3::Zero();               // principal moments per unit density (m^5)
  double size = 0.0;                              // equivalent diameter (m)
  SupportShape exact;                             // scaled polyhedron, for aggpack's GJK
  std::uint32_t source = 0;                       // index into Packing::shapes
  double scale = 1.0;                             // Particle::scale
};

// Bullet's sequential-impulse solver, fed in a canonical order. Bullet hands the solver an
// island's bodies in union-find order and its manifolds in the order the pairs first reached the
// narrow phase; the Gauss-Seidel sweeps, and so the rounding, follow that order. Here the bodies
// are taken in particle order and the manifolds sorted by the two particles they join (walls have
// negative indices), a pure function of the contacts: skipping the narrow phase of a pair that
// cannot touch (near_callback) then changes nothing, and runs stay bit-identical.
class OrderedSolver final : public btSequentialImpulseConstraintSolver {
 protected:
  void convertBodies(btCollisionObject** bodies, int count,
                     const btContactSolverInfo& info) override {
    sorted_bodies_.assign(bodies, bodies + count);
    std::sort(sorted_bodies_.begin(), sorted_bodies_.end(),
              [](const btCollisionObject* a, const btCollisionObject* b) {
                return a->getUserIndex() < b->getUserIndex();
              });
    btSequentialImpulseConstraintSolver::convertBodies(sorted_bodies_.data(), count, info);
  }

  void convertContacts(btPersistentManifold** manifolds, int count,
                       const btContactSolverInfo& info) override {
    sorted_manifolds_.assign(manifolds, manifolds + count);
    // One manifold per pair, so the key is unique.
    auto key = [](const btPersistentManifold* m) {
      const int a = m->getBody0()->getUserIndex();
      const int b = m->getBody1()->getUserIndex();
      return std::pair(std::max(a, b), std::min(a, b));
    };
    std::sort(sorted_manifolds_.begin(), sorted_manifolds_.end(),
              [&key](const btPersistentManifold* a, const btPersistentManifold* b) {
                return key(a) < key(b);
              });
    btSequentialImpulseConstraintSolver::convertContacts(sorted_manifolds_.data(), count, info);
  }

 private:
  std::vector<btCollisionObject*> sorted_bodies_;
  std::vector<btPersistentManifold*> sorted_manifolds_;
};

struct Wall {
  std::unique_ptr<btBoxShape> shape;
  std::unique_ptr<btBoxShape> exact_shape;
  std::unique_ptr<btDefaultMotionState> motion;
  std::unique_ptr<btRigidBody> body;
  Vec3 half_extent = Vec3::Zero();  // m
  Vec3 velocity = Vec3::Zero();     // m/s
  bool is_kinematic = false;
  bool is_removed = false;
};

}  // namespace

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
  require_in_range("margin_fraction", options.margin_fraction, 1e-4, 0.1);
}

struct World::Impl {
  Packing packing;
  PhysicsOptions options;
  double scale = 1.0;  // sim length = scale * SI length
  double time_step = 0.0;
  double time = 0.0;
  std::size_t steps = 0;
  double smallest_size = 0.0;
  double median_size = 0.0;
  double margin = 0.0;          // sim units
  double wall_thickness = 0.0;  // m

  std::vector<double> bounding_radius;  // per particle, about its centroid (sim units)
  // Bullet keeps contact points up to gContactBreakingThreshold (0.02) x the shape's angular
  // motion disc (at most sqrt(3) x its bounding radius + margin); reach 10% beyond the spheres.
  static constexpr double kPairReach = 1.1;
  // Largest contact breaking threshold of any shape (sim units): Bullet keeps and adds contact
  // points up to a manifold's threshold, the smaller of its two shapes'.
  double breaking_threshold = 0.0;
  std::vector<ShapeData> shapes;                     // one per distinct (shape, scale)
  std::vector<std::uint32_t> body_shape;             // per particle: index into shapes
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // one per particle, index = particle index
  std::vector<Wall> walls;

  // Declared last so they are destroyed first (bodies and shapes must outlive the world).
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<OrderedSolver> solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;

  ~Impl() {
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

  [[nodiscard]] double wall_friction() const {
    return options.wall_friction.value_or(options.friction);
  }

  static void near_callback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher,
                            const btDispatcherInfo& info);
  void build_shapes();
  void build_world();
  void add_particles();
  void add_container_walls(double wall_height);
  std::size_t add_wall(const WallBox& wall);
};

namespace {

// Extent of a particle's collision body (hull + margin) along the world direction `axis`,
// measured from its centre of mass.
double support_extent(const btCollisionObject& body, const btVector3& axis) {
  const auto* hull = static_cast<const btConvexHullShape*>(body.getCollisionShape());
  const btVector3 local = axis * body.getWorldTransform().getBasis();  // R^T axis
  return hull->localGetSupportVertexWithoutMarginNonVirtual(local).dot(local) + hull->getMargin();
}

}  // namespace

// Bullet's broad phase pairs bodies whose (rotation-inflated) AABBs overlap: about 24 pairs per
// particle in a pile, each costing two GJK runs per step (Bullet 3.24 runs a libccd intersection
// test and then its own GJK, both from a fixed start axis: ~14,000 instructions a pair), although
// only ~3 per particle touch. Two cheap tests skip the pairs that cannot make a contact point:
//  1. bounding spheres (sphere against sphere, or against the wall box);
//  2. a separating axis: the line between the two centres for two particles, the wall's face
//     normal for a particle and a wall. If the two bodies' extents along it (support mapping of
//     the hull + margin, ~300 instructions each) leave a gap wider than Bullet's contact breaking
//     threshold, Bullet's narrow phase would add no point and drop every point it keeps.
// A skipped pair's manifold is cleared so that no stale contact point survives.
void World::Impl::near_callback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher,
                                const btDispatcherInfo& info) {
  const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
  const auto* impl = static_cast<const Impl*>(a->getUserPointer());
  const int index_a = a->getUserIndex();
  const int index_b = b->getUserIndex();
  bool is_far = false;
  if (impl != nullptr && (index_a >= 0 || index_b >= 0)) {
    if (index_a >= 0 && index_b >= 0) {
      const double reach = kPairReach * (impl->bounding_radius[static_cast<std::size_t>(index_a)] +
                                         impl->bounding_radius[static_cast<std::size_t>(index_b)]);
      const btVector3 between =
          b->getWorldTransform().getOrigin() - a->getWorldTransform().getOrigin();
      const double distance2 = between.length2();
      is_far = distance2 > reach * reach;
      if (!is_far && distance2 > 0.0) {
        const btVector3 axis = between / std::sqrt(distance2);
        const double gap = axis.dot(between) - support_extent(*a, axis) - support_extent(*b, -axis);
        is_far = gap > impl->breaking_threshold;
      }
    } else {
      const auto* particle = index_a >= 0 ? a : b;
      const auto* wall = index_a >= 0 ? b : a;
      const auto* box = static_cast<const btBoxShape*>(wall->getCollisionShape());
      const btVector3 local =
          wall->getWorldTransform().invXform(particle->getWorldTransform().getOrigin());
      const btVector3 half = box->getHalfExtentsWithMargin();
      btVector3 outside(0, 0, 0);
      for (int axis = 0; axis < 3; ++axis) {
        outside[axis] = std::max(btScalar(0), btFabs(local[axis]) - half[axis]);
      }
      const double reach =
          kPairReach * impl->bounding_radius[static_cast<std::size_t>(particle->getUserIndex())];
      is_far = outside.length2() > reach * reach;
      // Separating axis: the normal of the box face the centre lies beyond.
      for (int axis = 0; axis < 3 && !is_far; ++axis) {
        if (!(outside[axis] > 0.0)) continue;
        btVector3 normal = wall->getWorldTransform().getBasis().getColumn(axis);
        if (local[axis] < 0.0) normal = -normal;
        is_far = outside[axis] - support_extent(*particle, -normal) > impl->breaking_threshold;
      }
    }
  }
  if (!is_far) {
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
    return;
  }
  if (pair.m_algorithm != nullptr) {
    btManifoldArray manifolds;
    pair.m_algorithm->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) manifolds[m]->clearManifold();
  }
}

void World::Impl::build_shapes() {
  // One hull per distinct (stored shape, scale): a shape library reuses one stored shape at many
  // sizes, and Bullet's local scaling is a property of the shared shape, not of the body.
  std::map<std::pair<std::uint32_t, double>, std::uint32_t> keys;
  body_shape.reserve(packing.particles.size());
  for (const auto& particle : packing.particles) {
    if (particle.shape >= packing.shapes.size()) {
      throw InvalidInput("particle.shape", std::to_string(particle.shape),
                         "[0, " + std::to_string(packing.shapes.size()) + ")");
    }
    if (!(particle.scale > 0.0) || !std::isfinite(particle.scale)) {
      throw InvalidInput("particle.scale", format_value(particle.scale), "> 0");
    }
    const auto [it, is_new] = keys.try_emplace({particle.shape, particle.scale},
                                               static_cast<std::uint32_t>(shapes.size()));
    if (is_new) {
      ShapeData shape;
      shape.source = particle.shape;
      shape.scale = particle.scale;
      shapes.push_back(std::move(shape));
    }
    body_shape.push_back(it->second);
  }
  for (auto& shape : shapes) {
    const ConvexPolyhedron& stored = packing.shapes[shape.source];
    const MassProperties mass = mass_properties(stored);
    if (!(mass.volume > 0.0)) {
      throw InvalidInput("shape " + std::to_string(shape.source) + " volume",
                         format_value(mass.volume), "> 0 (a closed outward mesh)");
    }
    const double s = shape.scale;
    shape.volume = mass.volume * s * s * s;
    shape.centroid = s * mass.centroid;  // in the stored (unscaled-pose) local frame, scaled
    shape.size = equivalent_diameter(shape.volume);
    // Masses, inertias and the time step (from the smallest size) must stay finite and non-zero:
    // a particle at scale 1e-200 has volume 0, a time step of 0 and made settle run forever.
    if (!(shape.size >= kMinSize && shape.size <= kMaxSize)) {
      std::size_t particle = 0;
      while (packing.particles[particle].shape != shape.source ||
             packing.particles[particle].scale != s) {
        ++particle;
      }
      throw InvalidInput(
          "particle " + std::to_string(particle) + " scale",
          format_value(s) + " (equivalent diameter " + format_value(shape.size) + " m)",
          "a size giving an equivalent diameter in [1e-9, 1e6] m");
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(mass.inertia);
    Mat3 axes = eigen.eigenvectors();
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
    shape.principal = Quat(axes).normalized();
    shape.unit_inertia = eigen.eigenvalues() * std::pow(s, 5);
  }
  std::vector<double> sizes;
  sizes.reserve(body_shape.size());
  for (const auto index : body_shape) sizes.push_back(shapes[index].size);
  std::sort(sizes.begin(), sizes.end());
  smallest_size = sizes.front();
  median_size = sizes[sizes.size() / 2];
  if (sizes.back() > kMaxSizeRatio * sizes.front()) {
    throw InvalidInput("particle sizes",
                       format_value(sizes.front()) + " to " + format_value(sizes.back()) + " m",
                       "largest / smallest <= 10^6 (Bullet's tolerances follow the median size)");
  }
  scale = 1.0 / median_size;
  margin = options.margin_fraction * smallest_size * scale;
  for (auto& shape : shapes) {
    const Mat3 to_principal = shape.principal.conjugate().toRotationMatrix();
    const ConvexPolyhedron& stored = packing.shapes[shape.source];
    std::vector<btScalar> points;
    points.reserve(3 * stored.vertex_count());
    for (const auto& v : stored.vertices()) {
      const Vec3 p = scale * (to_principal * (shape.scale * v - shape.centroid));
      points.insert(points.end(), {p.x(), p.y(), p.z()});
    }
    const int count = static_cast<int>(points.size() / 3);
    // Bullet collides the hull inflated by the margin (a body with rounded edges) and runs GJK on
    // the hull itself, needing the slower EPA only when hulls interpenetrate. So the hull is
    // scaled about the centroid by s = 1 - margin / h_min (h_min: distance from the centroid to
    // the nearest face plane): the support function of s * hull + margin is then at most that of
    // the polyhedron in every direction, i.e. the rounded body lies inside the polyhedron, touches
    // its nearest face, and is nowhere more than margin * (h_face / h_min - 1) inside a face.
    // (Moving every face in by the margin instead, btConvexHullComputer's shrink, splits each
    // vertex into several and triples the support-mapping cost.) The computer also keeps only
    // extreme points: the generator leaves many vertices on an edge or a face plane.
    btConvexHullComputer computer;
    computer.compute(points.data(), 3 * sizeof(btScalar), count, 0.0, 0.0);
    if (computer.vertices.size() < 4 || computer.faces.size() < 4) {
      throw InvalidInput("shape " + std::to_string(shape.source), "degenerate hull",
                         "a convex body with positive volume");
    }
    double nearest_face = std::numeric_limits<double>::infinity();
    for (int f = 0; f < computer.faces.size(); ++f) {
      const auto* edge = &computer.edges[computer.faces[f]];
      const btVector3 a = computer.vertices[edge->getSourceVertex()];
      const btVector3 b = computer.vertices[edge->getTargetVertex()];
      const btVector3 c = computer.vertices[edge->getNextEdgeOfFace()->getTargetVertex()];
      const btVector3 normal = (b - a).cross(c - a);
      if (normal.length2() > 0.0) nearest_face = std::min(nearest_face, normal.normalized().dot(a));
    }
    if (!(nearest_face > 2.0 * margin)) {
      throw InvalidInput("shape " + std::to_string(shape.source) + " inner radius",
                         format_value(nearest_face / scale), "> 2 x collision margin");
    }
    const btScalar factor = 1.0 - margin / nearest_face;
    btAlignedObjectArray<btVector3> scaled;
    for (int v = 0; v < computer.vertices.size(); ++v)
      scaled.push_back(factor * computer.vertices[v]);
    shape.hull =
        std::make_unique<btConvexHullShape>(&scaled[0].x(), scaled.size(), sizeof(btVector3));
    shape.hull->setMargin(margin);
    shape.exact = SupportShape(shape.scale == 1.0 ? stored : stored.scaled(shape.scale));
    shape.exact_hull =
        std::make_unique<btConvexHullShape>(points.data(), count, 3 * sizeof(btScalar));
    shape.exact_hull->optimizeConvexHull();
    shape.exact_hull->setMargin(0.0);
  }
}

void World::Impl::build_world() {
  configuration = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
  dispatcher->setNearCallback(&Impl::near_callback);

  broadphase = std::make_unique<btDbvtBroadphase>();
  solver = std::make_unique<OrderedSolver>();
  world = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), broadphase.get(),
                                                    solver.get(), configuration.get());
  world->setGravity(to_bt(scale * options.gravity));
  auto& info = world->getSolverInfo();
  info.m_numIterations = options.solver_iterations;
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

std::size_t World::Impl::add_wall(const WallBox& box) {
  if (box.box.is_empty() || !((box.box.upper - box.box.lower).array() > 0.0).all()) {
    throw InvalidInput("wall box", "empty", "lower < upper on every axis");
  }
  Wall wall;
  wall.is_kinematic = box.is_kinematic;
  wall.half_extent = 0.5 * (box.box.upper - box.box.lower);
  const Vec3 centre = 0.5 * (box.box.upper + box.box.lower);
  wall.shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
  wall.shape->setMargin(margin);  // a box's margin lies inside its faces
  wall.shape->initializePolyhedralFeatures();
  wall.exact_shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
  wall.exact_shape->setMargin(0.0);
  btTransform transform;
  transform.setIdentity();
  transform.setOrigin(to_bt(scale * centre));
  wall.motion = std::make_unique<btDefaultMotionState>(transform);
  btRigidBody::btRigidBodyConstructionInfo construction(0.0, wall.motion.get(), wall.shape.get());
  construction.m_friction = wall_friction();
  construction.m_restitution = options.restitution;
  wall.body = std::make_unique<btRigidBody>(construction);
  if (wall.is_kinematic) {
    wall.body->setCollisionFlags(wall.body->getCollisionFlags() |
                                 btCollisionObject::CF_KINEMATIC_OBJECT);
    wall.body->setActivationState(DISABLE_DEACTIVATION);
  }
  wall.body->setUserIndex(-1 - static_cast<int>(walls.size()));
  wall.body->setUserPointer(this);
  world->addRigidBody(wall.body.get());
  walls.push_back(std::move(wall));
  return walls.size() - 1;
}

void World::Impl::add_container_walls(double wall_height) {
  const auto& container = packing.container;
  const double t = wall_thickness;
  if (container.kind == ContainerKind::kBox) {
    const double l = container.length;
    const double w = container.width;
    const double h = std::max(container.depth, wall_height);
    add_wall({.box = {Vec3(-t, -t, -t), Vec3(l + t, w + t, 0.0)}});  // floor
    add_wall({.box = {Vec3(-t, -t, 0.0), Vec3(0.0, w + t, h)}});     // x = 0
    add_wall({.box = {Vec3(l, -t, 0.0), Vec3(l + t, w + t, h)}});    // x = length
    add_wall({.box = {Vec3(0.0, -t, 0.0), Vec3(l, 0.0, h)}});        // y = 0
    add_wall({.box = {Vec3(0.0, w, 0.0), Vec3(l, w + t, h)}});       // y = width
    return;
  }
  const double r = container.radius;
  const double h = std::max(container.height, wall_height);
  add_wall({.box = {Vec3(-r - t, -r - t, -t), Vec3(r + t, r + t, 0.0)}});  // floor
  // The side wall: boxes whose inner faces are tangent to the cylinder. add_wall takes axis-aligned
  // boxes, so these are made directly with a rotation.
  const double half_chord = r * std::tan(std::numbers::pi / kCylinderSegments) * 1.02;
  for (int k = 0; k < kCylinderSegments; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kCylinderSegments;
    Wall wall;
    wall.half_extent = Vec3(0.5 * t, half_chord, 0.5 * h);
    wall.shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
    wall.shape->setMargin(margin);
    wall.shape->initializePolyhedralFeatures();
    wall.exact_shape = std::make_unique<btBoxShape>(to_bt(scale * wall.half_extent));
    wall.exact_shape->setMargin(0.0);
    btTransform transform;
    transform.setIdentity();
    transform.setOrigin(to_bt(
        scale * Vec3((r + 0.5 * t) * std::cos(angle), (r + 0.5 * t) * std::sin(angle), 0.5 * h)));
    transform.setRotation(btQuaternion(btVector3(0, 0, 1), angle));
    wall.motion = std::make_unique<btDefaultMotionState>(transform);
    btRigidBody::btRigidBodyConstructionInfo construction(0.0, wall.motion.get(), wall.shape.get());
    construction.m_friction = wall_friction();
    construction.m_restitution = options.restitution;
    wall.body = std::make_unique<btRigidBody>(construction);
    wall.body->setUserIndex(-1 - static_cast<int>(walls.size()));
    wall.body->setUserPointer(this);
    world->addRigidBody(wall.body.get());
    walls.push_back(std::move(wall));
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

std::size_t World::add_wall(const WallBox& wall) { return impl_->add_wall(wall); }

void World::set_wall_velocity(std::size_t wall, const Vec3& velocity) {
  if (wall >= impl_->walls.size() || !impl_->walls[wall].is_kinematic) {
    throw InvalidInput("wall", std::to_string(wall), "a kinematic wall id");
  }
  impl_->walls[wall].velocity = velocity;
}

void World::remove_wall(std::size_t wall) {
  if (wall >= impl_->walls.size() || impl_->walls[wall].is_removed) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  impl_->world->removeRigidBody(impl_->walls[wall].body.get());
  impl_->walls[wall].is_removed = true;
}

Aabb World::wall_box(std::size_t wall) const {
  if (wall >= impl_->walls.size()) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  const auto& w = impl_->walls[wall];
  const Vec3 centre = from_bt(w.body->getWorldTransform().getOrigin()) / impl_->scale;
  return {centre - w.half_extent, centre + w.half_extent};
}

bool World::is_wall_touched(std::size_t wall, double gap) const {
  if (wall >= impl_->walls.size()) {
    throw InvalidInput("wall", std::to_string(wall), "an existing wall id");
  }
  const auto* body = impl_->walls[wall].body.get();
  auto* dispatcher = impl_->dispatcher.get();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    if (manifold->getBody0() != body && manifold->getBody1() != body) continue;
    for (int c = 0; c < manifold->getNumContacts(); ++c) {
      if (manifold->getContactPoint(c).getDistance() <= gap * impl_->scale) return true;
    }
  }
  return false;
}

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

ContactStatistics World::contact_statistics() const {
  ContactStatistics stats;
  auto* dispatcher = impl_->dispatcher.get();
  double deepest = 0.0;
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    for (int c = 0; c < manifold->getNumContacts(); ++c) {
      const double distance = manifold->getContactPoint(c).getDistance();
      if (distance <= 0.0) {
        ++stats.contact_count;
        deepest = std::max(deepest, -distance);
      }
    }
  }
  stats.max_contact_penetration = deepest / impl_->scale;
  return stats;
}

OverlapStatistics World::overlap_statistics() const {
  const auto& impl = *impl_;
  OverlapStatistics stats;
  auto& pairs = impl.world->getPairCache()->getOverlappingPairArray();
  double deepest = 0.0;
  for (int p = 0; p < pairs.size(); ++p) {
    const auto* a = static_cast<const btCollisionObject*>(pairs[p].m_pProxy0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(pairs[p].m_pProxy1->m_clientObject);
    const int index_a = a->getUserIndex();
    const int index_b = b->getUserIndex();
    if (index_a < 0 && index_b < 0) continue;  // wall-wall
    if (index_a >= 0 && index_b >= 0) {
      // Whether the exact polyhedra intersect is decided by aggpack's own GJK; Bullet's EPA (on
      // the unshrunk hulls, margin 0) only measures how deep.
      const auto& shape_a = impl.shapes[impl.body_shape[static_cast<std::size_t>(index_a)]];
      const auto& shape_b = impl.shapes[impl.body_shape[static_cast<std::size_t>(index_b)]];
      if (!gjk_distance(shape_a.exact, pose(static_cast<std::size_t>(index_a)), shape_b.exact,
                        pose(static_cast<std::size_t>(index_b)))
               .is_intersecting) {
        continue;
      }
      ++stats.overlapping_pairs;
    }
    auto exact_hull = [&impl](int index) -> const btConvexShape* {
      if (index >= 0) {
        return impl.shapes[impl.body_shape[static_cast<std::size_t>(index)]].exact_hull.get();
      }
      return impl.walls[static_cast<std::size_t>(-1 - index)].exact_shape.get();
    };
    btGjkEpaSolver2::sResults result;
    const btVector3 guess = b->getWorldTransform().getOrigin() - a->getWorldTransform().getOrigin();
    if (btGjkEpaSolver2::Penetration(exact_hull(index_a), a->getWorldTransform(),
                                     exact_hull(index_b), b->getWorldTransform(), guess, result,
                                     false)) {
      deepest = std::max(deepest, static_cast<double>(-result.distance));
    }
  }
  stats.max_depth = deepest / impl.scale;
  stats.max_depth_fraction = stats.max_depth / impl.smallest_size;
  return stats;
}

}  // namespace aggpack
