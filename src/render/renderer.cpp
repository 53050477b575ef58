// OpenGL 3.3 core drawing of a Packing. See renderer.h for the approach; comments here say why.
// This file: the packing's upload (set_packing) and accessors. Also renderer_setup.cpp (GL
// objects), renderer_frame.cpp (a frame: culling, occlusion, steps), renderer_submit.cpp (levels
// of detail and draw calls).

#include "aggpack/render/renderer.h"

#include <unordered_map>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
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

// Shape `candidate` as a scaled copy of `base`: the factor c with candidate = c * base (same
// triangles, every vertex in proportion to 1e-9 of the size), or 0 when it is not one.
double copy_scale(const ConvexPolyhedron& base, double base_radius,
                  const ConvexPolyhedron& candidate, double candidate_radius) {
  if (base_radius <= 0.0 || candidate_radius <= 0.0) return 0.0;
  if (base.vertices().size() != candidate.vertices().size() ||
      base.triangles() != candidate.triangles()) {
    return 0.0;
  }
  const double c = candidate_radius / base_radius;
  const double tolerance = 1e-9 * candidate_radius;
  for (std::size_t k = 0; k < base.vertices().size(); ++k) {
    if ((candidate.vertices()[k] - c * base.vertices()[k]).lpNorm<Eigen::Infinity>() > tolerance) {
      return 0.0;
    }
  }
  return c;
}

// A hash of a shape up to scale: its triangles and its vertices divided by its radius, rounded
// to 1e-6 (scaled copies whose rounding differs only miss the sharing).
std::uint64_t shape_key(const ConvexPolyhedron& shape, double radius) {
  std::uint64_t hash = 1469598103934665603ull ^ shape.vertices().size();
  auto mix = [&hash](std::uint64_t value) {
    hash ^= value + 0x9e3779b97f4a7c15ull + (hash << 6) + (hash >> 2);
  };
  for (const Triangle& t : shape.triangles()) {
    for (auto index : t) mix(index);
  }
  if (radius <= 0.0) return hash;
  for (const Vec3& v : shape.vertices()) {
    for (int axis = 0; axis < 3; ++axis) {
      mix(static_cast<std::uint64_t>(std::llround(1e6 * v[axis] / radius)));
    }
  }
  return hash;
}

}  // namespace

std::shared_ptr<SceneData> prepare_scene(const Packing& packing,
                                         const std::function<void(double)>& progress,
                                         const std::atomic<bool>* cancel,
                                         std::size_t mesh_page_bytes) {
  const std::size_t page_bytes = mesh_page_bytes > 0 ? mesh_page_bytes : kPageBytes;
  auto scene = std::make_shared<SceneData>();
  SceneData& s = *scene;
  const std::size_t particle_count = packing.particles.size();
  const std::size_t shape_count = packing.shapes.size();
  for (std::size_t i = 0; i < particle_count; ++i) {
    if (packing.particles[i].shape >= shape_count) {
      throw InvalidInput("particles[" + std::to_string(i) + "].shape",
                         std::to_string(packing.particles[i].shape),
                         "[0, " + std::to_string(shape_count) + ")");
    }
  }
  // Progress: shapes measured (40 %), colours (40 %), meshes and transforms (20 %).
  auto report = [&](double fraction) {
    if (progress) progress(fraction);
    return cancel == nullptr || !cancel->load();
  };
  if (!report(0.0)) return nullptr;

  // Per shape: its radius and inner radius (every shape, on all cores), then which earlier
  // shape it is a scaled copy of (drawn with that one's mesh).
  s.shapes.assign(shape_count, ShapeRange{});
  std::vector<std::uint8_t> is_used(shape_count, 0);
  for (const auto& particle : packing.particles) is_used[particle.shape] = 1;
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (shape_count + kBlock - 1) / kBlock;
  std::atomic<bool> is_cancelled{false};
  parallel_for_index(0, blocks, [&](std::size_t block) {
    if (is_cancelled.load()) return;
    for (std::size_t k = block * kBlock; k < std::min(shape_count, (block + 1) * kBlock); ++k) {
      ShapeRange& range = s.shapes[k];
      const ConvexPolyhedron& shape = packing.shapes[k];
      for (const Vec3& v : shape.vertices()) range.radius = std::max(range.radius, v.norm());
      range.inner_radius = std::min(range.radius, inner_radius(shape));
    }
    if (cancel != nullptr && cancel->load()) is_cancelled = true;
  });
  if (!report(0.2)) return nullptr;
  std::vector<std::uint32_t> mesh_of(shape_count);   // shape whose mesh draws shape k
  std::vector<double> mesh_scale(shape_count, 1.0);  // shape k = mesh_scale * that mesh
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_key;
  for (std::size_t k = 0; k < shape_count; ++k) {
    mesh_of[k] = static_cast<std::uint32_t>(k);
    if (is_used[k] == 0 || packing.shapes[k].is_empty()) continue;
    auto& same_key = by_key[shape_key(packing.shapes[k], s.shapes[k].radius)];
    for (std::uint32_t base : same_key) {
      const double c = copy_scale(packing.shapes[base], s.shapes[base].radius, packing.shapes[k],
                                  s.shapes[k].radius);
      if (c > 0.0) {
        mesh_of[k] = base;
        mesh_scale[k] = c;
        ++s.merged_shapes;
        break;
      }
    }
    if (mesh_of[k] == k) same_key.push_back(static_cast<std::uint32_t>(k));
  }
  by_key.clear();

  // Which meshes are used, and how often: a mesh used once carries its particle index in its
  // vertices and joins one multi-draw; a mesh used more often is drawn instanced.
  for (const auto& particle : packing.particles) ++s.shapes[mesh_of[particle.shape]].instances;
  std::vector<std::uint32_t> single_owner(shape_count, 0);
  for (std::size_t i = 0; i < particle_count; ++i) {
    single_owner[mesh_of[packing.particles[i].shape]] = static_cast<std::uint32_t>(i);
  }
  if (!report(0.4)) return nullptr;

  const ShapeMeasures measures = measure_shapes(packing);
  if (!report(0.6)) return nullptr;
  for (ColorMode mode : {ColorMode::kParticle, ColorMode::kSize, ColorMode::kAlpha}) {
    s.colors[static_cast<std::size_t>(mode)] = particle_colors(packing, measures, mode);
  }
  if (!report(0.8)) return nullptr;

  // Per particle: its transform (translation, scale with the mesh's, unit quaternion; float is
  // ample: 1e-7 relative to the scene size), mesh, spheres and impostor radius.
  auto& transforms = s.transforms;
  transforms.resize(particle_count);
  s.particle_shape.resize(particle_count);
  s.particle_sphere.resize(particle_count);
  s.impostor_radius.resize(particle_count);
  const Aabb container_bounds = packing.container.bounds();
  if (!container_bounds.is_empty()) {
    s.bounds.expand(container_bounds.lower);
    s.bounds.expand(container_bounds.upper);
  }
  for (std::size_t i = 0; i < particle_count; ++i) {
    const Particle& particle = packing.particles[i];
    const Quat rotation = particle.pose.rotation.normalized();
    const Vec3& t = particle.pose.position;
    transforms[i].placement = {static_cast<float>(t.x()), static_cast<float>(t.y()),
                               static_cast<float>(t.z()),
                               static_cast<float>(particle.scale * mesh_scale[particle.shape])};
    transforms[i].rotation = {static_cast<float>(rotation.x()), static_cast<float>(rotation.y()),
                              static_cast<float>(rotation.z()), static_cast<float>(rotation.w())};
    // The impostor radius (volume-equivalent, m).
    s.impostor_radius[i] =
        static_cast<float>(0.5 * measures.equivalent_diameter[particle.shape] * particle.scale);
    const double radius = s.shapes[particle.shape].radius * particle.scale;
    s.particle_shape[i] = mesh_of[particle.shape];
    s.particle_sphere[i] = {
        static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z()),
        static_cast<float>(radius),
        static_cast<float>(s.shapes[particle.shape].inner_radius * particle.scale)};
    s.bounds.expand(t - Vec3::Constant(radius));
    s.bounds.expand(t + Vec3::Constant(radius));
  }

  // Meshes in pages of at most page_bytes of vertices and of indices, whole shapes per page (a
  // shape larger than a page has a page of its own). Indices are 16-bit when every shape has at
  // most 65,536 vertices (indices are local to a shape: each draw adds its base vertex).
  std::size_t most_vertices = 0;
  for (std::size_t k = 0; k < shape_count; ++k) {
    if (s.shapes[k].instances > 0) {
      most_vertices = std::max(most_vertices, packing.shapes[k].vertices().size());
    }
  }
  s.is_short_index = most_vertices <= 65536;
  const std::size_t index_bytes = s.is_short_index ? 2 : 4;
  for (std::size_t shape_index = 0; shape_index < shape_count; ++shape_index) {
    ShapeRange& range = s.shapes[shape_index];
    const ConvexPolyhedron& shape = packing.shapes[shape_index];
    if (range.instances == 0 || shape.is_empty()) continue;
    if (range.instances >= 2) s.instanced_shapes.push_back(static_cast<std::uint32_t>(shape_index));
    const std::size_t index_count = 3 * (shape.triangle_count() + 24);
    if (s.pages.empty() ||
        (!s.pages.back().vertices.empty() &&
         ((s.pages.back().vertices.size() + shape.vertices().size()) * sizeof(GpuVertex) >
              page_bytes ||
          (s.pages.back().indices.size() + index_count) * index_bytes > page_bytes))) {
      s.pages.emplace_back();
    }
    auto& vertices = s.pages.back().vertices;
    auto& indices = s.pages.back().indices;
    range.page = static_cast<std::uint32_t>(s.pages.size() - 1);
    range.base_vertex = static_cast<GLint>(vertices.size());
    if (range.instances == 1) {
      // Used once: in world coordinates, with its particle's index.
      const std::uint32_t owner = single_owner[shape_index];
      const Particle& particle = packing.particles[owner];
      const Quat rotation = particle.pose.rotation.normalized();
      const double scale = particle.scale * mesh_scale[particle.shape];
      for (const Vec3& v : shape.vertices()) {
        const Vec3 world = particle.pose.position + rotation * (scale * v);
        vertices.push_back({static_cast<float>(world.x()), static_cast<float>(world.y()),
                            static_cast<float>(world.z()), owner});
      }
    } else {
      for (const Vec3& v : shape.vertices()) {
        vertices.push_back(
            {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()), 0});
      }
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
  if (s.is_short_index) {
    for (ScenePage& page : s.pages) {
      page.short_indices.assign(page.indices.begin(), page.indices.end());
      page.indices = std::vector<std::uint32_t>();
    }
  }
  if (!report(0.9)) return nullptr;

  // The first frames' scratch, touched here (the drawing thread then reuses it).
  FrameScratch& scratch = s.scratch;
  scratch.candidates.resize(particle_count);
  scratch.sorted.resize(particle_count);
  scratch.sort_keys.resize(particle_count);
  scratch.sort_scratch.resize(particle_count);
  scratch.is_hidden_flag.resize(particle_count);
  scratch.was_visible.assign(particle_count, 0);
  scratch.chunk_candidates.resize((particle_count + kFrustumChunk - 1) / kFrustumChunk);
  for (auto& chunk : scratch.chunk_candidates) chunk.resize(kFrustumChunk);
  scratch.group_counts.resize(2 * s.shapes.size());
  scratch.group_start.resize(2 * s.shapes.size());
  scratch.cursor.resize(2 * s.shapes.size());

  // Container outline as line segments.
  auto& lines = s.lines;
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
  if (!report(1.0)) return nullptr;
  return scene;
}

void PackingRenderer::set_packing(const Packing& packing) {
  begin_upload(prepare_scene(packing));
  while (!upload_step(std::numeric_limits<std::size_t>::max())) {
  }
}

void PackingRenderer::begin_upload(std::shared_ptr<SceneData> scene) {
  State& s = *state_;
  if (!scene) throw InvalidInput("scene", "null", "a prepared scene");
  const std::size_t particle_count = scene->particle_shape.size();
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (static_cast<double>(particle_count) > static_cast<double>(max_texels)) {  // colours
    throw LimitExceeded(Wording{Sentence::kParticleCount, {}},
                        Wording{Sentence::kText, {std::to_string(particle_count)}},
                        Wording{Sentence::kOpenGlTexels, {std::to_string(max_texels)}});
  }
  s.frame.step = 0;  // the frame under way used the buffers about to change
  s.pending = std::move(scene);
  s.pending_buffer = 0;
  s.pending_offset = 0;
  SceneData& pending = *s.pending;
  s.upload_list.clear();
  // All pages' GL objects first: the pieces point at their capacities.
  if (!pending.pages.empty()) s.ensure_mesh_page(pending.pages.size() - 1);
  for (std::size_t page = 0; page < pending.pages.size(); ++page) {
    const ScenePage& data = pending.pages[page];
    MeshPage& mesh = s.mesh_pages[page];
    s.upload_list.push_back({mesh.vertex_buffer, data.vertices.size() * sizeof(GpuVertex),
                             data.vertices.data(), &mesh.vertex_capacity});
    s.upload_list.push_back(
        pending.is_short_index
            ? UploadPiece{mesh.index_buffer, data.short_indices.size() * sizeof(std::uint16_t),
                          data.short_indices.data(), &mesh.index_capacity}
            : UploadPiece{mesh.index_buffer, data.indices.size() * sizeof(std::uint32_t),
                          data.indices.data(), &mesh.index_capacity});
  }
  s.upload_list.push_back({s.line_buffer, pending.lines.size() * sizeof(float),
                           pending.lines.data(), &s.line_capacity});
  s.upload_total = 0;
  s.upload_done = 0;
  for (const UploadPiece& piece : s.upload_list) s.upload_total += piece.bytes;
}

void PackingRenderer::State::release_piece(std::size_t piece) {
  const std::size_t page = piece / 2;
  if (page < pending->pages.size()) {
    ScenePage& data = pending->pages[page];
    if (piece % 2 == 0) {
      data.vertices = std::vector<GpuVertex>();
    } else {
      data.indices = std::vector<std::uint32_t>();
      data.short_indices = std::vector<std::uint16_t>();
    }
  }
}

bool PackingRenderer::State::needs_storage() const {
  const UploadPiece& piece = upload_list[pending_buffer];
  return piece.bytes > *piece.capacity;  // else the buffer holds it (a repeated pack, or done)
}

std::size_t PackingRenderer::State::copy_bytes(std::size_t max_bytes) const {
  return std::min(std::max<std::size_t>(max_bytes, 1),
                  upload_list[pending_buffer].bytes - pending_offset);
}

std::size_t PackingRenderer::next_upload_bytes(std::size_t max_bytes) const {
  const State& s = *state_;
  if (!s.pending) return 0;
  if (s.pending_buffer == s.upload_list.size()) return 4 * s.pending->particle_shape.size();
  return s.needs_storage() ? s.upload_list[s.pending_buffer].bytes : s.copy_bytes(max_bytes);
}

bool PackingRenderer::upload_step(std::size_t max_bytes) {
  State& s = *state_;
  if (!s.pending) return true;
  const auto& pieces = s.upload_list;
  if (s.pending_buffer < pieces.size()) {
    // One unit of work: a buffer's new storage (the driver clears it: about as costly per byte
    // as a copy), or a copy of at most max_bytes into it; the scene goes into use in a step of
    // its own after the last piece.
    const UploadPiece& piece = pieces[s.pending_buffer];
    glBindBuffer(GL_COPY_WRITE_BUFFER, piece.buffer);
    if (s.needs_storage()) {
      *piece.capacity = std::max<std::size_t>(piece.bytes, 4);
      glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(*piece.capacity), nullptr,
                   GL_STATIC_DRAW);
      glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
      return false;
    }
    const std::size_t bytes = s.copy_bytes(max_bytes);
    if (bytes > 0) {
      glBufferSubData(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(s.pending_offset),
                      static_cast<GLsizeiptr>(bytes),
                      static_cast<const char*>(piece.data) + s.pending_offset);
      s.pending_offset += bytes;
      s.upload_done += bytes;
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    if (s.pending_offset >= piece.bytes) {
      s.release_piece(s.pending_buffer);
      ++s.pending_buffer;
      s.pending_offset = 0;
    }
    return false;
  }

  // All uploaded: the scene's CPU side replaces the last one's.
  SceneData& scene = *s.pending;
  s.shapes = std::move(scene.shapes);
  s.instanced_shapes = std::move(scene.instanced_shapes);
  s.particle_shape = std::move(scene.particle_shape);
  s.particle_sphere = std::move(scene.particle_sphere);
  s.transforms = std::move(scene.transforms);
  s.impostor_radius = std::move(scene.impostor_radius);
  s.colors = std::move(scene.colors);
  s.bounds = scene.bounds;
  s.merged_shapes = scene.merged_shapes;
  s.index_type = scene.is_short_index ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
  s.index_size = scene.is_short_index ? 2u : 4u;
  s.page_count = scene.pages.size();
  s.line_vertex_count = static_cast<GLsizei>(scene.lines.size() / 3);
  // The scratch touched on the preparing thread, where it is larger than what is here.
  FrameScratch& scratch = scene.scratch;
  auto take = [](auto& mine, auto& prepared) {
    if (prepared.capacity() > mine.capacity()) mine.swap(prepared);
  };
  take(s.candidates, scratch.candidates);
  take(s.sorted, scratch.sorted);
  take(s.sort_keys, scratch.sort_keys);
  take(s.sort_scratch, scratch.sort_scratch);
  take(s.is_hidden_flag, scratch.is_hidden_flag);
  take(s.chunk_candidates, scratch.chunk_candidates);
  take(s.group_counts, scratch.group_counts);
  take(s.group_start, scratch.group_start);
  take(s.cursor, scratch.cursor);
  s.candidates.clear();
  s.was_visible.swap(scratch.was_visible);  // all zero, one per particle
  s.pending.reset();
  s.has_visibility = false;
  s.visible_count = 0;
  glBindTexture(GL_TEXTURE_BUFFER, s.color_texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA8, s.color_buffer);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  s.upload_colors(ColorMode::kParticle);
  return true;
}

bool PackingRenderer::is_upload_pending() const { return state_->pending != nullptr; }

double PackingRenderer::upload_progress() const {
  const State& s = *state_;
  if (!s.pending) return 1.0;
  const std::size_t total = s.upload_total, done = s.upload_done;
  return total > 0 ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
}

std::size_t PackingRenderer::merged_shape_count() const { return state_->merged_shapes; }

const DrawStats& PackingRenderer::frame_stats() const { return state_->frame.stats; }

bool PackingRenderer::is_frame_pending() const { return state_->frame.step != 0; }

const Aabb& PackingRenderer::scene_bounds() const { return state_->bounds; }

const ParticleColors& PackingRenderer::colors(ColorMode mode) const {
  return state_->colors[static_cast<std::size_t>(mode)];
}

std::size_t PackingRenderer::particle_count() const { return state_->particle_shape.size(); }

std::size_t PackingRenderer::shape_count() const { return state_->shapes.size(); }

}  // namespace aggpack
