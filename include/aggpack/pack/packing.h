#pragma once
// Packing: the one central value (DESIGN.md). Container + particles (shape in a local frame with
// its centroid at the origin, plus a pose) + provenance. Everything downstream of the packer takes
// a `const Packing&` and nothing else.

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/pack/container_box.h"
#include "aggpack/pack/container_cylinder.h"

namespace aggpack {

/// Every container kind, one alternative each: the list a new kind is added to (see
/// container_kind.h for what a kind provides). The first alternative is the default.
using ContainerShape = std::variant<BoxContainer, CylinderContainer>;

/// The region particles are packed into: one kind's geometry plus the wall gap. Lengths in metres.
/// Its operations (bounds, volume, containment, walls, ...) are in container.h.
struct Container {
  ContainerShape shape{};  ///< the kind and its sizes
  double wall_gap = 0.0;   ///< minimum distance from any particle to any wall (m), >= 0

  /// Bounding box of the container.
  [[nodiscard]] Aabb bounds() const;
  /// Interior volume (m^3).
  [[nodiscard]] double volume() const;
  /// The kind's value when the container is of kind K, else nullptr.
  template <class K>
  [[nodiscard]] const K* get_if() const {
    return std::get_if<K>(&shape);
  }
  template <class K>
  [[nodiscard]] K* get_if() {
    return std::get_if<K>(&shape);
  }
  /// f(kind value), for whichever kind the container holds.
  template <class F>
  decltype(auto) visit(F&& f) const {
    return std::visit(std::forward<F>(f), shape);
  }
  bool operator==(const Container&) const = default;
};

/// One placed particle.
/// world = pose.rotation * (scale * local) + pose.position. `scale` is 1 unless the shape comes
/// from a shape library (RandomPackOptions::shape.library_size > 0), where one unit-size shape is
/// reused at many sizes. Always go through Packing::placed() (or apply the scale yourself).
struct Particle {
  std::uint32_t shape = 0;       ///< index into Packing::shapes
  Pose pose{};                   ///< world = rotation * (scale * local) + position
  double control_radius = 0.0;   ///< radius r the shape was grown with, after scaling (m)
  std::uint32_t size_class = 0;  ///< grading class index (0 when there is no grading)
  double scale = 1.0;            ///< uniform scale of the stored shape, > 0 (1 = as stored)
};

/// Where a packing came from: enough to reproduce it.
struct Provenance {
  std::string aggpack_version = AGGPACK_VERSION;
  std::string config_toml{};  ///< the full, resolved configuration
  std::uint64_t seed = 1;
  std::string packer{};  ///< "lattice", "random", "settled", ...
  /// particle.library's files (ShapeLibrary::provenance(): a header line, then one line per
  /// shape: file name, TAB, content hash); empty when the
  /// particles were grown. Shape k of the packing is the library's line k + 1 (only the shapes
  /// some particle uses are stored).
  std::string shape_library{};
};

struct Packing {
  Container container{};
  std::vector<ConvexPolyhedron> shapes{};  ///< local frame, centroid at the origin
  std::vector<Particle> particles{};
  Provenance provenance{};

  /// Particle i's polyhedron in world coordinates (scale, then rotation, then translation).
  [[nodiscard]] ConvexPolyhedron placed(std::size_t i) const {
    const Particle& particle = particles[i];
    if (particle.scale == 1.0) return shapes[particle.shape].transformed(particle.pose);
    return shapes[particle.shape].scaled(particle.scale).transformed(particle.pose);
  }

  /// Particle i's polyhedron in its local frame at its true size (scale applied, no pose).
  [[nodiscard]] ConvexPolyhedron local_body(std::size_t i) const {
    const Particle& particle = particles[i];
    if (particle.scale == 1.0) return shapes[particle.shape];
    return shapes[particle.shape].scaled(particle.scale);
  }
};

}  // namespace aggpack
