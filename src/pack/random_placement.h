#pragma once
// Internal to the random packer (random_packer*.cpp): the size-list entries, the placed particles
// with their broad phase (Placement), and candidate poses.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "aggpack/core/rng.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/random_packer.h"
#include "hierarchical_grid.h"
#include "shape_util.h"

namespace aggpack::random_detail {

constexpr std::uint64_t kMaxParticles = 100000000;               // size-list cap (10^8)
constexpr std::uint64_t kMaxLibrary = 1000000;                   // shape-library cap
constexpr std::uint64_t kPlacementSalt = 0x5851F42D4C957F2DULL;  // placement streams
constexpr std::uint64_t kLibrarySalt = 0x6C62272E07BB0142ULL;    // library shape streams
constexpr std::size_t kMaxBatch = 64;  // parallel attempts evaluated together for one particle
constexpr std::size_t kMaxGroup = 32;  // consecutive particles searched together

// One entry of the size list.
struct Item {
  std::uint64_t draw = 0;     // draw index: the particle's stream
  double size = 0.0;          // control diameter (m)
  std::uint32_t shape = 0;    // index into Shapes::bodies
  double scale = 1.0;         // library: control radius; unique: 1
  double volume = 0.0;        // exact, at true size (m^3)
  double outer_radius = 0.0;  // bounding radius about the centroid, true size (m)
  double inner_radius = 0.0;  // inscribed-ball radius about the centroid, true size (m)
};

// Unit-size library shape or a per-particle shape, with its radii at stored size.
struct StoredShape {
  ConvexPolyhedron body;  // centroid at the origin
  double volume = 0.0;
  double outer_radius = 0.0;
  double inner_radius = 0.0;
};

// A placed particle near a candidate: the squared centre distance (broad phase), its id, and
// which of the candidate's periodic images met it (0 = the candidate itself; ImageShifts order).
struct Close {
  double distance_squared = 0.0;
  std::uint32_t id = 0;
  std::uint32_t image = 0;
  bool operator<(const Close& other) const {
    if (distance_squared != other.distance_squared) {
      return distance_squared < other.distance_squared;
    }
    if (id != other.id) return id < other.id;
    return image < other.image;
  }
};
using CloseList = std::vector<Close>;

// The particles placed so far, and the broad phase over them. In a periodic box the centres stay
// in [0, extent) and a candidate is tested through each of its images that can reach the box.
class Placement {
 public:
  Placement(const RandomPackOptions& options, const std::vector<StoredShape>& shapes,
            const std::vector<Item>& items)
      : options_(options),
        shapes_(shapes),
        items_(items),
        grid_(options.container.bounds(), min_outer(items) + options.gap / 2.0,
              max_outer(items) + options.gap / 2.0),
        max_outer_(max_outer(items)) {}

  // The true-size body of an item (a copy only for library shapes).
  [[nodiscard]] ConvexPolyhedron body_of(const Item& item) const {
    const ConvexPolyhedron& stored = shapes_[item.shape].body;
    return item.scale == 1.0 ? stored : stored.scaled(item.scale);
  }

  // Tests one candidate pose: inside the container minus wall_gap, and at least `gap` from every
  // placed particle. Cheap tests first: centre-region sphere test, vertex containment, then per
  // neighbour the bounding spheres (grid), the inscribed balls (certain overlap), and finally the
  // exact GJK test for the remaining close pairs.
  bool is_feasible(const Item& item, const ConvexPolyhedron& body, const Pose& pose,
                   CloseList& close) const {
    const Container& container = options_.container;
    if (!is_in_centre_region(container, item.outer_radius, pose.position) &&
        !contains(container, body, pose)) {
      return false;
    }
    const double gap = options_.gap;
    close.clear();
    const ImageShifts images = shifts_of(item, pose);
    for (int image = 0; image < images.count; ++image) {
      const Vec3 centre = pose.position + images.shifts[static_cast<std::size_t>(image)];
      const bool is_clear = grid_.for_each_near(
          centre, item.outer_radius + gap / 2.0,
          [&](const detail::GridEntry& other, double distance_squared) {
            const double inner = item.inner_radius + other.inner_radius + gap;
            if (distance_squared < inner * inner) return false;  // inscribed balls too close
            close.push_back({distance_squared, other.id, static_cast<std::uint32_t>(image)});
            return true;
          });
      if (!is_clear) return false;
    }
    // Closest first: the likeliest to conflict, so a rejection costs the fewest GJK calls.
    std::sort(close.begin(), close.end());
    for (const Close& each : close) {
      if (!is_separated_from(each.id, item, body, shifted(pose, images, each.image))) return false;
    }
    return true;
  }

  // Whether a pose is at least `gap` from every particle placed as number `first` or later (the
  // ones placed since a group of searches started).
  [[nodiscard]] bool is_clear_of_since(const Item& item, const ConvexPolyhedron& body,
                                       const Pose& pose, std::size_t first) const {
    // is_separated's own bounding-sphere test answers the far ones, with the same tolerance as
    // the grid path of is_feasible.
    const ImageShifts images = shifts_of(item, pose);
    for (std::size_t id = first; id < placed_items_.size(); ++id) {
      for (int image = 0; image < images.count; ++image) {
        if (!is_separated_from(static_cast<std::uint32_t>(id), item, body,
                               shifted(pose, images, static_cast<std::uint32_t>(image)))) {
          return false;
        }
      }
    }
    return true;
  }

  void add(std::size_t item_index, const Pose& pose) {
    const Item& item = items_[item_index];
    grid_.insert(pose.position, item.outer_radius + options_.gap / 2.0, item.inner_radius);
    placed_items_.push_back(item_index);
    poses_.push_back(pose);
  }

  [[nodiscard]] const std::vector<std::size_t>& placed_items() const { return placed_items_; }
  [[nodiscard]] const std::vector<Pose>& poses() const { return poses_; }

 private:
  // The candidate's images that may meet a placed particle (only itself unless periodic).
  [[nodiscard]] ImageShifts shifts_of(const Item& item, const Pose& pose) const {
    return image_shifts(options_.container, pose.position,
                        item.outer_radius + max_outer_ + options_.gap + grid_.margin());
  }
  static Pose shifted(const Pose& pose, const ImageShifts& images, std::uint32_t image) {
    if (image == 0) return pose;
    Pose moved = pose;
    moved.position += images.shifts[image];
    return moved;
  }

  // The exact test of a candidate against placed particle `id`.
  [[nodiscard]] bool is_separated_from(std::uint32_t id, const Item& item,
                                       const ConvexPolyhedron& body, const Pose& pose) const {
    // Unique shapes have scale 1 (exact: 1 * x == x), library shapes their control radius.
    const Item& other = items_[placed_items_[id]];
    return is_separated(body, pose, item.outer_radius, shapes_[other.shape].body, other.scale,
                        poses_[id], other.outer_radius, options_.gap);
  }

  static double min_outer(const std::vector<Item>& items) {
    double value = std::numeric_limits<double>::infinity();
    for (const auto& item : items) value = std::min(value, item.outer_radius);
    return items.empty() ? 1.0 : value;
  }
  static double max_outer(const std::vector<Item>& items) {
    double value = 0.0;
    for (const auto& item : items) value = std::max(value, item.outer_radius);
    return items.empty() ? 1.0 : value;
  }

  const RandomPackOptions& options_;
  const std::vector<StoredShape>& shapes_;
  const std::vector<Item>& items_;
  detail::HierarchicalGrid grid_;
  double max_outer_ = 0.0;
  std::vector<std::size_t> placed_items_;
  std::vector<Pose> poses_;
};

// Candidate pose number `attempt` of an item: from its own stream, so any thread can make it.
inline bool make_candidate(const Container& container, const Aabb& region, const Item& item,
                           std::uint64_t seed, std::uint64_t attempt, Pose& pose) {
  Rng rng(seed ^ kPlacementSalt, (item.draw << 32) | attempt);
  const Vec3 extent = region.extent();
  // Rejection sampling into the cylinder's disc (box: first draw always accepted).
  for (int tries = 0; tries < 64; ++tries) {
    const Vec3 centre(region.lower.x() + extent.x() * rng.uniform(),
                      region.lower.y() + extent.y() * rng.uniform(),
                      region.lower.z() + extent.z() * rng.uniform());
    if (centre_region_is_bounds(container) ||
        is_in_centre_region(container, item.inner_radius, centre)) {
      pose.position = centre;
      pose.rotation = detail::random_rotation(rng);
      return true;
    }
  }
  return false;
}

}  // namespace aggpack::random_detail
