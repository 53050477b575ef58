// The periodic box's piecewise linear complex (mesomodel_plc.h, periodic_complex): every particle
// image that meets the box, clipped to it, and the box faces with the clipped images' caps in
// them, built so that the points on opposite faces are exact translations of each other.

#include <algorithm>
#include <cmath>
#include <map>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"
#include "mesomodel_plc.h"

namespace aggpack::detail {

namespace {

// A convex body as planar polygons; cap_face >= 0 marks a polygon on a box face (axis * 2 + side,
// side 0 at the lower bound, 1 at the upper).
struct PeriodicPolygon {
  std::vector<Vec3> points;
  int cap_face = -1;
};

bool is_before_lexicographic(const Vec3& a, const Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// The polygons of `faces` on the side `side` (0: coordinate >= value, 1: <= value) of the plane
// axis = value, plus the cap the plane cuts. An edge's crossing is computed from its endpoints in
// one fixed order, so the two faces sharing the edge get the same point, bit for bit, and its
// coordinate on the axis is set to the plane's value exactly.
std::vector<PeriodicPolygon> clip_periodic(const std::vector<PeriodicPolygon>& faces, int axis,
                                           int side, double value) {
  const auto inside = [&](const Vec3& p) {
    return side == 0 ? p[axis] >= value : p[axis] <= value;
  };
  std::vector<PeriodicPolygon> out;
  std::vector<Vec3> on_plane;
  for (const PeriodicPolygon& face : faces) {
    PeriodicPolygon kept{{}, face.cap_face};
    const std::size_t n = face.points.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3& p = face.points[k];
      const Vec3& q = face.points[(k + 1) % n];
      if (inside(p)) kept.points.push_back(p);
      if (inside(p) != inside(q) && p[axis] != value && q[axis] != value) {
        const auto [a, b] = is_before_lexicographic(p, q) ? std::pair(p, q) : std::pair(q, p);
        Vec3 r = a + (value - a[axis]) / (b[axis] - a[axis]) * (b - a);
        r[axis] = value;
        kept.points.push_back(r);
      }
    }
    for (const Vec3& p : kept.points) {
      if (p[axis] == value) on_plane.push_back(p);
    }
    if (kept.points.size() >= 3) out.push_back(std::move(kept));
  }
  std::sort(on_plane.begin(), on_plane.end(), is_before_lexicographic);
  on_plane.erase(std::unique(on_plane.begin(), on_plane.end()), on_plane.end());
  if (on_plane.size() >= 3) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : on_plane) centre += p;
    centre /= static_cast<double>(on_plane.size());
    std::sort(on_plane.begin(), on_plane.end(), [&](const Vec3& a, const Vec3& b) {
      return std::atan2(a[v] - centre[v], a[u] - centre[u]) <
             std::atan2(b[v] - centre[v], b[u] - centre[u]);
    });
    // Counter-clockwise about +axis; outward is -axis at the lower bound.
    if (side == 0) std::reverse(on_plane.begin(), on_plane.end());
    out.push_back({std::move(on_plane), 2 * axis + side});
  }
  return out;
}

// Exact point numbers: equal coordinates, one number.
struct ExactPointNumbers {
  std::vector<Vec3>& points;
  std::map<std::array<double, 3>, std::uint32_t> numbers;

  std::uint32_t at(const Vec3& p) {
    const auto [it, is_new] =
        numbers.try_emplace({p.x(), p.y(), p.z()}, static_cast<std::uint32_t>(points.size()));
    if (is_new) points.push_back(p);
    return it->second;
  }
};

// Makes every point on an upper periodic face the exact translation of its partner on the lower
// face (their in-plane coordinates are computed from different images and may differ in the last
// bits); refuses when one has no partner within `tolerance`.
void match_periodic_faces(std::vector<Vec3>& points, const std::array<bool, 3>& periodic,
                          const Vec3& extent, double tolerance) {
  for (int round = 0; round < 2; ++round) {  // twice: an edge point is on two face pairs
    for (int axis = 0; axis < 3; ++axis) {
      if (!periodic[static_cast<std::size_t>(axis)]) continue;
      const int u = (axis + 1) % 3;
      const int v = (axis + 2) % 3;
      std::vector<std::uint32_t> lower;
      for (std::uint32_t i = 0; i < points.size(); ++i) {
        if (points[i][axis] == 0.0) lower.push_back(i);
      }
      std::sort(lower.begin(), lower.end(),
                [&](std::uint32_t a, std::uint32_t b) { return points[a][u] < points[b][u]; });
      for (Vec3& p : points) {
        if (p[axis] != extent[axis]) continue;
        auto it =
            std::lower_bound(lower.begin(), lower.end(), p[u] - tolerance,
                             [&](std::uint32_t a, double value) { return points[a][u] < value; });
        const Vec3* partner = nullptr;
        for (; it != lower.end() && points[*it][u] <= p[u] + tolerance; ++it) {
          if (std::abs(points[*it][v] - p[v]) <= tolerance) partner = &points[*it];
        }
        if (partner == nullptr) {
          throw LimitExceeded(Wording{Sentence::kMesomodelMesh, {}},
                              Wording{Sentence::kPeriodicPointNoPartner, {}},
                              Wording{Sentence::kComplexTetGenKeeps, {}});
        }
        p[u] = (*partner)[u];
        p[v] = (*partner)[v];
      }
    }
  }
}

// Whether 2D point p (coordinates u, v) is within `margin` of convex polygon `cap` (or inside).
bool is_near_periodic_cap(const std::vector<Vec3>& points, const std::vector<std::uint32_t>& cap,
                          int u, int v, const Vec3& p, double margin) {
  double outside = -std::numeric_limits<double>::infinity();
  Vec3 centre = Vec3::Zero();
  for (const std::uint32_t k : cap) centre += points[k];
  centre /= static_cast<double>(cap.size());
  for (std::size_t k = 0; k < cap.size(); ++k) {
    const Vec3& a = points[cap[k]];
    const Vec3& b = points[cap[(k + 1) % cap.size()]];
    Eigen::Vector2d normal(b[v] - a[v], -(b[u] - a[u]));
    normal.normalize();
    if (normal.dot(Eigen::Vector2d(centre[u] - a[u], centre[v] - a[v])) > 0) normal = -normal;
    outside = std::max(outside, normal.dot(Eigen::Vector2d(p[u] - a[u], p[v] - a[v])));
  }
  return outside < margin;
}

// Rotates a polygon to start at its widest corner: TetGen takes a facet's plane from the first
// three points of its first polygon, and an outline that starts with collinear edge points gives
// it no plane (it then triangulates the facet into overlapping triangles).
void start_at_widest_corner(const std::vector<Vec3>& points, std::vector<std::uint32_t>& polygon) {
  const std::size_t n = polygon.size();
  std::size_t best = 0;
  double widest = -1.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = points[polygon[k]];
    const double area =
        (points[polygon[(k + 1) % n]] - a).cross(points[polygon[(k + 2) % n]] - a).norm();
    if (area > widest) {
      widest = area;
      best = k;
    }
  }
  std::rotate(polygon.begin(), polygon.begin() + static_cast<std::ptrdiff_t>(best), polygon.end());
}

}  // namespace

PeriodicComplex periodic_complex(const Packing& packing, double wall_spacing, double min_gap) {
  // A periodic container is a box [0, extent] (container.h: periodic_axes).
  const std::array<bool, 3> periodic = periodic_axes(packing.container);
  const Vec3 extent = packing.container.bounds().upper;
  PeriodicComplex complex;
  Plc& plc = complex.plc;
  ExactPointNumbers table{plc.points, {}};
  for (int corner = 0; corner < 8; ++corner) {
    table.at(Vec3(corner & 1 ? extent.x() : 0.0, corner & 2 ? extent.y() : 0.0,
                  corner & 4 ? extent.z() : 0.0));
  }
  // Every image of every particle that meets the box (the extents exceed twice the enclosing
  // radius, so the shifts -1, 0, +1 periods find them all), clipped to it.
  std::vector<std::vector<PeriodicPolygon>> pieces;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron particle = packing.placed(i);
    for (int shift = 0; shift < 27; ++shift) {
      Vec3 offset = Vec3::Zero();
      bool is_used = true;
      for (int axis = 0, code = shift; axis < 3; ++axis, code /= 3) {
        const int step = code % 3 == 2 ? -1 : code % 3;
        if (step != 0 && !periodic[static_cast<std::size_t>(axis)]) is_used = false;
        offset[axis] = step * extent[axis];
      }
      const Aabb bounds = particle.bounds();
      for (int axis = 0; axis < 3; ++axis) {
        is_used &= bounds.lower[axis] + offset[axis] < extent[axis] &&
                   bounds.upper[axis] + offset[axis] > 0.0;
      }
      if (!is_used) continue;
      std::vector<PeriodicPolygon> faces;
      for (const Triangle& tri : particle.triangles()) {
        PeriodicPolygon face;
        for (const std::uint32_t k : tri) face.points.push_back(particle.vertices()[k] + offset);
        faces.push_back(std::move(face));
      }
      // A vertex on or within min_gap of a periodic face would leave a sliver or a point that
      // TetGen cannot place; a walled face keeps the walled box's clearance.
      for (const Vec3& vertex : particle.vertices()) {
        for (int axis = 0; axis < 3; ++axis) {
          const double p = vertex[axis] + offset[axis];
          const double clearance = std::min(std::abs(p), std::abs(p - extent[axis]));
          const bool is_periodic = periodic[static_cast<std::size_t>(axis)];
          if (clearance <= min_gap && is_periodic) {
            throw InvalidInput(Wording{Sentence::kParticleNumber, {std::to_string(i + 1)}},
                               Wording{Sentence::kFromAPeriodicFace, {format_value(clearance)}},
                               Wording{Sentence::kPeriodicFaceClearance, {format_value(min_gap)}});
          }
          if (!is_periodic && std::min(p, extent[axis] - p) <= min_gap) {
            throw InvalidInput(
                Wording{Sentence::kParticleNumber, {std::to_string(i + 1)}},
                Wording{Sentence::kFromAWall, {format_value(std::min(p, extent[axis] - p)) + " m"}},
                Wording{Sentence::kWallClearance,
                        {format_value(min_gap) + " m", "container.wall_gap"}});
          }
        }
      }
      for (int axis = 0; axis < 3 && !faces.empty(); ++axis) {
        if (!periodic[static_cast<std::size_t>(axis)]) continue;
        faces = clip_periodic(faces, axis, 0, 0.0);
        faces = clip_periodic(faces, axis, 1, extent[axis]);
      }
      if (faces.size() < 4) continue;
      pieces.push_back(std::move(faces));
      complex.piece_particle.push_back(static_cast<std::uint32_t>(i + 1));
    }
  }
  // Point numbers (equal points shared), then the upper faces' points moved onto their partners.
  std::vector<std::vector<std::vector<std::uint32_t>>> piece_faces(pieces.size());
  std::vector<std::vector<int>> piece_caps(pieces.size());
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (const PeriodicPolygon& face : pieces[p]) {
      std::vector<std::uint32_t> polygon;
      for (const Vec3& point : face.points) polygon.push_back(table.at(point));
      piece_faces[p].push_back(std::move(polygon));
      piece_caps[p].push_back(face.cap_face);
    }
  }
  const double size = extent.maxCoeff();
  match_periodic_faces(plc.points, periodic, extent, 1e-9 * size);

  // The six box faces: outline through every point on its edges, the caps in it, a point grid
  // (made on the lower face of a periodic pair and copied to the upper one).
  std::array<std::vector<std::vector<std::uint32_t>>, 6> caps;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (std::size_t f = 0; f < piece_faces[p].size(); ++f) {
      if (piece_caps[p][f] >= 0)
        caps[static_cast<std::size_t>(piece_caps[p][f])].push_back(piece_faces[p][f]);
    }
  }
  std::array<std::vector<Vec3>, 6> grids;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const auto nu = static_cast<int>(std::ceil(extent[u] / wall_spacing));
    const auto nv = static_cast<int>(std::ceil(extent[v] / wall_spacing));
    for (int side = 0; side < 2; ++side) {
      if (side == 1 && periodic[static_cast<std::size_t>(axis)]) {
        for (Vec3 p : grids[static_cast<std::size_t>(2 * axis)]) {
          p[axis] = extent[axis];
          grids[static_cast<std::size_t>(2 * axis + 1)].push_back(p);
        }
        continue;
      }
      if (nu < 2 || nv < 2) continue;
      const double du = extent[u] / nu;
      const double dv = extent[v] / nv;
      for (int j = 1; j < nv; ++j) {
        for (int i = 1; i < nu; ++i) {
          Vec3 p = Vec3::Zero();
          p[axis] = side == 0 ? 0.0 : extent[axis];
          // Jittered by up to 1/10 of the spacing: TetGen 1.5 triangulates a facet whose points
          // are a regular grid (many cocircular points) crossed by the caps' segments into
          // overlapping triangles for some grids; the jitter is a fixed function of (i, j).
          const double jitter_u = std::fmod(0.6180339887 * i + 0.4142135624 * j, 1.0) - 0.5;
          const double jitter_v = std::fmod(0.7320508076 * i + 0.2360679775 * j, 1.0) - 0.5;
          p[u] = du * (i + 0.2 * jitter_u);
          p[v] = dv * (j + 0.2 * jitter_v);
          bool is_free = true;
          for (const auto& cap : caps[static_cast<std::size_t>(2 * axis + side)]) {
            is_free &= !is_near_periodic_cap(plc.points, cap, u, v, p, 0.5 * std::min(du, dv));
          }
          if (is_free) grids[static_cast<std::size_t>(2 * axis + side)].push_back(p);
        }
      }
    }
  }
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    const double at = face % 2 == 0 ? 0.0 : extent[axis];
    // Corners counter-clockwise about +axis: (0,0) (U,0) (U,V) (0,V) in (u, v).
    std::array<Vec3, 4> corners;
    for (int c = 0; c < 4; ++c) {
      corners[static_cast<std::size_t>(c)][axis] = at;
      corners[static_cast<std::size_t>(c)][u] = c == 1 || c == 2 ? extent[u] : 0.0;
      corners[static_cast<std::size_t>(c)][v] = c >= 2 ? extent[v] : 0.0;
    }
    std::vector<std::uint32_t> outline;
    for (int c = 0; c < 4; ++c) {
      const Vec3& a = corners[static_cast<std::size_t>(c)];
      const Vec3& b = corners[static_cast<std::size_t>((c + 1) % 4)];
      const int along = c % 2 == 0 ? u : v;
      outline.push_back(table.at(a));
      std::vector<std::uint32_t> on_edge;
      for (std::uint32_t k = 8; k < plc.points.size(); ++k) {
        const Vec3& p = plc.points[k];
        bool is_on = true;
        for (int w = 0; w < 3; ++w) is_on &= w == along || p[w] == a[w];
        if (is_on && p[along] > 0.0 && p[along] < extent[along]) on_edge.push_back(k);
      }
      std::sort(on_edge.begin(), on_edge.end(), [&](std::uint32_t m, std::uint32_t n) {
        return (plc.points[m][along] < plc.points[n][along]) == (b[along] > a[along]);
      });
      outline.insert(outline.end(), on_edge.begin(), on_edge.end());
    }
    if (face % 2 == 0) std::reverse(outline.begin(), outline.end());  // outward
    start_at_widest_corner(plc.points, outline);
    PlcFacet facet{{outline}, -face - 1};
    // The caps' edges as segments, but not those on the outline: a segment twice in one facet
    // breaks TetGen's triangulation of the facet (it then reports the facet intersecting itself).
    const auto is_on_outline = [&](std::uint32_t m, std::uint32_t n) {
      const Vec3& p = plc.points[m];
      const Vec3& q = plc.points[n];
      return (p[u] == q[u] && (p[u] == 0.0 || p[u] == extent[u])) ||
             (p[v] == q[v] && (p[v] == 0.0 || p[v] == extent[v]));
    };
    for (const auto& cap : caps[static_cast<std::size_t>(face)]) {
      for (std::size_t k = 0; k < cap.size(); ++k) {
        const std::uint32_t m = cap[k];
        const std::uint32_t n = cap[(k + 1) % cap.size()];
        if (!is_on_outline(m, n)) facet.polygons.push_back({m, n});
      }
    }
    for (const Vec3& p : grids[static_cast<std::size_t>(face)]) {
      facet.polygons.push_back({table.at(p)});
    }
    plc.facets.push_back(std::move(facet));
  }
  // The pieces: their faces other than the caps, and each as a polyhedron (fans of its faces).
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    std::vector<Vec3> vertices;
    std::vector<Triangle> triangles;
    std::vector<HalfSpace> planes;
    std::map<std::uint32_t, std::uint32_t> local;
    for (std::size_t f = 0; f < piece_faces[p].size(); ++f) {
      auto& polygon = piece_faces[p][f];
      if (piece_caps[p][f] < 0) {
        start_at_widest_corner(plc.points, polygon);
        plc.facets.push_back({{polygon}, 2 * static_cast<int>(complex.piece_particle[p])});
      }
      std::vector<std::uint32_t> at;
      for (const std::uint32_t k : polygon) {
        const auto [it, is_new] = local.try_emplace(k, static_cast<std::uint32_t>(vertices.size()));
        if (is_new) vertices.push_back(plc.points[k]);
        at.push_back(it->second);
      }
      for (std::size_t k = 1; k + 1 < at.size(); ++k)
        triangles.push_back({at[0], at[k], at[k + 1]});
      // The face's plane from the whole polygon (Newell): a fan's thin triangles next to a cut
      // point have normals that rounding can turn any way.
      Vec3 normal = Vec3::Zero();
      Vec3 centre = Vec3::Zero();
      for (std::size_t k = 0; k < polygon.size(); ++k) {
        const Vec3& a = plc.points[polygon[k]];
        const Vec3& b = plc.points[polygon[(k + 1) % polygon.size()]];
        normal += a.cross(b);
        centre += a;
      }
      if (normal.norm() > 0.0) {
        normal.normalize();
        planes.push_back({normal, normal.dot(centre / static_cast<double>(polygon.size()))});
      }
    }
    complex.pieces.emplace_back(std::move(vertices), std::move(triangles));
    complex.piece_planes.push_back(std::move(planes));
  }
  return complex;
}

void copy_lower_face_triangles(const PlcMesh& first, const std::array<bool, 3>& periodic,
                               const Vec3& extent, Plc& plc) {
  // The boundary triangles of the first mesh (faces of one tetrahedron), by box face.
  std::map<std::array<std::uint32_t, 3>, int> faces;
  for (const Tetrahedron& tet : first.tetrahedra) {
    for (const auto& local : kTetraFaces) {
      std::array<std::uint32_t, 3> key{tet[local[0]], tet[local[1]], tet[local[2]]};
      std::sort(key.begin(), key.end());
      ++faces[key];
    }
  }
  std::map<std::array<double, 3>, std::uint32_t> numbers;
  for (std::uint32_t i = 0; i < plc.points.size(); ++i) {
    numbers.try_emplace({plc.points[i].x(), plc.points[i].y(), plc.points[i].z()}, i);
  }
  std::array<std::vector<std::vector<std::uint32_t>>, 3> lower;
  for (const auto& [key, count] : faces) {
    if (count != 1) continue;
    for (int axis = 0; axis < 3; ++axis) {
      const bool is_on = std::all_of(key.begin(), key.end(), [&](std::uint32_t k) {
        return k < plc.points.size() && first.nodes[k][axis] == 0.0;
      });
      if (is_on && periodic[static_cast<std::size_t>(axis)]) {
        lower[static_cast<std::size_t>(axis)].push_back({key[0], key[1], key[2]});
      }
    }
  }
  // Facets 0-5 are the box's faces (periodic_complex): each periodic pair becomes the lower
  // face's triangles and their translations, one facet each, which -Y keeps as they are.
  std::vector<PlcFacet> facets;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    if (!periodic[static_cast<std::size_t>(axis)]) {
      facets.push_back(plc.facets[static_cast<std::size_t>(face)]);
      continue;
    }
    for (const auto& triangle : lower[static_cast<std::size_t>(axis)]) {
      std::vector<std::uint32_t> polygon;
      for (const std::uint32_t k : triangle) {
        Vec3 p = plc.points[k];
        if (face % 2 == 1) p[axis] = extent[axis];
        const auto found = numbers.find({p.x(), p.y(), p.z()});
        if (found == numbers.end()) {
          throw LimitExceeded(Wording{Sentence::kMesomodelMesh, {}},
                              Wording{Sentence::kPeriodicPointNoPartner, {}},
                              Wording{Sentence::kComplexTetGenKeeps, {}});
        }
        polygon.push_back(found->second);
      }
      facets.push_back({{polygon}, -face - 1});
    }
  }
  facets.insert(facets.end(), plc.facets.begin() + 6, plc.facets.end());
  plc.facets = std::move(facets);
}

}  // namespace aggpack::detail
