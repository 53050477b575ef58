// The HPMC engine of the densifying packer: checkerboard sweeps and exact container shrinks.
// See hpmc.h and include/aggpack/pack/dense_packer.h.

#include "hpmc.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <utility>

#include "aggpack/core/parallel.h"
#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"
#include "hpmc_neighbours.h"

namespace aggpack::detail {

namespace {

// Streams: particle moves use (seed, sweep << 32 | particle); the grid shift of a sweep uses a
// seed of its own so the two families never collide.
constexpr std::uint64_t kShiftSeedMix = 0x6A09E667F3BCC909ULL;

// Particle indices in the Morton (Z-curve) order of their centres in `bounds`, ties by index.
std::vector<std::uint32_t> spatial_order(const std::vector<Pose>& poses, const Aabb& bounds) {
  auto spread = [](std::uint64_t v) {  // 21 bits -> every third bit
    v &= 0x1FFFFF;
    v = (v | v << 32) & 0x1F00000000FFFFULL;
    v = (v | v << 16) & 0x1F0000FF0000FFULL;
    v = (v | v << 8) & 0x100F00F00F00F00FULL;
    v = (v | v << 4) & 0x10C30C30C30C30C3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  const Vec3 extent = bounds.extent().cwiseMax(1e-300);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    std::uint64_t code = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double t = (poses[i].position[axis] - bounds.lower[axis]) / extent[axis];
      const auto q = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 1023.0);
      code |= spread(q) << axis;
    }
    keys[i] = {code, static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(poses.size());
  for (std::size_t k = 0; k < keys.size(); ++k) order[k] = keys[k].second;
  return order;
}

}  // namespace

Hpmc::Hpmc(const Packing& packing, double gap, std::uint64_t seed, double max_compression)
    : container_(packing.container), gap_(gap), seed_(seed) {
  std::map<std::pair<std::uint32_t, double>, std::uint32_t> index;
  body_of_.assign(packing.particles.size(), 0);
  poses_.reserve(packing.particles.size());
  for (const Particle& particle : packing.particles) poses_.push_back(particle.pose);
  // Bodies are prepared in the spatial order of the particles, so that neighbours' shapes lie
  // close together in memory: with 10^4-10^5 distinct shapes the support scans of a move
  // otherwise miss the cache at nearly every neighbour. Only the memory layout depends on it.
  for (const std::uint32_t i : spatial_order(poses_, container_.bounds())) {
    const Particle& particle = packing.particles[i];
    const auto key = std::make_pair(particle.shape, particle.scale);
    auto found = index.find(key);
    if (found == index.end()) {
      Body body;
      body.local = packing.local_body(i);
      body.support = SupportShape(body.local);
      body.outer = body.support.bounding_radius();
      body.volume = mass_properties(body.local).volume;
      found = index.emplace(key, static_cast<std::uint32_t>(bodies_.size())).first;
      bodies_.push_back(std::move(body));
    }
    body_of_[i] = found->second;
  }
  double outer_sum = 0.0;
  for (const std::uint32_t b : body_of_) {
    max_outer_ = std::max(max_outer_, bodies_[b].outer);
    outer_sum += bodies_[b].outer;
    solid_volume_ += bodies_[b].volume;
  }
  const auto n = static_cast<double>(std::max<std::size_t>(1, body_of_.size()));
  mean_outer_ = outer_sum / n;
  mean_volume_ = solid_volume_ / n;
  // Same-colour cells are two apart, so one whole cell lies between their particles: a cell as
  // wide as the largest interaction range (grown by the largest shrink of one compress step)
  // keeps the particles moved at the same time out of each other's reach.
  grid_.width = (2.0 * max_outer_ + gap_) / (1.0 - max_compression) * 1.001;
  AxisCache empty{};
  std::fill(std::begin(empty.neighbour), std::end(empty.neighbour), 0xFFFFFFFFu);
  axes_.assign(poses_.size(), empty);
  blockers_.assign(poses_.size(), kNone);
}

bool Hpmc::is_apart(std::uint32_t i, const Pose& pose, std::uint32_t j, double gap,
                    const Image& image) const {
  AxisCache& cache = axes_[i];
  int slot = -1;
  for (int k = 0; k < kAxes; ++k) {
    if (cache.neighbour[k] == j) {
      slot = k;
      break;
    }
  }
  Vec3 axis = Vec3::Zero();
  if (slot >= 0) axis = Vec3(cache.axis[slot][0], cache.axis[slot][1], cache.axis[slot][2]);
  // The cached direction is per neighbour, not per image: only a warm start either way.
  Pose other = poses_[j];
  if (image != kSelf) other.position += shift_of(image);
  const bool is_apart = is_separated(bodies_[body_of_[i]].support, pose,
                                     bodies_[body_of_[j]].support, other, gap, axis);
  const double norm = axis.norm();
  if (is_apart && norm > 0.0) {
    if (slot < 0) {
      slot = cache.next;
      cache.next = static_cast<std::uint8_t>((cache.next + 1) % kAxes);
      cache.neighbour[slot] = j;
    }
    for (int c = 0; c < 3; ++c) cache.axis[slot][c] = static_cast<float>(axis[c] / norm);
  }
  return is_apart;
}

double Hpmc::mean_height() const {
  double sum = 0.0;
  for (std::size_t i = 0; i < poses_.size(); ++i) {
    sum += bodies_[body_of_[i]].volume * poses_[i].position.z();
  }
  return solid_volume_ > 0.0 ? sum / solid_volume_ : 0.0;
}

bool Hpmc::is_clear(std::uint32_t i, const Pose& pose, double gap) const {
  // The neighbour that blocked i's last rejected move is tested first: a rejection usually
  // comes from the same neighbour again, and testing it first ends the search at once. Only a
  // neighbour in an adjacent cell is read (a stale one elsewhere may be moving in another
  // thread); the order of the tests never changes the answer.
  std::uint32_t& blocker = blockers_[i];
  const bool has_blocker = blocker != kNone && blocker != i && is_adjacent(i, blocker);
  if (has_blocker) {
    if (!grid_.is_periodic) {
      if (!is_apart(i, pose, blocker, gap)) return false;
    } else if (!for_each_image(i, pose.position, blocker, gap, [&](const Image& image) {
                 return is_apart(i, pose, blocker, gap, image);
               })) {
      return false;
    }
  }
  bool is_ok = true;
  for_each_close(i, pose.position, gap, [&](std::uint32_t j, const Image& image) {
    if (has_blocker && j == blocker) return true;
    is_ok = is_apart(i, pose, j, gap, image);
    if (!is_ok) blocker = j;
    return is_ok;
  });
  return is_ok;
}

std::size_t Hpmc::flagged_count() const {
  std::size_t count = 0;
  for (const std::uint8_t flag : flagged_) count += flag;
  return count;
}

void Hpmc::restore(const State& state) {
  container_ = state.container;
  poses_ = state.poses;
  if (state.flagged.empty()) {
    std::fill(flagged_.begin(), flagged_.end(), 0);
  } else {
    flagged_ = state.flagged;
  }
  build_grid(Vec3::Zero());  // the packed spheres follow the poses
}

std::size_t Hpmc::squeeze(const Container& target, double t) {
  const Vec3 k = shrink_shares(target);
  const Vec3 factor = Vec3::Ones() - std::min(1.0, t) * k;
  return rescale(factor, target, t);
}

std::size_t Hpmc::expand(const Container& larger, double t) {
  Vec3 factor = container_ratio(container_, larger);
  factor = (Vec3::Ones() + std::min(1.0, t) * (factor - Vec3::Ones())).cwiseMax(1.0);
  return rescale(factor, larger, t);
}

std::size_t Hpmc::rescale(const Vec3& factor, const Container& end, double t) {
  for (Pose& pose : poses_) pose.position = pose.position.cwiseProduct(factor);
  if (t >= 1.0) {
    const double wall_gap = container_.wall_gap;
    container_ = end;
    container_.wall_gap = wall_gap;
  } else {
    container_ = container_scaled(container_, factor);
  }
  return refresh_flags();
}

std::size_t Hpmc::refresh_flags() {
  build_grid(Vec3::Zero());
  flagged_.assign(poses_.size(), 0);
  parallel_for_index(0, poses_.size(), [&](std::size_t index) {
    const auto i = static_cast<std::uint32_t>(index);
    flagged_[i] = static_cast<std::uint8_t>(!is_inside(i, poses_[i], container_) ||
                                            !is_clear(i, poses_[i], gap_));
  });
  return flagged_count();
}

bool Hpmc::is_inside(std::uint32_t i, const Pose& pose, const Container& box) const {
  const Body& body = bodies_[body_of_[i]];
  return is_in_centre_region(box, body.outer, pose.position) || contains(box, body.local, pose);
}

void Hpmc::repair(std::uint32_t i, Rng& rng, const SweepParameters& parameters) {
  // Repair moves of a squeezed, overlapping particle (not counted for the step adaptation): up
  // to kTries pushes away from its partners (and into the container) with a little noise (small
  // random rotations here made the packings measurably less dense), no longer than
  // parameters.repair_step bounding radii (about the depth a squeeze makes). Overlap transfer: a
  // push may overlap new particles as long as its count of partners does not rise (partners
  // resolved >= new ones); the new partners are flagged, so an overlap walks on through a
  // crowded region until it meets room instead of waiting for that room to come to it. The
  // partners it keeps must not come closer (else overlapping pairs drift deeper), and it goes no
  // further out of the container. The partners (the neighbours it overlaps, exact test) are
  // found once and updated after an accepted push.
  //
  // Flagging a new partner k from i's move is independent of the thread count: k is within i's
  // reach, so in an adjacent cell of another colour, not moved at the same time (and only ever
  // set to 1 by others, atomically).
  constexpr int kTries = 8;
  constexpr int kMaxPartners = 64;
  const Body& body = bodies_[body_of_[i]];
  // A partner is a neighbour's image (periodic box: one neighbour may overlap through two).
  struct Partner {
    std::uint32_t id;
    Image image;
  };
  Partner partners[kMaxPartners];
  int count = 0;
  bool is_crowded = false;
  for_each_close(i, poses_[i].position, gap_, [&](std::uint32_t j, const Image& image) {
    if (!is_apart(i, poses_[i], j, gap_, image)) {
      if (count == kMaxPartners) {
        is_crowded = true;
        return false;
      }
      partners[count++] = {j, image};
    }
    return true;
  });
  if (is_crowded) return;  // left flagged; the squeeze schedule backs off
  auto is_partner = [&](std::uint32_t j, const Image& image) {
    return std::find_if(partners, partners + count, [&](const Partner& partner) {
             return partner.id == j && partner.image == image;
           }) != partners + count;
  };
  auto centre_of = [&](const Partner& partner) {
    return partner.image == kSelf ? poses_[partner.id].position
                                  : Vec3(poses_[partner.id].position + shift_of(partner.image));
  };
  bool was_inside = is_inside(i, poses_[i], container_);
  const double step = own_translation_.empty() ? parameters.translation_step
                                               : static_cast<double>(own_translation_[i]);
  const double reach = std::min({step, 0.2, parameters.repair_step});
  for (int attempt = 0; attempt < kTries; ++attempt) {
    if (count == 0 && was_inside) {
      flagged_[i] = 0;  // clean (its partners moved away)
      return;
    }
    const Pose& pose = poses_[i];
    Pose trial = pose;
    Vec3 push = Vec3::Zero();
    for (int p = 0; p < count; ++p) {
      const Vec3 away = pose.position - centre_of(partners[p]);
      if (away.squaredNorm() > 0.0) push += away.normalized();
    }
    if (!was_inside) {
      const Aabb bounds = container_.bounds();
      Vec3 inward = 0.5 * (bounds.lower + bounds.upper) - pose.position;
      for (int axis = 0; axis < 3; ++axis) {
        if (grid_.periodic[axis]) inward[axis] = 0.0;  // no wall to come back from
      }
      if (inward.squaredNorm() > 0.0) push += inward.normalized();
    }
    if (push.squaredNorm() > 0.0) push.normalize();
    const double size = reach * body.outer * rng.uniform();
    const Vec3 noise(2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0,
                     2.0 * rng.uniform() - 1.0);
    trial.position += size * push + 0.02 * body.outer * noise;
    if (cell_index(trial.position) != static_cast<std::int64_t>(grid_.cell_of[i])) continue;
    const bool is_in = is_inside(i, trial, container_);
    if (was_inside && !is_in) continue;
    if (!is_in && wall_clearance(container_, body.local, trial) <
                      wall_clearance(container_, body.local, pose)) {
      continue;
    }
    auto is_relievable = [&](std::uint32_t j, const Image& image) {
      if (!(parameters.relief_scale > 1.0)) return true;
      Pose scaled_i = trial;
      scaled_i.position *= parameters.relief_scale;
      Pose scaled_j = poses_[j];
      scaled_j.position = (scaled_j.position + shift_of(image)) * parameters.relief_scale;
      return is_separated(body.support, scaled_i, bodies_[body_of_[j]].support, scaled_j, gap_);
    };
    Partner fresh[kMaxPartners];
    int fresh_count = 0;
    int kept_count = 0;
    bool is_ok = true;
    for_each_close(i, trial.position, gap_, [&](std::uint32_t j, const Image& image) {
      const bool was_partner = is_partner(j, image);
      if (is_apart(i, trial, j, gap_, image)) return true;
      if (was_partner) {
        ++kept_count;
        const Vec3 centre = centre_of({j, image});
        is_ok = (centre - trial.position).squaredNorm() >= (centre - pose.position).squaredNorm();
      } else if (fresh_count + kept_count < count && is_relievable(j, image)) {
        fresh[fresh_count++] = {j, image};
      } else {
        is_ok = false;  // more partners than before
      }
      return is_ok;
    });
    if (!is_ok || kept_count + fresh_count > count) continue;
    // Wrapped back into the box across a periodic face: the images it meets move with it.
    const Image periods = place(i, trial);
    auto follow = [&periods](Partner& partner) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        partner.image[axis] = static_cast<std::int8_t>(partner.image[axis] - periods[axis]);
      }
    };
    was_inside = is_in;
    int kept = 0;
    for (int p = 0; p < count; ++p) {
      follow(partners[p]);
      if (!is_apart(i, poses_[i], partners[p].id, gap_, partners[p].image)) {
        partners[kept++] = partners[p];
      }
    }
    count = kept;
    for (int f = 0; f < fresh_count; ++f) {
      follow(fresh[f]);
      partners[count++] = fresh[f];
      // Two particles moved at once (cells two apart) may both flag one between them: the
      // same value either way, stored atomically.
      std::atomic_ref<std::uint8_t>(flagged_[fresh[f].id]).store(1, std::memory_order_relaxed);
    }
  }
  if (count == 0 && was_inside) flagged_[i] = 0;
}

void Hpmc::move_cell(std::uint32_t i, std::uint64_t sweep, const SweepParameters& parameters,
                     SweepCounts& counts) {
  Rng rng(seed_, (sweep << 32) | i);
  if (!flagged_.empty() && flagged_[i] != 0) {
    repair(i, rng, parameters);
    return;
  }
  const Body& body = bodies_[body_of_[i]];
  Pose trial = poses_[i];
  const bool is_rotation = rng.uniform() < parameters.rotation_probability;
  // Own steps: a move's outcome nudges the particle's step, up on acceptance and down on
  // rejection, in the ratio that balances at the target acceptance rate (Robbins-Monro). In a
  // dense packing the room differs from particle to particle (rattlers, caged ones, walls); one
  // global step is too small for some and too large for others.
  const bool is_own = parameters.per_particle_acceptance > 0.0;
  float* own = nullptr;
  if (is_own) own = is_rotation ? &own_rotation_[i] : &own_translation_[i];
  const double p = parameters.per_particle_acceptance;
  const auto outcome = [&](bool is_accepted) {
    if (own == nullptr) return;
    constexpr double kRate = 0.1;
    const double cap = is_rotation ? 3.14159 : 1.0;
    *own = static_cast<float>(
        std::clamp(*own * std::exp(is_accepted ? kRate * (1.0 - p) : -kRate * p), 1e-7, cap));
  };
  if (is_rotation) {
    ++counts.rotations_tried;
    const Vec3 axis(rng.normal(), rng.normal(), rng.normal());
    const double angle = (is_own ? *own : parameters.rotation_step) * (2.0 * rng.uniform() - 1.0);
    if (axis.norm() < 1e-9) return;
    trial.rotation = (Quat(Eigen::AngleAxisd(angle, axis.normalized())) * trial.rotation);
    trial.rotation.normalize();
  } else {
    ++counts.translations_tried;
    const double step = (is_own ? *own : parameters.translation_step) * body.outer;
    const double dx = 2.0 * rng.uniform() - 1.0;
    const double dy = 2.0 * rng.uniform() - 1.0;
    const double dz = 2.0 * rng.uniform() - 1.0;
    trial.position += step * Vec3(dx, dy, dz);
    if (parameters.is_bed && dz > 0.0) {
      // Metropolis on m g z: a rise is accepted with probability exp(-dU / kT).
      if (parameters.temperature <= 0.0) return;
      const double energy = (body.volume / mean_volume_) * (step * dz / mean_outer_);
      if (rng.uniform() >= std::exp(-energy / parameters.temperature)) return;
    }
    if (cell_index(trial.position) != static_cast<std::int64_t>(grid_.cell_of[i])) {
      outcome(false);
      return;
    }
  }
  if (!is_inside(i, trial, container_) || !is_clear(i, trial, gap_)) {
    outcome(false);
    return;
  }
  outcome(true);
  place(i, trial);
  if (is_rotation) {
    ++counts.rotations_accepted;
  } else {
    ++counts.translations_accepted;
  }
}

std::pair<double, double> Hpmc::mean_steps() const {
  if (own_translation_.empty()) return {0.0, 0.0};
  double t = 0.0;
  double r = 0.0;
  for (std::size_t i = 0; i < own_translation_.size(); ++i) {
    t += std::log(static_cast<double>(own_translation_[i]));
    r += std::log(static_cast<double>(own_rotation_[i]));
  }
  const auto n = static_cast<double>(own_translation_.size());
  return {std::exp(t / n), std::exp(r / n)};
}

SweepCounts Hpmc::sweep(std::uint64_t sweep, const SweepParameters& parameters) {
  if (parameters.per_particle_acceptance > 0.0 && own_translation_.empty()) {
    own_translation_.assign(poses_.size(), static_cast<float>(parameters.translation_step));
    own_rotation_.assign(poses_.size(), static_cast<float>(parameters.rotation_step));
  }
  Rng shift_rng(seed_ ^ kShiftSeedMix, sweep);
  // The same three draws as a plain shift of up to one cell width per axis.
  const Vec3 fractions(shift_rng.uniform(), shift_rng.uniform(), shift_rng.uniform());
  build_grid(fractions);
  int colours[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  for (int k = 7; k > 0; --k) {
    const auto pick = static_cast<int>(shift_rng.next() % static_cast<std::uint64_t>(k + 1));
    std::swap(colours[k], colours[pick]);
  }
  const std::size_t cells = grid_.start.size() - 1;
  std::vector<std::uint32_t> active;
  SweepCounts total;
  for (const int colour : colours) {
    active.clear();
    for (std::size_t cell = 0; cell < cells; ++cell) {
      if (grid_.start[cell] == grid_.start[cell + 1]) continue;
      std::int64_t c[3];
      cell_coordinates(static_cast<std::int64_t>(cell), c);
      const int parity = static_cast<int>((c[0] & 1) | ((c[1] & 1) << 1) | ((c[2] & 1) << 2));
      if (parity == colour) active.push_back(static_cast<std::uint32_t>(cell));
    }
    std::vector<SweepCounts> counts(active.size());
    parallel_for_index(0, active.size(), [&](std::size_t a) {
      const std::uint32_t cell = active[a];
      for (std::uint32_t k = grid_.start[cell]; k < grid_.start[cell + 1]; ++k) {
        move_cell(grid_.items[k], sweep, parameters, counts[a]);
      }
    });
    for (const SweepCounts& c : counts) {
      total.translations_tried += c.translations_tried;
      total.translations_accepted += c.translations_accepted;
      total.rotations_tried += c.rotations_tried;
      total.rotations_accepted += c.rotations_accepted;
    }
  }
  return total;
}

Vec3 Hpmc::shrink_shares(const Container& target) const {
  const Vec3 k = Vec3::Ones() - container_ratio(container_, target);
  return k.cwiseMax(0.0);
}

}  // namespace aggpack::detail
