#pragma once
// What every container kind provides (the ContainerKindType concept) and the small value types
// its operations return. The kinds themselves: container_box.h, container_cylinder.h; the list of
// kinds: ContainerShape in packing.h.

#include <array>
#include <concepts>
#include <string_view>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"

namespace aggpack {

/// One length parameter of kind K (m): the config key `container.<name>`, the native-file
/// attribute `/container/<name>` and the GUI field all come from it.
template <class K>
struct KindParam {
  const char* name;         ///< "length"
  const char* description;  ///< one line for docs and tooltips
  double K::*member;        ///< where the value lives in K
};

/// A static wall box for the physics: centre, half extents, then a rotation by `angle` (rad)
/// about the z axis through the centre (0 = axis-aligned). Metres.
struct ContainerWall {
  Vec3 centre = Vec3::Zero();
  Vec3 half_extent = Vec3::Zero();
  double angle = 0.0;

  /// The axis-aligned wall filling `box`.
  static ContainerWall from_box(const Aabb& box) {
    return {0.5 * (box.upper + box.lower), 0.5 * (box.upper - box.lower), 0.0};
  }
};

/// One straight segment of a container's outline (for drawing), metres.
using OutlineSegment = std::array<Vec3, 2>;

/// Everything a container kind must provide. A kind missing one of these fails to compile
/// (packing.h checks every alternative of ContainerShape against this concept).
template <class K>
concept ContainerKindType = std::equality_comparable<K> && std::default_initializable<K> &&
    requires(const K& k, const Vec3& point, const ConvexPolyhedron& body, const Mat3& rotation,
             double value, int axis) {
  // The word in configs and native files, a one-line description, and the CLI summary: an fmt
  // pattern taking the params' values in order.
  { K::kName } -> std::convertible_to<std::string_view>;
  { K::kDescription } -> std::convertible_to<std::string_view>;
  { K::kSummary } -> std::convertible_to<std::string_view>;
  // True when the exact centre region is its bounding box (a draw in it needs no rejection).
  { K::kCentreRegionIsBounds } -> std::convertible_to<bool>;
  // The parameters, in the order of the config keys and native-file attributes.
  { K::params() } -> std::same_as<const std::vector<KindParam<K>>&>;
  // Bounding box, interior volume, floor (z = 0) area, smallest extent (for the wall gap).
  { k.bounds() } -> std::same_as<Aabb>;
  { k.volume() } -> std::same_as<double>;
  { k.floor_area() } -> std::same_as<double>;
  { k.smallest_extent() } -> std::same_as<double>;
  // Signed clearance of a point from the walls (>= 0 inside).
  { k.clearance(point) } -> std::same_as<double>;
  // Whether every vertex of `body` (rotated, then moved by `point`) keeps `value` from walls.
  { k.contains(body, rotation, point, value) } -> std::same_as<bool>;
  // Whether a centre at `point` keeps `value` (radius + wall gap) from every wall.
  { k.is_in_centre_region(value, point) } -> std::same_as<bool>;
  // Volume between planes axis = lo and axis = hi, both inside bounds().
  { k.slab_volume(axis, value, value) } -> std::same_as<double>;
  // Static walls for the physics, `value` thick, at least `value` high.
  { k.walls(value, value) } -> std::same_as<std::vector<ContainerWall>>;
  // Line segments to draw.
  { k.outline() } -> std::same_as<std::vector<OutlineSegment>>;
  // Per-axis size ratio other / this (x, y, z), and this scaled per axis (the dense packer's
  // compression).
  { k.ratio(k) } -> std::same_as<Vec3>;
  { k.scaled(point) } -> std::same_as<K>;
  // The straight prism a mesomodel fills (z from 0 to bounds().upper.z()): its floor polygon at
  // z = 0, counter-clockwise seen from above, a curved wall replaced by `axis` sides (the
  // mesomodel's cylinder_segments) that circumscribe it; whether a point lies on that prism's
  // side walls within `value`; and the CLI's name for the prism, an fmt pattern taking the sides.
  { k.prism_floor(axis) } -> std::same_as<std::vector<Vec3>>;
  { k.is_on_prism_side(point, axis, value) } -> std::same_as<bool>;
  { K::kPrismSummary } -> std::convertible_to<std::string_view>;
};

}  // namespace aggpack
