#pragma once
// Particle colours for the viewer and headless rendering. Pure functions of the Packing (no
// OpenGL), so the same packing and mode always give the same colours.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/core/rgb.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

/// How particles are coloured.
enum class ColorMode {
  kParticle,  ///< a distinct hue per particle (golden-ratio hue walk over the particle index)
  kSize,      ///< volume-equivalent diameter of the particle on a colour scale (min..max)
  kAlpha      ///< measured shape parameter alpha (Eq. 2) on a colour scale (min..max)
};

/// "id" | "particle" -> kParticle, "size" -> kSize, "alpha" -> kAlpha.
/// \throw InvalidInput naming `field` otherwise.
ColorMode parse_color_mode(const std::string& text, const std::string& field = "--color");
/// The canonical name of `mode` ("id", "size", "alpha").
const char* color_mode_name(ColorMode mode);

/// Colours of every particle plus, for the scale modes, the range the scale spans.
struct ParticleColors {
  std::vector<Rgb> colors;  ///< one per particle, in particle order
  double minimum = 0.0;     ///< value at the low end of the scale (m for kSize, - for kAlpha)
  double maximum = 0.0;     ///< value at the high end of the scale
  std::string quantity;     ///< what the scale shows, with unit ("" for kParticle)
};

/// Per-shape measures the colour modes use, computed once per distinct shape.
struct ShapeMeasures {
  std::vector<double> equivalent_diameter;  ///< diameter of the sphere of equal volume (m)
  std::vector<double> measured_alpha;       ///< Eq. 2: V / V_b, V_b the equal-surface sphere
};

/// Measures every shape of `packing` (exact volume and surface by the divergence theorem).
ShapeMeasures measure_shapes(const Packing& packing);

/// Colours of the particles of `packing` in `mode`. `measures` must come from measure_shapes of
/// the same packing (it is passed in so a viewer switching modes measures only once).
ParticleColors particle_colors(const Packing& packing, const ShapeMeasures& measures,
                               ColorMode mode);

/// Perceptually ordered colour scale (viridis-like, dark blue -> green -> yellow), t in [0, 1]
/// (clamped).
Rgb scale_color(double t);

}  // namespace aggpack
