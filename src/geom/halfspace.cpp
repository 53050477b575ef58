// Convex polyhedra cut by half-spaces (geom/halfspace.h).

#include "aggpack/geom/halfspace.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// A convex polyhedron as face loops (outward, counter-clockwise) over one vertex array.
struct PolygonMesh {
  std::vector<Vec3> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
};

PolygonMesh from_triangles(const ConvexPolyhedron& body) {
  PolygonMesh mesh;
  mesh.vertices = body.vertices();
  mesh.faces.reserve(body.triangle_count());
  for (const Triangle& t : body.triangles()) mesh.faces.push_back({t[0], t[1], t[2]});
  return mesh;
}

// Where a vertex lies relative to a plane, tolerance included.
enum class Side : std::uint8_t { kIn, kOn, kOut };

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t{std::min(a, b)} << 32U) | std::max(a, b);
}

// Cuts `mesh` by one half-space; false when nothing is left.
bool clip_once(PolygonMesh& mesh, const HalfSpace& h, double tolerance) {
  std::vector<Side> side(mesh.vertices.size());
  bool has_out = false;
  bool has_in = false;
  for (std::size_t i = 0; i < side.size(); ++i) {
    const double s = h.normal.dot(mesh.vertices[i]) - h.offset;
    side[i] = s > tolerance ? Side::kOut : (s < -tolerance ? Side::kIn : Side::kOn);
    has_out |= side[i] == Side::kOut;
    has_in |= side[i] == Side::kIn;
  }
  if (!has_out) return true;
  if (!has_in) return false;
  std::unordered_map<std::uint64_t, std::uint32_t> crossing;  // edge -> new vertex
  const auto cross = [&](std::uint32_t a, std::uint32_t b) {
    const auto [it, is_new] = crossing.try_emplace(edge_key(a, b), 0U);
    if (is_new) {
      // Computed from the ordered pair, so both faces of the edge get the same point.
      const Vec3& p = mesh.vertices[std::min(a, b)];
      const Vec3& q = mesh.vertices[std::max(a, b)];
      const double sp = h.normal.dot(p) - h.offset;
      const double sq = h.normal.dot(q) - h.offset;
      it->second = static_cast<std::uint32_t>(mesh.vertices.size());
      mesh.vertices.push_back(p + (sp / (sp - sq)) * (q - p));
      side.push_back(Side::kOn);
    }
    return it->second;
  };
  std::vector<std::vector<std::uint32_t>> faces;
  faces.reserve(mesh.faces.size() + 1);
  for (const auto& face : mesh.faces) {
    std::vector<std::uint32_t> kept;
    bool is_all_on = true;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const std::uint32_t a = face[k];
      const std::uint32_t b = face[(k + 1) % face.size()];
      if (side[a] != Side::kOut) kept.push_back(a);
      is_all_on &= side[a] == Side::kOn;
      if ((side[a] == Side::kIn && side[b] == Side::kOut) ||
          (side[a] == Side::kOut && side[b] == Side::kIn)) {
        kept.push_back(cross(a, b));
      }
    }
    // A face lying in the cutting plane is replaced by the cap.
    if (kept.size() >= 3 && !is_all_on) faces.push_back(std::move(kept));
  }
  // The cap closes the hole the cut left: its edges are the kept faces' edges that have no twin
  // (the reverse edge in another kept face), reversed and chained into loops. Built from the
  // topology rather than by sorting points around the plane, so the result is a closed manifold
  // even where the tolerance leaves a vertex a little off the plane.
  std::unordered_map<std::uint32_t, std::uint32_t> cap_next;
  {
    std::unordered_map<std::uint64_t, int> directed;  // (from << 32 | to) -> uses
    for (const auto& face : faces) {
      for (std::size_t k = 0; k < face.size(); ++k) {
        ++directed[(std::uint64_t{face[k]} << 32U) | face[(k + 1) % face.size()]];
      }
    }
    for (const auto& [key, uses] : directed) {
      const auto from = static_cast<std::uint32_t>(key >> 32U);
      const auto to = static_cast<std::uint32_t>(key & 0xFFFFFFFFU);
      if (!directed.contains((std::uint64_t{to} << 32U) | from)) cap_next.emplace(to, from);
    }
  }
  std::vector<std::uint32_t> starts;
  for (const auto& [from, to] : cap_next) starts.push_back(from);
  std::sort(starts.begin(), starts.end());  // loops in a fixed order, whatever the hashing
  for (const std::uint32_t start : starts) {
    if (!cap_next.contains(start)) continue;
    std::vector<std::uint32_t> loop;
    std::uint32_t at = start;
    while (cap_next.contains(at)) {
      loop.push_back(at);
      const std::uint32_t next = cap_next[at];
      cap_next.erase(at);
      at = next;
    }
    if (loop.size() >= 3) faces.push_back(std::move(loop));
  }
  mesh.faces = std::move(faces);
  return mesh.faces.size() >= 4;
}

// True unless every corner of the loop turns strictly left about the loop's normal (Newell's):
// a fan from a corner is then safe. A straight corner (a cut through a coplanar pair of
// triangles leaves one on the cap's edge) or a slightly reflex one (a vertex within the clipping
// tolerance of a plane counts as on it, so a cap can be a little non-convex) is not.
bool has_straight_corner(const std::vector<Vec3>& vertices,
                         const std::vector<std::uint32_t>& loop) {
  Vec3 normal = Vec3::Zero();
  double size = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec3& a = vertices[loop[k]];
    const Vec3& b = vertices[loop[(k + 1) % loop.size()]];
    normal += a.cross(b);
    size = std::max(size, (a - vertices[loop[0]]).norm());
  }
  normal.normalize();
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec3& a = vertices[loop[(k + loop.size() - 1) % loop.size()]];
    const Vec3& b = vertices[loop[k]];
    const Vec3& c = vertices[loop[(k + 1) % loop.size()]];
    if ((b - a).cross(c - b).dot(normal) <= 1e-9 * size * size) return true;
  }
  return false;
}

// Fan triangulation of every face loop; a loop with a straight corner (a cut through a coplanar
// pair of triangles leaves one on the cap's edge) is fanned from its centroid instead, a new
// vertex on the face.
ConvexPolyhedron triangulate(const PolygonMesh& mesh) {
  std::vector<std::uint32_t> index(mesh.vertices.size(), UINT32_MAX);
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  const auto node = [&](std::uint32_t v) {
    if (index[v] == UINT32_MAX) {
      index[v] = static_cast<std::uint32_t>(vertices.size());
      vertices.push_back(mesh.vertices[v]);
    }
    return index[v];
  };
  for (const auto& face : mesh.faces) {
    if (face.size() > 3 && has_straight_corner(mesh.vertices, face)) {
      Vec3 centre = Vec3::Zero();
      for (const std::uint32_t v : face) centre += mesh.vertices[v];
      const auto middle = static_cast<std::uint32_t>(vertices.size());
      vertices.push_back(centre / static_cast<double>(face.size()));
      for (std::size_t k = 0; k < face.size(); ++k) {
        triangles.push_back({node(face[k]), node(face[(k + 1) % face.size()]), middle});
      }
      continue;
    }
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      triangles.push_back({node(face[0]), node(face[k]), node(face[k + 1])});
    }
  }
  return {std::move(vertices), std::move(triangles)};
}

// An axis-aligned box as six quadrilaterals (no diagonals to cut through).
PolygonMesh box_mesh(const Vec3& lower, const Vec3& upper) {
  PolygonMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.emplace_back((i & 1) != 0 ? upper.x() : lower.x(),
                               (i & 2) != 0 ? upper.y() : lower.y(),
                               (i & 4) != 0 ? upper.z() : lower.z());
  }
  mesh.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  return mesh;
}

void check_half_spaces(std::span<const HalfSpace> half_spaces, double tolerance) {
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) {
    throw InvalidInput("tolerance", std::to_string(tolerance), ">= 0 (m)");
  }
  for (const HalfSpace& h : half_spaces) {
    if (!h.normal.allFinite() || !std::isfinite(h.offset) ||
        std::abs(h.normal.squaredNorm() - 1.0) > 1e-12) {
      throw InvalidInput("half-space normal", "not a finite unit vector", "a unit normal");
    }
  }
}

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

}  // namespace

ConvexPolyhedron clip(const ConvexPolyhedron& body, std::span<const HalfSpace> half_spaces,
                      double tolerance) {
  if (body.is_empty()) throw InvalidInput("body", "empty", "a convex polyhedron");
  check_half_spaces(half_spaces, tolerance);
  PolygonMesh mesh = from_triangles(body);
  bool is_cut = false;
  for (const HalfSpace& h : half_spaces) {
    const std::size_t before = mesh.vertices.size();
    const std::size_t faces_before = mesh.faces.size();
    if (!clip_once(mesh, h, tolerance)) return {};
    is_cut |= mesh.vertices.size() != before || mesh.faces.size() != faces_before;
  }
  if (!is_cut) return body;
  return triangulate(mesh);
}

std::vector<HalfSpace> face_half_spaces(const ConvexPolyhedron& body) {
  std::vector<HalfSpace> planes;
  planes.reserve(body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 n = body.face_normal(f);
    if (!n.allFinite()) continue;  // a zero-area triangle bounds nothing
    planes.push_back({n, n.dot(body.vertices()[body.triangles()[f][0]])});
  }
  return planes;
}

namespace {

PolygonMesh mitred_offset_faces(const ConvexPolyhedron& body, double thickness,
                                std::span<const HalfSpace> bounds, double tolerance) {
  if (!(thickness > 0.0) || !std::isfinite(thickness)) {
    throw InvalidInput("offset thickness", std::to_string(thickness), "> 0 (m)");
  }
  if (body.is_empty()) throw InvalidInput("body", "empty", "a convex polyhedron");
  check_half_spaces(bounds, tolerance);
  // Start from a box far larger than any mitre can reach, cut by the moved planes.
  const Aabb box = body.bounds();
  const double margin = 4.0 * (box.extent().maxCoeff() + thickness);
  PolygonMesh mesh =
      box_mesh(box.lower - Vec3::Constant(margin), box.upper + Vec3::Constant(margin));
  for (HalfSpace h : face_half_spaces(body)) {
    h.offset += thickness;
    if (!clip_once(mesh, h, tolerance)) return {};
  }
  for (const HalfSpace& h : bounds) {
    if (!clip_once(mesh, h, tolerance)) return {};
  }
  // Keep only the vertices the faces use, numbered in order of first use.
  std::vector<std::uint32_t> index(mesh.vertices.size(), UINT32_MAX);
  PolygonMesh result;
  for (auto& face : mesh.faces) {
    for (std::uint32_t& v : face) {
      if (index[v] == UINT32_MAX) {
        index[v] = static_cast<std::uint32_t>(result.vertices.size());
        result.vertices.push_back(mesh.vertices[v]);
      }
      v = index[v];
    }
  }
  result.faces = std::move(mesh.faces);
  const double reach = margin - thickness;
  for (const Vec3& v : result.vertices) {
    if ((v - box.lower).minCoeff() < -reach || (v - box.upper).maxCoeff() > reach) {
      throw LimitExceeded("mitred offset", "a corner reaches beyond 4 x the body's size",
                          "a body without needle-sharp corners");
    }
  }
  return result;
}

}  // namespace

ConvexPolyhedron mitred_offset(const ConvexPolyhedron& body, double thickness,
                               std::span<const HalfSpace> bounds, double tolerance) {
  const PolygonMesh faces = mitred_offset_faces(body, thickness, bounds, tolerance);
  if (faces.faces.empty()) return {};
  return triangulate(faces);
}

double mitre_factor(const ConvexPolyhedron& body, const ConvexPolyhedron& offset,
                    double thickness) {
  double reach = 0.0;
  for (const Vec3& v : offset.vertices()) reach = std::max(reach, distance_to_body(body, v));
  return reach / thickness;
}

double distance_to_body(const ConvexPolyhedron& body, const Vec3& point) {
  const auto& v = body.vertices();
  bool is_inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Triangle& t = body.triangles()[f];
    const Vec3 n = body.face_normal_scaled(f);
    if (n.dot(point - v[t[0]]) > 0.0) is_inside = false;
    best = std::min(best, (point - closest_on_triangle(point, v[t[0]], v[t[1]], v[t[2]])).norm());
  }
  return is_inside ? 0.0 : best;
}

}  // namespace aggpack
