#pragma once
// Internal: the hard-particle Monte Carlo engine of the densifying packer (dense_packer.cpp).
// Holds the particles' prepared shapes and poses, runs checkerboard sweeps and container squeezes.
// Every decision about overlap goes through is_separated (exact); containment through contains().

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "aggpack/core/rng.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/packing.h"

namespace aggpack::detail {

/// Step sizes and acceptance rules of one sweep.
struct SweepParameters {
  double translation_step = 0.1;      // / bounding radius
  double rotation_step = 0.1;         // rad
  double rotation_probability = 0.5;  // [0, 1]
  bool is_bed = false;                // Metropolis on potential energy
  double temperature = 0.0;           // bed: see DensifyOptions::bed_temperature
  double repair_step = 1.0;           // largest repair push / bounding radius
  // > 1: a repair push may overlap a new partner only when the pair is apart once positions are
  // expanded by this factor (the way back to the last clean container), so that every overlap
  // stays shallow enough for Hpmc::relieve.
  double relief_scale = 0.0;
  // > 0: every particle keeps translation and rotation steps of its own (starting at the two
  // steps above, which are then ignored) adapted to this acceptance rate by its own moves.
  double per_particle_acceptance = 0.0;
};

struct SweepCounts {
  std::uint64_t translations_tried = 0;
  std::uint64_t translations_accepted = 0;
  std::uint64_t rotations_tried = 0;
  std::uint64_t rotations_accepted = 0;
};

class Hpmc {
 public:
  /// Prepares one SupportShape per distinct (shape, scale). `max_compression` bounds the shrink
  /// per squeeze() (the cells are sized for it).
  Hpmc(const Packing& packing, double gap, std::uint64_t seed, double max_compression);

  /// One sweep (index `sweep` feeds the random streams): one trial move per particle.
  SweepCounts sweep(std::uint64_t sweep, const SweepParameters& parameters);

  /// Soft shrink (HOOMD-blue QuickCompress style): moves the container a share t of the way to
  /// `target` and rescales positions WITHOUT checking, then flags every particle that now
  /// overlaps a neighbour (exact test) or leaves the container. Until flagged_count() is 0 the
  /// state is not a valid packing: a flagged particle's move is accepted only if it makes no new
  /// overlap partner and does not go further out of the container; a clean particle's only if it
  /// overlaps nothing. So no clean particle ever gets an overlap, and once no particle is
  /// flagged the packing is overlap-free again. Returns flagged_count().
  std::size_t squeeze(const Container& target, double t);
  [[nodiscard]] std::size_t flagged_count() const;
  /// The reverse of squeeze (partly undoing one that does not repair): positions and container
  /// scaled up a share t of the way to `larger` (no extent smaller than now), flags recomputed.
  std::size_t expand(const Container& larger, double t);
  /// The clean state nearest the current one by a uniform expansion: the smallest s in
  /// (1, max_scale] (found per overlapping pair and per particle outside the container, by
  /// bisection on the exact tests) such that positions and container times s separate every
  /// pair and hold every particle; then the flags are recomputed exactly. Returns true and keeps
  /// the expanded state when it is clean (no flag); otherwise restores the state it was given
  /// and returns false. Sound because a convex body holds its centre: expanding the centres'
  /// frame only moves a separated pair further apart along its separating direction and a
  /// contained particle further from the walls (and the refresh checks it anyway).
  bool relieve(double max_scale);
  /// Recomputes the flags exactly (a flag can outlive its overlap when the partner moved away).
  std::size_t refresh_flags();
  /// Shared by squeeze and expand: positions times `factor` (per axis), the container scaled the
  /// same way, or exactly `end` (keeping the wall gap) once t >= 1; then refresh_flags().
  std::size_t rescale(const Vec3& factor, const Container& end, double t);

  /// A copy of the container and poses, to return to when a squeeze cannot be repaired.
  struct State {
    Container container;
    std::vector<Pose> poses;
    std::vector<std::uint8_t> flagged;  // empty: none (a checkpoint is clean)
  };
  /// The container and poses; with `with_flags`, the flags too (a state taken mid-repair).
  [[nodiscard]] State state(bool with_flags = false) const {
    return {container_, poses_, with_flags ? flagged_ : std::vector<std::uint8_t>{}};
  }
  void restore(const State& state);

  [[nodiscard]] const Container& container() const { return container_; }
  /// The poses; along a periodic axis a centre may lie up to one move outside [0, extent) until
  /// the next sweep wraps it (wrapped_poses() wraps them all).
  [[nodiscard]] const std::vector<Pose>& poses() const { return poses_; }
  /// The poses with every centre wrapped into [0, extent) along the periodic axes.
  [[nodiscard]] std::vector<Pose> wrapped_poses() const;
  [[nodiscard]] double solid_volume() const { return solid_volume_; }
  [[nodiscard]] double mean_outer_radius() const { return mean_outer_; }
  [[nodiscard]] double max_outer_radius() const { return max_outer_; }
  /// Geometric means of the per-particle translation (/ bounding radius) and rotation (rad)
  /// steps (SweepParameters::per_particle_acceptance); 0 before the first such sweep.
  [[nodiscard]] std::pair<double, double> mean_steps() const;
  /// Volume-weighted mean centroid height (m).
  [[nodiscard]] double mean_height() const;

 private:
  struct Body {
    SupportShape support;
    ConvexPolyhedron local;  // true size, local frame
    double outer = 0.0;
    double volume = 0.0;
  };
  struct Grid {
    double width = 0.0;
    Vec3 origin = Vec3::Zero();  // lower corner minus the shift
    std::int64_t dims[3] = {1, 1, 1};
    // Periodic box: along a periodic axis the cells tile the period (an even number of them,
    // or one), `cell` wide, and the cell coordinates wrap; `period` is the box extent.
    bool is_periodic = false;
    bool periodic[3] = {false, false, false};
    double cell[3] = {0.0, 0.0, 0.0};
    double period[3] = {0.0, 0.0, 0.0};
    std::vector<std::uint32_t> start;  // CSR: cell c holds items[start[c], start[c + 1])
    std::vector<std::uint32_t> items;
    std::vector<std::uint32_t> cell_of;  // per particle
    // Per item (same order as `items`): centre and bounding radius, packed for the broad phase
    // (kept current as particles move), and each particle's item slot.
    struct Sphere {
      double x, y, z, radius;
    };
    std::vector<Sphere> spheres;
    std::vector<std::uint32_t> slot_of;
  };

  /// An image of a neighbour: the neighbour's centre moved by image[axis] periods per axis.
  using Image = std::array<std::int8_t, 3>;
  static constexpr Image kSelf{0, 0, 0};
  /// The grid of a sweep, shifted by `fractions` of a cell per axis (all zero: unshifted); along
  /// periodic axes it wraps every centre into [0, extent) first.
  void build_grid(const Vec3& fractions);
  /// Wraps `position` into [0, extent) along the periodic axes; returns the periods subtracted.
  Image wrap(Vec3& position) const;
  /// The translation (m) of `image`.
  [[nodiscard]] Vec3 shift_of(const Image& image) const;
  /// Calls visit(image) for every image of particle j whose bounding sphere comes within `gap`
  /// of particle i's centred at `centre` (periodic axes: the nearest image and the two beside
  /// it); false from visit stops it and is returned.
  template <class Visit>
  bool for_each_image(std::uint32_t i, const Vec3& centre, std::uint32_t j, double gap,
                      Visit&& visit) const;
  /// Per-axis shrink shares toward `target` (p becomes p (1 - t k)).
  [[nodiscard]] Vec3 shrink_shares(const Container& target) const;
  [[nodiscard]] std::int64_t cell_index(const Vec3& position) const;
  void cell_coordinates(std::int64_t cell, std::int64_t (&c)[3]) const;
  /// Whether particles i and j sit in the same or adjacent grid cells.
  [[nodiscard]] bool is_adjacent(std::uint32_t i, std::uint32_t j) const;
  /// Whether particle i placed at `pose` is clear of every other particle (exact test, gap
  /// `gap`, neighbours from the grid).
  [[nodiscard]] bool is_clear(std::uint32_t i, const Pose& pose, double gap) const;
  /// Calls visit(j, image) for every other particle j (and, in a periodic box, each of its images)
  /// whose bounding sphere comes within `gap` of particle i's centred at `centre` (neighbour
  /// cells of i's cell); stops when visit is false.
  template <class Visit>
  void for_each_close(std::uint32_t i, const Vec3& centre, double gap, Visit&& visit) const;
  /// The periodic case of for_each_close: the neighbour cells wrap around the periodic axes.
  template <class Visit>
  void for_each_close_periodic(std::uint32_t i, const Vec3& centre, double gap,
                               Visit&& visit) const;
  /// The exact test of particle i at `pose` against particle j's `image` (is_separated), warm-
  /// started from i's cached separating direction for j and updating it.
  [[nodiscard]] bool is_apart(std::uint32_t i, const Pose& pose, std::uint32_t j, double gap,
                              const Image& image = kSelf) const;
  /// Moves particle i to `pose` (its packed sphere too), its centre wrapped into the box along
  /// the periodic axes; returns the periods subtracted (Hpmc::wrap).
  Image place(std::uint32_t i, const Pose& pose);
  [[nodiscard]] bool is_inside(std::uint32_t i, const Pose& pose, const Container& box) const;
  void repair(std::uint32_t i, Rng& rng, const SweepParameters& parameters);
  void move_cell(std::uint32_t i, std::uint64_t sweep, const SweepParameters& parameters,
                 SweepCounts& counts);

  Container container_;
  std::vector<Body> bodies_;
  std::vector<std::uint32_t> body_of_;
  std::vector<Pose> poses_;
  double gap_ = 0.0;
  std::uint64_t seed_ = 1;
  double max_outer_ = 0.0;
  double mean_outer_ = 0.0;
  double mean_volume_ = 0.0;
  double solid_volume_ = 0.0;
  Grid grid_;
  std::vector<std::uint8_t> flagged_;  // may overlap something / be outside (squeeze)
  // Warm starts of the exact test: per particle, the separating directions last found against
  // up to kAxes neighbours (replaced round robin). They only make is_separated faster (most
  // repeated queries of a slowly moving pair take one support pair instead of a whole GJK run);
  // answers do not depend on them. Written only by the particle's own tests (its moves, repairs
  // and flag refresh), so the cache, like everything else, is independent of the thread count.
  static constexpr int kAxes = 16;
  struct AxisCache {
    std::uint32_t neighbour[kAxes];
    float axis[kAxes][3];
    std::uint8_t next;
  };
  mutable std::vector<AxisCache> axes_;
  // Per particle, the neighbour that blocked its last rejected move (tested first; kNone: none).
  // Written only by the particle's own tests, like axes_.
  static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
  mutable std::vector<std::uint32_t> blockers_;
  // Per particle, its own translation (/ bounding radius) and rotation (rad) steps (empty until
  // the first sweep with per_particle_acceptance > 0). Written only by the particle's own moves.
  std::vector<float> own_translation_;
  std::vector<float> own_rotation_;
};

}  // namespace aggpack::detail
