#pragma once
// Small in-memory packings for the render tests: generated particles on a grid, and exact boxes.

#include <cmath>
#include <cstdint>

#include "aggpack/core/rng.h"
#include "aggpack/pack/packing.h"
#include "aggpack/shape/generator.h"

namespace aggpack::test {

/// nx * ny * nz generated particles (control radius `radius`, spacing 2.2 r) on a grid filling
/// a box container that fits them with a margin of 0.1 r. With `library_size` > 0 the particles
/// reuse that many shapes (instanced drawing), each randomly rotated; otherwise each particle has
/// its own shape. Particle i is at grid cell (i % nx, (i / nx) % ny, i / (nx ny)).
inline Packing grid_packing(int nx, int ny, int nz, double radius = 0.1,
                            std::uint32_t library_size = 0, std::uint64_t seed = 7,
                            double edge_ratio = 1.0) {
  Packing packing;
  const double spacing = 2.2 * radius;
  const double margin = 0.1 * radius;
  packing.container.get_if<BoxContainer>()->length = nx * spacing + 2 * margin;
  packing.container.get_if<BoxContainer>()->width = ny * spacing + 2 * margin;
  packing.container.get_if<BoxContainer>()->depth = nz * spacing + 2 * margin;
  const GeneratorOptions options{.alpha = 0.5,
                                 .radius_min = radius,
                                 .radius_max = radius,
                                 .edge_length = radius * edge_ratio,
                                 .seed = seed};
  const int count = nx * ny * nz;
  const int shape_count = library_size > 0 ? static_cast<int>(library_size) : count;
  for (int s = 0; s < shape_count; ++s) {
    packing.shapes.push_back(generate_particle(options, static_cast<std::uint64_t>(s)).body);
  }
  for (int i = 0; i < count; ++i) {
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(i % shape_count);
    particle.control_radius = radius;
    particle.pose.position =
        Vec3(margin + spacing * (0.5 + i % nx), margin + spacing * (0.5 + (i / nx) % ny),
             margin + spacing * (0.5 + i / (nx * ny)));
    if (library_size > 0) {
      Rng rng(seed + 1, static_cast<std::uint64_t>(i));
      particle.pose.rotation =
          Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized();
    }
    packing.particles.push_back(particle);
  }
  return packing;
}

/// The same packing with every particle given its own copy of its shape (pose unchanged), so it
/// is drawn by the single-shape path instead of the instanced one.
inline Packing with_unique_shapes(const Packing& packing) {
  Packing result = packing;
  result.shapes.clear();
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    result.shapes.push_back(packing.shapes[packing.particles[i].shape]);
    result.particles[i].shape = static_cast<std::uint32_t>(i);
  }
  return result;
}

}  // namespace aggpack::test
