// Tetrahedron quality measures (see aggpack/mesh/quality.h).

#include "aggpack/mesh/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aggpack {

void TetQuality::add(const TetQuality& other, std::uint64_t times) {
  if (other.tetrahedra == 0 || times == 0) return;
  tetrahedra += other.tetrahedra * times;
  below_10_degrees += other.below_10_degrees * times;
  min_dihedral_degrees = std::min(min_dihedral_degrees, other.min_dihedral_degrees);
  max_dihedral_degrees = std::max(max_dihedral_degrees, other.max_dihedral_degrees);
  max_aspect_ratio = std::max(max_aspect_ratio, other.max_aspect_ratio);
}

std::array<double, 6> dihedral_angles_degrees(const Vec3& a, const Vec3& b, const Vec3& c,
                                              const Vec3& d) {
  const std::array<Vec3, 4> p = {a, b, c, d};
  // Outward normal of the face opposite each node (not normalised: only directions matter).
  std::array<Vec3, 4> normal;
  for (int k = 0; k < 4; ++k) {
    const Vec3& u = p[(k + 1) % 4];
    const Vec3& v = p[(k + 2) % 4];
    const Vec3& w = p[(k + 3) % 4];
    Vec3 n = (v - u).cross(w - u);
    if (n.dot(p[k] - u) > 0) n = -n;
    normal[k] = n;
  }
  std::array<double, 6> angles{};
  for (std::size_t e = 0; e < kTetraEdges.size(); ++e) {
    // The edge (i, j) is shared by the faces opposite the two other nodes k and l; the interior
    // angle is pi minus the angle between their outward normals. atan2 keeps small angles exact.
    const int i = kTetraEdges[e][0];
    const int j = kTetraEdges[e][1];
    int others[2];
    int count = 0;
    for (int m = 0; m < 4; ++m) {
      if (m != i && m != j) others[count++] = m;
    }
    const Vec3& nk = normal[others[0]];
    const Vec3& nl = normal[others[1]];
    if (nk.squaredNorm() == 0 || nl.squaredNorm() == 0) {
      angles[e] = 0;
      continue;
    }
    angles[e] = std::atan2(nk.cross(nl).norm(), -nk.dot(nl)) * 180.0 / M_PI;
  }
  return angles;
}

double aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a;
  const Vec3 v = c - a;
  const Vec3 w = d - a;
  const double six_volume = u.dot(v.cross(w));
  if (!(six_volume > 0)) return std::numeric_limits<double>::infinity();
  // Circumcentre relative to a.
  const Vec3 centre =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) /
      (2.0 * six_volume);
  const double circumradius = centre.norm();
  const double area = 0.5 * (u.cross(v).norm() + v.cross(w).norm() + w.cross(u).norm() +
                             (c - b).cross(d - b).norm());
  const double inradius = 3.0 * (six_volume / 6.0) / area;
  return circumradius / (3.0 * inradius);
}

TetQuality measure_quality(std::span<const Vec3> nodes, std::span<const Tetrahedron> tetrahedra) {
  TetQuality quality;
  for (const Tetrahedron& t : tetrahedra) {
    const Vec3& a = nodes[t[0]];
    const Vec3& b = nodes[t[1]];
    const Vec3& c = nodes[t[2]];
    const Vec3& d = nodes[t[3]];
    const auto angles = dihedral_angles_degrees(a, b, c, d);
    const double smallest = *std::min_element(angles.begin(), angles.end());
    quality.min_dihedral_degrees = std::min(quality.min_dihedral_degrees, smallest);
    quality.max_dihedral_degrees =
        std::max(quality.max_dihedral_degrees, *std::max_element(angles.begin(), angles.end()));
    quality.max_aspect_ratio = std::max(quality.max_aspect_ratio, aspect_ratio(a, b, c, d));
    if (smallest < kPoorDihedralDegrees) ++quality.below_10_degrees;
    ++quality.tetrahedra;
  }
  return quality;
}

}  // namespace aggpack
