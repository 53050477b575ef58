#pragma once
// Container operations: each dispatches to the kind the container holds (container_box.cpp,
// container_cylinder.cpp, ...). The Container value itself lives in packing.h (it is part of
// every Packing).

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/pack/packing.h"

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace aggpack {

/// One length parameter of a container kind (m, allowed (0, 1e6]): the config key
/// `container.<name>`, the native-file attribute `<name>` and the GUI field all come from it.
/// get() of a container of another kind gives this kind's default; set() on a container of
/// another kind does nothing (the value has no place there).
struct ContainerParam {
  const char* name;         ///< "length"
  const char* description;  ///< one line for docs and tooltips
  std::function<double(const Container&)> get;
  std::function<void(Container&, double)> set;
};

/// One container kind: the word used in configs and native files, its parameters in order, and
/// the container of that kind with every parameter at its default. Every front end (config keys,
/// native file fields, GUI) iterates over container_kinds() instead of naming kinds itself.
struct ContainerKindInfo {
  const char* name;         ///< "box"
  const char* description;  ///< one line
  const char* summary;      ///< fmt pattern of the CLI summary, the params' values in order
  std::vector<ContainerParam> params;
  Container defaults;
  /// Whether `container` is of this kind.
  std::function<bool(const Container&)> holds;
};

/// Every container kind, in documentation order (the order of ContainerShape).
const std::vector<ContainerKindInfo>& container_kinds();

/// The entry of container_kinds() for the kind `container` holds.
const ContainerKindInfo& container_kind_info(const Container& container);

/// The entry of container_kinds() named `name` ("box"), or nullptr.
const ContainerKindInfo* find_container_kind(std::string_view name);

/// The kind names joined for messages: "box or cylinder".
std::string container_kind_names();

/// Throws InvalidInput naming the field ("container.length", "container.radius",
/// "container.wall_gap", ...) unless the extents of the chosen kind are finite and > 0 and the
/// wall gap is >= 0 and leaves a non-empty interior (2 * wall_gap < every extent).
void validate(const Container& container);

/// The periodic axes (x, y, z) of a container: a box's `periodic`; none for other kinds.
std::array<bool, 3> periodic_axes(const Container& container);

/// Whether any axis of the container is periodic.
bool is_periodic(const Container& container);

/// The words of `container.periodic`, in documentation order: "none", "x", "y", "z", "xy", "xz",
/// "yz", "xyz".
const std::vector<std::string>& periodic_words();

/// "none", or the letters of the periodic axes in x, y, z order ("xz").
std::string periodic_word(const std::array<bool, 3>& axes);

/// Sets `axes` from one of periodic_words(); false (axes unchanged) when `word` is not one.
bool parse_periodic_word(std::string_view word, std::array<bool, 3>& axes);

/// The translations (m) of a point's periodic images that may come within `reach` (m) of the
/// container's bounds: the zero shift first, then every combination of -extent, 0, +extent on the
/// periodic axes where the shifted point is within `reach` of the bounds. At most 27.
struct ImageShifts {
  std::array<Vec3, 27> shifts{};
  int count = 0;
};
ImageShifts image_shifts(const Container& container, const Vec3& point, double reach);

/// Throws InvalidInput naming `container.periodic` unless every periodic extent is larger than
/// 2 * largest_radius + gap (m): then a particle cannot touch its own image and the images one
/// period away are the only ones a neighbour can touch.
void require_periodic_room(const Container& container, double largest_radius, double gap);

/// Throws InvalidInput naming `container.periodic` when the container is periodic: `what` ("the
/// lattice packer") does not support periodic containers yet.
void refuse_periodic(const Container& container, const std::string& what);

/// Signed clearance of a point from the container walls (m): the distance to the nearest wall when
/// inside (>= 0), minus the distance to the container when outside (< 0). Ignores wall_gap. A
/// periodic axis has no walls (+infinity when every axis is periodic).
double wall_clearance(const Container& container, const Vec3& point);

/// Smallest wall clearance over the vertices of `body` placed by `pose` (m). Because the container
/// and the body are both convex, this is exactly the body's distance to the walls when >= 0.
double wall_clearance(const Container& container, const ConvexPolyhedron& body, const Pose& pose);

/// Exact containment: every vertex of the placed body is inside the container shrunk by
/// container.wall_gap (a convex region, so the vertex test is exact for a convex body).
bool contains(const Container& container, const ConvexPolyhedron& body, const Pose& pose);

/// Region where a centre may lie so that a sphere of radius `radius` (m) around it keeps
/// `wall_gap` from the walls: the box shrunk by radius + wall_gap (not along a periodic axis,
/// where it is the whole extent), or the cylinder shrunk the same way. Returned as an AABB (for a
/// cylinder, the AABB of the shrunk cylinder); empty when nothing fits. Used by the packers to draw
/// candidate positions.
Aabb centre_region(const Container& container, double radius);

/// Whether `centre` lies in the exact (box or cylinder) centre region for `radius` (m).
bool is_in_centre_region(const Container& container, double radius, const Vec3& centre);

/// Volume of the container between planes axis = lo and axis = hi (m^3); axis 0 = x, 1 = y, 2 = z.
/// Exact for every kind (circular segments for the cylinder's x and y).
double container_slab_volume(const Container& container, int axis, double lo, double hi);

/// Whether centre_region() is exactly the region of is_in_centre_region() (a box), so that a
/// point drawn in it needs no rejection test.
bool centre_region_is_bounds(const Container& container);

/// Area of the container's floor (z = 0), m^2.
double container_floor_area(const Container& container);

/// The static walls of the container for the physics: `thickness` thick (m), at least
/// `min_height` high (m). Every wall lies outside the interior and together they close it.
std::vector<ContainerWall> container_walls(const Container& container, double thickness,
                                           double min_height);

/// Line segments that draw the container.
std::vector<OutlineSegment> container_outline(const Container& container);

/// The floor polygon (z = 0, counter-clockwise seen from above) of the straight prism a mesomodel
/// of the container fills, up to its bounds' top: a box's rectangle; for a cylinder, `sides`
/// sides circumscribing its circle, side k tangent at angle 2 pi k / sides.
std::vector<Vec3> container_prism_floor(const Container& container, int sides);

/// The bounding box of that prism.
Aabb prism_bounds(const Container& container, int sides);

/// Whether `point` lies on the side walls of that prism, within `tolerance` (m).
bool is_on_prism_side(const Container& container, const Vec3& point, int sides, double tolerance);

/// The CLI's name of that prism: "box", "prism of 96 sides about the cylinder".
std::string prism_summary(const Container& container, int sides);

/// Per-axis size ratio other / from (x, y, z). Throws InvalidInput if the kinds differ.
Vec3 container_ratio(const Container& from, const Container& other);

/// The container scaled per axis by `factor` (the kind decides how: a cylinder takes x for its
/// radius and z for its height); the wall gap is kept.
Container container_scaled(const Container& container, const Vec3& factor);

}  // namespace aggpack
