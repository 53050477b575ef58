#pragma once
// A uniformly random rotation for tests: a quaternion of four normal deviates, normalised (the
// uniform distribution on the unit 3-sphere, so on SO(3)).

#include "aggpack/core/rng.h"
#include "aggpack/geom/vec.h"

namespace aggpack::test {

inline Quat random_rotation(Rng& rng) {
  Quat q(rng.normal(), rng.normal(), rng.normal(), rng.normal());
  return q.normalized();
}

}  // namespace aggpack::test
