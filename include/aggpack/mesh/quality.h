#pragma once
// Shape quality of tetrahedra: the smallest dihedral angle and the aspect ratio
// circumradius / (3 x inradius), which is 1 for the regular tetrahedron and grows without bound
// as a tetrahedron flattens (a sliver, a needle, a cap). Both are scale-free, so a shape's mesh is
// measured once for all particles that share it.

#include <array>
#include <cstdint>
#include <span>

#include "aggpack/mesh/tetrahedra.h"

namespace aggpack {

/// Dihedral angle (degrees) below which a tetrahedron counts as poorly shaped.
inline constexpr double kPoorDihedralDegrees = 10.0;

/// Quality of a set of tetrahedra. An empty set has tetrahedra == 0 and the neutral values below.
struct TetQuality {
  std::uint64_t tetrahedra = 0;
  double min_dihedral_degrees = 180.0;  ///< smallest interior dihedral angle over the set
  double max_dihedral_degrees = 0.0;    ///< largest interior dihedral angle over the set
  double max_aspect_ratio = 1.0;        ///< largest circumradius / (3 inradius); 1 = regular
  std::uint64_t below_10_degrees = 0;   ///< tetrahedra whose smallest dihedral < 10 degrees

  /// Adds `times` copies of `other` (e.g. a shape's mesh once per particle of that shape).
  void add(const TetQuality& other, std::uint64_t times = 1);
};

/// The six interior dihedral angles (degrees) of tetrahedron (a, b, c, d), at the edges in
/// kTetraEdges order. A degenerate tetrahedron (zero-area face) gives 0 at the affected edges.
std::array<double, 6> dihedral_angles_degrees(const Vec3& a, const Vec3& b, const Vec3& c,
                                              const Vec3& d);

/// circumradius / (3 inradius) of tetrahedron (a, b, c, d): 1 for the regular tetrahedron,
/// larger otherwise; +infinity when it has no positive volume (flat or inverted).
double aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Quality of `tetrahedra` over `nodes` (node numbers index `nodes`).
TetQuality measure_quality(std::span<const Vec3> nodes, std::span<const Tetrahedron> tetrahedra);

}  // namespace aggpack
