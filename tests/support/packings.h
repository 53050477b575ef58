#pragma once
// Packings that several test programs build.

#include <vector>

#include "aggpack/core/parallel.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/packing.h"

namespace aggpack::test {

/// An empty packing in a box [0, length] x [0, width] x [0, depth] (m).
inline Packing box_container(double length, double width, double depth) {
  Packing packing;
  packing.container.get_if<BoxContainer>()->length = length;
  packing.container.get_if<BoxContainer>()->width = width;
  packing.container.get_if<BoxContainer>()->depth = depth;
  return packing;
}

/// A box of side `side` (m) holding shape i at position at[i] (unturned, scale 1).
inline Packing box_with(double side, std::vector<ConvexPolyhedron> shapes, std::vector<Vec3> at) {
  Packing packing = box_container(side, side, side);
  packing.shapes = std::move(shapes);
  for (std::size_t i = 0; i < at.size(); ++i) {
    Particle particle;
    particle.shape = static_cast<std::uint32_t>(i);
    particle.pose.position = at[i];
    packing.particles.push_back(particle);
  }
  return packing;
}

/// What `run()` returns with the worker threads limited to `threads` (a determinism test runs the
/// same work at 1 and 2 threads and compares).
template <class Run>
auto with_threads(int threads, Run run) {
  const ThreadLimit limit(threads);
  return run();
}

}  // namespace aggpack::test
