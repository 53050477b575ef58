// The concrete mesomodel (mesh/mesomodel.h): container, aggregates and the outer surfaces of their
// ITZ layers as one piecewise linear complex meshed by TetGen (mesomodel_tetgen.cpp; the layers
// are holes there), phases from TetGen's regions checked against the geometry, then the layers
// filled with prisms (mesomodel_itz.cpp). Its report and face node sets: mesomodel_measure.cpp.

#include "aggpack/mesh/mesomodel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/halfspace.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "mesomodel_plc.h"

namespace aggpack {

namespace {

// The meshed container: a convex prism (a box, or the prism circumscribed about a cylinder).
struct Prism {
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;  // outward, counter-clockwise
  std::vector<HalfSpace> planes;                  // one per face
  double volume = 0.0;
};

Prism make_prism(const Container& container, int segments) {
  Prism prism;
  const std::vector<Vec3> ring = container_prism_floor(container, segments);
  const double height = container.bounds().upper.z();
  const auto n = static_cast<std::uint32_t>(ring.size());
  for (const Vec3& p : ring) prism.points.push_back(p);
  for (const Vec3& p : ring) prism.points.emplace_back(p.x(), p.y(), height);
  std::vector<std::uint32_t> floor;
  std::vector<std::uint32_t> roof;
  for (std::uint32_t k = 0; k < n; ++k) {
    floor.push_back(n - 1 - k);
    roof.push_back(n + k);
  }
  prism.faces.push_back(floor);
  prism.faces.push_back(roof);
  double area = 0.0;
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t next = (k + 1) % n;
    prism.faces.push_back({k, next, n + next, n + k});
    area += 0.5 * ring[k].cross(ring[next]).z();
  }
  prism.volume = area * height;
  prism.planes.push_back({-Vec3::UnitZ(), 0.0});
  prism.planes.push_back({Vec3::UnitZ(), height});
  for (std::uint32_t k = 0; k < n; ++k) {
    const Vec3 edge = ring[(k + 1) % n] - ring[k];
    const Vec3 normal = Vec3(edge.y(), -edge.x(), 0.0).normalized();
    prism.planes.push_back({normal, normal.dot(ring[k])});
  }
  return prism;
}

// Points on a square grid of `spacing` inside wall `w` of the prism, at least a quarter spacing
// from its edges.
std::vector<Vec3> wall_grid(const Prism& prism, std::size_t w, double spacing) {
  const auto& face = prism.faces[w];
  const Vec3 normal = prism.planes[w].normal;
  const Vec3 origin = prism.points[face[0]];
  const Vec3 u = (prism.points[face[1]] - origin).normalized();
  const Vec3 v = normal.cross(u);
  double u_lo = 0, u_hi = 0, v_lo = 0, v_hi = 0;
  for (const std::uint32_t k : face) {
    const Vec3 d = prism.points[k] - origin;
    u_lo = std::min(u_lo, d.dot(u));
    u_hi = std::max(u_hi, d.dot(u));
    v_lo = std::min(v_lo, d.dot(v));
    v_hi = std::max(v_hi, d.dot(v));
  }
  std::vector<Vec3> points;
  const auto nu = static_cast<int>(std::ceil((u_hi - u_lo) / spacing));
  const auto nv = static_cast<int>(std::ceil((v_hi - v_lo) / spacing));
  if (nu < 2 || nv < 2) return points;
  for (int j = 1; j < nv; ++j) {
    for (int i = 1; i < nu; ++i) {
      const Vec3 p =
          origin + (u_lo + (u_hi - u_lo) * i / nu) * u + (v_lo + (v_hi - v_lo) * j / nv) * v;
      bool is_inside = true;  // at least a quarter spacing inside every edge (convex face)
      for (std::size_t k = 0; k < face.size() && is_inside; ++k) {
        const Vec3& a = prism.points[face[k]];
        const Vec3& b = prism.points[face[(k + 1) % face.size()]];
        const Vec3 inward = normal.cross(b - a).normalized();
        is_inside = inward.dot(p - a) >= 0.25 * spacing;
      }
      if (is_inside) points.push_back(p);
    }
  }
  return points;
}

// What the mesher is told about one particle.
struct Inclusion {
  ConvexPolyhedron aggregate;
  std::vector<HalfSpace> planes;  // the aggregate's face planes
  // The ITZ layer's outer surface: the aggregate's triangles over moved vertices (empty without
  // an ITZ).
  ConvexPolyhedron shell;
  double aggregate_volume = 0.0;
  double aggregate_area = 0.0;   // surface area (the cohesive ITZ's exact area)
  Vec3 centroid = Vec3::Zero();  // of the aggregate (its region seed lies near it)
  double shell_volume = 0.0;     // enclosed by the outer surface
  double reach = 1.0;            // largest vertex displacement / thickness
  double wall_clearance = 0.0;
  Aabb bounds;                 // of the outer body (shell, or aggregate without ITZ)
  std::uint32_t particle = 0;  // 1-based (a periodic box has pieces of a particle's images)
};

double regular_tetra_volume(double edge) { return edge * edge * edge / (6.0 * std::sqrt(2.0)); }

// A number with `digits` significant digits (%g).
std::string number(double value, int digits = 4) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

std::string metres(double value) { return number(value) + " m"; }

// Refuses a packing whose outer bodies (ITZ shells, or aggregates without ITZ) meet.
void check_gaps(const std::vector<Inclusion>& inclusions, const MesoOptions& options,
                double min_gap) {
  const bool has_itz = options.itz_thickness > 0.0;
  std::vector<std::uint32_t> order(inclusions.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return inclusions[a].bounds.lower.x() < inclusions[b].bounds.lower.x();
  });
  const Pose identity{};
  double worst = std::numeric_limits<double>::infinity();
  std::uint32_t worst_a = 0;
  std::uint32_t worst_b = 0;
  std::size_t violations = 0;
  for (std::size_t u = 0; u < order.size(); ++u) {
    const Inclusion& a = inclusions[order[u]];
    for (std::size_t w = u + 1; w < order.size(); ++w) {
      const Inclusion& b = inclusions[order[w]];
      if (b.bounds.lower.x() > a.bounds.upper.x() + min_gap) break;
      if ((b.bounds.lower.array() > a.bounds.upper.array() + min_gap).any() ||
          (a.bounds.lower.array() > b.bounds.upper.array() + min_gap).any()) {
        continue;
      }
      const ConvexPolyhedron& body_a = has_itz ? a.shell : a.aggregate;
      const ConvexPolyhedron& body_b = has_itz ? b.shell : b.aggregate;
      const double d = gjk_distance(body_a, identity, body_b, identity).distance;
      if (d > min_gap) continue;
      ++violations;
      const auto [i, j] = std::minmax(order[u], order[w]);
      if (d < worst || (d == worst && std::make_pair(i, j) < std::make_pair(worst_a, worst_b))) {
        worst = d;
        worst_a = i;
        worst_b = j;
      }
    }
  }
  if (violations == 0) return;
  const double gap =
      gjk_distance(inclusions[worst_a].aggregate, identity, inclusions[worst_b].aggregate, identity)
          .distance;
  double reach = 1.0;
  for (const Inclusion& inclusion : inclusions) reach = std::max(reach, inclusion.reach);
  const double needed =
      has_itz ? 2.0 * reach * options.itz_thickness + 2.0 * min_gap : 2.0 * min_gap;
  const auto [first, second] =
      std::minmax(inclusions[worst_a].particle, inclusions[worst_b].particle);
  const Wording pair{Sentence::kParticlesPair, {std::to_string(first), std::to_string(second)}};
  const std::string pairs = std::to_string(violations);
  if (has_itz) {
    throw InvalidInput(
        pair, Wording{Sentence::kApartItzMeet, {metres(gap), metres(options.itz_thickness), pairs}},
        Wording{Sentence::kPackWithGapItz, {"packer.gap", metres(needed), number(reach, 3)}});
  }
  throw InvalidInput(pair, Wording{Sentence::kApartTouch, {metres(gap), pairs}},
                     Wording{Sentence::kPackWithGap, {"packer.gap", metres(needed)}});
}

}  // namespace

const char* to_string(ItzKind kind) { return kind == ItzKind::kCohesive ? "cohesive" : "solid"; }

const char* phase_set_name(MesoPhase phase) {
  switch (phase) {
    case MesoPhase::kMortar:
      return "MORTAR";
    case MesoPhase::kItz:
      return "ITZ";
    case MesoPhase::kAggregate:
      return "AGGREGATE";
  }
  return "?";
}

void validate(const MesoOptions& options) {
  const auto check = [](const char* field, double value, bool is_ok, const char* allowed) {
    if (!is_ok || !std::isfinite(value)) throw InvalidInput(field, format_value(value), allowed);
  };
  check("itz_thickness", options.itz_thickness, options.itz_thickness >= 0.0, ">= 0 (m)");
  if (options.itz_kind != ItzKind::kSolid && options.itz_kind != ItzKind::kCohesive) {
    throw InvalidInput("itz_kind", std::to_string(static_cast<int>(options.itz_kind)),
                       "solid or cohesive");
  }
  if (options.itz_kind == ItzKind::kCohesive) {
    detail::check_cohesive_thickness(options.itz_thickness);
  }
  check("aggregate_size", options.aggregate_size, options.aggregate_size >= 0.0,
        ">= 0 (m), 0 = no bound");
  check("mortar_size", options.mortar_size, options.mortar_size >= 0.0, ">= 0 (m), 0 = no bound");
  check("radius_edge_ratio", options.radius_edge_ratio,
        options.radius_edge_ratio == 0.0 ||
            (options.radius_edge_ratio >= 1.2 && options.radius_edge_ratio <= 10.0),
        "0 (none) or [1.2, 10]");
  if (options.cylinder_segments < 8 || options.cylinder_segments > 4096) {
    throw InvalidInput("cylinder_segments", std::to_string(options.cylinder_segments), "[8, 4096]");
  }
  check("min_dihedral", options.min_dihedral_degrees,
        options.min_dihedral_degrees >= 0.0 && options.min_dihedral_degrees < 70.0,
        "[0, 70) degrees");
  check("max_aspect_ratio", options.max_aspect_ratio, options.max_aspect_ratio >= 1.0, ">= 1");
  check("time_limit", options.time_limit,
        options.time_limit >= 0.001 && options.time_limit <= 604800.0, "[0.001, 604800] s");
}

namespace {

// Each particle's aggregate, shell, volumes and wall clearance; refuses a particle crossing or
// touching a wall.
std::vector<Inclusion> make_inclusions(const Packing& packing, const Prism& prism,
                                       const MesoOptions& options, double min_gap) {
  const double t = options.itz_thickness;
  std::vector<Inclusion> inclusions(packing.particles.size());
  parallel_for_index(0, inclusions.size(), [&](std::size_t i) {
    Inclusion& inclusion = inclusions[i];
    inclusion.particle = static_cast<std::uint32_t>(i + 1);
    inclusion.aggregate = packing.placed(i);
    const MassProperties mass = mass_properties(inclusion.aggregate);
    inclusion.aggregate_volume = mass.volume;
    inclusion.aggregate_area = mass.surface_area;
    inclusion.centroid = mass.centroid;
    inclusion.planes = face_half_spaces(inclusion.aggregate);
    inclusion.wall_clearance = std::numeric_limits<double>::infinity();
    for (const HalfSpace& wall : prism.planes) {
      for (const Vec3& v : inclusion.aggregate.vertices()) {
        inclusion.wall_clearance =
            std::min(inclusion.wall_clearance, wall.offset - wall.normal.dot(v));
      }
    }
    if (t > 0.0 && inclusion.wall_clearance > min_gap) {
      const detail::ItzLayer layer = detail::itz_layer(inclusion.aggregate, t, prism.planes);
      inclusion.shell = ConvexPolyhedron(layer.outer, inclusion.aggregate.triangles());
      inclusion.shell_volume = mass_properties(inclusion.shell).volume;
      inclusion.reach = layer.max_offset / t;
      inclusion.bounds = inclusion.shell.bounds();
    } else {
      inclusion.bounds = inclusion.aggregate.bounds();
    }
  });
  for (std::size_t i = 0; i < inclusions.size(); ++i) {
    if (inclusions[i].wall_clearance <= min_gap) {
      throw InvalidInput(
          Wording{Sentence::kParticleNumber, {std::to_string(i + 1)}},
          Wording{Sentence::kFromAWall, {metres(inclusions[i].wall_clearance)}},
          Wording{Sentence::kWallClearance, {metres(min_gap), "container.wall_gap"}});
    }
  }
  return inclusions;
}

// A periodic box's clipped images as inclusions (no ITZ: refused with a periodic box).
std::vector<Inclusion> piece_inclusions(const detail::PeriodicComplex& complex) {
  std::vector<Inclusion> inclusions(complex.pieces.size());
  parallel_for_index(0, inclusions.size(), [&](std::size_t i) {
    Inclusion& inclusion = inclusions[i];
    inclusion.particle = complex.piece_particle[i];
    inclusion.aggregate = complex.pieces[i];
    const MassProperties mass = mass_properties(inclusion.aggregate);
    inclusion.aggregate_volume = mass.volume;
    inclusion.aggregate_area = mass.surface_area;
    inclusion.centroid = mass.centroid;
    inclusion.planes = complex.piece_planes[i];
    inclusion.bounds = inclusion.aggregate.bounds();
  });
  return inclusions;
}

// A point of the mortar, searched on ever finer grids: outside every aggregate by more than its
// layer can reach (the aggregate is convex and exact, the layer's outer surface only nearly), and
// `margin` inside the walls.
bool find_mortar_seed(const std::vector<Inclusion>& inclusions, const Prism& prism,
                      double thickness, double margin, Vec3& seed) {
  Aabb box;
  for (const Vec3& p : prism.points) box.expand(p);
  for (int n = 2; n <= 32; n *= 2) {
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const Vec3 p =
              box.lower + (Vec3(i + 0.4142, j + 0.5317, k + 0.4729) / n).cwiseProduct(box.extent());
          bool is_free = true;
          for (const HalfSpace& wall : prism.planes)
            is_free &= wall.normal.dot(p) < wall.offset - margin;
          for (std::size_t b = 0; is_free && b < inclusions.size(); ++b) {
            const Inclusion& inclusion = inclusions[b];
            if ((p.array() < inclusion.bounds.lower.array() - margin).any() ||
                (p.array() > inclusion.bounds.upper.array() + margin).any()) {
              continue;
            }
            const double reach = thickness > 0.0 ? 2.0 * inclusion.reach * thickness : 0.0;
            is_free = plane_excess(inclusion.planes, p) > reach + margin;
          }
          if (is_free) {
            seed = p;
            return true;
          }
        }
      }
    }
  }
  return false;
}

// Region seeds avoid symmetric places (centroids, grid centres): Debian's TetGen 1.5 fails an
// assertion in locate() when a seed lies exactly on a face of its working mesh, which a cube's
// centroid or a face's centroid often does.
Vec3 generic_point(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.2913 * a + 0.3307 * b + 0.378 * c;
}

// A point inside the ITZ layer of `inclusion`: in the middle section of its thickest prism
// (largest area x smallest corner displacement), off the section's centre.
Vec3 itz_seed(const Inclusion& inclusion) {
  const ConvexPolyhedron& inner = inclusion.aggregate;
  const ConvexPolyhedron& outer = inclusion.shell;
  double best_score = -1.0;
  Vec3 best = Vec3::Zero();
  for (std::size_t f = 0; f < inner.triangle_count(); ++f) {
    const Triangle& tri = inner.triangles()[f];
    double thinnest = std::numeric_limits<double>::infinity();
    std::array<Vec3, 3> middle;
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = inner.vertices()[tri[k]];
      const Vec3& b = outer.vertices()[tri[k]];
      thinnest = std::min(thinnest, (b - a).norm());
      middle[k] = 0.5 * (a + b);
    }
    const double score = inner.face_normal_scaled(f).norm() * thinnest;
    if (score > best_score) {
      best_score = score;
      best = generic_point(middle[0], middle[1], middle[2]);
    }
  }
  return best;
}

// Fills each ITZ layer with its prisms' tetrahedra (3 per aggregate triangle). The layer's outer
// vertices follow the aggregate's in the PLC, so TetGen (which keeps the input points first and
// in order, checked here) numbered them aggregate_base + vertices + k. \throw LimitExceeded when
// a layer folds (its tetrahedra would overlap: an ITZ too thick for a particle's sharp corners).
void add_itz_layers(const std::vector<Inclusion>& inclusions,
                    const std::vector<std::uint32_t>& aggregate_base, int count, MesoMesh& mesh) {
  for (int i = 0; i < count; ++i) {
    const Inclusion& inclusion = inclusions[static_cast<std::size_t>(i)];
    const std::uint32_t inner = aggregate_base[static_cast<std::size_t>(i)];
    const auto outer = static_cast<std::uint32_t>(inner + inclusion.aggregate.vertex_count());
    for (std::size_t v = 0; v < inclusion.shell.vertex_count(); ++v) {
      if (mesh.nodes[outer + v] != inclusion.shell.vertices()[v] ||
          mesh.nodes[inner + v] != inclusion.aggregate.vertices()[v]) {
        throw LimitExceeded(Wording{Sentence::kMesomodelMesh, {}},
                            Wording{Sentence::kTetGenMovedPoint, {std::to_string(i + 1)}},
                            Wording{Sentence::kComplexTetGenKeeps, {}});
      }
    }
    std::vector<Tetrahedron> layer;
    detail::append_prism_tetrahedra(inclusion.aggregate.triangles(), inner, outer, layer);
    double volume = 0.0;
    for (Tetrahedron& tet : layer) {
      double v = tetra_volume(mesh.nodes[tet[0]], mesh.nodes[tet[1]], mesh.nodes[tet[2]],
                              mesh.nodes[tet[3]]);
      if (v < 0.0) {
        std::swap(tet[0], tet[1]);
        v = -v;
      }
      volume += v;
      mesh.tetrahedra.push_back(tet);
      mesh.phase.push_back(MesoPhase::kItz);
      mesh.particle.push_back(static_cast<std::uint32_t>(i + 1));
    }
    const double expected = inclusion.shell_volume - inclusion.aggregate_volume;
    if (!(std::abs(volume - expected) <= 1e-9 * expected)) {
      throw LimitExceeded(
          Wording{Sentence::kText, {"itz_thickness"}},
          Wording{Sentence::kItzFolds,
                  {std::to_string(i + 1), number((volume - expected) / expected, 3)}},
          Wording{Sentence::kThinnerItz, {}});
    }
  }
}

}  // namespace

MesoMesh build_mesomodel(const Packing& packing, const MesoOptions& given, MesoReport* report) {
  validate(given);
  const bool is_periodic_box = is_periodic(packing.container);
  if (is_periodic_box && given.itz_thickness > 0.0) {
    throw InvalidInput("itz_thickness", format_value(given.itz_thickness),
                       Wording{Sentence::kPeriodicNoItz, {}});
  }
  // A cohesive ITZ has no geometric thickness: the aggregates and the mortar are meshed bonded,
  // then split along the interfaces (split_cohesive_interfaces).
  const bool is_cohesive = given.itz_kind == ItzKind::kCohesive;
  MesoOptions options = given;
  if (is_cohesive) options.itz_thickness = 0.0;
  validate(packing.container);
  const Prism prism = make_prism(packing.container, options.cylinder_segments);
  const Aabb box = prism_bounds(packing.container, options.cylinder_segments);
  const double size = box.extent().maxCoeff();
  // Bodies closer than this count as touching (TetGen's own coplanarity tolerance is 1e-8 of the
  // domain's size; stay well clear of it).
  const double min_gap = 1e-7 * size;
  const double t = options.itz_thickness;
  const bool has_itz = t > 0.0;
  // Walls: each a facet with points on a grid inside it (one-vertex polygons), so that the mortar
  // at the walls, and the node sets a load acts on, are not a handful of long triangles (-Y keeps
  // every input facet as TetGen triangulates it, adding no point of its own).
  const double wall_spacing = options.mortar_size > 0.0 ? options.mortar_size : size / 50.0;
  std::vector<Inclusion> inclusions;
  detail::Plc plc;
  if (is_periodic_box) {
    detail::PeriodicComplex complex = detail::periodic_complex(packing, wall_spacing, min_gap);
    inclusions = piece_inclusions(complex);
    plc = std::move(complex.plc);
  } else {
    inclusions = make_inclusions(packing, prism, options, min_gap);
    plc.points = prism.points;
  }
  check_gaps(inclusions, options, min_gap);
  for (std::size_t w = 0; w < prism.faces.size() && !is_periodic_box; ++w) {
    detail::PlcFacet facet{{prism.faces[w]}, -static_cast<int>(w) - 1};
    for (const Vec3& p : wall_grid(prism, w, wall_spacing)) {
      facet.polygons.push_back({static_cast<std::uint32_t>(plc.points.size())});
      plc.points.push_back(p);
    }
    plc.facets.push_back(std::move(facet));
  }
  const auto count = static_cast<int>(packing.particles.size());
  std::vector<std::uint32_t> aggregate_base;  // PLC number of each aggregate's first vertex
  for (const Inclusion& inclusion : inclusions) {
    const auto id = static_cast<int>(inclusion.particle);
    auto base = static_cast<std::uint32_t>(plc.points.size());
    aggregate_base.push_back(base);
    if (!is_periodic_box) {  // a periodic box's pieces are in the complex already
      plc.points.insert(plc.points.end(), inclusion.aggregate.vertices().begin(),
                        inclusion.aggregate.vertices().end());
      for (const Triangle& tri : inclusion.aggregate.triangles()) {
        plc.facets.push_back({{{base + tri[0], base + tri[1], base + tri[2]}}, 2 * id});
      }
    }
    const Vec3& centroid = inclusion.centroid;
    const Triangle& first = inclusion.aggregate.triangles()[0];
    const Vec3 off_centre = generic_point(inclusion.aggregate.vertices()[first[0]],
                                          inclusion.aggregate.vertices()[first[1]],
                                          inclusion.aggregate.vertices()[first[2]]);
    plc.regions.push_back({centroid + 0.1372 * (off_centre - centroid), id,
                           regular_tetra_volume(options.aggregate_size)});
    if (!has_itz) continue;
    base = static_cast<std::uint32_t>(plc.points.size());
    // The layer's outer surface bounds a hole in TetGen's domain; aggpack fills the layer with
    // prisms after TetGen (append_prism_tetrahedra).
    plc.points.insert(plc.points.end(), inclusion.shell.vertices().begin(),
                      inclusion.shell.vertices().end());
    for (const Triangle& tri : inclusion.shell.triangles()) {
      plc.facets.push_back({{{base + tri[0], base + tri[1], base + tri[2]}}, 2 * id + 1});
    }
    plc.holes.push_back(itz_seed(inclusion));
  }
  Vec3 mortar_seed;
  if (find_mortar_seed(inclusions, prism, t, min_gap, mortar_seed)) {
    plc.regions.push_back({mortar_seed, 0, regular_tetra_volume(options.mortar_size)});
  }

  std::string switches = "pYzQA";
  if (options.radius_edge_ratio > 0.0) switches += "q" + number(options.radius_edge_ratio, 6);
  if (options.aggregate_size > 0.0 || options.mortar_size > 0.0) switches += 'a';
  // For experiments and bug reports only: TetGen's switches as given (docs/mesomodel.md).
  if (const char* own = std::getenv("AGGPACK_TETGEN_SWITCHES"); own != nullptr && *own != 0) {
    switches = own;
  }
  const auto start = std::chrono::steady_clock::now();
  detail::PlcMesh raw = detail::tetrahedralize_plc(plc, switches, options.time_limit);
  if (is_periodic_box) {  // again, with the lower faces' triangles on the upper faces too
    detail::copy_lower_face_triangles(raw, periodic_axes(packing.container), box.extent(), plc);
    raw = detail::tetrahedralize_plc(plc, switches, options.time_limit);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  MesoMesh mesh;
  mesh.nodes = std::move(raw.nodes);
  mesh.tetrahedra = std::move(raw.tetrahedra);
  mesh.phase.resize(mesh.tetrahedra.size(), MesoPhase::kMortar);
  mesh.particle.resize(mesh.tetrahedra.size(), 0);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const int a = raw.attributes[e];
    if (a >= 1 && a <= count) {
      mesh.phase[e] = MesoPhase::kAggregate;
      mesh.particle[e] = static_cast<std::uint32_t>(a);
    } else if (a > count && a <= 2 * count) {
      mesh.phase[e] = MesoPhase::kItz;
      mesh.particle[e] = static_cast<std::uint32_t>(a - count);
    }
  }
  mesh.particle_count = static_cast<std::uint32_t>(count);
  mesh.bounds = box;
  mesh.periodic = periodic_axes(packing.container);
  mesh.itz_thickness = t;
  mesh.container = packing.container;
  mesh.prism_sides = options.cylinder_segments;

  std::vector<detail::PhaseBody> bodies(inclusions.size());
  parallel_for_index(0, bodies.size(), [&](std::size_t i) {
    bodies[i].planes = inclusions[i].planes;
    bodies[i].bounds = inclusions[i].aggregate.bounds();
    bodies[i].particle = inclusions[i].particle;
  });
  const std::size_t relabelled = detail::relabel_by_geometry(bodies, 1e-10 * size, mesh);
  if (has_itz) add_itz_layers(inclusions, aggregate_base, count, mesh);
  if (is_cohesive) split_cohesive_interfaces(mesh, given.itz_thickness);

  MesoReport measured = measure_mesomodel(mesh);
  measured.relabelled_tetrahedra = relabelled;
  measured.container_volume = prism.volume;
  measured.mesh_seconds = seconds;
  measured.tetgen_switches = switches;
  double aggregates = 0.0;
  double shells = 0.0;
  for (const Inclusion& inclusion : inclusions) {
    aggregates += inclusion.aggregate_volume;
    shells += has_itz ? inclusion.shell_volume : inclusion.aggregate_volume;
    if (is_cohesive) {
      measured.expected_interface_area += inclusion.aggregate_area;
    }
  }
  measured.phases[static_cast<int>(MesoPhase::kAggregate)].expected_volume = aggregates;
  measured.phases[static_cast<int>(MesoPhase::kItz)].expected_volume = shells - aggregates;
  measured.phases[static_cast<int>(MesoPhase::kMortar)].expected_volume = prism.volume - shells;
  double min_dihedral = 180.0;
  double max_aspect = 1.0;
  for (const MesoPhaseReport& phase : measured.phases) {
    if (phase.quality.tetrahedra == 0) continue;
    min_dihedral = std::min(min_dihedral, phase.quality.min_dihedral_degrees);
    max_aspect = std::max(max_aspect, phase.quality.max_aspect_ratio);
  }
  if (report != nullptr) *report = measured;
  if (min_dihedral < options.min_dihedral_degrees) {
    throw LimitExceeded(Wording{Sentence::kText, {"min_dihedral"}},
                        Wording{Sentence::kDegreesInMesh, {number(min_dihedral, 3)}},
                        Wording{Sentence::kMinDihedral, {number(options.min_dihedral_degrees)}});
  }
  if (max_aspect > options.max_aspect_ratio) {
    throw LimitExceeded(Wording{Sentence::kText, {"max_aspect_ratio"}},
                        Wording{Sentence::kInTheMesh, {number(max_aspect)}},
                        Wording{Sentence::kAtMost, {number(options.max_aspect_ratio)}});
  }
  return mesh;
}

}  // namespace aggpack
