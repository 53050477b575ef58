#pragma once
// A periodic packing cut to its box: every particle and each of its periodic images clipped to
// the box, so that copies of the result tile space (`aggpack export --cut-to-box`).

#include "aggpack/pack/packing.h"

namespace aggpack {

/// The pieces of a periodic packing inside its box: for every particle (in order) its part in
/// the box, then the parts of its images (shifted by one extent along the periodic axes, in the
/// order -1, 0, +1 per axis x, y, z) that reach into it, each clipped to the box faces it crosses
/// (exact plane crossings; the hull of the rest, geom/clip.h). A particle wholly inside is one
/// piece, unchanged. Each piece is a shape of its own in world coordinates (its particle's pose
/// is the identity, scale 1, control radius and size class kept). The pieces' volumes add up to
/// the particles' (the images tile the box), and no vertex lies outside the box.
/// \throw InvalidInput naming `cut-to-box` when the container has no periodic axis.
Packing cut_to_box(const Packing& packing);

}  // namespace aggpack
