#pragma once
// Periodic boxes and the independent brute-force overlap check over all images that several test
// programs use (tests/pack/periodic_test.cpp, periodic_dense_test.cpp), and a small periodic RVE
// (tests/io/homogenize_test.cpp, mesomodel_periodic_ccx_test.cpp).

#include <algorithm>
#include <array>
#include <vector>

#include "aggpack/geom/mass_properties.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/packing.h"
#include "aggpack/pack/random_packer.h"

namespace aggpack::test {

/// A box [0, length] x [0, width] x [0, depth] (m), periodic along `axes`.
inline Container periodic_box(double length, double width, double depth, std::array<bool, 3> axes) {
  return {.shape =
              BoxContainer{.length = length, .width = width, .depth = depth, .periodic = axes}};
}

/// A small RVE for the periodic mesomodel's CalculiX tests: a 40 x 36 x 32 mm box periodic in x,
/// y and z, particles of radius 6-10 mm (alpha 0.5, L = r) at `fraction`, 0.8 mm apart, seed 4.
inline Packing small_periodic_packing(double fraction) {
  const RandomPackOptions options{
      .container = periodic_box(0.04, 0.036, 0.032, {true, true, true}),
      .grading = {.kind = GradingKind::kUniform, .radius_min = 0.006, .radius_max = 0.01},
      .shape = {.alpha = 0.5, .edge_length_ratio = 1.0},
      .target = PackTarget::kVolumeFraction,
      .volume_fraction = fraction,
      .gap = 0.0008,
      .seed = 4};
  return pack_random(options).packing;
}

/// Independent of the packers and verify(): every pair and every particle with itself, through
/// every image one period away on the periodic axes (27 shifts), by the exact GJK distance.
/// Returns the number of pairs (image pairs included) closer than `gap`; `closest` the smallest
/// such distance.
inline std::size_t periodic_brute_force_overlaps(const Packing& packing, double gap,
                                                 double& closest) {
  const std::array<bool, 3> axes = periodic_axes(packing.container);
  const Vec3 extent = packing.container.bounds().extent();
  const std::size_t n = packing.particles.size();
  std::vector<ConvexPolyhedron> bodies;
  std::vector<double> radius;
  for (std::size_t i = 0; i < n; ++i) {
    bodies.push_back(packing.local_body(i));
    radius.push_back(bounding_radius(bodies.back()));
  }
  std::size_t overlaps = 0;
  closest = 1e300;
  for (int a = -1; a <= 1; ++a) {
    for (int b = -1; b <= 1; ++b) {
      for (int c = -1; c <= 1; ++c) {
        if ((a != 0 && !axes[0]) || (b != 0 && !axes[1]) || (c != 0 && !axes[2])) continue;
        const Vec3 shift(a * extent.x(), b * extent.y(), c * extent.z());
        const bool is_zero = a == 0 && b == 0 && c == 0;
        for (std::size_t i = 0; i < n; ++i) {
          for (std::size_t j = is_zero ? i + 1 : i; j < n; ++j) {
            Pose moved = packing.particles[j].pose;
            moved.position += shift;
            const double centres = (packing.particles[i].pose.position - moved.position).norm();
            if (centres > radius[i] + radius[j] + gap) continue;
            const DistanceResult result =
                gjk_distance(bodies[i], packing.particles[i].pose, bodies[j], moved);
            closest = std::min(closest, result.distance);
            if (result.is_intersecting || result.distance < gap) ++overlaps;
          }
        }
      }
    }
  }
  return overlaps;
}

}  // namespace aggpack::test
