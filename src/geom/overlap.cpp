#include "aggpack/geom/overlap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "aggpack/core/error.h"
#include "gjk.h"

namespace aggpack {

namespace {

void require_valid(const Pose& pose, const char* field) {
  // x - x is 0 for finite x and NaN otherwise; NaN fails every comparison below. Cheap enough
  // for the hot path (this runs on every query).
  const Vec3& p = pose.position;
  const double probe = (p.x() - p.x()) + (p.y() - p.y()) + (p.z() - p.z());
  const double norm_squared = pose.rotation.squaredNorm();
  if (!(probe == 0.0) || !(std::abs(norm_squared - 1.0) <= 1e-9)) {
    if (!(probe == 0.0) || !std::isfinite(norm_squared)) {
      throw InvalidInput(field, "non-finite pose", "finite position and rotation");
    }
    throw InvalidInput(std::string(field) + ".rotation", "|q|^2 = " + format_value(norm_squared),
                       "a unit quaternion (|q|^2 = 1 within 1e-9)");
  }
}

void require_valid_gap(double gap) {
  if (!(gap >= 0.0) || !std::isfinite(gap)) {
    throw InvalidInput("gap", format_value(gap), "finite and >= 0 (m)");
  }
}

// B's local frame expressed in A's local frame.
struct RelativeFrame {
  Mat3 rotation;
  Vec3 translation;
};

RelativeFrame relative_frame(const Pose& pose_a, const Pose& pose_b) {
  // Compose the quaternions first: one matrix conversion instead of two and a matrix product.
  const Quat inverse_a = pose_a.rotation.conjugate();
  return {(inverse_a * pose_b.rotation).toRotationMatrix(),
          inverse_a * (pose_b.position - pose_a.position)};
}

template <class SupportA, class SupportB>
DistanceResult distance_query(const SupportA& a, const Pose& pose_a, const SupportB& b,
                              const Pose& pose_b, double scale) {
  const RelativeFrame frame = relative_frame(pose_a, pose_b);
  const GjkResult run =
      run_gjk(a, b, frame.rotation, frame.translation, kProximityTolerance * scale, -1.0);
  DistanceResult result;
  result.iterations = run.iterations;
  if (run.outcome == GjkOutcome::kIntersecting) {
    result.is_intersecting = true;
    return result;
  }
  Vec3 local_a = Vec3::Zero();
  Vec3 local_b = Vec3::Zero();
  for (int m = 0; m < run.simplex.size; ++m) {
    local_a += run.simplex.lambda[m] * a.vertex(run.simplex.index_a[m]);
    local_b += run.simplex.lambda[m] * b.vertex(run.simplex.index_b[m]);
  }
  result.distance = run.v.norm();
  result.point_a = pose_a.apply(local_a);
  result.point_b = pose_b.apply(local_b);
  return result;
}

// `axis`: see is_separated's warm-started overload (world frame; null = none).
template <class SupportA, class SupportB>
bool separation_query(const SupportA& a, const Pose& pose_a, const SupportB& b, const Pose& pose_b,
                      double scale, double gap, Vec3* axis = nullptr) {
  const RelativeFrame frame = relative_frame(pose_a, pose_b);
  const double tolerance = kProximityTolerance * scale;
  Vec3 local = Vec3::Zero();
  if (axis != nullptr) local = pose_a.rotation.conjugate() * *axis;
  const FastAnswer fast = boolean_gjk(a, b, frame.rotation, frame.translation, gap + tolerance,
                                      axis != nullptr ? &local : nullptr);
  if (axis != nullptr && fast == FastAnswer::kSeparated) *axis = pose_a.rotation * local;
  if (fast != FastAnswer::kUnknown) return fast == FastAnswer::kSeparated;
  const GjkResult run =
      run_gjk(a, b, frame.rotation, frame.translation, tolerance, gap + tolerance);
  return run.outcome == GjkOutcome::kSeparated;
}

// The polyhedron overloads of is_separated: input checks, the bounding spheres, then GJK with
// `support_b` (b's vertices as stored, or scaled).
template <class SupportB>
bool separated_polyhedra(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                         const ConvexPolyhedron& b, const SupportB& support_b, const Pose& pose_b,
                         double radius_b, double gap) {
  if (a.is_empty() || b.is_empty()) {
    throw InvalidInput("is_separated", "empty polyhedron", ">= 4 vertices");
  }
  require_valid_gap(gap);
  require_valid(pose_a, "pose_a");
  require_valid(pose_b, "pose_b");
  // The spheres' test is widened by tol like GJK's, so that both agree at exact touching.
  const double reach = (radius_a + radius_b) * (1.0 + kProximityTolerance) + gap;
  if ((pose_b.position - pose_a.position).squaredNorm() > reach * reach) return true;
  return separation_query(PolyhedronSupport{a.vertices()}, pose_a, support_b, pose_b,
                          radius_a + radius_b, gap);
}

}  // namespace

double bounding_radius(const ConvexPolyhedron& body) {
  double radius_squared = 0.0;
  for (const auto& v : body.vertices()) radius_squared = std::max(radius_squared, v.squaredNorm());
  return std::sqrt(radius_squared);
}

double inner_radius(const ConvexPolyhedron& body) {
  double radius = std::numeric_limits<double>::infinity();
  const auto& vertices = body.vertices();
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 normal = body.face_normal(f);
    radius = std::min(radius, normal.dot(vertices[body.triangles()[f][0]]));
  }
  return radius > 0.0 ? radius : 0.0;  // NaN (non-finite vertices) gives 0 too
}

// --- queries ---------------------------------------------------------------------------------

DistanceResult gjk_distance(const ConvexPolyhedron& a, const Pose& pose_a,
                            const ConvexPolyhedron& b, const Pose& pose_b) {
  if (a.is_empty() || b.is_empty()) {
    throw InvalidInput("gjk_distance", "empty polyhedron", ">= 4 vertices");
  }
  require_valid(pose_a, "pose_a");
  require_valid(pose_b, "pose_b");
  return distance_query(PolyhedronSupport{a.vertices()}, pose_a, PolyhedronSupport{b.vertices()},
                        pose_b, bounding_radius(a) + bounding_radius(b));
}

DistanceResult gjk_distance(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                            const Pose& pose_b) {
  if (a.vertex_count() == 0 || b.vertex_count() == 0) {
    throw InvalidInput("gjk_distance", "empty support shape", ">= 4 vertices");
  }
  require_valid(pose_a, "pose_a");
  require_valid(pose_b, "pose_b");
  return distance_query(ShapeSupport{a}, pose_a, ShapeSupport{b}, pose_b,
                        a.bounding_radius() + b.bounding_radius());
}

bool is_separated(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                  const ConvexPolyhedron& b, const Pose& pose_b, double radius_b, double gap) {
  return separated_polyhedra(a, pose_a, radius_a, b, PolyhedronSupport{b.vertices()}, pose_b,
                             radius_b, gap);
}

bool is_separated(const ConvexPolyhedron& a, const Pose& pose_a, double radius_a,
                  const ConvexPolyhedron& b, double scale_b, const Pose& pose_b, double radius_b,
                  double gap) {
  if (!(scale_b > 0.0) || !std::isfinite(scale_b)) {
    throw InvalidInput("scale_b", format_value(scale_b), "finite and > 0");
  }
  return separated_polyhedra(a, pose_a, radius_a, b, ScaledPolyhedronSupport{b.vertices(), scale_b},
                             pose_b, radius_b, gap);
}

bool is_separated(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                  const Pose& pose_b, double gap) {
  Vec3 none = Vec3::Zero();
  return is_separated(a, pose_a, b, pose_b, gap, none);
}

bool is_separated(const SupportShape& a, const Pose& pose_a, const SupportShape& b,
                  const Pose& pose_b, double gap, Vec3& axis) {
  if (a.vertex_count() == 0 || b.vertex_count() == 0) {
    throw InvalidInput("is_separated", "empty support shape", ">= 4 vertices");
  }
  require_valid_gap(gap);
  require_valid(pose_a, "pose_a");
  require_valid(pose_b, "pose_b");
  const double centre_distance_squared = (pose_b.position - pose_a.position).squaredNorm();
  const double reach =
      (a.bounding_radius() + b.bounding_radius()) * (1.0 + kProximityTolerance) + gap;
  if (centre_distance_squared > reach * reach) return true;
  // The inner balls (inside the bodies) are closer than gap, so the bodies are too.
  if (a.inner_radius() > 0.0 && b.inner_radius() > 0.0) {
    const double inner_reach = a.inner_radius() + b.inner_radius() + gap;
    if (centre_distance_squared < inner_reach * inner_reach) return false;
  }
  return separation_query(ShapeSupport{a}, pose_a, ShapeSupport{b}, pose_b,
                          a.bounding_radius() + b.bounding_radius(), gap, &axis);
}

}  // namespace aggpack
