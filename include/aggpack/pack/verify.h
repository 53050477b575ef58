#pragma once
// Independent verification of a packing: containment, non-overlap and gaps, by the exact test.

#include <cstddef>
#include <string>

#include "aggpack/core/error_words.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

struct VerifyOptions {
  double gap = 0.0;  ///< required minimum distance between particles (m), >= 0
  /// Relative tolerance on distances, as a fraction of the largest particle size: distances
  /// within tolerance * size of the required gap still pass (GJK round-off), >= 0.
  double tolerance = 1e-9;
  bool is_brute_force = false;  ///< test all N(N-1)/2 pairs (slow; for tests) instead of a grid
};

struct VerifyResult {
  bool is_ok = true;
  std::size_t pairs_tested = 0;       ///< pairs passed to gjk_distance
  std::size_t overlapping_pairs = 0;  ///< pairs closer than gap (minus tolerance)
  std::size_t outside_particles = 0;  ///< particles not inside container minus wall_gap
  double min_distance = 0.0;          ///< smallest pair distance found (m); +inf if < 2 particles
  double min_wall_clearance = 0.0;    ///< smallest vertex-to-wall distance (m)
  std::string message{};              ///< first problem found, or empty
  Wording wording{};                  ///< the message in words (error_words.h), or none
};

/// Checks every particle against the container (vertex test, exact for convex bodies) and every
/// close pair (or all pairs) with gjk_distance. \throw InvalidInput for bad options.
VerifyResult verify(const Packing& packing, const VerifyOptions& options = {});

}  // namespace aggpack
