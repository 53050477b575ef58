#pragma once
// The cylinder container kind (its geometry: src/pack/container_cylinder.cpp).

#include <vector>

#include "aggpack/pack/container_kind.h"

namespace aggpack {

/// Cylinder with its axis along z through x = y = 0, z in [0, height]. Metres.
struct CylinderContainer {
  static constexpr const char* kName = "cylinder";
  static constexpr const char* kDescription = "cylinder about the z axis";
  static constexpr const char* kSummary = "cylinder radius {} m x height {} m";
  static constexpr bool kCentreRegionIsBounds = false;
  static constexpr const char* kPrismSummary = "prism of {} sides about the cylinder";

  double radius = 0.05;  ///< m
  double height = 0.1;   ///< m

  static const std::vector<KindParam<CylinderContainer>>& params();
  [[nodiscard]] Aabb bounds() const;
  [[nodiscard]] double volume() const;
  [[nodiscard]] double floor_area() const;
  [[nodiscard]] double smallest_extent() const;
  [[nodiscard]] double clearance(const Vec3& point) const;
  [[nodiscard]] bool contains(const ConvexPolyhedron& body, const Mat3& rotation,
                              const Vec3& position, double gap) const;
  [[nodiscard]] bool is_in_centre_region(double margin, const Vec3& centre) const;
  [[nodiscard]] double slab_volume(int axis, double lo, double hi) const;
  [[nodiscard]] std::vector<ContainerWall> walls(double thickness, double min_height) const;
  [[nodiscard]] std::vector<OutlineSegment> outline() const;
  [[nodiscard]] Vec3 ratio(const CylinderContainer& other) const;
  [[nodiscard]] CylinderContainer scaled(const Vec3& factor) const;
  [[nodiscard]] std::vector<Vec3> prism_floor(int sides) const;
  [[nodiscard]] bool is_on_prism_side(const Vec3& point, int sides, double tolerance) const;
  bool operator==(const CylinderContainer&) const = default;
};

}  // namespace aggpack
