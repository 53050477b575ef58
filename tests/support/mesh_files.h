#pragma once
// Test meshes made in the tests (no fixture files): a cube with a dent, a dented icosahedron
// (a bumpy, non-convex rock whose hull is the icosahedron), broken meshes, and writers of STL
// (binary, ASCII), OBJ and PLY (ASCII, binary little- and big-endian) for them.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <string>

#include "aggpack/geom/triangle_mesh.h"

namespace aggpack::test {

// Cube [0, a]^3 whose top face is pushed in: 4 triangles to a centre at depth `dent` below it.
// Volume a^3 - a^2 dent / 3; its convex hull is the cube (volume a^3).
inline TriangleMesh dented_cube(double a, double dent) {
  TriangleMesh mesh;
  for (int k = 0; k < 8; ++k) {
    mesh.vertices.emplace_back((k & 1) != 0 ? a : 0.0, (k & 2) != 0 ? a : 0.0,
                               (k & 4) != 0 ? a : 0.0);
  }
  mesh.vertices.emplace_back(a / 2, a / 2, a - dent);  // 8: the dent's bottom
  // Outward counter-clockwise: bottom, sides, then the top as a fan around the dent.
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {0, 1, 5}, {0, 5, 4}, {1, 3, 7}, {1, 7, 5}, {3, 2, 6},
                    {3, 6, 7}, {2, 0, 4}, {2, 4, 6}, {4, 5, 8}, {5, 7, 8}, {7, 6, 8}, {6, 4, 8}};
  return mesh;
}

// Regular icosahedron of circumradius r about `centre`, each face split into 3 around a point
// pulled in to `inward` x the face centre: a bumpy, non-convex rock whose convex hull is the
// icosahedron, of volume (5/12)(3 + sqrt 5) e^3 with edge e = r / sin(2 pi / 5).
inline TriangleMesh dented_icosahedron(double r, double inward, const Vec3& centre) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const double unit = std::sqrt(1.0 + phi * phi);
  TriangleMesh mesh;
  const double base[12][3] = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                              {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                              {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (const auto& v : base) mesh.vertices.push_back(centre + Vec3(v[0], v[1], v[2]) * (r / unit));
  const std::uint32_t faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& f : faces) {
    const Vec3 middle =
        (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0 - centre;
    const auto m = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(centre + middle * inward);
    mesh.triangles.push_back({f[0], f[1], m});
    mesh.triangles.push_back({f[1], f[2], m});
    mesh.triangles.push_back({f[2], f[0], m});
  }
  return mesh;
}

inline double icosahedron_volume(double r) {
  const double edge = r / std::sin(2.0 * std::numbers::pi / 5.0);
  return 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * edge * edge * edge;
}

// Two tetrahedra that share only vertex 0: closed, edges fine, but not a 2-manifold there.
inline TriangleMesh bowtie() {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                    {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}};
  return mesh;
}

// Three triangles on one edge: a dented cube with a fin glued to its bottom edge (0, 1).
inline TriangleMesh finned_cube() {
  TriangleMesh mesh = dented_cube(1.0, 0.2);
  mesh.vertices.emplace_back(0.5, -1.0, -1.0);
  const auto fin = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
  mesh.triangles.push_back({0, 1, fin});
  return mesh;
}

// ---- writers ----------------------------------------------------------------------------------

inline void append_float(std::string& bytes, float value) {
  char raw[4];
  std::memcpy(raw, &value, 4);
  bytes.append(raw, 4);
}

inline std::string stl_binary(const TriangleMesh& mesh) {
  std::string bytes(80, ' ');
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  char raw[4];
  std::memcpy(raw, &count, 4);
  bytes.append(raw, 4);
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) append_float(bytes, 0.0F);
    for (const auto v : t) {
      for (int axis = 0; axis < 3; ++axis) {
        append_float(bytes, static_cast<float>(mesh.vertices[v][axis]));
      }
    }
    bytes.append(2, '\0');
  }
  return bytes;
}

inline std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

inline std::string stl_ascii(const TriangleMesh& mesh) {
  std::string text = "solid test\n";
  for (const auto& t : mesh.triangles) {
    text += "facet normal 0 0 0\n outer loop\n";
    for (const auto v : t) {
      text += "  vertex " + number(mesh.vertices[v].x()) + " " + number(mesh.vertices[v].y()) +
              " " + number(mesh.vertices[v].z()) + "\n";
    }
    text += " endloop\nendfacet\n";
  }
  return text + "endsolid test\n";
}

inline std::string obj_text(const TriangleMesh& mesh) {
  std::string text = "# test mesh\no rock\n";
  for (const auto& p : mesh.vertices) {
    text += "v " + number(p.x()) + " " + number(p.y()) + " " + number(p.z()) + "\n";
  }
  text += "vn 0 0 1\n";
  for (const auto& t : mesh.triangles) {
    // 1-based, in the v//vn form, to exercise the slash forms.
    text += "f " + std::to_string(t[0] + 1) + "//1 " + std::to_string(t[1] + 1) + "//1 " +
            std::to_string(t[2] + 1) + "//1\n";
  }
  return text;
}

enum class PlyEncoding { kAscii, kLittle, kBig };

inline std::string ply_bytes(const TriangleMesh& mesh, PlyEncoding encoding) {
  std::string text = "ply\nformat ";
  text += encoding == PlyEncoding::kAscii    ? "ascii"
          : encoding == PlyEncoding::kLittle ? "binary_little_endian"
                                             : "binary_big_endian";
  text += " 1.0\ncomment made by a test\nelement vertex " + std::to_string(mesh.vertices.size()) +
          "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\n"
          "element face " +
          std::to_string(mesh.triangles.size()) +
          "\nproperty list uchar int vertex_indices\nend_header\n";
  auto put = [&](const void* data, std::size_t size) {
    char raw[8];
    std::memcpy(raw, data, size);
    if (encoding == PlyEncoding::kBig) std::reverse(raw, raw + size);
    text.append(raw, size);
  };
  for (const auto& p : mesh.vertices) {
    if (encoding == PlyEncoding::kAscii) {
      text += number(p.x()) + " " + number(p.y()) + " " + number(p.z()) + " 7\n";
      continue;
    }
    for (int axis = 0; axis < 3; ++axis) {
      const double value = p[axis];
      put(&value, 8);
    }
    const unsigned char red = 7;
    put(&red, 1);
  }
  for (const auto& t : mesh.triangles) {
    if (encoding == PlyEncoding::kAscii) {
      text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " +
              std::to_string(t[2]) + "\n";
      continue;
    }
    const unsigned char three = 3;
    put(&three, 1);
    for (const auto v : t) {
      const auto index = static_cast<std::int32_t>(v);
      put(&index, 4);
    }
  }
  return text;
}

inline void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace aggpack::test
