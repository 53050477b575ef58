#include "aggpack/pack/random_packer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/resources.h"
#include "aggpack/shape/generator.h"
#include "hierarchical_grid.h"
#include "shape_util.h"

namespace aggpack {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::uint64_t kMaxParticles = 100000000;               // size-list cap (10^8)
constexpr std::uint64_t kMaxLibrary = 1000000;                   // shape-library cap
constexpr std::uint64_t kPlacementSalt = 0x5851F42D4C957F2DULL;  // placement streams
constexpr std::uint64_t kLibrarySalt = 0x6C62272E07BB0142ULL;    // library shape streams
constexpr std::size_t kMaxBatch = 64;  // parallel attempts evaluated together for one particle
constexpr std::size_t kMaxGroup = 32;  // consecutive particles searched together

// The outcome of a particle's search: the first feasible attempt and its pose, or none.
struct Found {
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t attempt = kNone;
  Pose pose;
  [[nodiscard]] bool is_found() const { return attempt != kNone; }
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

double edge_length_for(const ShapeOptions& shape, double radius) {
  return shape.edge_length > 0.0 ? shape.edge_length : shape.edge_length_ratio * radius;
}

StoredShape make_stored(const ConvexPolyhedron& grown) {
  StoredShape stored;
  Vec3 centroid;
  stored.body = detail::centred_on_centroid(grown, centroid, stored.volume);
  stored.outer_radius = bounding_radius(stored.body);
  stored.inner_radius = detail::inner_radius(stored.body);
  return stored;
}

// Size, library slot and (unique mode) shape of draw i, all from stream (seed, i).
struct Draw {
  double size = 0.0;
  std::uint32_t library_index = 0;
  StoredShape shape;  // unique mode only
};

Draw make_draw(const RandomPackOptions& options, std::uint64_t index) {
  Rng rng(options.seed, index);
  Draw draw;
  draw.size = sample_size(options.grading, rng.uniform());
  const double radius = draw.size / 2.0;
  if (options.shape.library_size > 0) {
    draw.library_index = static_cast<std::uint32_t>(std::min<double>(
        std::floor(rng.uniform() * options.shape.library_size), options.shape.library_size - 1));
    return draw;
  }
  const GrowthParams params{.alpha = options.shape.alpha,
                            .radius = radius,
                            .edge_length = edge_length_for(options.shape, radius),
                            .max_vertices = options.shape.max_vertices};
  draw.shape = make_stored(grow_aggregate(params, rng));
  return draw;
}

// Throttled progress reporting; never throws into the packer.
class ProgressReporter {
 public:
  explicit ProgressReporter(const PackControl& control) : control_(control) {}
  [[nodiscard]] bool is_cancelled() const {
    return control_.cancel != nullptr && control_.cancel->load(std::memory_order_relaxed);
  }
  void report(const PackProgress& progress, bool is_final) {
    if (!control_.on_progress) return;
    const auto now = Clock::now();
    if (!is_final &&
        std::chrono::duration<double>(now - last_).count() < control_.progress_interval) {
      return;
    }
    last_ = now;
    control_.on_progress(progress);
  }

 private:
  const PackControl& control_;
  Clock::time_point last_ = Clock::now() - std::chrono::hours(1);
};

// The particles placed so far, and the broad phase over them.
class Placement {
 public:
  Placement(const RandomPackOptions& options, const std::vector<StoredShape>& shapes,
            const std::vector<Item>& items)
      : options_(options),
        shapes_(shapes),
        items_(items),
        grid_(options.container.bounds(), min_outer(items) + options.gap / 2.0,
              max_outer(items) + options.gap / 2.0) {}

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
                   std::vector<std::pair<double, std::uint32_t>>& close) const {
    const Container& container = options_.container;
    if (!is_in_centre_region(container, item.outer_radius, pose.position) &&
        !contains(container, body, pose)) {
      return false;
    }
    const double gap = options_.gap;
    close.clear();
    const bool is_clear =
        grid_.for_each_near(pose.position, item.outer_radius + gap / 2.0,
                            [&](const detail::GridEntry& other, double distance_squared) {
                              const double inner = item.inner_radius + other.inner_radius + gap;
                              if (distance_squared < inner * inner)
                                return false;  // inscribed balls too close
                              close.emplace_back(distance_squared, other.id);
                              return true;
                            });
    if (!is_clear) return false;
    // Closest first: the likeliest to conflict, so a rejection costs the fewest GJK calls.
    std::sort(close.begin(), close.end());
    for (const auto& [distance_squared, id] : close) {
      if (!is_separated_from(id, item, body, pose)) return false;
    }
    return true;
  }

  // Whether a pose is at least `gap` from every particle placed as number `first` or later (the
  // ones placed since a group of searches started).
  [[nodiscard]] bool is_clear_of_since(const Item& item, const ConvexPolyhedron& body,
                                       const Pose& pose, std::size_t first) const {
    // is_separated's own bounding-sphere test answers the far ones, with the same tolerance as
    // the grid path of is_feasible.
    for (std::size_t id = first; id < placed_items_.size(); ++id) {
      if (!is_separated_from(static_cast<std::uint32_t>(id), item, body, pose)) return false;
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
  std::vector<std::size_t> placed_items_;
  std::vector<Pose> poses_;
};

// Candidate pose number `attempt` of an item: from its own stream, so any thread can make it.
bool make_candidate(const Container& container, const Aabb& region, const Item& item,
                    std::uint64_t seed, std::uint64_t attempt, Pose& pose) {
  Rng rng(seed ^ kPlacementSalt, (item.draw << 32) | attempt);
  const Vec3 extent = region.extent();
  // Rejection sampling into the cylinder's disc (box: first draw always accepted).
  for (int tries = 0; tries < 64; ++tries) {
    const Vec3 centre(region.lower.x() + extent.x() * rng.uniform(),
                      region.lower.y() + extent.y() * rng.uniform(),
                      region.lower.z() + extent.z() * rng.uniform());
    if (container.kind == ContainerKind::kBox ||
        is_in_centre_region(container, item.inner_radius, centre)) {
      pose.position = centre;
      pose.rotation = detail::random_rotation(rng);
      return true;
    }
  }
  return false;
}

void validate_shape(const ShapeOptions& shape, double largest_radius) {
  require_in_range("shape.alpha", shape.alpha, 0.0, 1.0);
  if (!std::isfinite(shape.edge_length) || shape.edge_length < 0.0) {
    throw InvalidInput("shape.edge_length", format_value(shape.edge_length),
                       "finite and >= 0 (0 = relative, use shape.edge_length_ratio)");
  }
  if (shape.edge_length == 0.0) {
    require_in_range("shape.edge_length_ratio", shape.edge_length_ratio, 0.05, 10.0);
  }
  if (shape.max_vertices < 6 || shape.max_vertices > 1000000) {
    throw InvalidInput("shape.max_vertices", std::to_string(shape.max_vertices), "[6, 1000000]");
  }
  if (shape.library_size > kMaxLibrary) {
    throw InvalidInput("shape.library_size", std::to_string(shape.library_size), "[0, 1000000]");
  }
  if (shape.library_size > 0 && shape.edge_length > 0.0) {
    throw InvalidInput("shape.library_size", std::to_string(shape.library_size),
                       "0 when shape.edge_length > 0 (a library rescales shapes, so L must be "
                       "relative: set shape.edge_length = 0 and use shape.edge_length_ratio)");
  }
  const double estimate = shape.edge_length > 0.0
                              ? estimated_vertex_count(largest_radius, shape.edge_length)
                              : estimated_vertex_count(1.0, shape.edge_length_ratio);
  if (estimate > shape.max_vertices) {
    const std::string field =
        shape.edge_length > 0.0 ? "shape.edge_length" : "shape.edge_length_ratio";
    throw LimitExceeded(
        field, format_value(shape.edge_length > 0.0 ? shape.edge_length : shape.edge_length_ratio),
        "a value needing at most shape.max_vertices = " + std::to_string(shape.max_vertices) +
            " vertices (needs about " + format_value(std::round(estimate)) + ")");
  }
}

}  // namespace

void validate(const RandomPackOptions& options) {
  validate(options.container);
  validate(options.grading);
  validate_shape(options.shape, largest_size(options.grading) / 2.0);
  if (options.target == PackTarget::kCount) {
    if (options.count < 1 || options.count > kMaxParticles) {
      throw InvalidInput("random.count", std::to_string(options.count), "[1, 100000000]");
    }
  } else if (options.target == PackTarget::kVolumeFraction) {
    if (!std::isfinite(options.volume_fraction) || options.volume_fraction <= 0.0 ||
        options.volume_fraction > 0.9) {
      throw InvalidInput("random.volume_fraction", format_value(options.volume_fraction),
                         "(0, 0.9]");
    }
  } else {
    throw InvalidInput("random.target", std::to_string(static_cast<int>(options.target)),
                       "count or volume_fraction");
  }
  if (!std::isfinite(options.gap) || options.gap < 0.0) {
    throw InvalidInput("random.gap", format_value(options.gap), "finite and >= 0");
  }
  if (options.max_attempts_per_particle < 1 || options.max_attempts_per_particle > 1000000000ULL) {
    throw InvalidInput("random.max_attempts_per_particle",
                       std::to_string(options.max_attempts_per_particle), "[1, 1000000000]");
  }
  if (options.max_total_attempts < 1 || options.max_total_attempts > 1000000000000ULL) {
    throw InvalidInput("random.max_total_attempts", std::to_string(options.max_total_attempts),
                       "[1, 1000000000000]");
  }
  if (options.max_consecutive_failures < 1 || options.max_consecutive_failures > 1000000000ULL) {
    throw InvalidInput("random.max_consecutive_failures",
                       std::to_string(options.max_consecutive_failures), "[1, 1000000000]");
  }
  // Every grown particle contains the octahedron of its six base vertices, each at least
  // r (alpha + 0.2 (1 - alpha)) from the centre (Eq. 3), and so a ball of that radius / sqrt(3).
  // If even the smallest such ball plus the wall gaps does not fit, nothing can be placed.
  const Aabb bounds = options.container.bounds();
  const double interior = bounds.extent().minCoeff() - 2.0 * options.container.wall_gap;
  const double smallest_ball = smallest_size(options.grading) / 2.0 *
                               (options.shape.alpha + 0.2 * (1.0 - options.shape.alpha)) /
                               std::sqrt(3.0);
  if (2.0 * smallest_ball > interior) {
    throw InvalidInput(
        "grading", "smallest size " + format_value(smallest_size(options.grading)) + " m",
        "particles that fit in the container's interior (" + format_value(interior) + " m across)");
  }
  if (options.target == PackTarget::kVolumeFraction) {
    // Lower bound on the list length: particles no larger than their control spheres.
    const double sphere = std::numbers::pi / 6.0 * mean_cubed_size(options.grading);
    const double least = options.volume_fraction * options.container.volume() / sphere;
    if (least > static_cast<double>(kMaxParticles)) {
      throw LimitExceeded("random.volume_fraction", format_value(options.volume_fraction),
                          "a target needing at most 10^8 particles (needs more than " +
                              format_value(std::round(least)) + ")");
    }
  }
  // Runs the container cannot hold or the memory cannot take (issue 12), before any work.
  check_resources(options);
}

PackResult pack_random(const RandomPackOptions& options, const PackControl& control) {
  validate(options);
  ProgressReporter progress(control);
  PackResult result;
  PackReport& report = result.report;
  const double container_volume = options.container.volume();
  report.container_volume = container_volume;
  const bool is_by_volume = options.target == PackTarget::kVolumeFraction;
  const double target_volume = is_by_volume ? options.volume_fraction * container_volume : 0.0;
  report.target_solid_fraction = is_by_volume ? options.volume_fraction : 0.0;

  // --- 1. The size list and the shapes ----------------------------------------------------------
  const auto shape_start = Clock::now();
  std::vector<StoredShape> shapes;
  const bool is_library = options.shape.library_size > 0;
  if (is_library) {
    shapes.resize(options.shape.library_size);
    const double ratio = options.shape.edge_length_ratio;
    parallel_for_index(0, shapes.size(), [&](std::size_t k) {
      Rng rng(options.seed ^ kLibrarySalt, k);
      const GrowthParams params{.alpha = options.shape.alpha,
                                .radius = 1.0,
                                .edge_length = ratio,
                                .max_vertices = options.shape.max_vertices};
      shapes[k] = make_stored(grow_aggregate(params, rng));
    });
  }
  std::vector<Item> items;
  double list_volume = 0.0;
  bool is_cancelled = false;
  {
    // Draws are made in batches (in parallel) and accepted in draw order, so the list is the same
    // for any thread count; a volume target stops at the first draw that reaches it.
    const std::uint64_t wanted = is_by_volume ? kMaxParticles : options.count;
    const std::uint64_t batch_size = is_library ? 65536 : 4096;
    std::vector<Draw> batch;
    for (std::uint64_t begin = 0; begin < wanted;) {
      if (progress.is_cancelled()) {
        is_cancelled = true;
        break;
      }
      const std::uint64_t count = std::min(batch_size, wanted - begin);
      batch.assign(count, Draw{});
      parallel_for_index(0, count,
                         [&](std::size_t k) { batch[k] = make_draw(options, begin + k); });
      bool is_done = false;
      for (std::uint64_t k = 0; k < count && !is_done; ++k) {
        Draw& draw = batch[k];
        Item item;
        item.draw = begin + k;
        item.size = draw.size;
        if (is_library) {
          const StoredShape& stored = shapes[draw.library_index];
          const double scale = draw.size / 2.0;
          item.shape = draw.library_index;
          item.scale = scale;
          item.volume = stored.volume * scale * scale * scale;
          item.outer_radius = stored.outer_radius * scale;
          item.inner_radius = stored.inner_radius * scale;
        } else {
          item.shape = static_cast<std::uint32_t>(shapes.size());
          item.volume = draw.shape.volume;
          item.outer_radius = draw.shape.outer_radius;
          item.inner_radius = draw.shape.inner_radius;
          shapes.push_back(std::move(draw.shape));
        }
        // A non-finite or empty shape would keep a volume target from ever being reached.
        if (!std::isfinite(item.volume) || !(item.volume > 0.0) ||
            !std::isfinite(item.outer_radius)) {
          throw Error(ErrorKind::kLimitExceeded,
                      "random packer: draw " + std::to_string(item.draw) + " (size " +
                          format_value(item.size) + " m) grew a shape of volume " +
                          format_value(item.volume) + " m^3; stopped (sizes out of range?)");
        }
        items.push_back(item);
        list_volume += item.volume;
        if (is_by_volume && list_volume >= target_volume) is_done = true;
      }
      begin += count;
      const double fraction = is_by_volume
                                  ? std::min(1.0, list_volume / target_volume)
                                  : static_cast<double>(begin) / static_cast<double>(wanted);
      progress.report({.stage = PackStage::kShapes, .fraction = fraction, .total = items.size()},
                      false);
      if (is_done) break;
    }
    if (is_by_volume && !is_cancelled && list_volume < target_volume) {
      throw LimitExceeded("random.volume_fraction", format_value(options.volume_fraction),
                          "a target reachable with 10^8 particles");
    }
  }
  report.requested = items.size();
  report.shape_seconds = seconds_since(shape_start);

  // --- 2. Largest first
  // ---------------------------------------------------------------------------
  std::vector<std::size_t> order(items.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return items[a].size > items[b].size;  // stable: ties keep draw order
  });

  // --- 3. Placement
  // -------------------------------------------------------------------------------
  // Each particle takes the first attempt (in attempt order) that is feasible against every
  // particle placed before it. Two kinds of parallelism keep exactly that result:
  //  - a group of consecutive particles searches at once, each against the particles placed
  //    before the group; they are then committed in order, and a particle whose found pose
  //    touches one committed earlier in the same group resumes its search from the next attempt
  //    (its earlier attempts failed against a subset, so they fail against the whole);
  //  - a single particle evaluates batches of attempts at once (used when the attempt budget is
  //    nearly spent, or with one worker).
  const auto placement_start = Clock::now();
  Placement placement(options, shapes, items);
  const int threads = concurrency();
  const std::size_t slots = static_cast<std::size_t>(std::max(1, threads)) + 1;
  std::vector<std::vector<std::pair<double, std::uint32_t>>> scratch(slots);
  std::vector<std::pair<double, std::uint32_t>> sequential_scratch;
  std::vector<Pose> batch_poses(kMaxBatch);
  std::vector<char> batch_ok(kMaxBatch);
  const std::size_t group_size =
      threads > 1 ? std::min<std::size_t>(kMaxGroup, 8 * static_cast<std::size_t>(threads)) : 1;
  std::vector<Found> found(group_size);
  std::vector<ConvexPolyhedron> group_bodies(group_size);
  double placed_volume = 0.0;
  std::uint64_t consecutive_failures = 0;
  StopReason stop = StopReason::kSizeListExhausted;
  bool is_stopped = is_cancelled;
  if (is_cancelled) stop = StopReason::kCancelled;
  std::uint64_t tried = 0;

  // Attempts [first, limit) of one particle, one by one, against everything placed so far.
  auto search = [&](const Item& item, const ConvexPolyhedron& body, std::uint64_t first,
                    std::uint64_t limit,
                    std::vector<std::pair<double, std::uint32_t>>& close) -> Found {
    Found outcome;
    const Aabb region = centre_region(options.container, item.inner_radius);
    if (region.is_empty()) return outcome;
    for (std::uint64_t attempt = first; attempt < limit; ++attempt) {
      Pose pose;
      if (make_candidate(options.container, region, item, options.seed, attempt, pose) &&
          placement.is_feasible(item, body, pose, close)) {
        outcome.attempt = attempt;
        outcome.pose = pose;
        return outcome;
      }
    }
    return outcome;
  };

  // Attempts [0, limit) of one particle, in parallel batches that double in size.
  auto search_batched = [&](const Item& item, const ConvexPolyhedron& body,
                            std::uint64_t limit) -> Found {
    if (threads <= 1) return search(item, body, 0, limit, sequential_scratch);
    Found outcome;
    const Aabb region = centre_region(options.container, item.inner_radius);
    if (region.is_empty()) return outcome;
    std::uint64_t attempt = 0;
    std::size_t batch = 1;
    while (attempt < limit && !outcome.is_found()) {
      const std::size_t count =
          static_cast<std::size_t>(std::min<std::uint64_t>(batch, limit - attempt));
      if (count == 1) {
        outcome = search(item, body, attempt, attempt + 1, sequential_scratch);
      } else {
        // The lowest successful attempt index wins, exactly as if tried one by one.
        std::atomic<std::uint64_t> best{Found::kNone};
        std::fill(batch_ok.begin(), batch_ok.begin() + static_cast<std::ptrdiff_t>(count), 0);
        parallel_for_index(0, count, [&](std::size_t k) {
          if (attempt + k > best.load(std::memory_order_relaxed)) return;
          auto& close = scratch[worker_slot() % slots];
          Pose pose;
          if (make_candidate(options.container, region, item, options.seed, attempt + k, pose) &&
              placement.is_feasible(item, body, pose, close)) {
            batch_poses[k] = pose;
            batch_ok[k] = 1;
            std::uint64_t current = best.load();
            while (attempt + k < current && !best.compare_exchange_weak(current, attempt + k)) {
            }
          }
        });
        for (std::size_t k = 0; k < count; ++k) {
          if (batch_ok[k]) {
            outcome.attempt = attempt + k;
            outcome.pose = batch_poses[k];
            break;
          }
        }
      }
      attempt += count;
      batch = std::min(batch * 2, kMaxBatch);
    }
    return outcome;
  };

  for (std::size_t rank = 0; rank < order.size() && !is_stopped;) {
    if (progress.is_cancelled()) {
      stop = StopReason::kCancelled;
      break;
    }
    const std::uint64_t remaining_budget = options.max_total_attempts - report.attempts;
    if (remaining_budget == 0) {
      stop = StopReason::kAttemptBudget;
      break;
    }
    // A group only while the budget cannot run out inside it (the per-particle limit then does
    // not depend on what the group's earlier members used).
    std::size_t group = std::min(group_size, order.size() - rank);
    if (static_cast<double>(remaining_budget) <
        static_cast<double>(group) * static_cast<double>(options.max_attempts_per_particle)) {
      group = 1;
    }
    const std::size_t first_new = placement.placed_items().size();
    if (group > 1) {
      parallel_for_index(0, group, [&](std::size_t k) {
        const Item& item = items[order[rank + k]];
        group_bodies[k] = placement.body_of(item);
        found[k] = search(item, group_bodies[k], 0, options.max_attempts_per_particle,
                          scratch[worker_slot() % slots]);
      });
    }
    for (std::size_t k = 0; k < group && !is_stopped; ++k) {
      if (k > 0 && progress.is_cancelled()) {
        stop = StopReason::kCancelled;
        is_stopped = true;
        break;
      }
      const Item& item = items[order[rank + k]];
      const std::uint64_t limit =
          std::min(options.max_attempts_per_particle, options.max_total_attempts - report.attempts);
      Found outcome;
      if (group == 1) {
        outcome = search_batched(item, placement.body_of(item), limit);
      } else {
        outcome = found[k];
        if (outcome.is_found() &&
            !placement.is_clear_of_since(item, group_bodies[k], outcome.pose, first_new)) {
          outcome = search(item, group_bodies[k], outcome.attempt + 1, limit, sequential_scratch);
        }
      }
      ++tried;
      if (outcome.is_found()) {
        report.attempts += outcome.attempt + 1;
        placement.add(order[rank + k], outcome.pose);
        placed_volume += item.volume;
        consecutive_failures = 0;
        if (is_by_volume && placed_volume >= target_volume) {
          stop = StopReason::kTargetReached;
          is_stopped = true;
        }
      } else {
        report.attempts += limit;
        ++report.rejected;
        ++consecutive_failures;
        if (limit < options.max_attempts_per_particle) {
          stop = StopReason::kAttemptBudget;
          is_stopped = true;
        } else if (consecutive_failures >= options.max_consecutive_failures) {
          stop = StopReason::kConsecutiveFailures;
          is_stopped = true;
        }
      }
      const std::uint64_t placed = placement.placed_items().size();
      progress.report({.stage = PackStage::kPlacement,
                       .fraction = is_by_volume ? std::min(1.0, placed_volume / target_volume)
                                                : static_cast<double>(placed) /
                                                      static_cast<double>(options.count),
                       .placed = placed,
                       .attempted = tried,
                       .total = items.size(),
                       .solid_fraction = placed_volume / container_volume},
                      false);
    }
    rank += group;
  }
  if (!is_by_volume && stop == StopReason::kSizeListExhausted && report.rejected == 0 &&
      placement.placed_items().size() == items.size()) {
    stop = StopReason::kTargetReached;
  }
  report.placement_seconds = seconds_since(placement_start);

  // --- 4. The Packing ----------------------------------------------------------------------------
  Packing& packing = result.packing;
  packing.container = options.container;
  packing.provenance.seed = options.seed;
  packing.provenance.packer = "random";
  const auto& placed_items = placement.placed_items();
  const auto& poses = placement.poses();
  packing.particles.reserve(placed_items.size());
  if (is_library) {
    packing.shapes.reserve(shapes.size());
    for (auto& stored : shapes) packing.shapes.push_back(std::move(stored.body));
  } else {
    packing.shapes.reserve(placed_items.size());
  }
  for (std::size_t i = 0; i < placed_items.size(); ++i) {
    const Item& item = items[placed_items[i]];
    Particle particle;
    particle.pose = poses[i];
    particle.control_radius = item.size / 2.0;
    particle.size_class = size_class(options.grading, item.size);
    particle.scale = item.scale;
    if (is_library) {
      particle.shape = item.shape;
    } else {
      particle.shape = static_cast<std::uint32_t>(packing.shapes.size());
      packing.shapes.push_back(std::move(shapes[item.shape].body));
    }
    packing.particles.push_back(particle);
  }
  report.placed = packing.particles.size();
  report.solid_volume = placed_volume;
  report.solid_fraction = placed_volume / container_volume;
  report.stop_reason = stop;
  report.is_target_reached = stop == StopReason::kTargetReached;
  progress.report({.stage = PackStage::kPlacement,
                   .fraction = report.is_target_reached ? 1.0
                               : is_by_volume ? std::min(1.0, placed_volume / target_volume)
                                              : static_cast<double>(report.placed) /
                                                    static_cast<double>(options.count),
                   .placed = report.placed,
                   .attempted = tried,
                   .total = items.size(),
                   .solid_fraction = report.solid_fraction},
                  true);
  return result;
}

}  // namespace aggpack
