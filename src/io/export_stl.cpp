// STL from a Packing: binary (80-byte header, uint32 count, 50 bytes per facet) or ASCII. Facet
// normals are recomputed from the placed triangle, outward (paper Section 4).

#include <cstdio>
#include <cstring>

#include "aggpack/core/error.h"
#include "export_detail.h"

namespace aggpack::detail {

namespace {

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 normal = (b - a).cross(c - a);
  const double length = normal.norm();
  return length > 0 ? Vec3(normal / length) : Vec3::Zero();
}

void append_float(std::string& out, double value) {
  const auto f = static_cast<float>(value);
  char bytes[4];
  std::memcpy(bytes, &f, 4);  // STL is little-endian; so is every platform we build on
  out.append(bytes, 4);
}

}  // namespace

void write_stl(const ExportModel& model, std::ostream& out) {
  if (model.options().stl_encoding == StlEncoding::kBinary) {
    if (model.element_count() > 0xFFFFFFFFULL) {
      throw LimitExceeded(Wording{Sentence::kBinaryStlTriangles, {}},
                          Wording{Sentence::kText, {std::to_string(model.element_count())}},
                          Wording{Sentence::kBinaryStlLimit, {"--per-particle"}});
    }
    char header[80] = {};
    std::snprintf(header, sizeof header, "binary STL from aggpack %s, %zu particles",
                  AGGPACK_VERSION, model.size());
    out.write(header, 80);
    const auto count = static_cast<std::uint32_t>(model.element_count());
    out.write(reinterpret_cast<const char*>(&count), 4);
    stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
      std::vector<Vec3> nodes;
      model.surface_nodes(k, nodes);
      const auto& triangles = model.triangles(k);
      buffer.reserve(50 * triangles.size());
      for (const auto& t : triangles) {
        const Vec3 normal = unit_normal(nodes[t[0]], nodes[t[1]], nodes[t[2]]);
        for (int axis = 0; axis < 3; ++axis) append_float(buffer, normal[axis]);
        for (auto index : t) {
          for (int axis = 0; axis < 3; ++axis) append_float(buffer, nodes[index][axis]);
        }
        buffer.append(2, '\0');  // attribute byte count
      }
    });
    return;
  }
  out << "solid aggpack\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.surface_nodes(k, nodes);
    for (const auto& t : model.triangles(k)) {
      const Vec3 normal = unit_normal(nodes[t[0]], nodes[t[1]], nodes[t[2]]);
      buffer += "  facet normal";
      for (int axis = 0; axis < 3; ++axis) {
        buffer += ' ';
        append_scientific(buffer, normal[axis], 8);
      }
      buffer += "\n    outer loop\n";
      for (auto index : t) {
        buffer += "      vertex";
        for (int axis = 0; axis < 3; ++axis) {
          buffer += ' ';
          append_scientific(buffer, nodes[index][axis], 8);
        }
        buffer += '\n';
      }
      buffer += "    endloop\n  endfacet\n";
    }
  });
  out << "endsolid aggpack\n";
}

}  // namespace aggpack::detail
