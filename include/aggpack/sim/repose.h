#pragma once
// The paper's angle-of-repose test (Section 6 of the paper notes): a trough with a baffle at its
// middle; particles placed in one half by the paper's lattice placement fall to a dense state
// (stage 1); the baffle then moves steadily toward the open side until it clears the pile, and
// the particles spread into a stable slope (stage 2). The angle is measured from the final pile's
// side view: a surface profile along the trough (highest particle point per bin), the slope
// region chosen automatically (plateau and toe left out), and a least-squares line.
//
// Coordinates: trough along x from 0 to trough_length, y across, z up; particles start in
// x < baffle_position and the slope descends toward +x.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"
#include "aggpack/sim/settle.h"
#include "aggpack/sim/world.h"

namespace aggpack {

/// Options of the repose test. Defaults = the paper's case: trough 6 x 1 x 1 m, baffle at the
/// middle, alpha 0.5, R 0.1 m, L 0.1 m, lattice 15 x 5 x 14 = 1,050 particles behind the baffle.
struct ReposeOptions {
  double trough_length = 6.0;  ///< m, x extent, > 0
  double trough_width = 1.0;   ///< m, y extent, > 0
  /// m, z extent of the trough walls, > 0. While particles are placed above it (stage 1) the
  /// walls and the baffle reach up to the top of the lattice region.
  double trough_height = 1.0;
  double baffle_position = 3.0;    ///< m, x of the baffle's face; particles fill [0, this]
  double baffle_thickness = 0.05;  ///< m, > 0
  double baffle_speed = 0.5;       ///< m/s toward +x in stage 2, > 0
  /// The baffle is removed once no particle has touched it for this long (s) and it stands one
  /// largest particle size beyond the pile; if it reaches the far wall first it stops there.
  double baffle_clear_time = 0.2;

  // Particles: the fill, made by the caller (the pipeline's pack() of repose_fill_options(), the
  // paper's lattice placement in the box [0, baffle_position] x [0, trough_width] x
  // [0, fill_height]) and passed to run_repose().
  double alpha = 0.5;        ///< Eq. 3 shape control, [0, 1]
  double radius = 0.1;       ///< control radius R (m), > 0; lattice spacing 2R
  double edge_length = 0.1;  ///< L (m), > 0
  double fill_height = 2.8;  ///< m, height of the lattice region (14 layers of 2R = 0.2 m)
  std::uint64_t seed = 1;    ///< master seed; particle i draws from Rng(seed, i)
  /// Turn each particle by a uniformly random rotation about its lattice site (stream
  /// Rng(seed ^ 0x726f74, i)); it stays inside its site's sphere, so nothing overlaps. Without it
  /// identical shapes (alpha = 1 grows the same body every time) stack into a stable crystal.
  /// Only for the lattice fill of repose_fill_options() (provenance.packer "lattice"); other
  /// fills (random, dense) are taken as they are.
  bool is_orientation_random = true;

  /// Materials. `friction` is the mu_s of the sweep; walls default to the same value.
  PhysicsOptions physics;
  /// Rest criterion of both stages (stage 1 adds the free-fall time of the highest particle).
  RestCriterion rest{};
  /// Stage 2 also ends when the pile's surface profile (bins above fit_lower x its height) has
  /// moved less than this fraction of the median particle size for rest.quiet_time: a few
  /// particles rolling away over the floor do not keep the test running. [0, 10].
  double surface_tolerance = 0.05;

  // Angle measurement.
  double bin_width = 0.0;  ///< m, profile bin width; 0 = radius / 2
  double fit_upper = 0.8;  ///< slope region: below this fraction of the pile height, (0, 1]
  double fit_lower = 0.2;  ///< and above this fraction, [0, fit_upper)
};

/// Throws InvalidInput naming the field ("repose.baffle_speed", ...) unless usable.
void validate(const ReposeOptions& options);

/// The paper's fill for the test: the lattice placement (alpha, radius, edge_length, seed) in the
/// box [0, baffle_position] x [0, trough_width] x [0, fill_height]. Pack it with the pipeline's
/// pack() (or pack_lattice) and pass the result to run_repose().
LatticeOptions repose_fill_options(const ReposeOptions& options);

/// Height of the pile surface along x: the highest particle point in each bin (0 = bare floor).
struct SurfaceProfile {
  double lower = 0.0;          ///< x of the first bin's left edge (m)
  double bin_width = 0.0;      ///< m
  std::vector<double> height;  ///< m, one per bin

  [[nodiscard]] double centre(std::size_t bin) const {
    return lower + (static_cast<double>(bin) + 0.5) * bin_width;
  }
};

/// Exact surface profile of `packing` over [lower, upper] in x (m): for every bin, the largest z
/// of any particle within the slab (vertices in it and edges crossing its planes).
/// \throw InvalidInput unless bin_width > 0 and lower < upper.
SurfaceProfile surface_profile(const Packing& packing, double lower, double upper,
                               double bin_width);

/// The least-squares line through the slope region of a profile.
struct SlopeFit {
  bool is_valid = false;      ///< false when fewer than 3 bins qualified
  std::string message;        ///< why not valid, else empty
  double pile_height = 0.0;   ///< m, crest height (largest smoothed profile value)
  std::size_t first_bin = 0;  ///< slope region, inclusive
  std::size_t last_bin = 0;   ///< inclusive
  std::size_t bin_count = 0;
  double slope = 0.0;          ///< dz/dx of the line (negative: descending toward +x)
  double intercept = 0.0;      ///< z at x = 0 (m)
  double angle_degrees = 0.0;  ///< atan(-slope) in degrees: the angle of repose
  double r_squared = 0.0;      ///< coefficient of determination of the line, [0, 1]
  /// 95 % confidence interval of the angle from the line fit alone (slope standard error, Student
  /// t with bin_count - 2 degrees of freedom). Neighbouring bins are correlated (a particle spans
  /// several), so this understates the uncertainty; a seed ensemble (`repose --seeds`) measures it.
  double angle_ci_lower = 0.0;
  double angle_ci_upper = 0.0;
};

/// Chooses the slope region and fits a line to the profile's heights there. The profile is
/// smoothed by a running median over `smoothing_bins` (odd; run_repose uses one particle
/// diameter) only to choose the region: the crest is the highest smoothed point, the toe the
/// first bin after it below fit_lower x crest (or the lowest bin after it when the pile leans on
/// the far wall), and the slope runs back from the toe while the smoothed surface stays at or
/// below fit_upper x crest. Plateau and toe are thereby left out.
/// \throw InvalidInput unless 0 <= fit_lower < fit_upper <= 1 and smoothing_bins is odd.
SlopeFit fit_slope(const SurfaceProfile& profile, double fit_upper = 0.8, double fit_lower = 0.2,
                   std::size_t smoothing_bins = 3);

/// Progress of a repose run: stage (1 or 2), simulated time of the stage (s), kinetic energy (J),
/// rest threshold (J). Must not throw.
using ReposeProgress =
    std::function<void(int stage, double time, double kinetic_energy, double threshold)>;

/// Everything a repose run measured.
struct ReposeResult {
  Packing initial;  ///< the fill in the trough (turned, for the lattice fill)
  Packing settled;  ///< after stage 1
  Packing final;    ///< after stage 2
  SurfaceProfile profile;
  SlopeFit fit;
  std::size_t particle_count = 0;
  double solid_volume = 0.0;         ///< m^3
  double mean_measured_alpha = 0.0;  ///< Eq. 2 alpha of the particles, mean
  double time_step = 0.0;            ///< s
  double smallest_size = 0.0;        ///< d_min, m
  bool is_stage1_at_rest = false;
  double stage1_time = 0.0;     ///< simulated s
  double stage1_height = 0.0;   ///< m, top of the settled pile
  double stage1_seconds = 0.0;  ///< wall-clock s (not reproducible)
  bool is_stage2_at_rest = false;
  double stage2_time = 0.0;           ///< simulated s, baffle motion + waiting
  double baffle_travel = 0.0;         ///< m the baffle moved
  bool is_baffle_removed = false;     ///< false: it reached the far wall and stayed there
  double stage2_seconds = 0.0;        ///< wall-clock s
  double max_overlap_fraction = 0.0;  ///< deepest exact overlap / d_min in the final pile
  double max_contact_penetration_fraction = 0.0;  ///< deepest Bullet contact / d_min, final
  std::size_t escaped_particles = 0;  ///< particles outside the trough (x, y) or below the floor
};

/// Runs both stages on `fill` and measures the angle. Deterministic for given options and fill.
/// `fill`: the particles behind the baffle and their report (report.solid_volume is the exact
/// solid volume), as the pipeline's pack() returns them; its container must be a box within
/// [0, baffle_position] x [0, trough_width] (else InvalidInput naming "repose fill"). The
/// result's packings carry the fill's provenance with packer "<fill packer>+repose".
/// \throw InvalidInput, LimitExceeded (as validate() and World).
ReposeResult run_repose(const ReposeOptions& options, PackResult fill,
                        const ReposeProgress& progress = {});

/// Makes the fill for a repose run (the sweep calls it once per case, from several threads).
using ReposeFill = std::function<PackResult(const ReposeOptions& options)>;

/// Writes the result as JSON (options, counts, stage summaries, fit) atomically. Wall-clock
/// times are left out so that the same options always give the same bytes.
/// \throw IoError.
void write_repose_json(const std::string& path, const ReposeOptions& options,
                       const ReposeResult& result);
/// Writes the profile as CSV: x_m,height_m,in_fit,fit_height_m. \throw IoError.
void write_profile_csv(const std::string& path, const ReposeResult& result);

/// Side view of a pile (x to the right, z up), particles shaded by depth, the profile and the
/// fitted line drawn on it, written as PNG (stb_image_write). `width` in pixels, [64, 16384].
/// \throw InvalidInput, IoError.
void write_side_view_png(const std::string& path, const Packing& packing,
                         const SurfaceProfile& profile, const SlopeFit& fit, int width = 1600);

}  // namespace aggpack
