// ExportModel (export_detail.h): the per-shape measures and meshes every exporter reads, and the
// per-particle placement of nodes in output coordinates.

#include <cmath>
#include <cstdint>

#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"
#include "export_detail.h"

namespace aggpack::detail {

ExportModel::ExportModel(const Packing& packing, const ExportOptions& options, ElementMode mode,
                         std::size_t first, std::size_t last)
    : packing_(packing), options_(options), mode_(mode), first_(first), last_(last) {
  std::vector<char> is_used(packing.shapes.size(), 0);
  for (std::size_t k = 0; k < size(); ++k) is_used[particle(k).shape] = 1;
  shapes_.resize(packing.shapes.size());
  const bool is_tetgen =
      mode != ElementMode::kSurface && options.tetrahedra.method == TetMethod::kTetGen;
  if (is_tetgen) mesh_with_tetgen(is_used);
  auto measure = [&](std::size_t s) {
    if (!is_used[s]) return;
    const ConvexPolyhedron& body = packing.shapes[s];
    const MassProperties properties = mass_properties(body);
    ShapeInfo& info = shapes_[s];
    info.volume = properties.volume;
    info.centroid = properties.centroid;
    if (properties.volume > 0 && properties.surface_area > 0) {
      info.sphericity = aggpack::sphericity(properties.volume, properties.surface_area);
      info.alpha = aggpack::measured_alpha(properties.volume, properties.surface_area);
    }
    if (mode == ElementMode::kSurface) {
      info.nodes = static_cast<std::uint32_t>(body.vertex_count());
      info.elements = static_cast<std::uint32_t>(body.triangle_count());
      return;
    }
    if (!is_tetgen && !(properties.volume > 0)) {
      throw InvalidInput(Wording{Sentence::kShapeVolume, {std::to_string(s)}},
                         Wording{Sentence::kText, {format_value(properties.volume)}},
                         Wording{Sentence::kClosedConvexBody, {}});
    }
    const std::size_t linear_nodes =
        is_tetgen ? shape_meshes_[s].nodes.size() : body.vertex_count() + 1;
    info.elements = static_cast<std::uint32_t>(is_tetgen ? shape_meshes_[s].tetrahedra.size()
                                                         : body.triangle_count());
    info.nodes = static_cast<std::uint32_t>(linear_nodes);
    if (is_tetgen) {
      info.quality = measure_quality(shape_meshes_[s].nodes, shape_meshes_[s].tetrahedra);
    } else {
      std::vector<Vec3> nodes = body.vertices();
      nodes.push_back(properties.centroid);
      std::vector<Tetrahedron> fan;
      fan.reserve(body.triangle_count());
      for (const Triangle& t : body.triangles()) {
        fan.push_back(fan_tetrahedron(t, static_cast<std::uint32_t>(body.vertex_count())));
      }
      info.quality = measure_quality(nodes, fan);
    }
    if (mode == ElementMode::kQuadraticTetrahedra) {
      // Fan edges are the surface edges (3F/2) plus one spoke per vertex.
      const std::size_t edges = is_tetgen ? count(shape_meshes_[s]).edges
                                          : body.triangle_count() * 3 / 2 + body.vertex_count();
      info.nodes = static_cast<std::uint32_t>(linear_nodes + edges);
    }
  };
  parallel_for_index(0, packing.shapes.size(), measure);
  node_offsets_.resize(size() + 1, 0);
  element_offsets_.resize(size() + 1, 0);
  for (std::size_t k = 0; k < size(); ++k) {
    const ShapeInfo& info = shapes_[particle(k).shape];
    node_offsets_[k + 1] = node_offsets_[k] + info.nodes;
    element_offsets_[k + 1] = element_offsets_[k] + info.elements;
  }
}

// TetGen runs in worker processes (tetgen_meshes); a shape it fails on, e.g. one where Debian's
// TetGen 1.5 aborts, is cut as the paper's centroid fan and reported instead of failing the export.
void ExportModel::mesh_with_tetgen(const std::vector<char>& is_used) {
  std::vector<std::uint32_t> shapes;
  std::vector<const ConvexPolyhedron*> bodies;
  for (std::size_t s = 0; s < is_used.size(); ++s) {
    if (!is_used[s]) continue;
    shapes.push_back(static_cast<std::uint32_t>(s));
    bodies.push_back(&packing_.shapes[s]);
  }
  std::vector<TetGenOutcome> outcomes = tetgen_meshes(bodies, options_.tetrahedra);
  shape_meshes_.resize(packing_.shapes.size());
  tetgen_shape_count_ = shapes.size();
  std::vector<std::size_t> fallback_of(packing_.shapes.size(), SIZE_MAX);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const std::uint32_t s = shapes[i];
    if (outcomes[i].is_meshed) {
      shape_meshes_[s] = std::move(outcomes[i].mesh);
      continue;
    }
    shape_meshes_[s] = centroid_fan(packing_.shapes[s]);
    fallback_of[s] = tetgen_fallbacks_.size();
    tetgen_fallbacks_.push_back(
        {.shape = s, .failure = std::move(outcomes[i].failure), .particles = {}});
  }
  for (std::size_t k = 0; k < size(); ++k) {
    const std::size_t fallback = fallback_of[particle(k).shape];
    if (fallback != SIZE_MAX) tetgen_fallbacks_[fallback].particles.push_back(particle_number(k));
  }
}

std::string ExportModel::particle_name(std::size_t k) const {
  std::string name = "P";
  name += std::to_string(particle_number(k));
  return name;
}

Vec3 ExportModel::place(std::size_t k, const Vec3& local) const {
  const Particle& p = particle(k);
  return options_.scale * (p.pose.rotation * (p.scale * local) + p.pose.position);
}

void ExportModel::surface_nodes(std::size_t k, std::vector<Vec3>& nodes) const {
  const auto& vertices = packing_.shapes[particle(k).shape].vertices();
  nodes.resize(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) nodes[i] = place(k, vertices[i]);
}

const std::vector<Triangle>& ExportModel::triangles(std::size_t k) const {
  return packing_.shapes[particle(k).shape].triangles();
}

void ExportModel::linear_nodes(std::size_t k, std::vector<Vec3>& nodes) const {
  const std::uint32_t s = particle(k).shape;
  if (!shape_meshes_.empty()) {
    const std::vector<Vec3>& local = shape_meshes_[s].nodes;
    nodes.resize(local.size());
    for (std::size_t i = 0; i < local.size(); ++i) nodes[i] = place(k, local[i]);
    return;
  }
  surface_nodes(k, nodes);
  if (mode_ != ElementMode::kSurface) nodes.push_back(place(k, shapes_[s].centroid));
}

const std::vector<Tetrahedron>& ExportModel::tetrahedra(std::size_t k,
                                                        std::vector<Tetrahedron>& scratch) const {
  const std::uint32_t s = particle(k).shape;
  if (!shape_meshes_.empty()) return shape_meshes_[s].tetrahedra;
  const ConvexPolyhedron& body = packing_.shapes[s];
  const auto centre = static_cast<std::uint32_t>(body.vertex_count());
  scratch.resize(body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    scratch[f] = fan_tetrahedron(body.triangles()[f], centre);
  }
  return scratch;
}

QuadraticTopology ExportModel::quadratic_topology(std::size_t k) const {
  if (mode_ != ElementMode::kQuadraticTetrahedra) return {};
  const std::uint32_t s = particle(k).shape;
  const std::size_t corners =
      shape_meshes_.empty() ? packing_.shapes[s].vertex_count() + 1 : shape_meshes_[s].nodes.size();
  std::vector<Tetrahedron> scratch;
  return aggpack::quadratic_topology(tetrahedra(k, scratch), static_cast<std::uint32_t>(corners));
}

const std::vector<std::uint8_t>& ExportModel::boundary_faces(std::size_t k) const {
  return shape_meshes_[particle(k).shape].boundary_faces;
}

double ExportModel::volume(std::size_t k) const {
  const double factor = particle(k).scale * options_.scale;
  return shapes_[particle(k).shape].volume * factor * factor * factor;
}
double ExportModel::sphericity(std::size_t k) const {
  return shapes_[particle(k).shape].sphericity;
}
double ExportModel::alpha(std::size_t k) const { return shapes_[particle(k).shape].alpha; }
double ExportModel::control_radius(std::size_t k) const {
  return particle(k).control_radius * options_.scale;
}
std::uint32_t ExportModel::size_class(std::size_t k) const { return particle(k).size_class; }

TetQuality ExportModel::quality() const {
  TetQuality total;
  if (mode_ == ElementMode::kSurface) return total;
  std::vector<std::uint64_t> uses(shapes_.size(), 0);
  for (std::size_t k = 0; k < size(); ++k) ++uses[particle(k).shape];
  for (std::size_t s = 0; s < shapes_.size(); ++s) total.add(shapes_[s].quality, uses[s]);
  return total;
}

}  // namespace aggpack::detail
