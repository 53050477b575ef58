#include "aggpack/render/colors.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"

namespace aggpack {

namespace {

Rgb to_rgb(double r, double g, double b) {
  auto channel = [](double value) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0));
  };
  return {channel(r), channel(g), channel(b)};
}

// HSV with h in [0, 1).
Rgb hsv(double h, double s, double v) {
  const double sector = h * 6.0;
  const int i = static_cast<int>(std::floor(sector)) % 6;
  const double f = sector - std::floor(sector);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0:
      return to_rgb(v, t, p);
    case 1:
      return to_rgb(q, v, p);
    case 2:
      return to_rgb(p, v, t);
    case 3:
      return to_rgb(p, q, v);
    case 4:
      return to_rgb(t, p, v);
    default:
      return to_rgb(v, p, q);
  }
}

// Colours of a scale mode: per-particle values mapped over their own min..max.
ParticleColors scale_colors(const std::vector<double>& values, std::string quantity) {
  ParticleColors result;
  result.quantity = std::move(quantity);
  if (values.empty()) return result;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  result.minimum = *low;
  result.maximum = *high;
  const double span = result.maximum - result.minimum;
  result.colors.reserve(values.size());
  for (double value : values) {
    // A single value (all particles alike) sits mid-scale rather than at one end.
    result.colors.push_back(scale_color(span > 0.0 ? (value - result.minimum) / span : 0.5));
  }
  return result;
}

}  // namespace

ColorMode parse_color_mode(const std::string& text, const std::string& field) {
  if (text == "id" || text == "particle") return ColorMode::kParticle;
  if (text == "size") return ColorMode::kSize;
  if (text == "alpha") return ColorMode::kAlpha;
  throw InvalidInput(field, text, "id, size, alpha");
}

const char* color_mode_name(ColorMode mode) {
  switch (mode) {
    case ColorMode::kParticle:
      return "id";
    case ColorMode::kSize:
      return "size";
    case ColorMode::kAlpha:
      return "alpha";
  }
  return "id";
}

ShapeMeasures measure_shapes(const Packing& packing) {
  ShapeMeasures measures;
  measures.equivalent_diameter.reserve(packing.shapes.size());
  measures.measured_alpha.reserve(packing.shapes.size());
  for (const auto& shape : packing.shapes) {
    const MassProperties mass = mass_properties(shape);
    const double volume = std::max(mass.volume, 0.0);
    measures.equivalent_diameter.push_back(equivalent_diameter(volume));
    measures.measured_alpha.push_back(
        volume > 0.0 && mass.surface_area > 0.0 ? measured_alpha(volume, mass.surface_area) : 0.0);
  }
  return measures;
}

ParticleColors particle_colors(const Packing& packing, const ShapeMeasures& measures,
                               ColorMode mode) {
  const std::size_t count = packing.particles.size();
  if (mode == ColorMode::kParticle) {
    ParticleColors result;
    result.colors.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      // Consecutive indices land far apart on the hue circle (golden-ratio steps), and a
      // three-step saturation/value cycle separates neighbours whose hues come close again.
      const double hue = std::fmod(0.11 + static_cast<double>(i) * 0.6180339887498949, 1.0);
      const double saturation = 0.45 + 0.15 * static_cast<double>(i % 3);
      const double value = 0.95 - 0.12 * static_cast<double>((i / 3) % 2);
      result.colors.push_back(hsv(hue, saturation, value));
    }
    return result;
  }
  const auto& per_shape =
      mode == ColorMode::kSize ? measures.equivalent_diameter : measures.measured_alpha;
  std::vector<double> values;
  values.reserve(count);
  for (const auto& particle : packing.particles) {
    double value = particle.shape < per_shape.size() ? per_shape[particle.shape] : 0.0;
    // Library shapes are stored at unit size: a diameter scales with the particle, alpha not.
    if (mode == ColorMode::kSize) value *= particle.scale;
    values.push_back(value);
  }
  return scale_colors(
      values, mode == ColorMode::kSize ? "equivalent diameter (m)" : "measured alpha (Eq. 2)");
}

Rgb scale_color(double t) {
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.0;
  // Viridis sampled at 9 points, linearly interpolated: close enough to the published map for
  // reading a value off the legend, and free of a table dependency.
  static constexpr std::array<std::array<double, 3>, 9> kStops = {{
      {0.267, 0.005, 0.329},
      {0.279, 0.175, 0.483},
      {0.230, 0.322, 0.546},
      {0.173, 0.449, 0.558},
      {0.128, 0.567, 0.551},
      {0.153, 0.682, 0.504},
      {0.361, 0.786, 0.388},
      {0.668, 0.862, 0.196},
      {0.993, 0.906, 0.144},
  }};
  const double position = t * static_cast<double>(kStops.size() - 1);
  const std::size_t index = std::min(static_cast<std::size_t>(position), kStops.size() - 2);
  const double f = position - static_cast<double>(index);
  const auto& a = kStops[index];
  const auto& b = kStops[index + 1];
  return to_rgb(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]));
}

}  // namespace aggpack
