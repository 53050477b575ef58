#pragma once
// Internal to the sim module: World::Impl and the Bullet types the world's files share.
// world.cpp: construction, stepping and the per-particle state; world_shapes.cpp: the Bullet hull
// of each shape; world_walls.cpp: container and user walls; world_contacts.cpp: the broad-phase
// filter and the contact / overlap statistics.

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/sim/world.h"

namespace aggpack {

namespace detail {

inline btVector3 to_bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 from_bt(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline btQuaternion to_bt(const Quat& q) { return {q.x(), q.y(), q.z(), q.w()}; }
inline Quat from_bt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

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
// island's bodies and manifolds in the order of its pair cache, which depends on the history of the
// narrow phase; the Gauss-Seidel sweeps, and so the rounding, follow that order. Here the bodies
// are taken in particle order and the manifolds sorted by the two particles they join (walls have
// negative indices), a pure function of the contacts: skipping the narrow phase of a pair that
// cannot touch (near_callback) then changes nothing, and runs stay bit-identical.
//
// With block_contacts > 0 (PhysicsOptions::solver = kBlocked) the velocity sweeps are cache-blocked
// (world_solver.cpp): the contacts, in that canonical order, are cut into blocks of block_contacts
// and each pass sweeps one block block_sweeps times (normal rows, then its friction rows) before
// the next; passes repeat until every row has had solver_iterations sweeps. The split-impulse
// (position) sweeps are blocked alike. A block's rows and
// bodies stay in cache across its sweeps, where a full sweep over a 10,000-particle pile's ~30 MB
// of rows streams them from memory. With a single block this is exactly Bullet's Gauss-Seidel.
// Compact copies of Bullet's solver bodies and rows for the Gauss-Seidel sweeps (world_solver.cpp):
// only what a row update reads or writes, so a sweep streams 176 bytes a row and 72 a body instead
// of Bullet's 288 and 488.
struct SweepBody {
  btScalar linear[3];    // delta linear velocity (push velocity in the split-impulse sweeps)
  btScalar angular[3];   // delta angular velocity (turn velocity in the split-impulse sweeps)
  btScalar inv_mass[3];  // Bullet's m_invMass (1/m times the linear factor, which is 1)
};

struct SweepRow {
  btScalar normal[3];  // contact normal 1; normal 2 is its negation (see world_solver.cpp)
  btScalar relpos1_cross_normal[3];
  btScalar relpos2_cross_normal[3];
  btScalar angular_a[3];
  btScalar angular_b[3];
  btScalar rhs;
  btScalar cfm;
  btScalar jac_diag_inv;
  btScalar applied;
  btScalar limit;  // contact row: its lower limit; friction row: its friction coefficient
  int body_a;
  int body_b;
  int normal_row;  // friction row: index of its contact row in the sweep order
};

class OrderedSolver final : public btSequentialImpulseConstraintSolver {
 public:
  OrderedSolver(int block_contacts, int block_sweeps)
      : block_contacts_(block_contacts), block_sweeps_(block_sweeps) {}

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

  btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int body_count,
                                             btPersistentManifold** manifolds, int manifold_count,
                                             btTypedConstraint** constraints, int constraint_count,
                                             const btContactSolverInfo& info,
                                             btIDebugDraw* debug) override;

 private:
  // Split-impulse (position) rows of contacts [begin, end); false if none changed.
  bool split_block(int begin, int end);
  // Velocity rows of contacts [begin, end): normal rows, their friction rows, their rolling rows.
  void sweep_block(int begin, int end);

  // Bullet's Gauss-Seidel sweeps (split impulse, then velocity) on compact rows and bodies, bit for
  // bit; false (nothing done) for set-ups World does not use, which go to Bullet's own sweeps.
  bool compact_sweeps(const btContactSolverInfo& info);
  bool load_compact();
  void store_compact();

  int block_contacts_ = 0;  // 0 = Bullet's sweeps over all contacts
  int block_sweeps_ = 1;
  std::vector<btCollisionObject*> sorted_bodies_;
  std::vector<btPersistentManifold*> sorted_manifolds_;
  std::vector<int> rolling_begin_;  // per contact + 1: first rolling-friction row of the contact
  std::vector<SweepBody> sweep_bodies_;
  std::vector<SweepRow> contact_rows_;     // in m_orderTmpConstraintPool's order
  std::vector<SweepRow> friction_rows_;    // in m_orderFrictionConstraintPool's order
  std::vector<btScalar> rhs_penetration_;  // per contact row
  std::vector<btScalar> push_applied_;     // per contact row: applied push impulse
  std::vector<int> contact_position_;      // contact pool index -> position in contact_rows_
  std::vector<int> split_rows_;            // contact rows the split-impulse sweeps visit
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

}  // namespace detail

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
  std::vector<detail::ShapeData> shapes;             // one per distinct (shape, scale)
  std::vector<std::uint32_t> body_shape;             // per particle: index into shapes
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // one per particle, index = particle index
  std::vector<detail::Wall> walls;

  // Declared last so they are destroyed first (bodies and shapes must outlive the world).
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<detail::OrderedSolver> solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;

  ~Impl();

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
  std::size_t add_wall(const ContainerWall& wall, bool is_kinematic);
};

}  // namespace aggpack
