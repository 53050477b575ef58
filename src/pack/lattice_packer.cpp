#include "aggpack/pack/lattice_packer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/resources.h"
#include "aggpack/shape/generator.h"
#include "lattice_sites.h"
#include "shape_util.h"

namespace aggpack {

namespace {

using Clock = std::chrono::steady_clock;

// Relative slack on "every vertex within R": the generator places vertices at exactly r times a
// unit direction, which rounds to within a few ulps of r.
constexpr double kRadiusSlack = 1e-12;
// Streams of the control ellipsoids' random orientations (one per site).
constexpr std::uint64_t kAxesSalt = 0x2545F4914F6CDD1DULL;

}  // namespace

namespace lattice_detail {

double effective_spacing(const LatticeOptions& options) {
  return options.spacing > 0.0 ? options.spacing : 2.0 * options.radius + options.gap;
}

std::array<std::uint32_t, 3> axis_counts(const LatticeOptions& options) {
  const double spacing = effective_spacing(options);
  const Aabb bounds = options.container.bounds();
  std::array<std::uint32_t, 3> counts{};
  for (int axis = 0; axis < 3; ++axis) {
    const double usable =
        bounds.extent()[axis] - 2.0 * options.container.wall_gap - 2.0 * options.radius;
    // The small epsilon keeps exact multiples (3.0 - 0.2 = 14 x 0.2) from losing a site to
    // rounding.
    // Saturated below 2^32 (validate() refuses more than 10^8 sites anyway).
    const double steps = std::min(std::floor(usable / spacing + 1e-9), 4.0e9);
    counts[static_cast<std::size_t>(axis)] =
        usable < 0.0 ? 0u : static_cast<std::uint32_t>(steps) + 1u;
  }
  return counts;
}

Lattice make_lattice(const LatticeOptions& options) {
  Lattice lattice;
  lattice.counts = axis_counts(options);
  const double spacing = effective_spacing(options);
  const Aabb bounds = options.container.bounds();
  Vec3 start;
  for (int axis = 0; axis < 3; ++axis) {
    const double usable =
        bounds.extent()[axis] - 2.0 * options.container.wall_gap - 2.0 * options.radius;
    const double span = (lattice.counts[static_cast<std::size_t>(axis)] - 1.0) * spacing;
    // Centre the lattice in the usable range, but never let rounding push it past either end.
    start[axis] = bounds.lower[axis] + options.container.wall_gap + options.radius +
                  std::max(0.0, (usable - span) / 2.0);
  }
  const Aabb region = centre_region(options.container, options.radius);
  const auto nx = static_cast<std::int64_t>(lattice.counts[0]);
  const auto ny = static_cast<std::int64_t>(lattice.counts[1]);
  const auto nz = static_cast<std::int64_t>(lattice.counts[2]);
  lattice.index.assign(static_cast<std::size_t>(nx * ny * nz), -1);
  for (std::int64_t z = 0; z < nz; ++z) {
    for (std::int64_t y = 0; y < ny; ++y) {
      for (std::int64_t x = 0; x < nx; ++x) {
        Vec3 site = start + spacing * Vec3(static_cast<double>(x), static_cast<double>(y),
                                           static_cast<double>(z));
        // Rounding can put the last site an ulp past the region (0.1 + 14 x 0.2 > 2.9): clamp.
        site = site.cwiseMax(region.lower).cwiseMin(region.upper);
        if (!is_in_centre_region(options.container, options.radius, site)) continue;
        lattice.index[static_cast<std::size_t>((z * ny + y) * nx + x)] =
            static_cast<std::int64_t>(lattice.sites.size());
        lattice.sites.push_back(site);
        lattice.coordinates.push_back({x, y, z});
      }
    }
  }
  return lattice;
}

std::vector<std::size_t> earlier_sites_within(const Lattice& lattice, std::size_t i, double reach,
                                              double spacing) {
  std::vector<std::size_t> result;
  const auto steps = static_cast<std::int64_t>(std::ceil(reach / spacing));
  const auto& c = lattice.coordinates[i];
  const auto nx = static_cast<std::int64_t>(lattice.counts[0]);
  const auto ny = static_cast<std::int64_t>(lattice.counts[1]);
  const auto nz = static_cast<std::int64_t>(lattice.counts[2]);
  for (std::int64_t dz = -steps; dz <= steps; ++dz) {
    for (std::int64_t dy = -steps; dy <= steps; ++dy) {
      for (std::int64_t dx = -steps; dx <= steps; ++dx) {
        const std::int64_t x = c[0] + dx;
        const std::int64_t y = c[1] + dy;
        const std::int64_t z = c[2] + dz;
        if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) continue;
        const std::int64_t j = lattice.index[static_cast<std::size_t>((z * ny + y) * nx + x)];
        if (j < 0 || static_cast<std::size_t>(j) >= i) continue;
        if ((lattice.sites[static_cast<std::size_t>(j)] - lattice.sites[i]).norm() < reach) {
          result.push_back(static_cast<std::size_t>(j));
        }
      }
    }
  }
  return result;
}

void finish_report(PackReport& report, const LatticeOptions& options, std::size_t site_count,
                   std::size_t done, double solid, bool was_cancelled,
                   std::chrono::steady_clock::time_point start) {
  report.requested = site_count;
  report.placed = done;
  report.attempts = done;
  report.solid_volume = solid;
  report.container_volume = options.container.volume();
  report.solid_fraction = solid / report.container_volume;
  report.stop_reason = was_cancelled ? StopReason::kCancelled : StopReason::kTargetReached;
  report.is_target_reached = !was_cancelled;
  report.placement_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace lattice_detail

namespace {

using namespace lattice_detail;  // NOLINT(google-build-using-namespace)

// A grown particle in its growth frame (origin = its lattice site).
struct Grown {
  ConvexPolyhedron body;
  double outer_radius = 0.0;  // about the site
};

// Outward face planes (unit normal n, offset h: inside <=> n.x <= h) of a body in world space.
struct Planes {
  std::vector<Vec3> normals;
  std::vector<double> offsets;
};

Planes world_planes(const ConvexPolyhedron& body, const Vec3& position) {
  Planes planes;
  planes.normals.reserve(body.triangle_count());
  planes.offsets.reserve(body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 normal = body.face_normal(f);
    planes.normals.push_back(normal);
    planes.offsets.push_back(normal.dot(body.vertices()[body.triangles()[f][0]] + position));
  }
  return planes;
}

// Where the ray origin + s * direction (s >= 0) first enters the polytope inflated by `gap`
// (every plane pushed out by gap: contains the gap-neighbourhood, so stopping there is safe).
// Returns +inf when the ray misses, 0 when the origin is already inside.
double ray_entry(const Planes& planes, double gap, const Vec3& origin, const Vec3& direction) {
  double enter = 0.0;
  double exit = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < planes.normals.size(); ++f) {
    const double denominator = planes.normals[f].dot(direction);
    const double numerator = planes.offsets[f] + gap - planes.normals[f].dot(origin);
    if (denominator == 0.0) {
      if (numerator < 0.0) return std::numeric_limits<double>::infinity();
      continue;
    }
    const double t = numerator / denominator;
    if (denominator < 0.0) {
      enter = std::max(enter, t);
    } else {
      exit = std::min(exit, t);
    }
    if (enter > exit) return std::numeric_limits<double>::infinity();
  }
  return enter;
}

}  // namespace

GrowthParams growth_params(const LatticeOptions& options) {
  return {.alpha = options.alpha,
          .radius = options.radius,
          .edge_length = options.edge_length,
          .max_vertices = options.max_vertices,
          .form = options.form};
}

void validate(const LatticeOptions& options) {
  validate(options.container);
  refuse_periodic(options.container, "packer.kind = lattice");

  const GrowthParams params = growth_params(options);
  require_in_range("lattice.alpha", options.alpha, 0.0, 1.0);
  require_positive("lattice.radius", options.radius);
  require_positive("lattice.edge_length", options.edge_length);
  if (!std::isfinite(options.gap) || options.gap < 0.0) {
    throw InvalidInput("lattice.gap", format_value(options.gap),
                       Wording{Sentence::kFiniteAtLeastZero, {}});
  }
  if (!std::isfinite(options.spacing) || options.spacing < 0.0) {
    throw InvalidInput("lattice.spacing", format_value(options.spacing),
                       Wording{Sentence::kLatticeSpacing, {}});
  }
  // A site must lie clear (by gap) of every neighbour, which reaches at most R from its own site.
  if (options.spacing > 0.0 && !(options.spacing > options.radius + options.gap)) {
    throw InvalidInput(
        "lattice.spacing", format_value(options.spacing),
        Wording{Sentence::kLatticeSpacingAbove, {format_value(options.radius + options.gap)}});
  }
  if (options.max_vertices < 6 || options.max_vertices > 1000000) {
    throw InvalidInput("lattice.max_vertices", std::to_string(options.max_vertices),
                       "[6, 1000000]");
  }
  validate(params);  // LimitExceeded when the vertex cap is too small for (radius, edge_length)
  const auto counts = axis_counts(options);
  if (counts[0] == 0 || counts[1] == 0 || counts[2] == 0) {
    throw InvalidInput("lattice.radius", format_value(options.radius),
                       Wording{Sentence::kRadiusFitsContainer, {}});
  }
  const double sites = static_cast<double>(counts[0]) * counts[1] * counts[2];
  if (sites > 1e8) {
    throw LimitExceeded("lattice.radius", format_value(options.radius),
                        Wording{Sentence::kLatticeSites, {format_value(sites)}});
  }
  check_resources(options, sites);  // shapes that would not fit in memory (issue 12)
}

std::array<std::uint32_t, 3> lattice_counts(const LatticeOptions& options) {
  validate(options);
  return axis_counts(options);
}

PackResult pack_lattice(const LatticeOptions& options, const PackControl& control) {
  validate(options);
  const auto start = Clock::now();
  const Lattice lattice = make_lattice(options);
  if (lattice.sites.empty()) {
    throw InvalidInput("lattice.radius", format_value(options.radius),
                       Wording{Sentence::kRadiusOneSite, {}});
  }
  if (options.files.is_used()) {
    if (!options.files.loaded) {
      throw InvalidInput("particle.library", options.files.options.paths_text(),
                         Wording{Sentence::kLibraryLoadedFirst, {}});
    }
    return pack_lattice_files(options, lattice, control);
  }
  const std::size_t site_count = lattice.sites.size();
  const double spacing = effective_spacing(options);
  const bool is_contact_mode = spacing < 2.0 * options.radius + options.gap;
  const GrowthParams params = growth_params(options);
  // A control ellipsoid turned at random at each site, from a stream of its own.
  const auto site_params = [&](std::size_t i) {
    GrowthParams turned = params;
    if (!options.form.is_sphere()) {
      Rng turn(options.seed ^ kAxesSalt, i);
      turned.axes = detail::random_rotation(turn);
    }
    return turned;
  };

  auto last_report = Clock::now() - std::chrono::hours(1);
  // Solid volume grown so far, for the live solid fraction (sites that settle() later shrinks
  // count at their grown size until the end; the final report is exact).
  const double container_volume = options.container.volume();
  std::vector<double> grown_volume(site_count, 0.0);
  double grown_solid = 0.0;
  std::size_t summed = 0;
  auto report_progress = [&](std::size_t done, bool is_final) {
    if (!control.on_progress) return;
    const auto now = Clock::now();
    if (!is_final &&
        std::chrono::duration<double>(now - last_report).count() < control.progress_interval) {
      return;
    }
    last_report = now;
    for (; summed < done; ++summed) grown_solid += grown_volume[summed];
    control.on_progress(
        {.stage = PackStage::kPlacement,
         .fraction = static_cast<double>(done) / static_cast<double>(site_count),
         .placed = done,
         .attempted = done,
         .total = site_count,
         .solid_fraction = container_volume > 0.0 ? grown_solid / container_volume : 0.0});
  };
  auto is_cancelled = [&] {
    return control.cancel != nullptr && control.cancel->load(std::memory_order_relaxed);
  };

  std::vector<Grown> grown(site_count);
  std::vector<char> needs_check(site_count, 0);
  std::size_t done = 0;
  bool was_cancelled = false;
  PackReport report;

  // Already-grown neighbours of site i that could come within gap: sites closer than 2R + gap.
  const double reach = 2.0 * options.radius + options.gap;
  auto earlier_neighbours = [&](std::size_t i) {
    return earlier_sites_within(lattice, i, reach, spacing);
  };

  // Exact check of site i against its grown neighbours; if it fails, shrink the particle about
  // its site (bisection on the scale) until it passes. Shrinking about the site keeps convexity,
  // and the site itself is clear of every neighbour by > gap (validate: spacing > R + gap).
  auto settle = [&](std::size_t i) {
    const std::vector<std::size_t> neighbours = earlier_neighbours(i);
    const Vec3& site = lattice.sites[i];
    auto is_clear = [&](const ConvexPolyhedron& body, double outer) {
      const Pose pose{.position = site};
      if (!contains(options.container, body, pose)) return false;
      for (const std::size_t j : neighbours) {
        const Pose other{.position = lattice.sites[j]};
        if (!is_separated(body, pose, outer, grown[j].body, other, grown[j].outer_radius,
                          options.gap)) {
          return false;
        }
      }
      return true;
    };
    Grown& particle = grown[i];
    if (is_clear(particle.body, particle.outer_radius)) return;
    double lo = 0.0;
    double hi = 1.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (is_clear(particle.body.scaled(mid), particle.outer_radius * mid)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    particle.body = particle.body.scaled(lo);
    particle.outer_radius *= lo;
    ++report.shrunk;
  };

  if (!is_contact_mode) {
    // Sites 2R + gap apart and every vertex within R of its site: no two particles can come
    // closer than gap, so sites grow independently (in parallel, each from its own stream).
    const std::size_t chunk = 256;
    for (std::size_t begin = 0; begin < site_count; begin += chunk) {
      if (is_cancelled()) {
        was_cancelled = true;
        break;
      }
      const std::size_t end = std::min(site_count, begin + chunk);
      parallel_for_index(begin, end, [&](std::size_t i) {
        Rng rng(options.seed, i);
        grown[i].body = grow_aggregate(site_params(i), rng);
        grown[i].outer_radius = bounding_radius(grown[i].body);
        if (control.on_progress) grown_volume[i] = mass_properties(grown[i].body).volume;
        // Verify the premise of the argument above, exactly; anything else goes to `settle`.
        needs_check[i] =
            grown[i].outer_radius > options.radius * (1.0 + kRadiusSlack) ||
            !contains(options.container, grown[i].body, Pose{.position = lattice.sites[i]});
      });
      done = end;
      report_progress(done, false);
    }
    for (std::size_t i = 0; i < done; ++i) {
      if (needs_check[i]) settle(i);
    }
  } else {
    // The paper's contact check: a new vertex may not come within gap of an already grown
    // neighbour (ray against its gap-inflated face planes). The vertex test cannot see
    // edge-through-edge contact, so `settle` then decides exactly.
    for (std::size_t i = 0; i < site_count; ++i) {
      if (is_cancelled()) {
        was_cancelled = true;
        break;
      }
      const Vec3& site = lattice.sites[i];
      std::vector<Planes> neighbour_planes;
      for (const std::size_t j : earlier_neighbours(i)) {
        neighbour_planes.push_back(world_planes(grown[j].body, lattice.sites[j]));
      }
      const GrowthLimit limit = [&](const Vec3& direction, double s_lo, double s_hi) {
        double allowed = s_hi;
        for (const Planes& planes : neighbour_planes) {
          allowed = std::min(allowed, ray_entry(planes, options.gap, site, direction));
        }
        return std::max(allowed, s_lo);
      };
      Rng rng(options.seed, i);
      grown[i].body =
          grow_aggregate(site_params(i), rng, neighbour_planes.empty() ? GrowthLimit{} : limit);
      grown[i].outer_radius = bounding_radius(grown[i].body);
      settle(i);
      if (control.on_progress) grown_volume[i] = mass_properties(grown[i].body).volume;
      done = i + 1;
      report_progress(done, false);
    }
  }

  // Store shapes with their centroid at the origin; the pose puts the centroid back in place.
  PackResult result;
  Packing& packing = result.packing;
  packing.container = options.container;
  packing.provenance.seed = options.seed;
  packing.provenance.packer = "lattice";
  packing.shapes.resize(done);
  packing.particles.resize(done);
  std::vector<double> volumes(done, 0.0);
  parallel_for_index(0, done, [&](std::size_t i) {
    Vec3 centroid;
    packing.shapes[i] = detail::centred_on_centroid(grown[i].body, centroid, volumes[i]);
    Particle& particle = packing.particles[i];
    particle.shape = static_cast<std::uint32_t>(i);
    particle.pose.position = lattice.sites[i] + centroid;
    particle.control_radius = options.radius;
  });
  double solid = 0.0;
  for (double v : volumes) solid += v;  // in site order: independent of threads

  finish_report(report, options, site_count, done, solid, was_cancelled, start);
  report_progress(done, true);
  result.report = report;
  return result;
}

}  // namespace aggpack
