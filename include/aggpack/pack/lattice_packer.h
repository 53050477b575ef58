#pragma once
// The paper's placement (Section 3): particle centres on a regular cubic lattice filling the
// container, a random aggregate grown in place at each site, growth stopped by a contact check,
// every particle verified with the exact containment and overlap tests.

#include <array>
#include <cstdint>

#include "aggpack/pack/packing.h"
#include "aggpack/pack/progress.h"
#include "aggpack/shape/generator.h"
#include "aggpack/shape/shape_library.h"

namespace aggpack {

/// Options of the lattice packer. Defaults = the paper's stacking case: alpha 0.5, R 0.1 m,
/// L 0.1 m in a 3.0 x 1.0 x 2.8 m box -> 15 x 5 x 14 = 1,050 sites (the paper reports 1,050
/// particles and 0.84 m^3 of solid).
struct LatticeOptions {
  Container container{};     ///< default: box 3.0 x 1.0 x 2.8 m, wall_gap 0
  double alpha = 0.5;        ///< Eq. 3 shape control, [0, 1]
  double radius = 0.1;       ///< control radius R of every particle (m), > 0
  double edge_length = 0.1;  ///< growth edge-length control L (m), > 0
  double gap = 0.0;          ///< minimum distance between particles (m), >= 0
  /// Centre-to-centre lattice spacing (m). 0 = 2 R + gap, where particles cannot touch and grow
  /// independently (in parallel). A positive value below 2 R + gap packs the sites closer and
  /// turns on the paper's contact check: growth toward an already grown neighbour is stopped
  /// where a new vertex would come within `gap` of it, and a particle that still overlaps after
  /// growth (edge-edge contact the vertex check cannot see) is shrunk about its centre until the
  /// exact test passes. Must be >= R (otherwise a site lies inside its neighbour's sphere).
  double spacing = 0.0;
  std::uint32_t max_vertices = 20000;  ///< vertex cap per particle, [6, 10^6]
  std::uint64_t seed = 1;              ///< master seed; site i draws from Rng(seed, i)
  /// Growth rule and control-surface axis ratios. A control ellipsoid is turned at random at each
  /// site (from its own stream, Rng(seed ^ salt, i), so spheres draw exactly as without it).
  GrowthForm form{};
  /// Shapes from mesh files (particle.library): each site holds a library shape drawn from its
  /// stream (or, use-once, a seeded permutation), randomly oriented, scaled so that its smallest
  /// enclosing sphere (radius R) is centred on the site. The pipeline loads `files.loaded`.
  ShapeFiles files{};
};

/// The growth controls of every site (the control ellipsoid unturned).
GrowthParams growth_params(const LatticeOptions& options);

/// Throws InvalidInput naming the field ("lattice.radius", "lattice.spacing",
/// "container.length", ...) unless the options are usable, and LimitExceeded if the vertex cap is
/// too small for (radius, edge_length). Also rejects a container in which no site fits.
void validate(const LatticeOptions& options);

/// Number of lattice sites per axis (x, y, z) for the options: along each axis
/// n = floor((extent - 2 wall_gap - 2 R) / spacing) + 1 (the lattice is centred in the box).
/// For a cylinder, the x/y counts are those of its bounding square; sites outside the cylinder's
/// centre region are dropped. \throw InvalidInput as validate().
std::array<std::uint32_t, 3> lattice_counts(const LatticeOptions& options);

/// Runs the paper's lattice placement. Sites are numbered x fastest, then y, then z; particle i of
/// the result is site i (no site is ever left empty). Deterministic for a given seed regardless
/// of thread count. The report's target is "all sites filled".
/// \throw InvalidInput, LimitExceeded (as validate()).
PackResult pack_lattice(const LatticeOptions& options, const PackControl& control = {});

}  // namespace aggpack
