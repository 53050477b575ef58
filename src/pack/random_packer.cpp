#include "aggpack/pack/random_packer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "aggpack/core/clock.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/resources.h"
#include "aggpack/shape/generator.h"
#include "random_placement.h"

namespace aggpack {

namespace {

using namespace random_detail;  // NOLINT(google-build-using-namespace)

// The outcome of a particle's search: the first feasible attempt and its pose, or none.
struct Found {
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t attempt = kNone;
  Pose pose;
  [[nodiscard]] bool is_found() const { return attempt != kNone; }
};

StoredShape make_stored(const ConvexPolyhedron& grown) {
  StoredShape stored;
  Vec3 centroid;
  stored.body = detail::centred_on_centroid(grown, centroid, stored.volume);
  stored.outer_radius = bounding_radius(stored.body);
  stored.inner_radius = inner_radius(stored.body);
  return stored;
}

// Size, library slot and (unique mode) shape of draw i, all from stream (seed, i).
struct Draw {
  double size = 0.0;
  std::uint32_t library_index = 0;
  StoredShape shape;  // unique mode only
};

Draw make_draw(const RandomPackOptions& options, std::uint64_t index,
               const std::vector<std::uint32_t>& use_once) {
  Rng rng(options.seed, index);
  Draw draw;
  draw.size = sample_size(options.grading, rng.uniform());
  const double radius = draw.size / 2.0;
  if (const ShapeLibrary* files = options.shape.files.loaded.get()) {
    draw.library_index =
        use_once.empty() ? detail::library_slot(rng, files->shapes.size()) : use_once[index];
    return draw;
  }
  if (options.shape.library_size > 0) {
    draw.library_index = static_cast<std::uint32_t>(std::min<double>(
        std::floor(rng.uniform() * options.shape.library_size), options.shape.library_size - 1));
    return draw;
  }
  draw.shape = make_stored(grow_aggregate(growth_params(options.shape, radius), rng));
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
}  // namespace

GrowthParams growth_params(const ShapeOptions& shape, double radius) {
  return {
      .alpha = shape.alpha,
      .radius = radius,
      .edge_length = shape.edge_length > 0.0 ? shape.edge_length : shape.edge_length_ratio * radius,
      .max_vertices = shape.max_vertices,
      .form = shape.form};
}

PackResult pack_random(const RandomPackOptions& options, const PackControl& control) {
  validate(options);
  if (options.shape.files.is_used() && !options.shape.files.loaded) {
    throw InvalidInput("particle.library", options.shape.files.options.paths_text(),
                       Wording{Sentence::kLibraryLoadedFirst, {}});
  }
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
  const ShapeLibrary* files = options.shape.files.loaded.get();
  const bool is_library = options.shape.library_size > 0 || files != nullptr;
  std::vector<std::uint32_t> use_once;
  if (files != nullptr) {
    // Unit-size shapes from mesh files (enclosing radius 1): scale = sieve size / 2, as grown.
    shapes.resize(files->shapes.size());
    parallel_for_index(0, shapes.size(),
                       [&](std::size_t k) { shapes[k] = make_stored(files->shapes[k].body); });
    if (options.shape.files.options.is_use_once) {
      use_once = detail::use_once_order(shapes.size(), options.seed);
    }
  } else if (is_library) {
    shapes.resize(options.shape.library_size);
    parallel_for_index(0, shapes.size(), [&](std::size_t k) {
      Rng rng(options.seed ^ kLibrarySalt, k);
      shapes[k] = make_stored(grow_aggregate(growth_params(options.shape, 1.0), rng));
    });
  }
  std::vector<Item> items;
  double list_volume = 0.0;
  bool is_cancelled = false;
  {
    // Draws are made in batches (in parallel) and accepted in draw order, so the list is the same
    // for any thread count; a volume target stops at the first draw that reaches it.
    std::uint64_t wanted = is_by_volume ? kMaxParticles : options.count;
    if (!use_once.empty()) wanted = std::min<std::uint64_t>(wanted, use_once.size());
    const std::uint64_t batch_size = is_library ? 65536 : 4096;
    std::vector<Draw> batch;
    for (std::uint64_t begin = 0; begin < wanted;) {
      if (progress.is_cancelled()) {
        is_cancelled = true;
        break;
      }
      const std::uint64_t count = std::min(batch_size, wanted - begin);
      batch.assign(count, Draw{});
      parallel_for_index(
          0, count, [&](std::size_t k) { batch[k] = make_draw(options, begin + k, use_once); });
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
                      Wording{Sentence::kGrewBadShape,
                              {std::to_string(item.draw), format_value(item.size),
                               format_value(item.volume)}});
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
    if (is_by_volume && !is_cancelled && list_volume < target_volume && !use_once.empty()) {
      throw LimitExceeded("particle.library_use_once", "true",
                          Wording{Sentence::kLibraryReachesFraction,
                                  {std::to_string(use_once.size()), "random.volume_fraction",
                                   format_value(options.volume_fraction),
                                   format_value(list_volume / container_volume)}});
    }
    if (is_by_volume && !is_cancelled && list_volume < target_volume) {
      throw LimitExceeded("random.volume_fraction", format_value(options.volume_fraction),
                          Wording{Sentence::kFractionReachable, {}});
    }
  }
  if (is_periodic(options.container) && !is_cancelled) {
    double largest = 0.0;
    for (const Item& item : items) largest = std::max(largest, item.outer_radius);
    require_periodic_room(options.container, largest, options.gap);
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
  std::vector<CloseList> scratch(slots);
  CloseList sequential_scratch;
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
                    std::uint64_t limit, CloseList& close) -> Found {
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
  // A library's packing keeps only the shapes its particles use, in order of first use: the file
  // and every later reader hold what was placed, not the whole library.
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> stored_index(is_library ? shapes.size() : 0, kUnused);
  packing.shapes.reserve(is_library ? std::min(shapes.size(), placed_items.size())
                                    : placed_items.size());
  for (std::size_t i = 0; i < placed_items.size(); ++i) {
    const Item& item = items[placed_items[i]];
    Particle particle;
    particle.pose = poses[i];
    particle.control_radius = item.size / 2.0;
    particle.size_class = size_class(options.grading, item.size);
    particle.scale = item.scale;
    if (is_library) {
      std::uint32_t& index = stored_index[item.shape];
      if (index == kUnused) {
        index = static_cast<std::uint32_t>(packing.shapes.size());
        packing.shapes.push_back(std::move(shapes[item.shape].body));
        result.library_shapes.push_back(item.shape);
      }
      particle.shape = index;
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
