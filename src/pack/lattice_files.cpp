// The lattice packer with shapes from mesh files (particle.library): each site holds a library
// shape, randomly turned, its smallest enclosing sphere (radius R) centred on the site. The
// library is stored once; particles refer to it with a scale.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "lattice_sites.h"
#include "shape_util.h"

namespace aggpack::lattice_detail {

namespace {

// Relative slack on "every vertex within R of its site" (Welzl's sphere is exact to ~1e-12).
constexpr double kReachSlack = 1e-9;

struct Site {
  std::uint32_t shape = 0;
  Quat rotation = Quat::Identity();
  double scale = 0.0;  // enclosing radius at this site (R, or less after shrinking)
};

}  // namespace

PackResult pack_lattice_files(const LatticeOptions& options, const Lattice& lattice,
                              const PackControl& control) {
  const auto start = std::chrono::steady_clock::now();
  const ShapeLibrary& library = *options.files.loaded;
  const std::size_t site_count = lattice.sites.size();
  const bool is_use_once = options.files.options.is_use_once;
  if (is_use_once && site_count > library.shapes.size()) {
    throw LimitExceeded("particle.library_use_once", "true",
                        Wording{Sentence::kLibraryShapesForSites,
                                {std::to_string(library.shapes.size()), std::to_string(site_count),
                                 "particle.radius"}});
  }
  const std::vector<std::uint32_t> order =
      is_use_once ? detail::use_once_order(library.shapes.size(), options.seed)
                  : std::vector<std::uint32_t>{};
  const double radius = options.radius;
  std::vector<Site> sites(site_count);
  parallel_for_index(0, site_count, [&](std::size_t i) {
    Rng rng(options.seed, i);
    sites[i].shape = is_use_once ? order[i] : detail::library_slot(rng, library.shapes.size());
    sites[i].rotation = detail::random_rotation(rng);
    sites[i].scale = radius;
  });
  const auto pose_of = [&](std::size_t i) {
    const Site& site = sites[i];
    const Vec3 offset = site.rotation * (library.shapes[site.shape].enclosing_centre * site.scale);
    return Pose{.position = lattice.sites[i] - offset, .rotation = site.rotation};
  };
  const auto body_of = [&](std::size_t i) {
    return library.shapes[sites[i].shape].body.scaled(sites[i].scale);
  };
  const double spacing = effective_spacing(options);
  const bool is_contact_mode = spacing < 2.0 * radius + options.gap;
  const double reach = 2.0 * radius * (1.0 + kReachSlack) + options.gap;
  PackReport report;

  // The earlier sites within reach of site i (only in contact mode can two particles meet).
  auto earlier_neighbours = [&](std::size_t i) {
    if (!is_contact_mode) return std::vector<std::size_t>{};
    return earlier_sites_within(lattice, i, reach, spacing);
  };
  // Site i clear of the walls and of its earlier neighbours; if not, shrunk about its site by
  // bisection until it is (the site itself is clear by > gap: validate's spacing rule).
  auto settle = [&](std::size_t i) {
    const std::vector<std::size_t> neighbours = earlier_neighbours(i);
    auto is_clear = [&] {
      const ConvexPolyhedron body = body_of(i);
      const Pose pose = pose_of(i);
      if (!contains(options.container, body, pose)) return false;
      const double outer = bounding_radius(body);
      for (const std::size_t j : neighbours) {
        const ConvexPolyhedron other = body_of(j);
        if (!is_separated(body, pose, outer, other, pose_of(j), bounding_radius(other),
                          options.gap)) {
          return false;
        }
      }
      return true;
    };
    if (is_clear()) return;
    double lo = 0.0;
    double hi = 1.0;
    for (int iteration = 0; iteration < 40; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      sites[i].scale = radius * mid;
      (is_clear() ? lo : hi) = mid;
    }
    sites[i].scale = radius * lo;
    ++report.shrunk;
  };
  bool was_cancelled = false;
  std::size_t done = 0;
  for (; done < site_count; ++done) {
    if (control.cancel != nullptr && control.cancel->load(std::memory_order_relaxed)) {
      was_cancelled = true;
      break;
    }
    settle(done);
    if (control.on_progress && (done % 1024 == 0)) {
      control.on_progress({.stage = PackStage::kPlacement,
                           .fraction = static_cast<double>(done) / static_cast<double>(site_count),
                           .placed = done,
                           .attempted = done,
                           .total = site_count});
    }
  }

  PackResult result;
  Packing& packing = result.packing;
  packing.container = options.container;
  packing.provenance.seed = options.seed;
  packing.provenance.packer = "lattice";
  // Only the shapes the placed particles use are stored, in order of first use (as the random
  // packer's library runs): the file holds what was placed, not the whole library.
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> stored_index(library.shapes.size(), kUnused);
  std::vector<double> unit_volumes;  // per stored shape
  packing.particles.resize(done);
  double solid = 0.0;
  for (std::size_t i = 0; i < done; ++i) {
    std::uint32_t& index = stored_index[sites[i].shape];
    if (index == kUnused) {
      const LibraryShape& shape = library.shapes[sites[i].shape];
      index = static_cast<std::uint32_t>(packing.shapes.size());
      packing.shapes.push_back(shape.body);
      unit_volumes.push_back(shape.volume / std::pow(shape.size / 2.0, 3));
      result.library_shapes.push_back(sites[i].shape);
    }
    Particle& particle = packing.particles[i];
    particle.shape = index;
    particle.pose = pose_of(i);
    particle.scale = sites[i].scale;
    particle.control_radius = radius;
    solid += unit_volumes[particle.shape] * std::pow(particle.scale, 3);  // site order
  }
  finish_report(report, options, site_count, done, solid, was_cancelled, start);
  result.report = report;
  return result;
}

}  // namespace aggpack::lattice_detail
