#pragma once
// The paper's random aggregate generator (Section 2): a random octahedron whose six vertex
// distances follow Eq. 3, grown on its longest edge until every edge is no longer than L.
//
// Growth, in the paper's words: "repeatedly generating new vertices at random on the largest
// edges of the aggregate surface". The default rule (Growth::kHull) reads it as written: a new
// vertex at a random point of the longest edge, moved out along the ray from the centre through
// that point to its Eq. 3 distance (never inward of the edge), the body kept convex by taking the
// convex hull. The earlier rule (Growth::kMidpoint) put the vertex on the midpoint ray and clamped
// it onto the neighbouring faces' planes; it is kept so that earlier configs and files reproduce.
//
// The control surface is the sphere of radius r, or, with axis ratios below 1, the ellipsoid of
// semi-axes r, elongation * r, elongation * flatness * r (long axis = the local x axis); Eq. 3
// then scales the surface's radius in each direction.
//
// Eq. 3 as printed, d = alpha*r + 0.2*(1-alpha) + 0.8*(1-alpha)*r*U, is not dimensionally
// consistent; we use the reading that agrees with it at r = 1 and scales with r:
//     d = r * (alpha + (1 - alpha) * (0.2 + 0.8 * U)),  U uniform in [0, 1),
// so d lies in [r * (alpha + 0.2 * (1 - alpha)), r]: alpha = 1 gives a regular octahedron,
// alpha = 0 draws d anywhere in [0.2 r, r].

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "aggpack/core/rng.h"
#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Where a new vertex of the growth goes.
enum class Growth {
  /// At a random point of the longest edge, out along the ray from the centre to its Eq. 3
  /// distance; convex hull taken (faces it sees replaced, vertices left inside dropped).
  kHull,
  /// On the ray through the edge midpoint, clamped onto the neighbouring faces' planes (aggpack
  /// 0.1's rule: particles stay close to the base octahedron; alpha 1 gives one polyhedron).
  kMidpoint,
};

/// "hull", "midpoint".
const char* growth_name(Growth growth);
/// The growth named `name`, or nothing.
std::optional<Growth> find_growth(std::string_view name);

/// The growth rule and the control surface's shape: what a family of particles shares besides
/// alpha, r and L. The defaults give the paper's reading on a control sphere.
struct GrowthForm {
  Growth growth = Growth::kHull;
  /// Control ellipsoid's intermediate / long semi-axis, in [0.1, 1] (1 = sphere).
  double elongation = 1.0;
  /// Control ellipsoid's short / intermediate semi-axis, in [0.1, 1] (1 = sphere).
  double flatness = 1.0;
  /// Minimum edge length as a fraction of L, in [0, 0.5]: the random point on the longest edge
  /// is drawn at least this x L from both its ends, so no split leaves a piece shorter than that
  /// (0 = anywhere on the edge, 0.5 = the midpoint). Hull rule only. The default keeps slivers
  /// out: a point near an end leaves a needle-thin triangle whose plane is ill-conditioned.
  double min_edge_ratio = 0.25;

  [[nodiscard]] bool is_sphere() const { return elongation == 1.0 && flatness == 1.0; }
};

/// Throws InvalidInput naming `prefix` + the field ("particle.elongation") unless usable.
void validate(const GrowthForm& form, const std::string& prefix = "");

/// Controls of one growth run. Lengths in metres.
struct GrowthParams {
  double alpha = 0.5;                  ///< Eq. 3 shape control, in [0, 1]
  double radius = 0.1;                 ///< control radius r (m), > 0; every vertex lies within r
  double edge_length = 0.1;            ///< L (m), > 0: growth stops when every edge <= L
  std::uint32_t max_vertices = 20000;  ///< cap on the vertex count, in [6, 10^6]
  GrowthForm form{};
  /// Orientation of the control ellipsoid (its long axis is rotation * x); unused on a sphere.
  Quat axes = Quat::Identity();
};

/// Radius (m) of the control surface of `params` in the unit direction `direction`.
double control_radius_along(const GrowthParams& params, const Vec3& direction);

/// Optional limit on how far out a new vertex may be placed along a ray from the particle centre:
/// given the unit direction and the feasible interval [s_lo, s_hi] (m), return the largest allowed
/// s (>= s_lo). The lattice packer uses it for the paper's "contact check stops growth".
using GrowthLimit = std::function<double(const Vec3& direction, double s_lo, double s_hi)>;

/// Eq. 3 radius for control radius r, shape control alpha and uniform deviate u in [0, 1).
double eq3_distance(double alpha, double radius, double u);

/// Throws InvalidInput naming the field unless every parameter is in range, and LimitExceeded
/// if estimated_vertex_count(radius, edge_length) exceeds max_vertices (the message names the
/// smallest edge_length that fits).
void validate(const GrowthParams& params);

/// Upper-range estimate of a grown particle's vertex count, used to reject hopeless inputs up
/// front: 3 (midpoint rule) or 12 (hull rule) times the vertex count of a sphere of radius r
/// tiled by equilateral triangles of side L (measured counts stay below 2.8 and 9.8 times that
/// tiling), and 6 when L >= sqrt(2) r (no growth). The cap is also enforced during growth.
double estimated_vertex_count(double radius, double edge_length, Growth growth = Growth::kHull);

/// Grows one particle centred at the origin, drawing every random number from `rng`.
/// The result is convex, closed, outward CCW, has every edge <= L and every vertex within r.
/// \throw InvalidInput, LimitExceeded (vertex cap reached).
ConvexPolyhedron grow_aggregate(const GrowthParams& params, Rng& rng,
                                const GrowthLimit& limit = {});

/// Controls of a family of particles (e.g. `aggpack shapes`).
struct GeneratorOptions {
  double alpha = 0.5;                  ///< Eq. 3 shape control, in [0, 1]
  double radius_min = 0.1;             ///< smallest control radius (m), > 0
  double radius_max = 0.1;             ///< largest control radius (m), >= radius_min
  double edge_length = 0.1;            ///< L (m), > 0
  std::uint32_t max_vertices = 20000;  ///< vertex cap per particle
  std::uint64_t seed = 1;              ///< master seed
  GrowthForm form{};
};

/// Throws InvalidInput / LimitExceeded naming the field unless the options are usable.
void validate(const GeneratorOptions& options);

/// One generated particle with the control radius it was grown with.
struct GeneratedParticle {
  ConvexPolyhedron body;      ///< centred on its growth centre (the origin)
  double control_radius = 0;  ///< m
};

/// Particle number `index` of the family: its radius (uniform in [radius_min, radius_max]) and
/// shape come from the stream (seed, index) only, so any thread may generate it.
GeneratedParticle generate_particle(const GeneratorOptions& options, std::uint64_t index);

}  // namespace aggpack
