#pragma once
// Adaptive level of detail for interactive views (progressive refinement, as CAD viewers do):
// while the camera moves, frames are made lighter until they fit a frame-time target; when the
// view rests, the caller draws the full-detail frame. Pure logic (no OpenGL), so it is tested
// with made-up frame times.

#include <cstddef>

namespace aggpack {

/// What a light frame may draw. 0 = no limit (as in RenderStyle).
struct DetailLevel {
  std::size_t triangle_budget = 0;  ///< RenderStyle::triangle_budget
  std::size_t max_particles = 0;    ///< RenderStyle::max_particles
  /// Scale of the light frame's pixel size, in [kMinResolutionScale, 1]: the frame is drawn at
  /// this fraction of the view's width and height and stretched to fit (pixel work falls with
  /// its square).
  double resolution_scale = 1.0;
};

/// Smallest DetailLevel::resolution_scale a light frame is drawn at.
inline constexpr double kMinResolutionScale = 0.5;

/// Chooses the detail of the frames drawn while the view moves from the time the last ones
/// took. First the triangle budget falls (more particles drawn as one-triangle impostors) down
/// to 1 (all impostors); if that is still too slow, the resolution falls (down to half the
/// view's width and height); only then does the number of particles drawn fall (an even thinning
/// of those in view). All rise again, in the opposite order, when frames are well under the
/// target. Steps are proportional to target / measured time, bounded to [1/2, 2] per frame
/// and with a dead band between 0.75 and 1 times the target, so the level settles instead of
/// oscillating.
class DetailController {
 public:
  /// `target_seconds` (> 0): frame time to hold while moving. `full_budget`: the triangle budget
  /// of still frames (0 = no limit), which light frames never exceed. `min_particles`: fewest
  /// particles a light frame draws.
  explicit DetailController(double target_seconds = 0.047, std::size_t full_budget = 250000,
                            std::size_t min_particles = 5000);

  /// The level for the next light frame.
  [[nodiscard]] DetailLevel level() const { return level_; }
  /// Changes the still frames' budget (the ceiling); keeps the level under it.
  void set_full_budget(std::size_t full_budget);
  /// Back to full detail (the ceiling).
  void reset();
  /// Reports one light frame drawn at level(): its whole frame time (s), the mesh triangles it
  /// drew and the particles it drew (DrawStats::triangles, particles_drawn); adjusts level().
  void update(double frame_seconds, std::size_t triangles_drawn, std::size_t particles_drawn);

  [[nodiscard]] double target_seconds() const { return target_seconds_; }

 private:
  double target_seconds_;
  std::size_t full_budget_;
  std::size_t min_particles_;
  DetailLevel level_;
};

}  // namespace aggpack
