// The HPMC engine's way out of a stalled repair (hpmc.h, Hpmc::relieve): the smallest uniform
// expansion that separates every overlapping pair, instead of waiting for local moves to clear
// the last overlaps or going back to the previous checkpoint.

#include <algorithm>
#include <vector>

#include "aggpack/pack/container.h"
#include "hpmc.h"
#include "hpmc_neighbours.h"

namespace aggpack::detail {

namespace {

// The smallest s in (1, high] with is_ok(s), is_ok being false at 1 and rising in s (once true,
// true for every larger s); `high` when is_ok(high) holds, else 0 (no such s). The bracket ends
// a relative 1e-7 apart; the upper end, where is_ok holds, is returned.
template <class IsOk>
double smallest_scale(double high, IsOk&& is_ok) {
  if (!is_ok(high)) return 0.0;
  double low = 1.0;
  while (high - low > 1e-7 * high) {
    const double middle = 0.5 * (low + high);
    if (is_ok(middle)) {
      high = middle;
    } else {
      low = middle;
    }
  }
  return high;
}

}  // namespace

bool Hpmc::relieve(double max_scale) {
  if (flagged_.empty() || flagged_count() == 0 || !(max_scale > 1.0)) return false;
  const State before = state(true);
  build_grid(Vec3::Zero());
  // The pairs and the particles outside are found at the current scale: a pair that is apart
  // now stays apart when expanded, so only flagged particles can need s > 1. In index order,
  // one thread: the result does not depend on the thread count.
  double scale = 1.0;
  bool is_possible = true;
  for (std::uint32_t i = 0; i < poses_.size() && is_possible; ++i) {
    if (flagged_[i] == 0) continue;
    const Pose& pose = poses_[i];
    if (!is_inside(i, pose, container_)) {
      const double s = smallest_scale(max_scale, [&](double factor) {
        Pose scaled = pose;
        scaled.position *= factor;
        return is_inside(i, scaled, container_scaled(container_, Vec3::Constant(factor)));
      });
      is_possible = s > 0.0;
      scale = std::max(scale, s);
    }
    for_each_close(i, pose.position, gap_, [&](std::uint32_t j, const Image& image) {
      if (is_apart(i, pose, j, gap_, image)) return true;
      const Vec3 other = poses_[j].position + shift_of(image);
      const double s = smallest_scale(max_scale, [&](double factor) {
        Pose scaled_i = pose;
        scaled_i.position *= factor;
        Pose scaled_j = poses_[j];
        scaled_j.position = other * factor;
        return is_separated(bodies_[body_of_[i]].support, scaled_i, bodies_[body_of_[j]].support,
                            scaled_j, gap_);
      });
      is_possible = s > 0.0;
      scale = std::max(scale, s);
      return is_possible;
    });
  }
  // A hair more than the bisection's upper end: the rescale computes positions and periods in
  // its own order of operations.
  scale *= 1.0 + 1e-9;
  if (is_possible && rescale(Vec3::Constant(scale),
                             container_scaled(container_, Vec3::Constant(scale)), 0.0) == 0) {
    return true;
  }
  restore(before);
  return false;
}

}  // namespace aggpack::detail
