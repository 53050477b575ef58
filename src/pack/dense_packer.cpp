// The densifying packer's driver: options, the sweep / compression schedule, budgets, progress,
// the bed's bulk measurement and the final exact verification. The engine is hpmc.cpp.

#include "aggpack/pack/dense_packer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <tuple>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/statistics.h"
#include "aggpack/pack/verify.h"
#include "hpmc.h"

namespace aggpack {

namespace {

std::string number(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

void require(bool is_ok, const std::string& option, double value, const std::string& allowed) {
  if (!is_ok) throw InvalidInput("densify." + option, number(value), allowed);
}

// The target container of kFixed: explicit, or the start shrunk uniformly to the target fraction.
Container target_of(const Packing& start, const DensifyOptions& options, double solid_volume) {
  const Container& from = start.container;
  if (options.target_container) {
    Container target = *options.target_container;
    validate(target);
    const std::string field = "densify.target_container";
    const ContainerKindInfo& kind = container_kind_info(target);
    if (target.shape.index() != from.shape.index()) {
      throw InvalidInput(field, kind.name, "the start container's kind");
    }
    if (target.wall_gap != from.wall_gap) {
      throw InvalidInput(field + ".wall_gap", number(target.wall_gap),
                         "the start container's wall_gap " + number(from.wall_gap));
    }
    auto no_larger = [&](const char* name, double to, double was) {
      if (to > was) {
        throw InvalidInput(field + "." + name, number(to),
                           "(0, " + number(was) + "], no larger than the start container");
      }
    };
    for (const ContainerParam& param : kind.params) {
      no_larger(param.name, param.get(target), param.get(from));
    }
    // The target has the start's periodic axes (the target's own sizes are all that is asked).
    if (auto* box = target.get_if<BoxContainer>()) box->periodic = periodic_axes(from);
    return target;
  }
  Container target = from;
  if (options.target_fraction > 0.0) {
    const double now = solid_volume / from.volume();
    if (now < options.target_fraction) {
      const double scale = std::cbrt(now / options.target_fraction);
      target = container_scaled(target, Vec3::Constant(scale));
    }
  }
  return target;
}

bool same_size(const Container& a, const Container& b) { return a.shape == b.shape; }

}  // namespace

void refuse_periodic_bed(const Container& container, DensifyMode mode) {
  const std::array<bool, 3> axes = periodic_axes(container);
  if (mode == DensifyMode::kBed && axes[2]) {
    throw InvalidInput("container.periodic", "\"" + periodic_word(axes) + "\"",
                       {Sentence::kPeriodicUnsupported,
                        {"\"none\", \"x\", \"y\" or \"xy\"", "densify.mode = bed"}});
  }
}

std::string to_string(DensifyMode mode) { return mode == DensifyMode::kFixed ? "fixed" : "bed"; }

DensifyMode parse_densify_mode(const std::string& field, const std::string& text) {
  if (text == "fixed") return DensifyMode::kFixed;
  if (text == "bed") return DensifyMode::kBed;
  throw InvalidInput(field, text, "fixed or bed");
}

std::string to_string(DensifyStop stop) {
  switch (stop) {
    case DensifyStop::kTargetReached:
      return "target reached";
    case DensifyStop::kSettled:
      return "settled (the bed stopped compacting)";
    case DensifyStop::kJammed:
      return "jammed (the fraction stopped rising)";
    case DensifyStop::kSweepBudget:
      return "sweep budget used up";
    case DensifyStop::kTimeBudget:
      return "time budget used up";
    case DensifyStop::kCancelled:
      return "cancelled";
  }
  return "unknown";
}

std::string DensifyReport::summary() const {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(4);
  out << start_fraction << " -> " << solid_fraction << " solid";
  if (bulk_fraction > 0.0) out << " (bulk " << bulk_fraction << ")";
  out << " in " << sweeps << " sweeps (" << format_seconds(seconds) << " s), " << to_string(stop);
  return out.str();
}

void validate(const DensifyOptions& o) {
  require(o.target_fraction >= 0.0 && o.target_fraction < 0.95, "target_fraction",
          o.target_fraction, "[0, 0.95); 0 = no fraction target");
  require(std::isfinite(o.gap) && o.gap >= 0.0, "gap", o.gap, ">= 0 (m)");
  require(o.max_sweeps >= 1 && o.max_sweeps <= 1000000000ULL, "max_sweeps",
          static_cast<double>(o.max_sweeps), "an integer in [1, 1e9]");
  require(std::isfinite(o.max_seconds) && o.max_seconds >= 0.0, "max_seconds", o.max_seconds,
          ">= 0 (s); 0 = no time budget");
  require(o.target_acceptance > 0.0 && o.target_acceptance < 1.0, "target_acceptance",
          o.target_acceptance, "(0, 1)");
  require(o.translation_step > 0.0 && o.translation_step <= 1.0, "translation_step",
          o.translation_step, "(0, 1] (bounding radii)");
  require(o.rotation_step > 0.0 && o.rotation_step <= std::numbers::pi, "rotation_step",
          o.rotation_step, "(0, pi] (rad)");
  require(o.rotation_probability >= 0.0 && o.rotation_probability <= 1.0, "rotation_probability",
          o.rotation_probability, "[0, 1]");
  require(o.compress_interval >= 1 && o.compress_interval <= 1000, "compress_interval",
          o.compress_interval, "an integer in [1, 1000]");
  require(o.max_compression > 0.0 && o.max_compression <= 0.1, "max_compression", o.max_compression,
          "(0, 0.1]");
  require(std::isfinite(o.bed_temperature) && o.bed_temperature >= 0.0, "bed_temperature",
          o.bed_temperature, ">= 0");
  require(o.bed_cooling > 0.0 && o.bed_cooling <= 1.0, "bed_cooling", o.bed_cooling, "(0, 1]");
  require(o.stall_sweeps >= 1 && o.stall_sweeps <= 1000000000ULL, "stall_sweeps",
          static_cast<double>(o.stall_sweeps), "an integer in [1, 1e9]");
  require(std::isfinite(o.stall_tolerance) && o.stall_tolerance >= 0.0, "stall_tolerance",
          o.stall_tolerance, ">= 0");
}

void measure_bulk(const Packing& packing, DensifyReport& report) {
  const Container& container = packing.container;
  const Aabb bounds = container.bounds();
  double r_max = 0.0;
  std::vector<double> tops;
  std::vector<ConvexPolyhedron> bodies;
  bodies.reserve(packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    bodies.push_back(packing.placed(i));
    r_max = std::max(r_max, packing.particles[i].control_radius);
  }
  // Columns of width 2 r_max (r_max from the bodies' extents when control radii are 0).
  double extent_max = 0.0;
  for (const auto& body : bodies) {
    const Aabb box = body.bounds();
    extent_max = std::max(extent_max, box.extent().maxCoeff());
  }
  r_max = std::max(r_max, 0.5 * extent_max);
  if (bodies.empty() || r_max <= 0.0) return;
  const double column = 2.0 * r_max;
  const auto nx = static_cast<std::int64_t>(std::max(1.0, std::ceil(bounds.extent().x() / column)));
  const auto ny = static_cast<std::int64_t>(std::max(1.0, std::ceil(bounds.extent().y() / column)));
  std::vector<double> highest(static_cast<std::size_t>(nx * ny), -1e300);
  for (const auto& body : bodies) {
    const Aabb box = body.bounds();
    const Vec3 centre = 0.5 * (box.lower + box.upper);
    const auto cx = std::clamp<std::int64_t>(
        static_cast<std::int64_t>((centre.x() - bounds.lower.x()) / column), 0, nx - 1);
    const auto cy = std::clamp<std::int64_t>(
        static_cast<std::int64_t>((centre.y() - bounds.lower.y()) / column), 0, ny - 1);
    double& h = highest[static_cast<std::size_t>(cy * nx + cx)];
    h = std::max(h, box.upper.z());
  }
  for (double h : highest) {
    if (h > -1e300) tops.push_back(h);
  }
  std::sort(tops.begin(), tops.end());
  const double surface = tops[tops.size() / 2];
  double lower = bounds.lower.z() + 2.0 * r_max;
  double upper = surface - 4.0 * r_max;
  if (upper <= lower) {
    lower = bounds.lower.z();
    upper = bounds.lower.z() + 0.5 * (surface - bounds.lower.z());
  }
  double solid = 0.0;
  for (const auto& body : bodies) {
    solid += volume_below(body, 2, upper) - volume_below(body, 2, lower);
  }
  report.surface_height = surface;
  report.bulk_lower = lower;
  report.bulk_upper = upper;
  const double slab = container_slab_volume(container, 2, lower, upper);
  report.bulk_fraction = slab > 0.0 ? solid / slab : 0.0;
}

DensifyResult densify(Packing start, const DensifyOptions& options, const PackControl& control) {
  using Clock = std::chrono::steady_clock;
  const auto began = Clock::now();
  validate(options);
  validate(start.container);
  refuse_periodic_bed(start.container, options.mode);
  {
    const VerifyResult check = verify(start, {.gap = options.gap});
    if (!check.is_ok) {
      throw InvalidInput(Wording{Sentence::kStartPacking, {}}, check.wording,
                         Wording{Sentence::kOverlapFreeStart, {number(options.gap)}});
    }
  }
  detail::Hpmc engine(start, options.gap, options.seed, options.max_compression);
  const double solid_volume = engine.solid_volume();
  const bool is_bed = options.mode == DensifyMode::kBed;
  const Container target = is_bed ? start.container : target_of(start, options, solid_volume);
  // A periodic box is compressed no further than its particles allow: a particle never meets
  // its own image, and a neighbour only the images one period away (the engine relies on it).
  if (is_periodic(target)) {
    require_periodic_room(target, engine.max_outer_radius(), options.gap);
  }

  DensifyReport report;
  report.start_fraction = solid_volume / start.container.volume();
  detail::SweepParameters parameters{
      .translation_step = options.translation_step,
      .rotation_step = options.rotation_step,
      .rotation_probability = options.rotation_probability,
      .is_bed = is_bed,
      .temperature = options.bed_temperature,
      .per_particle_acceptance = is_bed ? 0.0 : options.target_acceptance};
  // kFixed: squeeze (shrink without checking) whenever at most kAllowedShare of the particles
  // overlap; sweeps repair (with overlap transfer, hpmc.cpp). After kSqueezesPerCheckpoint
  // squeezes (or at the target container) no more squeezes until everything is repaired: that
  // clean state is the next checkpoint, the only kind of state ever returned. A consolidation
  // that stalls undoes part of the squeezes (every kStallSweeps sweeps) and finally goes back to
  // the checkpoint. Chosen by paired runs on 1,041 and 9,078 single-size particles
  // (bench/RESULTS.md): with overlap transfer, squeezes that flag more pay off (the earlier
  // "no new partner" repair had 5 %, 3-12 %, 16 squeezes, 16 sweeps).
  constexpr std::uint64_t kStallSweeps = 32;
  constexpr std::uint64_t kSqueezesPerCheckpoint = 64;  // at most; fewer after a failed repair
  constexpr double kAllowedShare = 0.15;  // squeeze only while at most this share is flagged
  constexpr double kFreshHigh = 0.25;     // a squeeze flagging more is undone and halved
  constexpr double kFreshLow = 0.10;      // a squeeze flagging less grows the next one x1.2
  constexpr double kRepairReach = 4.0;    // repair push <= this x the squeeze step (radii)
  std::uint64_t squeezes_per_checkpoint = kSqueezesPerCheckpoint;
  const auto particle_count = static_cast<double>(start.particles.size());
  const auto allowed_overlaps = static_cast<std::size_t>(kAllowedShare * particle_count);
  double squeeze_step = 0.25 * options.max_compression;  // relative shrink of the largest share
  bool is_repairing = false;                             // some particles overlap
  bool is_consolidating = false;                         // no squeezes until clean
  std::uint64_t since_checkpoint = 0;                    // squeezes since the checkpoint
  std::uint64_t consolidate_sweeps = 0;
  detail::Hpmc::State checkpoint = engine.state();
  std::vector<double> history;  // fraction (fixed) or mean height (bed) after each sweep
  auto last_progress = Clock::now() - std::chrono::hours(1);
  auto fraction_now = [&] {
    return solid_volume / (is_repairing ? checkpoint.container : engine.container()).volume();
  };
  // The largest uniform expansion that keeps every extent within the checkpoint's.
  auto relief_limit = [&] {
    return container_ratio(engine.container(), checkpoint.container).minCoeff();
  };
  auto is_at_target = [&] { return !is_repairing && same_size(engine.container(), target); };
  // Reached: the target container, and the fraction target (round-off of the derived container
  // aside).
  auto is_done = [&] {
    return !is_bed && is_at_target() &&
           (options.target_fraction <= 0.0 ||
            fraction_now() >= options.target_fraction * (1 - 1e-9));
  };
  auto report_progress = [&](bool is_final) {
    if (!control.on_progress) return;
    const auto now = Clock::now();
    if (!is_final &&
        std::chrono::duration<double>(now - last_progress).count() < control.progress_interval) {
      return;
    }
    last_progress = now;
    PackProgress progress;
    progress.stage = PackStage::kPlacement;
    progress.placed = report.sweeps;
    progress.attempted = report.moves_tried;
    progress.total = options.max_sweeps;
    progress.solid_fraction = fraction_now();
    if (is_bed) {
      // A bed of uniform fraction phi filling [0, H] has its mean centroid height near H / 2:
      // phi ~ V / (A 2 z_mean), a cheap running estimate (the exact bulk figure comes at the end).
      const Container& box = engine.container();
      const double height = box.bounds().extent().z();
      const double mean = engine.mean_height();
      if (mean > 0.0) {
        progress.solid_fraction =
            std::min(1.0, solid_volume / (box.volume() / height * 2.0 * mean));
      }
    }
    double share = static_cast<double>(report.sweeps) / static_cast<double>(options.max_sweeps);
    if (!is_bed && options.target_fraction > 0.0) {
      share = std::max(share, (progress.solid_fraction - report.start_fraction) /
                                  std::max(1e-12, options.target_fraction - report.start_fraction));
    }
    progress.fraction = is_final ? 1.0 : std::clamp(share, 0.0, 1.0);
    control.on_progress(progress);
  };

  report.stop = DensifyStop::kSweepBudget;
  for (std::uint64_t sweep = 0; sweep < options.max_sweeps; ++sweep) {
    if (control.cancel != nullptr && control.cancel->load()) {
      report.stop = DensifyStop::kCancelled;
      break;
    }
    if (options.max_seconds > 0.0 &&
        std::chrono::duration<double>(Clock::now() - began).count() >= options.max_seconds) {
      report.stop = DensifyStop::kTimeBudget;
      break;
    }
    if (is_done()) {
      report.stop = DensifyStop::kTargetReached;
      break;
    }
    parameters.repair_step = kRepairReach * squeeze_step;
    parameters.relief_scale = is_repairing ? relief_limit() : 0.0;
    const detail::SweepCounts counts = engine.sweep(sweep, parameters);
    ++report.sweeps;
    report.moves_tried += counts.translations_tried + counts.rotations_tried;
    report.moves_accepted += counts.translations_accepted + counts.rotations_accepted;
    // Bed: one pair of step sizes toward the target acceptance (a deterministic function of
    // exact counts). Fixed: every particle adapts its own steps (hpmc.cpp).
    auto adapt = [&](double& step, std::uint64_t tried, std::uint64_t accepted, double cap) {
      if (tried == 0) return;
      const double rate = static_cast<double>(accepted) / static_cast<double>(tried);
      step *= rate > options.target_acceptance ? 1.1 : 1.0 / 1.1;
      step = std::clamp(step, 1e-7, cap);
    };
    if (parameters.per_particle_acceptance <= 0.0) {
      adapt(parameters.translation_step, counts.translations_tried, counts.translations_accepted,
            1.0);
      adapt(parameters.rotation_step, counts.rotations_tried, counts.rotations_accepted,
            std::numbers::pi);
    }
    if (is_bed) {
      parameters.temperature *= options.bed_cooling;
      history.push_back(engine.mean_height());
      if (history.size() > options.stall_sweeps) {
        const double sank = history[history.size() - 1 - options.stall_sweeps] - history.back();
        if (sank < options.stall_tolerance * engine.mean_outer_radius()) {
          report.stop = DensifyStop::kSettled;
          break;
        }
      }
    } else {
      std::size_t flagged = engine.flagged_count();
      auto take_checkpoint = [&] {  // clean again: a new checkpoint
        is_repairing = false;
        squeezes_per_checkpoint = std::min(kSqueezesPerCheckpoint, 2 * squeezes_per_checkpoint);
        is_consolidating = false;
        report.compressions += since_checkpoint;
        since_checkpoint = 0;
        checkpoint = engine.state();
        flagged = 0;
      };
      if (is_repairing && flagged == 0) take_checkpoint();
      if (is_consolidating) {
        ++consolidate_sweeps;
        if (consolidate_sweeps % kStallSweeps == 0) {
          // Stalled (a few caged pairs): the smallest uniform expansion that clears every
          // overlap, a clean state between the checkpoint and now; where none is found, undo a
          // quarter, then half of the squeezes since the checkpoint, keeping the moves made
          // since; the third time, go back to it.
          squeeze_step *= 0.7;
          if (engine.relieve(relief_limit())) {
            take_checkpoint();
          } else if (consolidate_sweeps >= 3 * kStallSweeps) {
            engine.restore(checkpoint);
            is_repairing = false;
            is_consolidating = false;
            since_checkpoint = 0;
            squeezes_per_checkpoint = std::max<std::uint64_t>(1, squeezes_per_checkpoint / 4);
          } else {
            engine.expand(checkpoint.container, 0.25 * consolidate_sweeps / kStallSweeps);
          }
        }
      }
      const bool is_container_reached = same_size(engine.container(), target);
      if (!is_consolidating && !is_container_reached && flagged <= allowed_overlaps &&
          (sweep + 1) % options.compress_interval == 0 && squeeze_step > 1e-9) {
        const Container& now = engine.container();
        const double k_max = (Vec3::Ones() - container_ratio(now, target)).maxCoeff();
        const std::size_t before = flagged;
        // Aim at 3-12 % of the particles made to overlap per squeeze. A squeeze that flags more
        // is undone at once and retried half as large (a step adapted at a lower density, or a
        // continued run's first squeeze, would otherwise leave more overlaps than the repair can
        // undo at this density).
        const detail::Hpmc::State unsqueezed = engine.state(true);
        double fresh = 0.0;
        for (int retry = 0;; ++retry) {
          flagged = engine.squeeze(target, std::min(1.0, squeeze_step / k_max));
          fresh = flagged > before ? static_cast<double>(flagged - before) : 0.0;
          if (fresh <= kFreshHigh * particle_count || retry == 8) break;
          engine.restore(unsqueezed);
          squeeze_step *= 0.5;
        }
        ++since_checkpoint;
        if (fresh < kFreshLow * particle_count) {
          squeeze_step = std::min(options.max_compression, squeeze_step * 1.2);
        }
        if (flagged == 0) {
          report.compressions += since_checkpoint;
          since_checkpoint = 0;
          checkpoint = engine.state();
        } else {
          is_repairing = true;
          if (since_checkpoint >= squeezes_per_checkpoint ||
              same_size(engine.container(), target)) {
            is_consolidating = true;
            consolidate_sweeps = 0;
          }
        }
      }
      if (is_repairing && !is_consolidating && flagged > allowed_overlaps) {
        // No squeeze until the repair gets below the allowance: stalls are handled as in a
        // consolidation (partial undo, then the checkpoint), else the run could wait forever.
        is_consolidating = true;
        consolidate_sweeps = 0;
      }
      history.push_back(fraction_now());
      if (history.size() > options.stall_sweeps) {
        const double gained = history.back() - history[history.size() - 1 - options.stall_sweeps];
        if (gained < options.stall_tolerance && !is_done()) {
          report.stop = DensifyStop::kJammed;
          break;
        }
      }
    }
    report_progress(false);
  }
  if (report.stop != DensifyStop::kCancelled && is_done()) {
    report.stop = DensifyStop::kTargetReached;
  }

  if (is_repairing) {
    // Stopped mid-repair: the densest overlap-free state at hand, the current one expanded just
    // enough to clear its overlaps, else the last checkpoint.
    if (!engine.relieve(relief_limit())) engine.restore(checkpoint);
    is_repairing = false;
  }
  DensifyResult result;
  result.packing = std::move(start);
  Packing& packing = result.packing;
  packing.container = engine.container();
  // Periodic axes: every centre wrapped back into [0, extent) (a particle may cross the face).
  const std::vector<Pose> poses = engine.wrapped_poses();
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    packing.particles[i].pose = poses[i];
  }
  packing.provenance.packer = "dense";
  report.solid_fraction = fraction_now();
  report.translation_step = parameters.translation_step;
  report.rotation_step = parameters.rotation_step;
  if (parameters.per_particle_acceptance > 0.0 && report.sweeps > 0) {
    std::tie(report.translation_step, report.rotation_step) = engine.mean_steps();
  }
  if (is_bed) measure_bulk(packing, report);
  const VerifyResult check = verify(packing, {.gap = options.gap});
  if (!check.is_ok) {
    Error error(ErrorKind::kInvalidInput, Wording{Sentence::kDensifyVerifyFailed, {check.message}});
    error.word_value(check.message, check.wording);
    throw error;
  }
  report.verified_pairs = check.pairs_tested;
  report.min_distance = check.min_distance;
  report.seconds = std::chrono::duration<double>(Clock::now() - began).count();
  report_progress(true);
  result.report = report;
  return result;
}

}  // namespace aggpack
