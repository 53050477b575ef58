#include "aggpack/pack/verify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "hierarchical_grid.h"

namespace aggpack {

VerifyResult verify(const Packing& packing, const VerifyOptions& options) {
  if (!std::isfinite(options.gap) || options.gap < 0.0) {
    throw InvalidInput("verify.gap", format_value(options.gap),
                       Wording{Sentence::kFiniteAtLeastZero, {}});
  }
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0) {
    throw InvalidInput("verify.tolerance", format_value(options.tolerance),
                       Wording{Sentence::kFiniteAtLeastZero, {}});
  }
  validate(packing.container);
  const std::size_t n = packing.particles.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (packing.particles[i].shape >= packing.shapes.size()) {
      throw InvalidInput("particles[" + std::to_string(i) + "].shape",
                         std::to_string(packing.particles[i].shape),
                         "< shape count " + std::to_string(packing.shapes.size()));
    }
  }

  // True-size local bodies (copies only for scaled library shapes) and their bounding radii.
  std::vector<ConvexPolyhedron> bodies(n);
  std::vector<double> radius(n);
  parallel_for_index(0, n, [&](std::size_t i) {
    bodies[i] = packing.local_body(i);
    radius[i] = bounding_radius(bodies[i]);
  });
  double largest = 0.0;
  double smallest = std::numeric_limits<double>::infinity();
  for (double r : radius) {
    largest = std::max(largest, r);
    smallest = std::min(smallest, r);
  }
  const double slack = options.tolerance * 2.0 * largest;

  VerifyResult result;
  result.min_distance = std::numeric_limits<double>::infinity();
  result.min_wall_clearance = std::numeric_limits<double>::infinity();
  const Container& container = packing.container;
  for (std::size_t i = 0; i < n; ++i) {
    const double clearance = wall_clearance(container, bodies[i], packing.particles[i].pose);
    result.min_wall_clearance = std::min(result.min_wall_clearance, clearance);
    if (clearance < container.wall_gap - slack) {
      if (result.outside_particles == 0) {
        result.wording = {
            Sentence::kVerifyFromWalls,
            {std::to_string(i), format_value(clearance), format_value(container.wall_gap)}};
        result.message = english(result.wording);
      }
      ++result.outside_particles;
    }
  }

  // Candidate pairs: all of them, or those whose gap-inflated bounding spheres meet.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  if (options.is_brute_force) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
      }
    }
  } else if (n > 1) {
    const double half_gap = options.gap / 2.0 + slack;
    detail::HierarchicalGrid grid(container.bounds(), smallest + half_gap, largest + half_gap);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& centre = packing.particles[i].pose.position;
      grid.for_each_near(centre, radius[i] + half_gap, [&](const detail::GridEntry& other, double) {
        pairs.emplace_back(other.id, static_cast<std::uint32_t>(i));
        return true;
      });
      grid.insert(centre, radius[i] + half_gap);
    }
  }
  result.pairs_tested = pairs.size();
  std::vector<double> distance(pairs.size());
  parallel_for_index(0, pairs.size(), [&](std::size_t k) {
    const auto [i, j] = pairs[k];
    distance[k] =
        gjk_distance(bodies[i], packing.particles[i].pose, bodies[j], packing.particles[j].pose)
            .distance;
  });
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    result.min_distance = std::min(result.min_distance, distance[k]);
    if (distance[k] < options.gap - slack || (options.gap == 0.0 && distance[k] <= 0.0)) {
      if (result.overlapping_pairs == 0 && result.outside_particles == 0) {
        result.wording = {Sentence::kVerifyApart,
                          {std::to_string(pairs[k].first), std::to_string(pairs[k].second),
                           format_value(distance[k]), format_value(options.gap)}};
        result.message = english(result.wording);
      }
      ++result.overlapping_pairs;
    }
  }
  result.is_ok = result.overlapping_pairs == 0 && result.outside_particles == 0;
  return result;
}

}  // namespace aggpack
