#pragma once
// Packings that several test programs build.

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

}  // namespace aggpack::test
