#pragma once
// Containers (box, cylinder) and the exact containment test for placed convex bodies.
// The Container value itself lives in packing.h (it is part of every Packing).

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/pack/packing.h"

#include <vector>

namespace aggpack {

/// One length parameter of a container kind (m, allowed (0, 1e6]): the config key
/// `container.<name>`, the native-file attribute `<name>` and the GUI field all come from it.
struct ContainerParam {
  const char* name;         ///< "length"
  const char* description;  ///< one line for docs and tooltips
  double (*get)(const Container&);
  void (*set)(Container&, double);
};

/// One container kind: the word used in configs and native files, its parameters in order, and
/// the container of that kind with every parameter at its default. Every front end (config keys,
/// native file fields, GUI) iterates over container_kinds() instead of naming kinds itself.
struct ContainerKindInfo {
  ContainerKind kind;
  const char* name;         ///< "box"
  const char* description;  ///< one line
  std::vector<ContainerParam> params;
  Container defaults;
};

/// Every container kind, in documentation order.
const std::vector<ContainerKindInfo>& container_kinds();

/// The entry of container_kinds() for `kind`.
const ContainerKindInfo& container_kind_info(ContainerKind kind);

/// Throws InvalidInput naming the field ("container.length", "container.radius",
/// "container.wall_gap", ...) unless the extents of the chosen kind are finite and > 0 and the
/// wall gap is >= 0 and leaves a non-empty interior (2 * wall_gap < every extent).
void validate(const Container& container);

/// Signed clearance of a point from the container walls (m): the distance to the nearest wall when
/// inside (>= 0), minus the distance to the container when outside (< 0). Ignores wall_gap.
double wall_clearance(const Container& container, const Vec3& point);

/// Smallest wall clearance over the vertices of `body` placed by `pose` (m). Because the container
/// and the body are both convex, this is exactly the body's distance to the walls when >= 0.
double wall_clearance(const Container& container, const ConvexPolyhedron& body, const Pose& pose);

/// Exact containment: every vertex of the placed body is inside the container shrunk by
/// container.wall_gap (a convex region, so the vertex test is exact for a convex body).
bool contains(const Container& container, const ConvexPolyhedron& body, const Pose& pose);

/// Region where a centre may lie so that a sphere of radius `radius` (m) around it keeps
/// `wall_gap` from the walls: the box shrunk by radius + wall_gap, or the cylinder shrunk the same
/// way. Returned as an AABB (for a cylinder, the AABB of the shrunk cylinder); empty when nothing
/// fits. Used by the packers to draw candidate positions.
Aabb centre_region(const Container& container, double radius);

/// Whether `centre` lies in the exact (box or cylinder) centre region for `radius` (m).
bool is_in_centre_region(const Container& container, double radius, const Vec3& centre);

/// Volume of the container between planes axis = lo and axis = hi (m^3); axis 0 = x, 1 = y, 2 = z.
/// Exact for both kinds (circular segments for the cylinder's x and y).
double container_slab_volume(const Container& container, int axis, double lo, double hi);

}  // namespace aggpack
