// cut_to_box (include/aggpack/pack/cut_to_box.h): a periodic packing's pieces inside its box.

#include "aggpack/pack/cut_to_box.h"

#include <array>
#include <optional>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/geom/clip.h"
#include "aggpack/pack/container.h"

namespace aggpack {

Packing cut_to_box(const Packing& packing) {
  if (!is_periodic(packing.container)) {
    throw InvalidInput("cut-to-box", "true for a packing without periodic faces",
                       "only for a packing of a periodic box (container.periodic)");
  }
  const std::array<bool, 3> axes = periodic_axes(packing.container);
  const Aabb box = packing.container.bounds();
  const Vec3 extent = box.extent();
  Packing pieces;
  pieces.container = packing.container;
  pieces.provenance = packing.provenance;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Particle& particle = packing.particles[i];
    const ConvexPolyhedron body = packing.placed(i);
    const Aabb bounds = body.bounds();
    // Per axis the shifts (in extents) that bring the body into the box: 0, and -1 / +1 along a
    // periodic axis where it sticks out of the opposite face.
    std::array<std::array<int, 3>, 3> shifts{};
    std::array<int, 3> counts{};
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto a = static_cast<int>(axis);
      for (int shift = -1; shift <= 1; ++shift) {
        if (shift != 0 && !axes[axis]) continue;
        const double offset = shift * extent[a];
        if (bounds.lower[a] + offset < box.upper[a] && bounds.upper[a] + offset > box.lower[a]) {
          shifts[axis][static_cast<std::size_t>(counts[axis]++)] = shift;
        }
      }
    }
    for (int x = 0; x < counts[0]; ++x) {
      for (int y = 0; y < counts[1]; ++y) {
        for (int z = 0; z < counts[2]; ++z) {
          const Vec3 offset(shifts[0][static_cast<std::size_t>(x)] * extent.x(),
                            shifts[1][static_cast<std::size_t>(y)] * extent.y(),
                            shifts[2][static_cast<std::size_t>(z)] * extent.z());
          std::optional<ConvexPolyhedron> piece =
              offset == Vec3::Zero() ? body : body.translated(offset);
          for (int a = 0; a < 3 && piece; ++a) {
            if (!axes[static_cast<std::size_t>(a)]) continue;  // walls: already inside
            const Aabb now = piece->bounds();
            if (now.lower[a] < box.lower[a]) piece = clip_at_plane(*piece, a, box.lower[a], false);
            if (piece && now.upper[a] > box.upper[a]) {
              piece = clip_at_plane(*piece, a, box.upper[a], true);
            }
          }
          if (!piece) continue;
          pieces.shapes.push_back(std::move(*piece));
          pieces.particles.push_back({.shape = static_cast<std::uint32_t>(pieces.shapes.size() - 1),
                                      .pose = {},
                                      .control_radius = particle.control_radius,
                                      .size_class = particle.size_class,
                                      .scale = 1.0});
        }
      }
    }
  }
  return pieces;
}

}  // namespace aggpack
