#pragma once
// The box container kind (its geometry: src/pack/container_box.cpp).

#include <array>
#include <vector>

#include "aggpack/pack/container_kind.h"

namespace aggpack {

/// Box [0, length] x [0, width] x [0, depth] (x = length, y = width, z = depth, z up). Metres.
struct BoxContainer {
  static constexpr const char* kName = "box";
  static constexpr const char* kDescription = "box [0,length]x[0,width]x[0,depth]";
  static constexpr const char* kSummary = "box {} x {} x {} m";
  static constexpr bool kCentreRegionIsBounds = true;
  static constexpr const char* kPrismSummary = "box";

  double length = 3.0;  ///< x extent (m)
  double width = 1.0;   ///< y extent (m)
  double depth = 2.8;   ///< z extent (m)
  /// Which axes (x, y, z) are periodic: a particle may cross such a face and meets the particles
  /// near the opposite face through its periodic image; no wall stands there. None by default.
  std::array<bool, 3> periodic{};

  static const std::vector<KindParam<BoxContainer>>& params();
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
  [[nodiscard]] Vec3 ratio(const BoxContainer& other) const;
  [[nodiscard]] BoxContainer scaled(const Vec3& factor) const;
  [[nodiscard]] std::vector<Vec3> prism_floor(int sides) const;
  [[nodiscard]] bool is_on_prism_side(const Vec3& point, int sides, double tolerance) const;
  bool operator==(const BoxContainer&) const = default;
};

}  // namespace aggpack
