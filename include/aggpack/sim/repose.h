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
#include <string_view>
#include <vector>

#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"
#include "aggpack/shape/generator.h"
#include "aggpack/shape/shape_library.h"
#include "aggpack/sim/settle.h"
#include "aggpack/sim/world.h"

namespace aggpack {

/// The physics engine of the repose test: Bullet in this process (impulse-based rigid bodies,
/// world.h), or YADE (Debian's `yade`) as a subprocess: polyhedra with the volumetric
/// (overlap-volume) contact law, aggpack/sim/repose_yade.h.
enum class ReposeEngine { kBullet, kYade };
/// "bullet" or "yade".
std::string_view to_string(ReposeEngine engine);
/// The engine named `word`. \throw InvalidInput naming "repose.engine".
ReposeEngine repose_engine_from_string(std::string_view word);

/// YADE's own parameters (engine yade).
struct YadeOptions {
  /// PolyhedraMat.young, the volumetric law's stiffness: normal force per overlap volume
  /// (N/m^3). 0 = automatic: density x g x fill_height / (0.005 d), d the median equivalent
  /// diameter, so that a particle under the whole fill's weight overlaps its neighbours by
  /// about 0.5 % of d (a contact face of about d^2 carries density g fill_height d^2). [0, 1e15].
  double young = 0.0;
  /// NewtonIntegrator's damping (Cundall's local damping: each body's force is reduced by this
  /// fraction of its magnitude against the velocity), YADE's usual 0.3; [0, 1).
  double damping = 0.3;
  /// Wall-clock seconds a YADE run may take (the run then stops with an error); 0 = no limit.
  double time_limit = 0.0;
};

/// Options of the repose test. Defaults = the paper's case: trough 6 x 1 x 1 m, baffle at the
/// middle, alpha 0.5, R 0.1 m, L 0.1 m, lattice 15 x 5 x 14 = 1,050 particles behind the baffle.
struct ReposeOptions {
  double trough_length = 6.0;  ///< m, x extent, > 0
  double trough_width = 1.0;   ///< m, y extent, > 0
  /// Multiplies trough_width (and with it the fill's width): a wider trough, less wall effect
  /// and more particles, the pile's side view (height : length) unchanged. [1, 100].
  double width_factor = 1.0;
  /// The trough's y extent in use: trough_width x width_factor (m).
  [[nodiscard]] double width() const { return trough_width * width_factor; }
  /// m, z extent of the trough walls, > 0. While particles are placed above it (stage 1) the
  /// walls and the baffle reach up to the top of the lattice region.
  double trough_height = 1.0;
  double baffle_position = 3.0;    ///< m, x of the baffle's face; particles fill [0, this]
  double baffle_thickness = 0.05;  ///< m, > 0
  double baffle_speed = 0.5;       ///< m/s toward +x in stage 2, > 0
  /// The baffle is removed once no particle has touched it for this long (s) and it stands one
  /// largest particle size beyond the pile; if it reaches the far wall first it stops there.
  double baffle_clear_time = 0.2;

  // Particles: the fill, made by the caller (the study layer's study::repose_fill(): the
  // pipeline's pack() of study::repose_fill_options(), the paper's lattice placement in the box
  // [0, baffle_position] x [0, width()] x [0, fill_height]) and passed to run_repose(). The
  // simulation reads only radius (time step, bins) and the trough; the other particle fields
  // are the fill's, read by the study layer.
  double alpha = 0.5;        ///< Eq. 3 shape control, [0, 1]
  double radius = 0.1;       ///< control radius R (m), > 0; lattice spacing 2R
  double edge_length = 0.1;  ///< L (m), > 0
  GrowthForm form{};         ///< growth rule and control-surface axis ratios
  /// Shapes from mesh files (particle.library; no paths = grown particles): every lattice site
  /// holds a library shape (its convex hull, enclosing radius `radius`) instead of a grown
  /// particle; alpha, edge_length and form are then unused. The study layer's repose_fill()
  /// reads the files (LatticeOptions::files).
  ShapeLibraryOptions library{};
  double fill_height = 2.8;  ///< m, height of the lattice region (14 layers of 2R = 0.2 m)
  std::uint64_t seed = 1;    ///< master seed; particle i draws from Rng(seed, i)
  /// Turn each particle by a uniformly random rotation about its lattice site (stream
  /// Rng(seed ^ 0x726f74, i)); it stays inside its site's sphere, so nothing overlaps. Without it
  /// identical shapes (alpha = 1 grows the same body every time) stack into a stable crystal.
  /// Done by study::repose_fill() when it makes the lattice fill; a fill made otherwise
  /// (ReposeFill) is taken as it is.
  bool is_orientation_random = true;

  /// Materials. `friction` is the mu_s of the sweep; walls default to the same value.
  PhysicsOptions physics;
  ReposeEngine engine = ReposeEngine::kBullet;
  YadeOptions yade{};
  /// Rest criterion of both stages (stage 1 adds the free-fall time of the highest particle).
  RestCriterion rest{};
  /// Stage 2 also ends when the pile's surface profile (bins above fit_lower x its height) has
  /// moved less than this fraction of the median particle size for rest.quiet_time: a few
  /// particles rolling away over the floor do not keep the test running. [0, 10].
  double surface_tolerance = 0.05;
  /// Confirmation of rest (stage 2). The tests above stop on a pile whose kinetic energy is low and
  /// whose surface has not moved by surface_tolerance x d for rest.quiet_time; Bullet's iterative
  /// solver lets such a pile creep (mm/s) and a late avalanche can still take degrees off the
  /// angle. So once they pass, the pile is followed for confirm_window x sqrt(d / g) more (d the
  /// median equivalent diameter: a Froude-scaled time, the same number of particle fall times at
  /// any scale) and counts as at rest only if, over that whole window, the angle (fit as measured)
  /// stays within confirm_angle_tolerance of its value at the window's start, the crest height
  /// within confirm_height_tolerance x d, and 99 % of the pile's particles (centres above
  /// fit_lower x crest; all of them when fewer than 100) move slower than confirm_speed x
  /// sqrt(g d): single particles popping in Bullet's contact solver (seen up to 0.45 sqrt(g d))
  /// do not count, a collective motion does. Any violation restarts the wait (the energy/surface
  /// tests too). The window bounds the drift rates: angle confirm_angle_tolerance /
  /// confirm_window, crest confirm_height_tolerance / confirm_window x sqrt(g d). rest.max_time
  /// still bounds stage 2; a run that hits it reports is_stage2_at_rest = false.
  /// confirm_window = 0 turns the confirmation off.
  double confirm_window = 30.0;           ///< in units of sqrt(d / g), [0, 1e4]
  double confirm_angle_tolerance = 0.5;   ///< degrees, (0, 90]
  double confirm_height_tolerance = 0.1;  ///< fraction of d, (0, 10]
  double confirm_speed = 0.05;            ///< fraction of sqrt(g d), (0, 10]
  /// Diagnostic: after rest, follow the pile this many more simulated seconds and measure the
  /// angle again (ReposeResult::follow); the reported angle stays the one at rest. [0, 1e3].
  double follow_time = 0.0;

  // Angle measurement.
  double bin_width = 0.0;  ///< m, profile bin width; 0 = radius / 2
  double fit_upper = 0.8;  ///< slope region: below this fraction of the pile height, (0, 1]
  double fit_lower = 0.2;  ///< and above this fraction, [0, fit_upper)
};

/// Throws InvalidInput naming the field ("repose.baffle_speed", ...) unless usable by the
/// simulation. What the fill would refuse is checked by study::check_repose_inputs().
void validate(const ReposeOptions& options);

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

/// The slope fit of a packing as run_repose measures it: profile over [0, trough_length] with
/// `bin_width` (0 = radius / 2), smoothing over one particle diameter (2 R), the options' fit
/// window.
struct ReposeMeasurement {
  SurfaceProfile profile;
  SlopeFit fit;
};
ReposeMeasurement measure_repose(const Packing& packing, const ReposeOptions& options,
                                 double bin_width, double fit_upper, double fit_lower);
/// The same with the options' own bin width and fit window.
ReposeMeasurement measure_repose(const Packing& packing, const ReposeOptions& options);

/// One re-measurement of the final pile with another fit window or bin width.
struct SensitivityEntry {
  double fit_lower = 0.0;
  double fit_upper = 0.0;
  double bin_width = 0.0;   ///< m
  double bin_factor = 1.0;  ///< bin_width / the run's bin width
  bool is_valid = false;
  double angle_degrees = 0.0;
};
/// The angle re-measured for fit_lower - 0.05 / +0 / +0.05 x fit_upper - 0.05 / +0 / +0.05 (kept
/// inside [0, 1] with lower < upper) x bin width 0.5 / 1 / 2 x the run's: 27 entries, the run's
/// own setting among them. max_deviation: largest |angle - the run's angle| over valid entries.
struct FitSensitivity {
  std::vector<SensitivityEntry> entries;
  double max_deviation = 0.0;         ///< degrees
  double max_deviation_window = 0.0;  ///< degrees, over the fit windows at the run's bin width
  double max_deviation_bins = 0.0;    ///< degrees, over the bin widths at the run's fit window
};
FitSensitivity fit_sensitivity(const Packing& packing, const ReposeOptions& options,
                               const SlopeFit& reference);

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
  double stage2_time = 0.0;        ///< simulated s, baffle motion + waiting
  double baffle_travel = 0.0;      ///< m the baffle moved
  bool is_baffle_removed = false;  ///< false: it reached the far wall and stayed there
  double stage2_seconds = 0.0;     ///< wall-clock s
  /// Engine yade: the subprocess's CPU seconds (user + system; not reproducible), YADE's
  /// contact stiffness (PolyhedraMat.young, N/m^3) and its iterations.
  double engine_cpu_seconds = 0.0;
  double yade_young = 0.0;
  std::size_t yade_iterations = 0;
  double max_overlap_fraction = 0.0;  ///< deepest exact overlap / d_min in the final pile
  double max_contact_penetration_fraction = 0.0;  ///< deepest Bullet contact / d_min, final
  std::size_t escaped_particles = 0;  ///< particles outside the trough (x, y) or below the floor
  /// Rest confirmation (ReposeOptions::confirm_window) of stage 2.
  struct Confirmation {
    double window = 0.0;              ///< s, confirm_window x sqrt(d / g)
    std::size_t restarts = 0;         ///< windows that ended in a violation, of which by:
    std::size_t angle_restarts = 0;   ///< the angle
    std::size_t height_restarts = 0;  ///< the crest height
    std::size_t speed_restarts = 0;   ///< a fast pile particle
    double angle_change = 0.0;        ///< degrees, largest |change| over the last (passed) window
    double height_change = 0.0;       ///< m, largest |crest change| over the last window
    double max_speed = 0.0;           ///< m/s, largest 99 % pile speed over the last window
    double speed_limit = 0.0;         ///< m/s, confirm_speed x sqrt(g d)
  } confirmation;
  /// The measurement follow_time after rest (when follow_time > 0).
  struct FollowUp {
    double time = 0.0;  ///< s simulated after rest
    SlopeFit fit;
  } follow;
  /// Sensitivity of the angle to the fit window and bin width (fit_sensitivity of final).
  FitSensitivity sensitivity;
};

/// Runs both stages on `fill` and measures the angle. Deterministic for given options and fill.
/// `fill`: the particles behind the baffle and their report (report.solid_volume is the exact
/// solid volume), as the pipeline's pack() returns them; its container must be a box within
/// [0, baffle_position] x [0, width()] (else InvalidInput naming "repose fill"). The
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
