#pragma once
// The Bullet bridge (issue 6): a Packing turned into a rigid-body world. Every particle is a
// btRigidBody whose collision shape is a convex hull shared by all particles of the same shape;
// mass and inertia come from the exact polyhedron (aggpack::mass_properties) and a density. The
// container's walls are thick static boxes; extra static or moving (kinematic) boxes, such as the
// repose test's baffle, can be added. Bullet never appears in this header.
//
// Units are SI (m, kg, s). Internally Bullet runs in a scaled length unit in which the median
// particle's equivalent diameter is 1 (Bullet's tolerances are tuned for bodies of about that
// size); lengths, velocities and gravity are scaled by the same factor and time is not, so the
// dynamics are exactly those of the SI problem. Every value crossing this API is in SI units.
//
// Determinism: one single-threaded btDiscreteDynamicsWorld per World, bodies added in a fixed
// order, no randomised solver order, deactivation (sleeping) off: the same Packing and options
// give bit-identical poses after the same number of steps, on any thread.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/geom/vec.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// Velocity solver of a World (PhysicsOptions::solver).
enum class SolverKind {
  /// Bullet's sequential impulses: every sweep runs over all contacts (projected Gauss-Seidel).
  kGaussSeidel,
  /// The same row updates regrouped in cache-sized blocks of contacts (src/sim/world_solver.cpp):
  /// each block is swept solver_block_sweeps times before the next, and passes over all blocks
  /// repeat until every row has had solver_iterations sweeps. Faster on large piles (the rows
  /// stay in cache: -26% to -40% CPU per step at 4,000-10,000 particles); forces cross block
  /// borders once per pass instead of once per sweep, so a pile converges less: it packs lower
  /// and creeps about twice as fast as with kGaussSeidel (bench/RESULTS.md, "Cache-blocked
  /// solver").
  kBlocked
};

/// Material and integration settings of a World.
struct PhysicsOptions {
  double density = 2650.0;  ///< particle density (kg/m^3), > 0 (2650 = quartz-rich rock)
  /// Coulomb sliding friction mu_s between two particles, in [0, 10].
  double friction = 0.5;
  /// Coulomb sliding friction between a particle and a wall (container, baffle), in [0, 10];
  /// empty = same as `friction`.
  std::optional<double> wall_friction{};
  /// Coefficient of restitution (particle-particle and particle-wall), in [0, 1].
  double restitution = 0.1;
  /// Dimensionless rolling friction mu_r, in [0, 1]: the rolling resistance torque is at most
  /// mu_r * r * F_n with r the particles' mean equivalent radius (sphere of equal volume).
  /// 0 (the default) turns it off: polyhedra resist rolling through their shape.
  double rolling_friction = 0.0;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);  ///< m/s^2
  /// Time step (s); 0 = automatic: time_step_factor * sqrt(d_min / 9.81 m/s^2), with d_min the
  /// smallest particle's equivalent diameter (0.004 s for the paper's particles). Resting and
  /// slowly flowing contacts then penetrate < 0.1% of d_min (measured in tests/sim and
  /// bench/RESULTS.md); an impact at speed v penetrates up to v * time_step for one step.
  double time_step = 0.0;
  double time_step_factor = 0.04;  ///< see time_step, in [1e-6, 1]
  /// Sequential-impulse solver iterations per step, in [1, 1000]. Piles creep when the solver
  /// is not converged: 100 iterations cut the creep of a resting pile about 5-fold against 20
  /// at about 1.5x the cost (collision detection dominates).
  int solver_iterations = 100;
  /// Convergence tolerance of a step's solver sweeps (m/s), in [0, 1]: the sweeps (split-impulse
  /// and velocity) stop early once no contact row changes its relative velocity by more than
  /// this in a sweep (Bullet's least-squares residual threshold is its square). 0 = every one of
  /// the solver_iterations sweeps runs (the default; bench/RESULTS.md, "Fewer sweeps by a
  /// convergence tolerance", measures what a tolerance saves and what it does to creep and
  /// penetration: at most 12 % of the CPU on a settling pile of 4,000 particles).
  double solver_tolerance = 0.0;
  /// Collision margin as a fraction of d_min, in [0.0001, 0.1]. Each hull is shrunk by the
  /// margin so that hull + margin keeps the polyhedron's faces and rounds its edges and corners
  /// with radius margin; the exact polyhedra of two resting particles then overlap by about the
  /// margin at sharp corners (0.4% of d_min with the default).
  double margin_fraction = 0.005;
  /// Velocity solver; the default is Bullet's, kBlocked changes trajectories (not bit-identical).
  SolverKind solver = SolverKind::kGaussSeidel;
  /// kBlocked: contact points per block, in [1, 1000000] (1,000 contacts' rows and bodies, ~1 MB
  /// in double precision, fit in a core's L2 cache).
  int solver_block_contacts = 1000;
  /// kBlocked: sweeps of a block per pass, in [1, 1000] (1 = Gauss-Seidel in block order).
  int solver_block_sweeps = 4;
};

/// "gauss-seidel" or "blocked".
[[nodiscard]] const char* to_string(SolverKind kind);
/// Inverse of to_string; \throw InvalidInput naming `key` for another word.
[[nodiscard]] SolverKind solver_kind_from_string(const std::string& word,
                                                 const std::string& key = "solver");

/// Throws InvalidInput naming the field unless every option is in range.
void validate(const PhysicsOptions& options);

/// An axis-aligned wall box in world coordinates (m). Kinematic walls move with a set velocity.
struct WallBox {
  Aabb box;                   ///< lower < upper on every axis
  bool is_kinematic = false;  ///< moved by set_wall_velocity (a baffle), else static
};

/// Contact statistics of the current state.
struct ContactStatistics {
  std::size_t contact_count = 0;  ///< Bullet contact points with distance <= 0
  /// Largest penetration among Bullet's contact points (m, >= 0): the depth the solver sees.
  double max_contact_penetration = 0.0;
};

/// Largest true overlap between the exact polyhedra of the current state.
struct OverlapStatistics {
  /// Particle pairs whose exact polyhedra intersect or touch (aggpack::gjk_distance).
  std::size_t overlapping_pairs = 0;
  /// Largest penetration depth (m) over those pairs and over particle-wall pairs, by Bullet's
  /// GJK-EPA on the exact polyhedra (no margin, not shrunk).
  double max_depth = 0.0;
  double max_depth_fraction = 0.0;  ///< max_depth / d_min
};

/// A rigid-body world built from a Packing. Not copyable; one thread at a time.
class World {
 public:
  /// Builds bodies for every particle and static walls for the container (floor and sides; the
  /// top stays open). For a cylinder the side wall is 64 thick boxes whose inner faces touch the
  /// cylinder (the polygon's corners lie outside it by 0.12% of the radius).
  /// `wall_height` (m) raises the side walls above the container's depth (0 = the depth).
  /// \throw InvalidInput for bad options or an empty packing.
  World(const Packing& packing, const PhysicsOptions& options, double wall_height = 0.0);
  World(const World&) = delete;
  World& operator=(const World&) = delete;
  ~World();

  /// Adds a wall box; returns its id. \throw InvalidInput if the box is empty.
  std::size_t add_wall(const WallBox& wall);
  /// Sets a kinematic wall's velocity (m/s); it moves by velocity * dt each step.
  /// \throw InvalidInput if `wall` is not a kinematic wall id.
  void set_wall_velocity(std::size_t wall, const Vec3& velocity);
  /// Removes a wall from the simulation (its id stays reserved). \throw InvalidInput on a bad id.
  void remove_wall(std::size_t wall);
  /// Current box of a wall (m).
  [[nodiscard]] Aabb wall_box(std::size_t wall) const;
  /// True when some contact point between the wall and a particle has distance <= `gap` (m).
  [[nodiscard]] bool is_wall_touched(std::size_t wall, double gap) const;

  /// Advances the world by `count` fixed time steps.
  void step(std::size_t count = 1);

  [[nodiscard]] double time() const;       ///< simulated time (s)
  [[nodiscard]] double time_step() const;  ///< s
  [[nodiscard]] std::size_t step_count() const;
  [[nodiscard]] std::size_t particle_count() const;
  /// Smallest particle equivalent diameter d_min (m), the size the tolerances refer to.
  [[nodiscard]] double smallest_size() const;
  /// Median particle equivalent diameter (m).
  [[nodiscard]] double median_size() const;
  /// Collision margin in use (m).
  [[nodiscard]] double margin() const;

  [[nodiscard]] double kinetic_energy() const;    ///< translational + rotational (J)
  [[nodiscard]] double potential_energy() const;  ///< sum m g.(-x) relative to the origin (J)
  [[nodiscard]] double total_mass() const;        ///< kg
  [[nodiscard]] double max_speed() const;         ///< fastest particle centre of mass (m/s)
  /// True when every particle's position, orientation and velocities are finite.
  [[nodiscard]] bool is_finite() const;

  /// Pose of particle i in the Packing's convention (its shape's local frame -> world).
  [[nodiscard]] Pose pose(std::size_t i) const;
  [[nodiscard]] Vec3 linear_velocity(std::size_t i) const;   ///< of the centre of mass (m/s)
  [[nodiscard]] Vec3 angular_velocity(std::size_t i) const;  ///< rad/s, world frame
  /// Sets the velocities of particle i (m/s, rad/s about the centre of mass).
  void set_velocity(std::size_t i, const Vec3& linear, const Vec3& angular);
  /// Mass (kg) of particle i.
  [[nodiscard]] double mass(std::size_t i) const;

  /// The input packing with every particle at its current pose.
  [[nodiscard]] Packing packing() const;

  /// Bullet's contact points of the current state.
  [[nodiscard]] ContactStatistics contact_statistics() const;
  /// Exact overlaps of the current state (particle pairs from Bullet's broad phase).
  [[nodiscard]] OverlapStatistics overlap_statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aggpack
