#include "aggpack/geom/mass_properties.h"

namespace aggpack {

MassProperties mass_properties(const ConvexPolyhedron& body) {
  MassProperties result;
  const auto& vertices = body.vertices();
  if (vertices.empty()) return result;
  // Integrate relative to the vertex mean to avoid cancellation for bodies far from the origin.
  Vec3 reference = Vec3::Zero();
  for (const auto& v : vertices) reference += v;
  reference /= static_cast<double>(vertices.size());

  double volume = 0.0;
  Vec3 first_moment = Vec3::Zero();
  // Integral of x x^T over the body about `reference`, kept as its six distinct entries (the
  // matrix is symmetric): xx, yy, zz, xy, yz, zx. Half the work of full 3x3 outer products.
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, yz = 0.0, zx = 0.0;
  double twice_area = 0.0;
  for (const auto& t : body.triangles()) {
    const Vec3 a = vertices[t[0]] - reference;
    const Vec3 b = vertices[t[1]] - reference;
    const Vec3 c = vertices[t[2]] - reference;
    twice_area += (b - a).cross(c - a).norm();
    // Signed tetrahedron (0, a, b, c): positive for an outward CCW triangle seen from inside.
    const double tet_volume = a.dot(b.cross(c)) / 6.0;
    const Vec3 sum = a + b + c;
    volume += tet_volume;
    first_moment += tet_volume * sum;
    // For a tetrahedron with a vertex at the origin: integral x_i x_j = V/20 (sum_k p_ki p_kj +
    // S_i S_j) with S the vertex sum.
    const double w = tet_volume / 20.0;
    xx += w * (a.x() * a.x() + b.x() * b.x() + c.x() * c.x() + sum.x() * sum.x());
    yy += w * (a.y() * a.y() + b.y() * b.y() + c.y() * c.y() + sum.y() * sum.y());
    zz += w * (a.z() * a.z() + b.z() * b.z() + c.z() * c.z() + sum.z() * sum.z());
    xy += w * (a.x() * a.y() + b.x() * b.y() + c.x() * c.y() + sum.x() * sum.y());
    yz += w * (a.y() * a.z() + b.y() * b.z() + c.y() * c.z() + sum.y() * sum.z());
    zx += w * (a.z() * a.x() + b.z() * b.x() + c.z() * c.x() + sum.z() * sum.x());
  }
  first_moment /= 4.0;
  result.surface_area = 0.5 * twice_area;
  Mat3 second_moment;
  second_moment << xx, xy, zx, xy, yy, yz, zx, yz, zz;
  result.volume = volume;
  if (volume == 0.0) return result;
  const Vec3 centroid_offset = first_moment / volume;
  result.centroid = reference + centroid_offset;
  const Mat3 central = second_moment - volume * centroid_offset * centroid_offset.transpose();
  result.inertia = central.trace() * Mat3::Identity() - central;
  return result;
}

double signed_tetra_volume(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // (a-p).((b-p)x(c-p)) is positive when p is behind the CCW triangle; the paper's sign convention
  // makes "outside" positive, hence the minus.
  return -(a - p).dot((b - p).cross(c - p)) / 6.0;
}

PointLocation locate_point(const ConvexPolyhedron& body, const Vec3& point, double tolerance) {
  bool is_on_boundary = false;
  const auto& vertices = body.vertices();
  for (const auto& t : body.triangles()) {
    const double volume =
        signed_tetra_volume(point, vertices[t[0]], vertices[t[1]], vertices[t[2]]);
    if (volume > tolerance) return PointLocation::kOutside;
    if (volume >= -tolerance) is_on_boundary = true;
  }
  return is_on_boundary ? PointLocation::kOnBoundary : PointLocation::kInside;
}

}  // namespace aggpack
