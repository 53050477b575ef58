#include "aggpack/pack/statistics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"

namespace aggpack {

namespace {

constexpr std::size_t kBlock = 4096;  // fixed blocks: sums do not depend on the thread count

// Signed volume of the tetrahedron (origin, a, b, c) times 6.
double triple(const Vec3& origin, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (a - origin).dot((b - origin).cross(c - origin));
}

}  // namespace

double volume_below(const ConvexPolyhedron& body, int axis, double level) {
  if (axis < 0 || axis > 2) throw InvalidInput("axis", std::to_string(axis), "0, 1 or 2");
  const auto& vertices = body.vertices();
  // Divergence theorem with the reference point on the cutting plane: the cap face (in the plane)
  // then contributes nothing, so summing the clipped surface triangles gives the exact volume.
  Vec3 origin = vertices.front();
  origin[axis] = level;
  double six_volume = 0.0;
  std::array<Vec3, 4> polygon;
  for (const auto& triangle : body.triangles()) {
    // Clip the triangle to coordinate <= level (Sutherland-Hodgman against one plane).
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = vertices[triangle[static_cast<std::size_t>(k)]];
      const Vec3& q = vertices[triangle[static_cast<std::size_t>((k + 1) % 3)]];
      const bool p_in = p[axis] <= level;
      const bool q_in = q[axis] <= level;
      if (p_in) polygon[static_cast<std::size_t>(count++)] = p;
      if (p_in != q_in) {
        const double t = (level - p[axis]) / (q[axis] - p[axis]);
        Vec3 crossing = p + t * (q - p);
        crossing[axis] = level;
        polygon[static_cast<std::size_t>(count++)] = crossing;
      }
    }
    for (int k = 1; k + 1 < count; ++k) {
      six_volume += triple(origin, polygon[0], polygon[static_cast<std::size_t>(k)],
                           polygon[static_cast<std::size_t>(k + 1)]);
    }
  }
  return six_volume / 6.0;
}

PackingStatistics compute_statistics(const Packing& packing, const StatisticsOptions& options) {
  if (options.bins < 1 || options.bins > 10000) {
    throw InvalidInput("statistics.bins", std::to_string(options.bins), "[1, 10000]");
  }
  validate(packing.container);
  if (options.target) validate(*options.target);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Particle& particle = packing.particles[i];
    if (particle.shape >= packing.shapes.size()) {
      throw InvalidInput("particles[" + std::to_string(i) + "].shape",
                         std::to_string(particle.shape),
                         "< shape count " + std::to_string(packing.shapes.size()));
    }
    if (!(particle.scale > 0.0) || !std::isfinite(particle.scale)) {
      throw InvalidInput("particles[" + std::to_string(i) + "].scale", format_value(particle.scale),
                         "finite and > 0");
    }
  }

  PackingStatistics stats;
  const std::size_t n = packing.particles.size();
  stats.particle_count = n;
  stats.shape_count = packing.shapes.size();
  stats.container_volume = packing.container.volume();

  std::vector<double> shape_volume(packing.shapes.size());
  parallel_for_index(0, packing.shapes.size(), [&](std::size_t s) {
    shape_volume[s] = mass_properties(packing.shapes[s]).volume;
  });

  // Per block: solid volume and the per-axis bin volumes; summed in block order afterwards.
  const Aabb bounds = packing.container.bounds();
  const std::array<bool, 3> periodic = periodic_axes(packing.container);
  const auto bins = static_cast<std::size_t>(options.bins);
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<double> block_volume(blocks, 0.0);
  std::vector<std::vector<double>> block_bins(blocks, std::vector<double>(3 * bins, 0.0));
  parallel_for_index(0, blocks, [&](std::size_t b) {
    auto& local = block_bins[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      const Particle& particle = packing.particles[i];
      const double s = particle.scale;
      const double volume = shape_volume[particle.shape] * s * s * s;
      block_volume[b] += volume;
      const ConvexPolyhedron body = packing.placed(i);
      const Aabb box = body.bounds();
      for (int axis = 0; axis < 3; ++axis) {
        const double width = bounds.extent()[axis] / static_cast<double>(bins);
        const double lower = bounds.lower[axis];
        // Along a periodic axis a particle's part beyond a face counts in the bins of the
        // opposite side (bin numbers taken modulo bins); elsewhere it stays in the edge bin.
        const bool is_wrapped = periodic[static_cast<std::size_t>(axis)];
        const auto count = static_cast<std::int64_t>(bins);
        auto bin_of = [&](double x) {
          const double bin = std::floor((x - lower) / width);
          if (is_wrapped) return static_cast<std::int64_t>(bin);
          return static_cast<std::int64_t>(std::clamp(bin, 0.0, static_cast<double>(bins - 1)));
        };
        auto slot = [&](std::int64_t k) {
          return static_cast<std::size_t>(axis) * bins +
                 static_cast<std::size_t>(((k % count) + count) % count);
        };
        const std::int64_t first = bin_of(box.lower[axis]);
        const std::int64_t last = bin_of(box.upper[axis]);
        if (first == last) {
          local[slot(first)] += volume;
          continue;
        }
        double below = 0.0;
        for (std::int64_t k = first; k < last; ++k) {
          const double cut = volume_below(body, axis, lower + width * static_cast<double>(k + 1));
          local[slot(k)] += cut - below;
          below = cut;
        }
        local[slot(last)] += volume - below;
      }
    }
  });
  for (std::size_t b = 0; b < blocks; ++b) stats.solid_volume += block_volume[b];
  stats.solid_fraction = stats.solid_volume / stats.container_volume;
  for (int axis = 0; axis < 3; ++axis) {
    AxisProfile& profile = stats.profiles[static_cast<std::size_t>(axis)];
    profile.axis = axis;
    profile.lower = bounds.lower[axis];
    profile.bin_width = bounds.extent()[axis] / static_cast<double>(bins);
    profile.solid_fraction.assign(bins, 0.0);
    for (std::size_t k = 0; k < bins; ++k) {
      double solid = 0.0;
      for (std::size_t b = 0; b < blocks; ++b)
        solid += block_bins[b][static_cast<std::size_t>(axis) * bins + k];
      const double lo = profile.lower + profile.bin_width * static_cast<double>(k);
      const double slab =
          container_slab_volume(packing.container, axis, lo, lo + profile.bin_width);
      profile.solid_fraction[k] = slab > 0.0 ? solid / slab : 0.0;
    }
  }

  if (options.target) {
    stats.grading = achieved_grading(packing, *options.target, options.sieve_sizes);
  }

  if (options.has_descriptors && n > 0) {
    // Descriptors depend only on (shape, scale); a shape library reuses shapes at many scales,
    // so measure each stored shape once and scale the dimensional ones (exactly: lengths ~ s,
    // areas ~ s^2, volumes ~ s^3, the rest scale-free).
    std::vector<ShapeDescriptors> per_shape(packing.shapes.size());
    std::vector<char> is_used(packing.shapes.size(), 0);
    for (const auto& particle : packing.particles) is_used[particle.shape] = 1;
    parallel_for_index(0, packing.shapes.size(), [&](std::size_t s) {
      if (is_used[s]) per_shape[s] = describe(packing.shapes[s]);
    });
    const auto& columns = descriptor_columns();
    for (const auto& column : columns) {
      const std::string unit = column.unit;
      const int power = unit == "m" ? 1 : unit == "m^2" ? 2 : unit == "m^3" ? 3 : 0;
      std::vector<double> values(n);
      for (std::size_t i = 0; i < n; ++i) {
        const Particle& particle = packing.particles[i];
        values[i] = column.get(per_shape[particle.shape]) * std::pow(particle.scale, power);
      }
      stats.descriptors.push_back({column.name, column.unit, summarize(values)});
    }
  }
  return stats;
}

std::string format_grading(const std::vector<GradingPoint>& grading) {
  if (grading.empty()) return "";
  std::string text = "grading (volume % passing, size = control diameter)\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %12s %10s %10s %8s\n", "size [m]", "target", "achieved",
                "diff");
  text += line;
  for (const auto& point : grading) {
    std::snprintf(line, sizeof line, "  %12.6g %10.2f %10.2f %+8.2f\n", point.size,
                  point.target_percent, point.achieved_percent,
                  point.achieved_percent - point.target_percent);
    text += line;
  }
  return text;
}

std::string format_statistics(const PackingStatistics& stats) {
  std::string text;
  char line[512];
  auto add = [&](const char* format, auto... values) {
    std::snprintf(line, sizeof line, format, values...);
    text += line;
  };
  add("particles        %zu (%zu distinct shapes)\n", stats.particle_count, stats.shape_count);
  add("solid volume     %.6g m^3\n", stats.solid_volume);
  add("container volume %.6g m^3\n", stats.container_volume);
  add("solid fraction   %.4f (%.2f %%)\n", stats.solid_fraction, 100.0 * stats.solid_fraction);
  const char* names[3] = {"x", "y", "z"};
  for (const auto& profile : stats.profiles) {
    if (profile.solid_fraction.empty()) continue;
    add("solid fraction along %s (%zu bins of %.4g m):", names[profile.axis],
        profile.solid_fraction.size(), profile.bin_width);
    for (double value : profile.solid_fraction) add(" %.3f", value);
    text += "\n";
  }
  text += format_grading(stats.grading);
  if (!stats.descriptors.empty()) {
    text += "shape descriptors (per particle)\n";
    add("  %-22s %-5s %12s %12s %12s %12s\n", "name", "unit", "mean", "std dev", "min", "max");
    for (const auto& descriptor : stats.descriptors) {
      add("  %-22s %-5s %12.6g %12.6g %12.6g %12.6g\n", descriptor.name.c_str(),
          descriptor.unit.c_str(), descriptor.stats.mean, descriptor.stats.standard_deviation,
          descriptor.stats.minimum, descriptor.stats.maximum);
    }
  }
  return text;
}

}  // namespace aggpack
