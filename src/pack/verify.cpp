#include "aggpack/pack/verify.h"

#include <algorithm>
#include <array>
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

  // In a periodic box the broad phase works on centres wrapped into the box (`offset` moves a
  // particle there), and each pair is tested through every image of its second particle that can
  // reach the first (`shift`); a particle near a periodic face is also tested against its own
  // images. Without periodic axes every offset and shift is zero.
  const std::array<bool, 3> periodic = periodic_axes(container);
  const Aabb box = container.bounds();
  std::vector<Vec3> offset(n, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& centre = packing.particles[i].pose.position;
    for (int axis = 0; axis < 3; ++axis) {
      if (!periodic[static_cast<std::size_t>(axis)]) continue;
      const double extent = box.extent()[axis];
      const double wrapped =
          centre[axis] - extent * std::floor((centre[axis] - box.lower[axis]) / extent);
      offset[i][axis] = wrapped - centre[axis];
    }
  }
  struct Pair {
    std::uint32_t first = 0;
    std::uint32_t second = 0;
    Vec3 shift = Vec3::Zero();  // added to the second particle's wrapped pose
  };
  std::vector<Pair> pairs;
  const double half_gap = options.gap / 2.0 + slack;
  auto add_self_images = [&](std::size_t i, const ImageShifts& images) {
    for (int image = 1; image < images.count; ++image) {
      const Vec3& shift = images.shifts[static_cast<std::size_t>(image)];
      if (shift.norm() < 2.0 * (radius[i] + half_gap)) {
        pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i), shift});
      }
    }
  };
  if (options.is_brute_force) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 centre = packing.particles[i].pose.position + offset[i];
      // An unbounded reach: every image one period away on each periodic axis.
      const ImageShifts images =
          image_shifts(container, centre, std::numeric_limits<double>::infinity());
      add_self_images(i, images);
      for (std::size_t j = i + 1; j < n; ++j) {
        for (int image = 0; image < images.count; ++image) {
          pairs.push_back({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j),
                           images.shifts[static_cast<std::size_t>(image)]});
        }
      }
    }
  } else if (n > 0) {
    detail::HierarchicalGrid grid(container.bounds(), smallest + half_gap, largest + half_gap);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 centre = packing.particles[i].pose.position + offset[i];
      const ImageShifts images =
          image_shifts(container, centre, radius[i] + largest + 2.0 * half_gap + grid.margin());
      add_self_images(i, images);
      for (int image = 0; image < images.count; ++image) {
        const Vec3& shift = images.shifts[static_cast<std::size_t>(image)];
        grid.for_each_near(centre + shift, radius[i] + half_gap,
                           [&](const detail::GridEntry& other, double) {
                             pairs.push_back({other.id, static_cast<std::uint32_t>(i), shift});
                             return true;
                           });
      }
      grid.insert(centre, radius[i] + half_gap);
    }
  }
  result.pairs_tested = pairs.size();
  std::vector<double> distance(pairs.size());
  parallel_for_index(0, pairs.size(), [&](std::size_t k) {
    const Pair& pair = pairs[k];
    Pose first = packing.particles[pair.first].pose;
    Pose second = packing.particles[pair.second].pose;
    first.position += offset[pair.first];
    second.position += offset[pair.second] + pair.shift;
    distance[k] = gjk_distance(bodies[pair.first], first, bodies[pair.second], second).distance;
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
