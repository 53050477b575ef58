// A planar cut through a concrete mesomodel, and its picture (mesh/mesomodel_cut.h).

#include "aggpack/mesh/mesomodel_cut.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <system_error>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"

namespace aggpack {

namespace {

// printf into a std::string (the core library has no fmt).
[[gnu::format(printf, 1, 2)]] std::string printed(const char* format, ...) {
  std::array<char, 512> buffer{};
  va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(buffer.data(), buffer.size(), format, arguments);
  va_end(arguments);
  return buffer.data();
}

constexpr std::array<const char*, 3> kPhaseNames = {"mortar", "ITZ", "aggregate"};

std::array<double, 2> in_plane(const Vec3& point, const std::array<int, 2>& uv) {
  return {point[uv[0]], point[uv[1]]};
}

// Where the edge from a (below) to b (not below) meets the plane. The distances have opposite
// signs or db == 0, so the denominator is never 0; a node in the plane gives itself exactly.
std::array<double, 2> crossing(const Vec3& a, double da, const Vec3& b, double db,
                               const std::array<int, 2>& uv) {
  if (db == 0.0) return in_plane(b, uv);
  const double t = da / (da - db);
  return {a[uv[0]] + t * (b[uv[0]] - a[uv[0]]), a[uv[1]] + t * (b[uv[1]] - a[uv[1]])};
}

// A colour `delta` levels lighter (> 0) or darker, clamped.
Rgb shifted(const Rgb& colour, int delta) {
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<std::uint8_t>(std::clamp(colour[c] + delta, 0, 255));
  return out;
}

Rgb darker(const Rgb& colour) {
  Rgb out;
  for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(colour[c] * 55 / 100);
  return out;
}

// 1, 2 or 5 times a power of ten, the largest not above `limit` (> 0).
double nice_length(double limit) {
  const double power = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double step : {5.0, 2.0, 1.0}) {
    if (step * power <= limit) return step * power;
  }
  return power;
}

}  // namespace

const char* axis_name(int axis) {
  static constexpr std::array<const char*, 3> kNames = {"x", "y", "z"};
  return axis >= 0 && axis < 3 ? kNames[static_cast<std::size_t>(axis)] : "?";
}

std::array<int, 2> cut_plane_axes(int axis) {
  if (axis == 0) return {1, 2};
  if (axis == 1) return {0, 2};
  return {0, 1};
}

CutPlane parse_cut_plane(const std::string& text, const std::string& key) {
  const std::string allowed =
      "AXIS=VALUE with AXIS x, y or z and VALUE a finite number in m, e.g. z=0.05";
  if (text.size() < 3 || text[1] != '=' || (text[0] != 'x' && text[0] != 'y' && text[0] != 'z')) {
    throw InvalidInput(key, clipped(text), allowed);
  }
  CutPlane plane{.axis = text[0] - 'x', .value = 0.0};
  const char* first = text.data() + 2;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, plane.value);
  if (error != std::errc() || end != last || !std::isfinite(plane.value)) {
    throw InvalidInput(key, clipped(text), allowed);
  }
  return plane;
}

std::vector<CutPolygon> cut_mesomodel(const MesoMesh& mesh, int axis, double value,
                                      const std::string& key) {
  if (axis < 0 || axis > 2) {
    throw InvalidInput(key + " axis", std::to_string(axis), "0, 1 or 2 (x, y, z)");
  }
  if (mesh.tetrahedra.empty()) {
    throw InvalidInput(key, "a mesh with no tetrahedra", "a mesh with at least one tetrahedron");
  }
  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (const Tetrahedron& tet : mesh.tetrahedra) {
    for (const std::uint32_t n : tet) {
      lowest = std::min(lowest, mesh.nodes.at(n)[axis]);
      highest = std::max(highest, mesh.nodes[n][axis]);
    }
  }
  if (!(value >= lowest && value <= highest)) {
    throw InvalidInput(key, std::string(axis_name(axis)) + "=" + format_value(value),
                       std::string(axis_name(axis)) + " in [" + format_value(lowest) + ", " +
                           format_value(highest) + "] m (the mesh's extent along " +
                           axis_name(axis) + ")");
  }
  // At the lowest plane nothing is below: take the limit from above there (header comment).
  const bool is_flipped = value == lowest;
  const std::array<int, 2> uv = cut_plane_axes(axis);
  std::vector<CutPolygon> polygons;
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const Tetrahedron& tet = mesh.tetrahedra[t];
    std::array<double, 4> distance{};
    std::array<int, 4> below{};
    std::array<int, 4> above{};
    int below_count = 0;
    int above_count = 0;
    for (int k = 0; k < 4; ++k) {
      distance[k] = mesh.nodes[tet[k]][axis] - value;
      const bool is_below = is_flipped ? distance[k] <= 0.0 : distance[k] < 0.0;
      if (is_below) {
        below[below_count++] = k;
      } else {
        above[above_count++] = k;
      }
    }
    if (below_count == 0 || above_count == 0) continue;
    auto point = [&](int b, int a) {
      return crossing(mesh.nodes[tet[b]], distance[b], mesh.nodes[tet[a]], distance[a], uv);
    };
    CutPolygon polygon;
    if (below_count == 1 || above_count == 1) {  // one node alone on its side: a triangle
      const bool is_lone_below = below_count == 1;
      const int lone = is_lone_below ? below[0] : above[0];
      const auto& others = is_lone_below ? above : below;
      for (int i = 0; i < 3; ++i) {
        polygon.points.push_back(is_lone_below ? point(lone, others[i]) : point(others[i], lone));
      }
    } else {  // two and two: the crossings of b0a0, b0a1, b1a1, b1a0 go round the quadrilateral
      polygon.points = {point(below[0], above[0]), point(below[0], above[1]),
                        point(below[1], above[1]), point(below[1], above[0])};
    }
    // A node in the plane makes two crossings coincide: keep the distinct corners.
    auto& p = polygon.points;
    p.erase(std::unique(p.begin(), p.end()), p.end());
    while (p.size() > 1 && p.front() == p.back()) p.pop_back();
    if (p.size() < 3) continue;
    if (polygon_area(p) < 0.0) std::reverse(p.begin(), p.end());
    polygon.phase = t < mesh.phase.size() ? mesh.phase[t] : MesoPhase::kMortar;
    polygon.particle = t < mesh.particle.size() ? mesh.particle[t] : 0;
    polygon.tetrahedron = static_cast<std::uint32_t>(t);
    polygons.push_back(std::move(polygon));
  }
  return polygons;
}

double polygon_area(const std::vector<std::array<double, 2>>& points) {
  double twice = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& a = points[i];
    const auto& b = points[(i + 1) % points.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * twice;
}

std::array<double, 3> cut_phase_areas(const std::vector<CutPolygon>& polygons) {
  std::array<double, 3> areas{};
  for (const CutPolygon& polygon : polygons) {
    areas[static_cast<std::size_t>(polygon.phase)] += polygon_area(polygon.points);
  }
  return areas;
}

Rgb mesomodel_cut_colour(MesoPhase phase, std::uint32_t particle, bool is_tinted) {
  switch (phase) {
    case MesoPhase::kMortar:
      return {232, 224, 200};
    case MesoPhase::kItz:
      return {226, 84, 30};
    case MesoPhase::kAggregate:
      break;
  }
  const Rgb stone{128, 128, 136};
  if (!is_tinted) return stone;
  // A fixed hash of the id (the "lowbias32" integer mixer), so consecutive ids differ.
  std::uint32_t hash = particle;
  hash ^= hash >> 16U;
  hash *= 0x7feb352dU;
  hash ^= hash >> 15U;
  hash *= 0x846ca68bU;
  hash ^= hash >> 16U;
  return shifted(stone, static_cast<int>(hash % 49U) - 24);
}

Raster draw_mesomodel_cut(const std::vector<CutPolygon>& polygons, int axis, double value,
                          const CutImageOptions& options) {
  if (options.width < 200 || options.width > 8192) {
    throw InvalidInput("cut image width", std::to_string(options.width), "[200, 8192] pixels");
  }
  if (polygons.empty()) {
    throw InvalidInput("cut plane", std::string(axis_name(axis)) + "=" + format_value(value),
                       "a plane that crosses the mesh (the section is empty)");
  }
  std::array<double, 2> low{std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()};
  std::array<double, 2> high{-low[0], -low[1]};
  double edge_sum = 0.0;
  std::size_t edge_count = 0;
  for (const CutPolygon& polygon : polygons) {
    for (std::size_t i = 0; i < polygon.points.size(); ++i) {
      const auto& a = polygon.points[i];
      const auto& b = polygon.points[(i + 1) % polygon.points.size()];
      for (int c = 0; c < 2; ++c) {
        low[c] = std::min(low[c], a[c]);
        high[c] = std::max(high[c], a[c]);
      }
      edge_sum += std::hypot(b[0] - a[0], b[1] - a[1]);
      ++edge_count;
    }
  }
  const double extent_u = std::max(high[0] - low[0], 1e-300);
  const double extent_v = std::max(high[1] - low[1], 1e-300);
  constexpr int kMargin = kCutImageMargin;
  constexpr int kTitle = kCutImageTitle;
  constexpr int kLegend = 110;
  const int plot_width = options.width - 2 * kMargin;
  const int plot_height = static_cast<int>(
      std::clamp(std::lround(plot_width * extent_v / extent_u), 20L, 2L * plot_width));
  const double scale = std::min(plot_width / extent_u, plot_height / extent_v);  // pixels per m
  const double offset_x = kMargin + 0.5 * (plot_width - scale * extent_u);
  const double offset_y = kTitle + 0.5 * (plot_height - scale * extent_v);
  auto pixel = [&](const std::array<double, 2>& p) {
    return std::array<double, 2>{offset_x + (p[0] - low[0]) * scale,
                                 offset_y + (high[1] - p[1]) * scale};  // v up
  };
  Raster canvas(options.width, kTitle + plot_height + kLegend);
  const bool has_edges =
      options.has_edges && edge_sum / static_cast<double>(edge_count) * scale >= 3.0;
  std::vector<std::array<double, 2>> corners;
  for (const CutPolygon& polygon : polygons) {
    corners.clear();
    for (const auto& p : polygon.points) corners.push_back(pixel(p));
    canvas.fill_convex(corners,
                       mesomodel_cut_colour(polygon.phase, polygon.particle, options.is_tinted));
  }
  if (has_edges) {  // after every fill, so an interface shows the edges of both sides
    for (const CutPolygon& polygon : polygons) {
      const Rgb edge = darker(mesomodel_cut_colour(polygon.phase, polygon.particle, false));
      for (std::size_t i = 0; i < polygon.points.size(); ++i) {
        const auto a = pixel(polygon.points[i]);
        const auto b = pixel(polygon.points[(i + 1) % polygon.points.size()]);
        canvas.line(a[0], a[1], b[0], b[1], 1, edge);
      }
    }
  }

  const Rgb black{0, 0, 0};
  const auto uv = cut_plane_axes(axis);
  canvas.text(printed("Mesomodel cut %s = %.6g mm (%s right, %s up)", axis_name(axis), value * 1e3,
                      axis_name(uv[0]), axis_name(uv[1])),
              kMargin, 12, 2, black);
  if (!options.subtitle.empty()) canvas.text(options.subtitle, kMargin, 40, 2, black);

  // Legend: a swatch, the phase's name and its share of the section's area.
  const std::array<double, 3> areas = cut_phase_areas(polygons);
  const double total = areas[0] + areas[1] + areas[2];
  const int legend_top = kTitle + plot_height + 16;
  int x = kMargin;
  for (const int phase : {2, 1, 0}) {
    const auto code = static_cast<MesoPhase>(phase);
    const Rgb fill = mesomodel_cut_colour(code, 0, false);
    canvas.fill_rect(x, legend_top, x + 24, legend_top + 18, darker(fill));
    canvas.fill_rect(x + 2, legend_top + 2, x + 22, legend_top + 16, fill);
    const std::string label = printed("%s %.1f %%", kPhaseNames[static_cast<std::size_t>(phase)],
                                      100.0 * areas[static_cast<std::size_t>(phase)] / total);
    canvas.text(label, x + 32, legend_top + 3, 2, black);
    x += 32 + 12 * static_cast<int>(label.size()) + 30;
  }
  canvas.text(printed("area fractions of the section, %zu elements cut%s", polygons.size(),
                      has_edges || !options.has_edges ? "" : " (edges too small to draw)"),
              kMargin, legend_top + 32, 2, black);

  // Scale bar: a round length in mm about a fifth of the plot's width.
  const double bar_metres = nice_length(0.2 * plot_width / scale * 1e3) * 1e-3;
  const double bar_pixels = bar_metres * scale;
  const int bar_y = legend_top + 70;
  canvas.fill_rect(kMargin, bar_y, kMargin + static_cast<int>(std::lround(bar_pixels)), bar_y + 6,
                   black);
  canvas.text(printed("%g mm", bar_metres * 1e3),
              kMargin + static_cast<int>(std::lround(bar_pixels)) + 12, bar_y - 4, 2, black);
  return canvas;
}

void write_mesomodel_cut_png(const std::string& path, const MesoMesh& mesh, int axis, double value,
                             const CutImageOptions& options, const std::string& key) {
  const std::vector<CutPolygon> polygons = cut_mesomodel(mesh, axis, value, key);
  write_png(path, draw_mesomodel_cut(polygons, axis, value, options));
}

}  // namespace aggpack
