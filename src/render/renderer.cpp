// OpenGL 3.3 core drawing of a Packing. See renderer.h for the approach; comments here say why.
// This file: the packing's upload (set_packing) and accessors. Also renderer_setup.cpp (GL
// objects), renderer_frame.cpp (a frame: culling, occlusion, steps), renderer_submit.cpp (levels
// of detail and draw calls).

#include "aggpack/render/renderer.h"

#include "aggpack/core/error.h"
#include "aggpack/geom/overlap.h"
#include "aggpack/pack/container.h"
#include "renderer_state.h"

namespace aggpack {

namespace {

// The coarse level of detail: the shape's support vertices in the 6 axis and 8 diagonal
// directions, joined like a tetrakis hexahedron (each octant: its diagonal vertex fanned to the
// three axis vertices around it; 14 vertices, 24 triangles, closed). It reuses the shape's own
// vertices, so only indices are added. Orientation is fixed from the ideal directions, so the
// triangles face outward whenever the support points are in general position; coincident
// support points only give zero-area triangles.
std::vector<std::uint32_t> coarse_indices(const ConvexPolyhedron& shape) {
  const auto& vertices = shape.vertices();
  auto support = [&](const Vec3& direction) {
    std::uint32_t best = 0;
    double best_value = -std::numeric_limits<double>::infinity();
    for (std::uint32_t v = 0; v < vertices.size(); ++v) {
      const double value = vertices[v].dot(direction);
      if (value > best_value) {
        best_value = value;
        best = v;
      }
    }
    return best;
  };
  std::vector<std::uint32_t> indices;
  indices.reserve(72);
  for (int octant = 0; octant < 8; ++octant) {
    const Vec3 sign((octant & 1) ? -1.0 : 1.0, (octant & 2) ? -1.0 : 1.0,
                    (octant & 4) ? -1.0 : 1.0);
    const Vec3 diagonal_direction = sign;
    const std::array<Vec3, 3> axis_directions = {Vec3(sign.x(), 0, 0), Vec3(0, sign.y(), 0),
                                                 Vec3(0, 0, sign.z())};
    const std::uint32_t diagonal = support(diagonal_direction);
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = axis_directions[static_cast<std::size_t>(k)];
      const Vec3& b = axis_directions[static_cast<std::size_t>((k + 1) % 3)];
      const bool is_outward =
          (a - diagonal_direction).cross(b - diagonal_direction).dot(diagonal_direction) > 0.0;
      const std::uint32_t va = support(a);
      const std::uint32_t vb = support(b);
      indices.push_back(diagonal);
      indices.push_back(is_outward ? va : vb);
      indices.push_back(is_outward ? vb : va);
    }
  }
  return indices;
}

}  // namespace

void PackingRenderer::set_packing(const Packing& packing) {
  State& s = *state_;
  const std::size_t particle_count = packing.particles.size();
  for (std::size_t i = 0; i < particle_count; ++i) {
    if (packing.particles[i].shape >= packing.shapes.size()) {
      throw InvalidInput("particles[" + std::to_string(i) + "].shape",
                         std::to_string(packing.particles[i].shape),
                         "[0, " + std::to_string(packing.shapes.size()) + ")");
    }
  }
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (4.0 * static_cast<double>(particle_count) > static_cast<double>(max_texels)) {
    throw LimitExceeded("particle count", std::to_string(particle_count),
                        "<= " + std::to_string(max_texels / 4) + " for this OpenGL driver");
  }

  // Which shapes are used, and how often: a shape used once carries its particle index in its
  // vertices and joins one multi-draw; a shape used more often is drawn instanced.
  s.shapes.assign(packing.shapes.size(), ShapeRange{});
  for (const auto& particle : packing.particles) ++s.shapes[particle.shape].instances;
  std::vector<std::uint32_t> single_owner(packing.shapes.size(), 0);
  for (std::size_t i = 0; i < particle_count; ++i) {
    single_owner[packing.particles[i].shape] = static_cast<std::uint32_t>(i);
  }

  std::vector<GpuVertex> vertices;
  std::vector<std::uint32_t> indices;
  s.instanced_shapes.clear();
  for (std::size_t shape_index = 0; shape_index < packing.shapes.size(); ++shape_index) {
    ShapeRange& range = s.shapes[shape_index];
    const ConvexPolyhedron& shape = packing.shapes[shape_index];
    for (const Vec3& v : shape.vertices()) range.radius = std::max(range.radius, v.norm());
    range.inner_radius = std::min(range.radius, inner_radius(shape));
    if (range.instances == 0 || shape.is_empty()) continue;
    if (range.instances >= 2) s.instanced_shapes.push_back(static_cast<std::uint32_t>(shape_index));
    const std::uint32_t particle = range.instances == 1 ? single_owner[shape_index] : 0;
    range.base_vertex = static_cast<GLint>(vertices.size());
    for (const Vec3& v : shape.vertices()) {
      vertices.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()),
                          static_cast<float>(v.z()), particle});
    }
    range.full_offset = static_cast<GLuint>(indices.size());
    for (const Triangle& t : shape.triangles()) indices.insert(indices.end(), t.begin(), t.end());
    range.full_count = static_cast<GLsizei>(indices.size() - range.full_offset);
    range.coarse_offset = static_cast<GLuint>(indices.size());
    if (shape.triangle_count() > 24) {
      const auto coarse = coarse_indices(shape);
      indices.insert(indices.end(), coarse.begin(), coarse.end());
      range.coarse_count = static_cast<GLsizei>(coarse.size());
    } else {
      // Already as coarse as the coarse level: reuse the full mesh.
      range.coarse_offset = range.full_offset;
      range.coarse_count = range.full_count;
    }
  }

  // Transforms: rows of [scale * R | t] (float is ample: 1e-7 relative to the scene size), then
  // the impostor radius (volume-equivalent, m).
  const ShapeMeasures measures = measure_shapes(packing);
  std::vector<float> transforms(std::max<std::size_t>(particle_count, 1) * 16, 0.0f);
  s.particle_shape.resize(particle_count);
  s.particle_sphere.resize(particle_count);
  s.impostor_radius.resize(particle_count);
  s.bounds = Aabb{};
  const Aabb container_bounds = packing.container.bounds();
  if (!container_bounds.is_empty()) {
    s.bounds.expand(container_bounds.lower);
    s.bounds.expand(container_bounds.upper);
  }
  for (std::size_t i = 0; i < particle_count; ++i) {
    const Particle& particle = packing.particles[i];
    const Mat3 linear = particle.pose.rotation.normalized().toRotationMatrix() * particle.scale;
    const Vec3& t = particle.pose.position;
    for (int row = 0; row < 3; ++row) {
      for (int column = 0; column < 3; ++column) {
        transforms[16 * i + 4 * static_cast<std::size_t>(row) + static_cast<std::size_t>(column)] =
            static_cast<float>(linear(row, column));
      }
      transforms[16 * i + 4 * static_cast<std::size_t>(row) + 3] = static_cast<float>(t[row]);
    }
    transforms[16 * i + 12] =
        static_cast<float>(0.5 * measures.equivalent_diameter[particle.shape] * particle.scale);
    s.impostor_radius[i] = transforms[16 * i + 12];
    const double radius = s.shapes[particle.shape].radius * particle.scale;
    s.particle_shape[i] = particle.shape;
    s.particle_sphere[i] = {
        static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z()),
        static_cast<float>(radius),
        static_cast<float>(s.shapes[particle.shape].inner_radius * particle.scale)};
    s.bounds.expand(t - Vec3::Constant(radius));
    s.bounds.expand(t + Vec3::Constant(radius));
  }

  glBindBuffer(GL_ARRAY_BUFFER, s.vertex_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(GpuVertex)),
               vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindVertexArray(s.vertex_array);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);

  glBindBuffer(GL_TEXTURE_BUFFER, s.transform_buffer);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(transforms.size() * sizeof(float)),
               transforms.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  glBindTexture(GL_TEXTURE_BUFFER, s.transform_texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, s.transform_buffer);
  glBindTexture(GL_TEXTURE_BUFFER, s.color_texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA8, s.color_buffer);
  glBindTexture(GL_TEXTURE_BUFFER, 0);

  for (ColorMode mode : {ColorMode::kParticle, ColorMode::kSize, ColorMode::kAlpha}) {
    s.colors[static_cast<std::size_t>(mode)] = particle_colors(packing, measures, mode);
  }
  s.upload_colors(ColorMode::kParticle);

  // Container outline as line segments.
  std::vector<float> lines;
  auto add_segment = [&lines](const Vec3& a, const Vec3& b) {
    for (const Vec3* p : {&a, &b}) {
      lines.push_back(static_cast<float>(p->x()));
      lines.push_back(static_cast<float>(p->y()));
      lines.push_back(static_cast<float>(p->z()));
    }
  };
  for (const OutlineSegment& segment : container_outline(packing.container)) {
    add_segment(segment[0], segment[1]);
  }
  s.line_vertex_count = static_cast<GLsizei>(lines.size() / 3);
  glBindBuffer(GL_ARRAY_BUFFER, s.line_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(float)), lines.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

const DrawStats& PackingRenderer::frame_stats() const { return state_->frame.stats; }

bool PackingRenderer::is_frame_pending() const { return state_->frame.step != 0; }

const Aabb& PackingRenderer::scene_bounds() const { return state_->bounds; }

const ParticleColors& PackingRenderer::colors(ColorMode mode) const {
  return state_->colors[static_cast<std::size_t>(mode)];
}

std::size_t PackingRenderer::particle_count() const { return state_->particle_shape.size(); }

std::size_t PackingRenderer::shape_count() const { return state_->shapes.size(); }

}  // namespace aggpack
