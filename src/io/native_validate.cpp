// validate_packing: the content checks every reader of a native packing file goes through
// (read_packing calls it last), so no command accepts a packing that another rejects. The ranges
// are NativeLimits (include/aggpack/io/native.h), documented in docs/formats.md.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/native.h"
#include "native_container.h"

namespace aggpack {

namespace {

using Limits = NativeLimits;

[[noreturn]] void fail(const std::string& source, const std::string& field, const Wording& reason) {
  native_detail::fail_field(source, {Sentence::kText, {field}}, reason);
}
[[noreturn]] void fail(const std::string& source, const Wording& field, const Wording& reason) {
  native_detail::fail_field(source, field, reason);
}

std::string range_text(double lo, double hi) {
  return "[" + format_value(lo) + ", " + format_value(hi) + "]";
}

// True when lo <= value <= hi (false for NaN).
bool is_within(double value, double lo, double hi) { return value >= lo && value <= hi; }

void check_container(const Container& c, const std::string& source) {
  native_detail::check_container_values(container_kind_info(c), native_detail::container_values(c),
                                        source);
  // The packers' own rule (validate(Container)): a gap of half the smallest extent leaves no room.
  // Named here as the file's attribute, so every command refuses it the same way.
  const double half = c.visit([](const auto& kind) { return kind.smallest_extent(); }) / 2.0;
  if (!(c.wall_gap < half)) {
    fail(source, "/container/wall_gap = " + format_value(c.wall_gap),
         {Sentence::kNativeWallGapHalf, {format_value(half)}});
  }
}

// The first problem of shape `s` (vertex rows from `vertex_row`, triangle rows from
// `triangle_row` in the file), or nothing. Returns the shape's largest |coordinate| and its
// bounding-box diagonal through the out parameters.
void check_shape(const ConvexPolyhedron& shape, std::size_t s, std::uint64_t vertex_row,
                 std::uint64_t triangle_row, const std::string& source, double& largest,
                 double& diagonal) {
  const auto& vertices = shape.vertices();
  const auto& triangles = shape.triangles();
  const auto rows = [s](const char* dataset, std::uint64_t first, std::size_t count) {
    return Wording{Sentence::kNativeShapeRows,
                   {dataset, std::to_string(s), std::to_string(first),
                    std::to_string(first + count - (count > 0 ? 1 : 0))}};
  };
  const Wording vertex_field = rows("/shapes/vertices", vertex_row, vertices.size());
  const Wording triangle_field = rows("/shapes/triangles", triangle_row, triangles.size());
  if (vertices.size() < 4 || triangles.size() < 4) {
    fail(source, triangle_field,
         {Sentence::kNativeTooFewParts,
          {std::to_string(vertices.size()), std::to_string(triangles.size())}});
  }

  largest = 0.0;
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    const double size = vertices[v].cwiseAbs().maxCoeff();
    if (!vertices[v].allFinite() || !(size <= Limits::kMaxLength)) {
      fail(source, vertex_field,
           {Sentence::kNativeVertexMagnitude,
            {std::to_string(v), format_value(size),
             range_text(-Limits::kMaxLength, Limits::kMaxLength)}});
    }
    largest = std::max(largest, size);
  }

  // Topology: every edge in exactly two triangles, traversed once in each direction.
  struct HalfEdge {
    std::uint32_t low, high, face;
    bool is_forward;
  };
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * triangles.size());
  std::vector<bool> is_used(vertices.size(), false);
  for (std::uint32_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      fail(source, triangle_field,
           {Sentence::kNativeRepeatsVertex,
            {std::to_string(f), std::to_string(t[0]), std::to_string(t[1]), std::to_string(t[2])}});
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k];
      const std::uint32_t b = t[(k + 1) % 3];
      half_edges.push_back({std::min(a, b), std::max(a, b), f, a < b});
      is_used[a] = true;
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.low, x.high, x.face) < std::tie(y.low, y.high, y.face);
  });
  std::size_t edge_count = 0;
  for (std::size_t i = 0; i < half_edges.size();) {
    std::size_t j = i;
    while (j < half_edges.size() && half_edges[j].low == half_edges[i].low &&
           half_edges[j].high == half_edges[i].high) {
      ++j;
    }
    const std::string low = std::to_string(half_edges[i].low);
    const std::string high = std::to_string(half_edges[i].high);
    if (j - i == 1) {
      fail(source, triangle_field,
           {Sentence::kNativeEdgeOpen, {low, high, std::to_string(half_edges[i].face)}});
    }
    if (j - i > 2) {
      fail(source, triangle_field,
           {Sentence::kNativeEdgeShared, {low, high, std::to_string(j - i)}});
    }
    if (half_edges[i].is_forward == half_edges[i + 1].is_forward) {
      fail(source, triangle_field,
           {Sentence::kNativeEdgeSameWay,
            {low, high, std::to_string(half_edges[i].face),
             std::to_string(half_edges[i + 1].face)}});
    }
    ++edge_count;
    i = j;
  }
  for (std::size_t v = 0; v < is_used.size(); ++v) {
    if (!is_used[v]) {
      fail(source, triangle_field, {Sentence::kNativeUnusedVertex, {std::to_string(v)}});
    }
  }
  const long long euler = static_cast<long long>(vertices.size()) -
                          static_cast<long long>(edge_count) +
                          static_cast<long long>(triangles.size());
  if (euler != 2) {
    fail(source, triangle_field, {Sentence::kNativeEuler, {std::to_string(euler)}});
  }

  // Geometry: a real extent, no zero-area triangle, positive volume, convex.
  diagonal = shape.bounds().extent().norm();
  if (!(diagonal >= Limits::kMinLength)) {
    fail(source, vertex_field,
         {Sentence::kNativeCollapsed, {format_value(diagonal), format_value(Limits::kMinLength)}});
  }
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    // Relative to the extent: 1e-14 is far below what a convex hull of distinct points gives
    // and far above rounding of exactly collinear points.
    if (!(shape.face_normal_scaled(f).norm() > 1e-14 * diagonal * diagonal)) {
      fail(source, triangle_field, {Sentence::kNativeZeroArea, {std::to_string(f)}});
    }
  }
  const double volume = mass_properties(shape).volume;
  if (!(volume > 0.0)) {
    fail(source, triangle_field, {Sentence::kNativeInsideOut, {format_value(volume)}});
  }
  const double tolerance = Limits::kConvexTolerance * diagonal;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Vec3 normal = shape.face_normal(f);
    const double offset = normal.dot(vertices[triangles[f][0]]);
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const double height = normal.dot(vertices[v]) - offset;
      if (height > tolerance) {
        fail(source, vertex_field,
             {Sentence::kNativeNotConvex,
              {std::to_string(v), format_value(height), std::to_string(f),
               format_value(tolerance)}});
      }
    }
  }
}

void check_particles(const Packing& packing, const std::vector<double>& largest,
                     const std::vector<double>& diagonal, const std::string& source) {
  const std::size_t shape_count = packing.shapes.size();
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const Particle& p = packing.particles[i];
    const std::string index = "[" + std::to_string(i) + "]";
    if (p.shape >= shape_count) {
      fail(source, "/particles/shape" + index + " = " + std::to_string(p.shape),
           {Sentence::kNativeNoSuchShape, {std::to_string(shape_count)}});
    }
    const Vec3& x = p.pose.position;
    if (!x.allFinite() || !(x.cwiseAbs().maxCoeff() <= Limits::kMaxLength)) {
      fail(source,
           "/particles/position" + index + " = (" + format_value(x.x()) + ", " +
               format_value(x.y()) + ", " + format_value(x.z()) + ")",
           {Sentence::kNativeOutsideMetres, {range_text(-Limits::kMaxLength, Limits::kMaxLength)}});
    }
    const double norm_error = std::abs(p.pose.rotation.squaredNorm() - 1.0);
    if (!(norm_error <= Limits::kRotationTolerance)) {
      fail(source, "/particles/rotation" + index,
           {Sentence::kNativeNotUnitQuaternion,
            {format_value(p.pose.rotation.squaredNorm()),
             format_value(Limits::kRotationTolerance)}});
    }
    if (!is_within(p.scale, Limits::kMinScale, Limits::kMaxScale)) {
      fail(source, "/particles/scale" + index + " = " + format_value(p.scale),
           {Sentence::kNativeOutside, {range_text(Limits::kMinScale, Limits::kMaxScale)}});
    }
    const double world_largest = p.scale * largest[p.shape];
    const double world_diagonal = p.scale * diagonal[p.shape];
    if (!(world_largest <= Limits::kMaxLength) || !(world_diagonal >= Limits::kMinLength)) {
      fail(source, "/particles/scale" + index + " = " + format_value(p.scale),
           {Sentence::kNativeScaleSize,
            {std::to_string(p.shape), format_value(world_diagonal), format_value(world_largest),
             format_value(Limits::kMinLength), format_value(Limits::kMaxLength)}});
    }
    if (!is_within(p.control_radius, 0.0, Limits::kMaxLength)) {
      fail(source, "/particles/control_radius" + index + " = " + format_value(p.control_radius),
           {Sentence::kNativeOutsideMetres, {range_text(0.0, Limits::kMaxLength)}});
    }
  }
}

}  // namespace

namespace native_detail {

void fail_field(const std::string& source, const Wording& field, const Wording& reason,
                const std::vector<WordedValue>& words) {
  const std::string field_text = english(field);
  const std::string reason_text = english(reason);
  FormatError error(Wording{Sentence::kFieldInvalid, {source, field_text, reason_text}});
  if (field.sentence != Sentence::kText) error.word_value(field_text, field);
  error.word_value(reason_text, reason);
  for (const WordedValue& each : words) error.word_value(each.text, each.wording);
  throw error;
}

std::vector<double> container_values(const Container& container) {
  std::vector<double> values;
  for (const ContainerKindInfo& kind : container_kinds()) {
    for (const ContainerParam& param : kind.params) values.push_back(param.get(container));
  }
  values.push_back(container.wall_gap);
  return values;
}

void check_container_values(const ContainerKindInfo& kind, const std::vector<double>& values,
                            const std::string& source) {
  std::size_t field = 0;
  auto check = [&](const char* name, bool is_used) {
    // Sizes the container uses must be positive; the others are stored but not used.
    const double value = values.at(field++);
    const double lo = is_used ? Limits::kMinLength : 0.0;
    if (!is_within(value, lo, Limits::kMaxLength)) {
      const std::string range = range_text(lo, Limits::kMaxLength);
      fail(source, std::string("/container/") + name + " = " + format_value(value),
           is_used ? Wording{Sentence::kNativeContainerNeeds, {range, kind.name}}
                   : Wording{Sentence::kNativeOutsideMetres, {range}});
    }
  };
  for (const ContainerKindInfo& each : container_kinds()) {
    for (const ContainerParam& param : each.params) check(param.name, &each == &kind);
  }
  check("wall_gap", false);
}

}  // namespace native_detail

void validate_packing(const Packing& packing, const std::string& source) {
  check_container(packing.container, source);
  std::vector<double> largest(packing.shapes.size(), 0.0);
  std::vector<double> diagonal(packing.shapes.size(), 0.0);
  std::uint64_t vertex_row = 0;
  std::uint64_t triangle_row = 0;
  for (std::size_t s = 0; s < packing.shapes.size(); ++s) {
    check_shape(packing.shapes[s], s, vertex_row, triangle_row, source, largest[s], diagonal[s]);
    vertex_row += packing.shapes[s].vertex_count();
    triangle_row += packing.shapes[s].triangle_count();
  }
  check_particles(packing, largest, diagonal, source);
}

}  // namespace aggpack
