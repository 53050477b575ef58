#pragma once
// Exact convex-convex proximity: GJK distance between two placed convex polyhedra, with a
// bounding-sphere early out. Decides non-overlap in the packers (DESIGN.md: "geometry is exact
// where it decides validity"). The paper's vertex-in-body test (locate_point) misses
// edge-through-edge crossings; this does not.
//
// Algorithm: GJK (Gilbert-Johnson-Keerthi) on the Minkowski difference A - B, in A's local
// frame, with the signed-volumes sub-algorithm of Montanari, Petrinic & Barbieri (ACM TOG 36(3),
// 2017) for the closest point of each simplex. Each iteration yields a point v of A - B (so |v|
// is an upper bound on the distance) and a support point w (so the plane through w normal to the
// search direction gives a lower bound). The search direction is the simplex face's normal where
// there is one (accurate to ~1e-16 rad however small |v| is), so distances down to ~1e-15 of the
// size are resolved. "Separated" is only ever answered from a lower bound, i.e. from a certified
// separating plane.
//
// is_separated first runs a boolean GJK (region tests, no divisions; about half the cost per
// iteration). It answers only with a certificate -- a separating plane with margin > gap + tol,
// or a tetrahedron of A - B points whose signed volumes show it contains the origin -- and hands
// everything else (touching, distance in (0, gap + tol], degenerate simplices; ~0.02% of random
// calls) to the exact GJK.
//
// Tolerance: all decisions use an absolute length tol = kProximityTolerance * (R_a + R_b), where
// R is each body's bounding radius about its local origin. Bodies closer than tol count as
// touching (intersecting); in doubt (e.g. the iteration cap is reached without a certified
// separation) a pair is reported as intersecting / not separated, never the reverse.
//
// Two ways to call: with `ConvexPolyhedron` directly (support by a scan over every vertex; no
// preparation, no allocation), or with a `SupportShape` built once per shape (only hull
// vertices, SIMD scans; about 2-4x faster for generated particles, more for finely grown ones,
// most of whose vertices lie on hull faces). Both give the same answers within tol.
// Speed: bench/overlap_bench.cpp, figures in bench/RESULTS.md ("Overlap tests").

#include <cstdint>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// Relative tolerance of the proximity queries: distances below this fraction of the pair's size
/// (sum of bounding radii) count as touching.
inline constexpr double kProximityTolerance = 1e-12;

/// Result of a distance query between two placed bodies.
struct DistanceResult {
  double distance = 0.0;         ///< Euclidean distance (m); 0 when the bodies intersect
  bool is_intersecting = false;  ///< true when they share a point (touching within tol counts)
  Vec3 point_a = Vec3::Zero();   ///< closest point on A (world), valid when not intersecting
  Vec3 point_b = Vec3::Zero();   ///< closest point on B (world), valid when not intersecting
  int iterations = 0;            ///< GJK iterations used
};

/// Largest distance from the local origin to a vertex (bounding-sphere radius about the origin).
double bounding_radius(const ConvexPolyhedron& body);

/// Radius of the largest ball about the local origin inside a convex body: the smallest distance
/// from the origin to a face plane. 0 when the origin is not inside (or on a zero-area face's
/// line), infinity for a body without faces. The one definition used by the packers, the
/// SupportShape inner-ball test and the renderer's occluders.
double inner_radius(const ConvexPolyhedron& body);

/// How SupportShape finds the vertex farthest along a direction.
enum class SupportSearch {
  kAuto,      ///< hill-climbing above kHillClimbMinVertices hull vertices, else a linear scan
  kScan,      ///< always a linear scan over the hull vertices
  kHillClimb  ///< always hill-climbing over the hull adjacency
};

/// A convex polyhedron prepared for fast support queries: only its hull vertices (a vertex within
/// 1e-14 of the size of the hull of its mesh neighbours is dropped; the generator produces many
/// such vertices), stored coordinate-by-coordinate for SIMD scans (AVX2 when the CPU has it,
/// else SSE2; bit-identical answers), with their adjacency for hill-climbing on large shapes.
/// Build one per distinct shape (O(V * degree) work) and reuse it for every pose. Immutable
/// after construction; safe to share between threads.
class SupportShape {
 public:
  /// Shapes with more hull vertices than this use hill-climbing over the adjacency graph;
  /// smaller ones use a linear scan (measured crossover, see bench/RESULTS.md).
  static constexpr std::uint32_t kHillClimbMinVertices = 400;

  SupportShape() = default;
  /// \throw InvalidInput if `body` is empty or not a closed 2-manifold.
  explicit SupportShape(const ConvexPolyhedron& body, SupportSearch search = SupportSearch::kAuto);

  /// Number of hull vertices kept for the support search.
  [[nodiscard]] std::uint32_t vertex_count() const { return count_; }
  /// Hull vertex `index` (< vertex_count()) in the local frame (m).
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const {
    return {coordinates_[index], coordinates_[stride_ + index], coordinates_[2 * stride_ + index]};
  }
  /// Largest distance from the local origin to a vertex (m).
  [[nodiscard]] double bounding_radius() const { return bounding_radius_; }
  /// Radius (m) of a ball about the local origin that lies inside the body; 0 when the origin is
  /// not strictly inside. Used as a cheap "certainly overlapping" test.
  [[nodiscard]] double inner_radius() const { return inner_radius_; }
  /// True when support queries hill-climb instead of scanning.
  [[nodiscard]] bool uses_hill_climbing() const { return uses_hill_climbing_; }
  /// Index of a hull vertex maximising direction . x (local frame). `start` is a hint (a
  /// previous answer) for hill-climbing; pass kNoHint when there is none.
  [[nodiscard]] std::uint32_t support(const Vec3& direction, std::uint32_t start) const;

  static constexpr std::uint32_t kNoHint = 0xFFFFFFFFu;

 private:
  [[nodiscard]] std::uint32_t scan(const Vec3& direction) const;
  [[nodiscard]] std::uint32_t climb(const Vec3& direction, std::uint32_t start) const;

  std::uint32_t count_ = 0;
  std::uint32_t stride_ = 0;         // padded count: x at [0, stride), y, z follow
  std::vector<double> coordinates_;  // x..., y..., z... (padding repeats the last vertex)
  std::vector<std::uint32_t> neighbour_offsets_;  // CSR adjacency of hull vertices
  std::vector<std::uint32_t> neighbours_;
  std::vector<std::uint8_t> is_blunt_;                   // walk ending here is re-checked by a scan
  std::uint32_t axis_extremes_[6] = {0, 0, 0, 0, 0, 0};  // start vertices for +x,-x,+y,-y,+z,-z
  double bounding_radius_ = 0.0;
  double inner_radius_ = 0.0;
  bool uses_hill_climbing_ = false;
};

/// GJK distance between body `a` placed by `pose_a` and body `b` placed by `pose_b`.
/// Poses must hold unit quaternions. Robust to touching and nearly coplanar configurations.
/// \throw InvalidInput if a body is empty, a pose is not finite or its quaternion is not unit.
DistanceResult gjk_distance(const ConvexPolyhedron& a, const Pose& pose_a,
                            const ConvexPolyhedron& b, const Pose& pose_b);
/// As above, for prepared shapes (faster).
DistanceResult gjk_distance(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                            const Pose& pose_b);

/// True when the two placed bodies are more than `gap` (m, >= 0) + tol apart; bodies that touch
/// or overlap are never separated, and in doubt the answer is false. Uses bounding spheres
/// (radius_a/radius_b from bounding_radius, m) to answer most calls without GJK.
/// \throw InvalidInput if gap is negative or not finite, or as gjk_distance.
bool is_separated(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                  const ConvexPolyhedron& b, const Pose& pose_b, double radius_b, double gap);
/// As above, with `b` scaled by `scale_b` (> 0) about its local origin before it is placed, without
/// copying it (a shape library reused at many sizes). radius_b is the scaled body's bounding
/// radius. \throw InvalidInput also for a scale that is not finite and positive.
bool is_separated(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                  const ConvexPolyhedron& b, double scale_b, const Pose& pose_b, double radius_b,
                  double gap);
/// As above, for prepared shapes (radii come from the shapes; also uses their inner radii to
/// answer "certainly overlapping" without GJK).
bool is_separated(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                  const Pose& pose_b, double gap);
/// As above, warm-started for bodies that move a little between queries (Monte Carlo): `axis`
/// (world frame, any length; zero = none) is the first search direction, from a towards b; when
/// the answer is a separation certified along the search it receives that separating direction.
/// A caller that keeps `axis` per pair answers most repeated queries with one support pair. The
/// answer is the same as without the hint (only certified separations count either way).
bool is_separated(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                  const Pose& pose_b, double gap, Vec3& axis);

}  // namespace aggpack
