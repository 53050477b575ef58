#pragma once
// Internal to the exact convex-convex test (overlap.cpp, support_shape.cpp): the support
// providers, the signed-volumes sub-algorithm, GJK (distance/separation) and boolean GJK.
// Everything sits in an unnamed namespace on purpose: each of the two files gets its own copy,
// which the compiler inlines exactly as when this code was one file (speed, bench/RESULTS.md).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "aggpack/geom/overlap.h"

namespace aggpack {

namespace {  // NOLINT(cert-dcl59-cpp,google-build-namespaces): see the file comment

constexpr int kMaxIterations = 128;
// Convergence: stop when the gap between the upper bound |v| and the lower bound v.w/|v| is below
// this fraction of |v| (or below a tenth of tol). GJK on polytopes normally stops earlier, when
// the support point repeats.
constexpr double kRelativeGap = 1e-13;
// A triangle whose sine of angle is below ~1e-10 is treated as its three edges: its plane (and
// so the origin's projection) is not determined in double precision.
constexpr double kDegenerateTriangle = 1e-20;

// ---------------------------------------------------------------------------------------------
// Support providers. Each returns the index of a vertex maximising direction . x in its own
// local frame, and the vertex for an index.

// Every vertex of a ConvexPolyhedron (no preparation; exact).
struct PolyhedronSupport {
  const std::vector<Vec3>& vertices;
  [[nodiscard]] std::uint32_t support(const Vec3& direction, std::uint32_t /*hint*/) const {
    std::uint32_t best = 0;
    double best_value = direction.dot(vertices[0]);
    const auto count = static_cast<std::uint32_t>(vertices.size());
    for (std::uint32_t i = 1; i < count; ++i) {
      const double value = direction.dot(vertices[i]);
      if (value > best_value) {
        best_value = value;
        best = i;
      }
    }
    return best;
  }
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return vertices[index]; }
};

// A polyhedron scaled by a positive factor about its local origin, without copying it (the
// farthest vertex along a direction does not change with the scale).
struct ScaledPolyhedronSupport {
  const std::vector<Vec3>& vertices;
  double scale;
  [[nodiscard]] std::uint32_t support(const Vec3& direction, std::uint32_t hint) const {
    return PolyhedronSupport{vertices}.support(direction, hint);
  }
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return scale * vertices[index]; }
};

struct ShapeSupport {
  const SupportShape& shape;
  [[nodiscard]] std::uint32_t support(const Vec3& direction, std::uint32_t hint) const {
    return shape.support(direction, hint);
  }
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return shape.vertex(index); }
};

// A list of points (vertex links during SupportShape construction).
struct PointsSupport {
  const Vec3* points;
  std::uint32_t count;
  [[nodiscard]] std::uint32_t support(const Vec3& direction, std::uint32_t /*hint*/) const {
    std::uint32_t best = 0;
    double best_value = direction.dot(points[0]);
    for (std::uint32_t i = 1; i < count; ++i) {
      const double value = direction.dot(points[i]);
      if (value > best_value) {
        best_value = value;
        best = i;
      }
    }
    return best;
  }
  [[nodiscard]] Vec3 vertex(std::uint32_t index) const { return points[index]; }
};

// ---------------------------------------------------------------------------------------------
// Signed-volumes sub-algorithm (Montanari et al. 2017): closest point to the origin of a simplex
// of 1-4 points, as barycentric weights over a subset of them. Barycentric coordinates come from
// signed volumes/areas of the full-dimensional simplex (projected onto the best-conditioned
// coordinate plane for a triangle), so that the decision "origin inside / which face" is
// consistent across dimensions; no Gram-matrix inversions as in Johnson's algorithm.

struct SubResult {
  Vec3 v = Vec3::Zero();
  // Parallel to v, but computed from the simplex's shape where possible: when the origin projects
  // into a triangle, its normal (a cross product of edges) has a direction error of ~1e-16
  // whatever |v| is, while v (a weighted sum of points of size ~R) points only to within
  // ~1e-16 R / |v|. Searching and bounding along `direction` keeps tiny distances accurate.
  Vec3 direction = Vec3::Zero();
  double distance_squared = std::numeric_limits<double>::infinity();
  std::array<double, 4> lambda{};
  unsigned mask = 0;
};

inline bool same_sign(double a, double b) { return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0); }

inline void set_vertex(const Vec3* p, int i, SubResult& out) {
  out.v = p[i];
  out.direction = p[i];
  out.distance_squared = p[i].squaredNorm();
  out.lambda = {0.0, 0.0, 0.0, 0.0};
  out.lambda[i] = 1.0;
  out.mask = 1u << i;
}

void closest_on_segment(const Vec3* p, int i, int j, SubResult& out) {
  const Vec3 t = p[j] - p[i];
  const double length_squared = t.squaredNorm();
  const double along = -p[i].dot(t);  // weight of p[j] times |t|^2
  if (!(along > 0.0) || !(length_squared > 0.0)) {
    set_vertex(p, i, out);
    return;
  }
  if (along >= length_squared) {
    set_vertex(p, j, out);
    return;
  }
  const double u = along / length_squared;
  out.lambda = {0.0, 0.0, 0.0, 0.0};
  out.lambda[i] = 1.0 - u;
  out.lambda[j] = u;
  out.v = (1.0 - u) * p[i] + u * p[j];
  // v's rounding error along t would tilt the search off the segment's normal cone and spoil the
  // lower bound by ~|t| * 1e-16 / |v|; errors across t only turn it within the cone.
  out.direction = out.v - t * (out.v.dot(t) / length_squared);
  out.distance_squared = out.v.squaredNorm();
  out.mask = (1u << i) | (1u << j);
}

inline void keep_closer(const SubResult& candidate, SubResult& best) {
  if (candidate.distance_squared < best.distance_squared) best = candidate;
}

void closest_on_triangle(const Vec3* p, int i, int j, int k, SubResult& out) {
  const Vec3 e1 = p[j] - p[i];
  const Vec3 e2 = p[k] - p[i];
  const Vec3 n = e1.cross(e2);
  const double nn = n.squaredNorm();
  SubResult candidate;
  if (!(nn > kDegenerateTriangle * e1.squaredNorm() * e2.squaredNorm())) {
    out.distance_squared = std::numeric_limits<double>::infinity();
    closest_on_segment(p, i, j, candidate);
    keep_closer(candidate, out);
    closest_on_segment(p, j, k, candidate);
    keep_closer(candidate, out);
    closest_on_segment(p, k, i, candidate);
    keep_closer(candidate, out);
    return;
  }
  // Projection of the origin onto the plane, then signed areas in the coordinate plane where the
  // triangle's projection is largest (|n[axis]| >= |n| / sqrt(3)).
  const Vec3 q = n * (p[i].dot(n) / nn);
  int axis = 0;
  if (std::abs(n.y()) > std::abs(n.x())) axis = 1;
  if (std::abs(n.z()) > std::abs(n[axis])) axis = 2;
  const int u = (axis + 1) % 3;
  const int w = (axis + 2) % 3;
  // (u, w, axis) is cyclic, so the projected area of (p_i, p_j, p_k) has the sign of n[axis].
  const auto area = [u, w](const Vec3& a, const Vec3& b, const Vec3& c) {
    return (b[u] - a[u]) * (c[w] - a[w]) - (b[w] - a[w]) * (c[u] - a[u]);
  };
  const double mu = n[axis];
  const std::array<double, 3> c = {area(q, p[j], p[k]), area(p[i], q, p[k]), area(p[i], p[j], q)};
  if (same_sign(c[0], mu) && same_sign(c[1], mu) && same_sign(c[2], mu)) {
    const double inverse_sum = 1.0 / (c[0] + c[1] + c[2]);
    out.lambda = {0.0, 0.0, 0.0, 0.0};
    out.lambda[i] = c[0] * inverse_sum;
    out.lambda[j] = c[1] * inverse_sum;
    out.lambda[k] = c[2] * inverse_sum;
    out.v = out.lambda[i] * p[i] + out.lambda[j] * p[j] + out.lambda[k] * p[k];
    out.direction = p[i].dot(n) >= 0.0 ? n : Vec3(-n);
    out.distance_squared = out.v.squaredNorm();
    out.mask = (1u << i) | (1u << j) | (1u << k);
    return;
  }
  // The origin projects outside: the closest point lies on an edge opposite a vertex whose
  // weight is not positive (Montanari et al., Theorem 1).
  out.distance_squared = std::numeric_limits<double>::infinity();
  const std::array<std::array<int, 2>, 3> opposite = {{{j, k}, {i, k}, {i, j}}};
  for (int m = 0; m < 3; ++m) {
    if (!same_sign(c[m], mu)) {
      closest_on_segment(p, opposite[m][0], opposite[m][1], candidate);
      keep_closer(candidate, out);
    }
  }
}

inline double triple(const Vec3& a, const Vec3& b, const Vec3& c) { return a.dot(b.cross(c)); }

// Cofactors of [[p0 p1 p2 p3]; [1 1 1 1]] along the last row: the signed volume of the
// tetrahedron with vertex m replaced by the origin. They sum to the full signed volume `det`.
// The origin is strictly inside when all four have the sign of det.
struct Cofactors {
  std::array<double, 4> c;
  double det;
  [[nodiscard]] bool contains_origin() const {
    return same_sign(c[0], det) && same_sign(c[1], det) && same_sign(c[2], det) &&
           same_sign(c[3], det);
  }
};

Cofactors tetrahedron_cofactors(const Vec3* p) {
  Cofactors result{{triple(p[1], p[2], p[3]), -triple(p[0], p[2], p[3]), triple(p[0], p[1], p[3]),
                    -triple(p[0], p[1], p[2])},
                   0.0};
  result.det = result.c[0] + result.c[1] + result.c[2] + result.c[3];
  return result;
}

void closest_on_tetrahedron(const Vec3* p, SubResult& out) {
  const Cofactors cofactors = tetrahedron_cofactors(p);
  const auto& c = cofactors.c;
  const double det = cofactors.det;
  if (cofactors.contains_origin()) {
    out.v = Vec3::Zero();
    out.direction = Vec3::Zero();
    out.distance_squared = 0.0;
    const double inverse_det = 1.0 / det;
    for (int m = 0; m < 4; ++m) out.lambda[m] = c[m] * inverse_det;
    out.mask = 0xF;
    return;
  }
  out.distance_squared = std::numeric_limits<double>::infinity();
  SubResult candidate;
  const std::array<std::array<int, 3>, 4> opposite = {{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};
  for (int m = 0; m < 4; ++m) {
    if (!same_sign(c[m], det)) {
      closest_on_triangle(p, opposite[m][0], opposite[m][1], opposite[m][2], candidate);
      keep_closer(candidate, out);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// GJK on A - B in A's local frame. B's local frame maps into A's by x -> rotation * x +
// translation.

struct Simplex {
  std::array<Vec3, 4> points;
  std::array<std::uint32_t, 4> index_a{};
  std::array<std::uint32_t, 4> index_b{};
  std::array<double, 4> lambda{};
  int size = 0;
};

enum class GjkOutcome {
  kIntersecting,  // |v| <= tol, or the origin is inside a simplex, or no separation certified
  kSeparated,     // separation query: lower bound > threshold
  kWithin,        // separation query: upper bound <= threshold
  kConverged      // distance query: bounds met
};

struct GjkResult {
  GjkOutcome outcome = GjkOutcome::kIntersecting;
  Simplex simplex;
  Vec3 v = Vec3::Zero();
  double lower_bound = 0.0;
  int iterations = 0;
};

// `threshold` < 0 runs a full distance query; otherwise the query stops as soon as the distance
// is certified > threshold (kSeparated) or shown <= threshold (kWithin).
template <class SupportA, class SupportB>
GjkResult run_gjk(const SupportA& a, const SupportB& b, const Mat3& rotation,
                  const Vec3& translation, double tolerance, double threshold) {
  const bool is_separation_query = threshold >= 0.0;
  const double tolerance_squared = tolerance * tolerance;
  const double threshold_squared = threshold * threshold;
  GjkResult result;
  Simplex& simplex = result.simplex;
  // First direction: between the local origins (inside generated particles), so the first
  // support pair is usually already the closest.
  Vec3 v = -translation;
  if (!(v.squaredNorm() > 0.0)) v = Vec3::UnitX();
  Vec3 direction = v;               // search direction, parallel to v (see SubResult)
  bool is_v_in_difference = false;  // v is a point of A - B (then |v| bounds the distance)
  double v_squared = v.squaredNorm();
  std::uint32_t hint_a = SupportShape::kNoHint;
  std::uint32_t hint_b = SupportShape::kNoHint;
  double lower_bound = 0.0;
  Vec3 last_w = Vec3::Zero();

  for (int iteration = 1; iteration <= kMaxIterations; ++iteration) {
    result.iterations = iteration;
    hint_a = a.support(-direction, hint_a);
    hint_b = b.support(rotation.transpose() * direction, hint_b);
    const Vec3 w = a.vertex(hint_a) - (rotation * b.vertex(hint_b) + translation);
    last_w = w;
    const double dw = direction.dot(w);
    // Any direction gives a lower bound: w is the support point of A - B towards the origin,
    // so the plane through w normal to `direction` separates A - B from the origin by
    // direction.w / |direction|.
    if (dw > 0.0) {
      const double direction_squared = direction.squaredNorm();
      if (is_separation_query && dw * dw > threshold_squared * direction_squared) {
        result.outcome = GjkOutcome::kSeparated;
        break;
      }
      const double bound = dw / std::sqrt(direction_squared);
      lower_bound = std::max(lower_bound, bound);
      if (is_v_in_difference) {
        const double v_norm = std::sqrt(v_squared);
        if (v_norm - bound <= std::max(kRelativeGap * v_norm, 0.1 * tolerance)) {
          result.outcome = GjkOutcome::kConverged;
          break;
        }
      }
    }
    bool is_repeat = false;
    for (int m = 0; m < simplex.size; ++m) {
      if (simplex.index_a[m] == hint_a && simplex.index_b[m] == hint_b) is_repeat = true;
    }
    if (is_repeat) {
      // No new support point: the simplex already holds the closest feature.
      result.outcome = is_v_in_difference ? GjkOutcome::kConverged : GjkOutcome::kIntersecting;
      break;
    }
    simplex.points[simplex.size] = w;
    simplex.index_a[simplex.size] = hint_a;
    simplex.index_b[simplex.size] = hint_b;
    ++simplex.size;

    SubResult sub;
    switch (simplex.size) {
      case 1:
        set_vertex(simplex.points.data(), 0, sub);
        break;
      case 2:
        closest_on_segment(simplex.points.data(), 0, 1, sub);
        break;
      case 3:
        closest_on_triangle(simplex.points.data(), 0, 1, 2, sub);
        break;
      default:
        closest_on_tetrahedron(simplex.points.data(), sub);
        break;
    }
    if (sub.mask == 0xF || sub.distance_squared <= tolerance_squared) {
      v = sub.v;
      v_squared = sub.distance_squared;
      result.outcome = GjkOutcome::kIntersecting;
      break;
    }
    if (is_v_in_difference && !(sub.distance_squared < v_squared)) {
      // No progress (rounding): keep the previous, better simplex (drop the point just added;
      // nothing else has changed yet).
      --simplex.size;
      result.outcome = GjkOutcome::kConverged;
      break;
    }
    // Keep only the points with positive weight, in their order.
    int kept = 0;
    for (int m = 0; m < simplex.size; ++m) {
      if ((sub.mask & (1u << m)) != 0) {
        simplex.points[kept] = simplex.points[m];
        simplex.index_a[kept] = simplex.index_a[m];
        simplex.index_b[kept] = simplex.index_b[m];
        simplex.lambda[kept] = sub.lambda[m];
        ++kept;
      }
    }
    simplex.size = kept;
    v = sub.v;
    direction = sub.direction;
    v_squared = sub.distance_squared;
    is_v_in_difference = true;
    if (is_separation_query && v_squared <= threshold_squared) {
      result.outcome = GjkOutcome::kWithin;
      break;
    }
    if (iteration == kMaxIterations) {
      result.outcome = GjkOutcome::kConverged;  // judged below from the bounds
    }
  }
  // A stall on a segment (a CSO edge: vertex against edge) whose normal cone is thin -- nearly
  // coplanar faces -- can leave the bounds apart: the search direction, accurate to ~1e-16 R/|v|
  // rad, may point just outside the cone. The faces next to the edge are planes that the
  // segment and the last support point span; their normals are accurate, and the distance to
  // their planes is within (cone width)^2 of |v|. Bound along them.
  for (int polish = 0; polish < 4 && result.outcome == GjkOutcome::kConverged && simplex.size == 2;
       ++polish) {
    const double v_norm = std::sqrt(v_squared);
    if (v_norm - lower_bound <= std::max(kRelativeGap * v_norm, 0.1 * tolerance)) break;
    Vec3 normal = (simplex.points[1] - simplex.points[0]).cross(last_w - simplex.points[0]);
    if (!(normal.squaredNorm() > 0.0)) break;
    if (normal.dot(v) < 0.0) normal = -normal;
    const std::uint32_t index_a = a.support(-normal, hint_a);
    const std::uint32_t index_b = b.support(rotation.transpose() * normal, hint_b);
    last_w = a.vertex(index_a) - (rotation * b.vertex(index_b) + translation);
    const double bound = normal.dot(last_w) / normal.norm();
    lower_bound = std::max(lower_bound, bound);
    if (is_separation_query && bound > threshold) result.outcome = GjkOutcome::kSeparated;
  }
  if (result.outcome == GjkOutcome::kSeparated) lower_bound = std::max(lower_bound, threshold);
  result.v = v;
  result.lower_bound = lower_bound;
  // Only a certified lower bound above tol separates; anything else is contact.
  if ((result.outcome == GjkOutcome::kConverged) && !(lower_bound > tolerance)) {
    result.outcome = GjkOutcome::kIntersecting;
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Boolean GJK (region tests in the style of Muratori's "Implementing GJK", 2006): no closest
// points, no divisions, so an iteration costs about half of run_gjk's. It answers only with a
// certificate -- a separating plane with margin > threshold, or a tetrahedron of A - B points
// that the signed-volume cofactors show to contain the origin -- and otherwise gives up
// (kUnknown) so that the exact run_gjk decides: touching, near-degenerate and distance-in-
// (0, threshold] cases. Its region logic assumes exact arithmetic; rounding can only make it give
// up, never answer wrongly, because the answers are checked independently of that logic.

enum class FastAnswer { kSeparated, kOverlapping, kUnknown };

constexpr int kFastIterations = 16;

// Segment (b, a) = (p[0], p[1]), a the newest: the search direction towards the origin from the
// segment, or from a alone (size becomes 1) when the origin lies beyond a.
inline void update_line(std::array<Vec3, 4>& p, std::array<std::uint64_t, 4>& key, int& size,
                        Vec3& search) {
  const Vec3& a = p[1];
  const Vec3 ab = p[0] - a;
  const Vec3 ao = -a;
  if (ab.dot(ao) > 0.0) {
    search = ab.cross(ao).cross(ab);
  } else {
    p[0] = a;
    key[0] = key[1];
    size = 1;
    search = ao;
  }
}

// Triangle (c, b, a) = (p[0], p[1], p[2]), a the newest.
inline void update_triangle(std::array<Vec3, 4>& p, std::array<std::uint64_t, 4>& key, int& size,
                            Vec3& search) {
  const Vec3 a = p[2];
  const Vec3 ab = p[1] - a;
  const Vec3 ac = p[0] - a;
  const Vec3 ao = -a;
  const Vec3 abc = ab.cross(ac);
  const auto keep_edge_ab = [&]() {  // segment (b, a), or a alone
    p[0] = p[1];
    key[0] = key[1];
    p[1] = a;
    key[1] = key[2];
    size = 2;
    update_line(p, key, size, search);
  };
  if (abc.cross(ac).dot(ao) > 0.0) {  // beyond edge ac
    if (ac.dot(ao) > 0.0) {
      p[1] = a;  // segment (c, a)
      key[1] = key[2];
      size = 2;
      search = ac.cross(ao).cross(ac);
    } else {
      keep_edge_ab();
    }
  } else if (ab.cross(abc).dot(ao) > 0.0) {  // beyond edge ab
    keep_edge_ab();
  } else {
    search = abc.dot(ao) > 0.0 ? abc : Vec3(-abc);
  }
}

// Tetrahedron (d, c, b, a) = (p[0..3]), a the newest. kOverlapping when the origin is inside
// (confirmed by the cofactors); otherwise reduces to the face the origin is beyond (size 3 or
// less), or leaves size 4 when it cannot tell (the caller then gives up).
inline FastAnswer update_tetrahedron(std::array<Vec3, 4>& p, std::array<std::uint64_t, 4>& key,
                                     int& size, Vec3& search) {
  const Vec3 a = p[3];
  const Vec3 ao = -a;
  // Faces through a, each with the vertex opposite: (a, b, c | d), (a, c, d | b), (a, d, b | c).
  constexpr int kFaces[3][3] = {{2, 1, 0}, {1, 0, 2}, {0, 2, 1}};
  for (const auto& face : kFaces) {
    const Vec3& x = p[face[0]];
    const Vec3& y = p[face[1]];
    const Vec3& opposite = p[face[2]];
    const Vec3 normal = (x - a).cross(y - a);
    const double opposite_side = normal.dot(opposite - a);
    if (opposite_side == 0.0) return FastAnswer::kUnknown;  // flat tetrahedron
    const double origin_side = normal.dot(ao);
    if ((opposite_side > 0.0) ? origin_side < 0.0 : origin_side > 0.0) {
      const std::uint64_t key_x = key[face[0]];
      const std::uint64_t key_y = key[face[1]];
      const std::uint64_t key_a = key[3];
      const Vec3 px = x;
      const Vec3 py = y;
      p[0] = py;
      key[0] = key_y;
      p[1] = px;
      key[1] = key_x;
      p[2] = a;
      key[2] = key_a;
      size = 3;
      update_triangle(p, key, size, search);
      return FastAnswer::kUnknown;  // keep iterating
    }
  }
  return tetrahedron_cofactors(p.data()).contains_origin() ? FastAnswer::kOverlapping
                                                           : FastAnswer::kUnknown;
}

// kSeparated: distance certainly > threshold; kOverlapping: the bodies certainly overlap.
// `axis` (A's frame, from A towards B; null or zero = none) is tried as the first search
// direction; on kSeparated it receives the separating direction found (a warm start for the next
// query of the same pair).
template <class SupportA, class SupportB>
FastAnswer boolean_gjk(const SupportA& a, const SupportB& b, const Mat3& rotation,
                       const Vec3& translation, double threshold, Vec3* axis = nullptr) {
  const double threshold_squared = threshold * threshold;
  // Towards the origin from the point (centre of A) - (centre of B) = -translation.
  Vec3 search = translation;
  if (axis != nullptr && axis->squaredNorm() > 0.0) search = *axis;
  if (!(search.squaredNorm() > 0.0)) search = Vec3::UnitX();
  std::array<Vec3, 4> p;
  std::array<std::uint64_t, 4> key{};
  int size = 0;
  std::uint32_t hint_a = SupportShape::kNoHint;
  std::uint32_t hint_b = SupportShape::kNoHint;
  for (int iteration = 0; iteration < kFastIterations; ++iteration) {
    hint_a = a.support(search, hint_a);
    hint_b = b.support(-(rotation.transpose() * search), hint_b);
    const Vec3 w = a.vertex(hint_a) - (rotation * b.vertex(hint_b) + translation);
    const double progress = search.dot(w);
    if (!(progress > 0.0)) {
      // w did not pass the origin: the plane through w normal to `search` separates A - B from
      // the origin by -progress / |search|.
      if (progress < 0.0 && progress * progress > threshold_squared * search.squaredNorm()) {
        if (axis != nullptr) *axis = search;
        return FastAnswer::kSeparated;
      }
      return FastAnswer::kUnknown;
    }
    const std::uint64_t new_key = (static_cast<std::uint64_t>(hint_a) << 32) | hint_b;
    for (int m = 0; m < size; ++m) {
      if (key[m] == new_key) return FastAnswer::kUnknown;  // no progress
    }
    p[size] = w;
    key[size] = new_key;
    ++size;
    switch (size) {
      case 1:
        search = -w;
        break;
      case 2:
        update_line(p, key, size, search);
        break;
      case 3:
        update_triangle(p, key, size, search);
        break;
      default:
        if (update_tetrahedron(p, key, size, search) == FastAnswer::kOverlapping) {
          return FastAnswer::kOverlapping;
        }
        if (size == 4) return FastAnswer::kUnknown;  // cofactors disagreed: near a face
        break;
    }
    if (!(search.squaredNorm() > 0.0)) return FastAnswer::kUnknown;
  }
  return FastAnswer::kUnknown;
}

}  // namespace

}  // namespace aggpack
