#pragma once
// Internal to the renderer (renderer*.cpp): the GPU-side types, the depth pyramid and
// PackingRenderer::State, which the renderer's files share.

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/core/clock.h"
#include "aggpack/render/renderer.h"
#include "depth_pyramid.h"

namespace aggpack {

namespace render_detail {

// A mesh vertex. A mesh used by one particle is stored in world coordinates with that particle's
// index; an instanced mesh in its shape's coordinates with particle 0 (the particle index and
// its transform come from the per-instance attributes, GpuInstance). The shader adds both
// indices and applies the instance's transform (the identity for single-use meshes), so one
// program serves both paths.
struct GpuVertex {
  float x, y, z;
  std::uint32_t particle;
};

// A particle's transform: world = placement.xyz + rotate(rotation, placement.w * vertex), with
// the rotation a unit quaternion (x, y, z, w).
struct GpuTransform {
  std::array<float, 4> placement{0.0f, 0.0f, 0.0f, 1.0f};  // translation (m), scale
  std::array<float, 4> rotation{0.0f, 0.0f, 0.0f, 1.0f};
};

// One instance of an instanced draw, streamed each frame (element 0: the identity, which the
// single-use meshes read): its transform and particle index.
struct GpuInstance {
  GpuTransform transform;
  std::uint32_t particle = 0;
};

// Where a shape's data lives in the vertex and index buffers of its mesh page.
struct ShapeRange {
  std::uint32_t page = 0;  // mesh page (SceneData::pages, State::mesh_pages)
  GLint base_vertex = 0;   // in the page
  GLuint full_offset = 0;  // first index in the page (not bytes)
  GLsizei full_count = 0;
  GLuint coarse_offset = 0;
  GLsizei coarse_count = 0;
  std::uint32_t instances = 0;
  double radius = 0.0;  // largest vertex distance from the local origin (m, before scale)
  // Radius of the ball about the local origin that lies inside the shape (smallest distance to
  // a face plane): certainly solid, so it may hide what is behind it (m, before scale).
  double inner_radius = 0.0;
};

// A particle's bounding and inscribed spheres in world coordinates (m).
struct ParticleSphere {
  float x, y, z;
  float radius;
  float inner_radius;
};

// A particle in the view, for culling and level-of-detail decisions.
struct Candidate {
  float near_depth;          // view depth of the nearest point of the bounding sphere (m)
  float footprint;           // half-width of a screen square holding the bounding sphere (px)
  float depth;               // view depth of the centre (m)
  float pixels;              // projected diameter of the bounding sphere (px)
  float screen_x, screen_y;  // projected centre (px, origin lower left)
  std::uint32_t particle;
};

// One point of the impostor stream.
struct GpuPoint {
  float x, y, z, radius;
  std::uint8_t r, g, b, a;
};

// Unsigned key that orders like the float (negative values first).
inline std::uint32_t float_order_key(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

// Sorts 64-bit keys by their upper 32 bits, ties in their present order, with two 16-bit radix
// passes: linear in the count, where std::sort on 10^5 keys cost several milliseconds a frame.
void sort_by_high_word(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& scratch);

}  // namespace render_detail

using namespace render_detail;  // NOLINT(google-build-using-namespace): internal header

// One buffer of a scene upload: the GL buffer, its bytes and their data, and the bytes of
// storage the buffer has (a scene that fits is copied into it, with no new allocation).
struct UploadPiece {
  GLuint buffer;
  std::size_t bytes;
  const void* data;
  std::size_t* capacity;
};

// Most bytes of vertices, and of indices, in one mesh page. The driver clears a buffer's new
// storage (llvmpipe: about 1 ms per MB), so a scene's meshes go to buffers of a few MB, each
// allocated in an upload step of its own budget, not to one buffer of hundreds of MB.
constexpr std::size_t kPageBytes = std::size_t{4} << 20;

// A page of the scene's meshes: whole shapes (indices local to a shape; each draw adds the
// shape's base vertex in the page).
struct ScenePage {
  std::vector<GpuVertex> vertices;
  std::vector<std::uint32_t> indices;
  // The same indices in 16 bits when every shape has at most 65,536 vertices, else empty.
  std::vector<std::uint16_t> short_indices;
};

// Per-frame scratch of a scene's size, allocated and touched on the thread that prepares the
// scene, so the first frame does not pay for fresh memory on the drawing thread.
struct FrameScratch {
  std::vector<Candidate> candidates, sorted;
  std::vector<std::uint64_t> sort_keys, sort_scratch;
  std::vector<std::vector<Candidate>> chunk_candidates;
  std::vector<std::uint8_t> is_hidden_flag, was_visible;
  std::vector<std::uint32_t> group_counts, group_start, cursor;  // two per shape
};

// Everything drawn from a packing, computed without OpenGL (prepare_scene, on any thread) and
// uploaded by PackingRenderer::begin_upload / upload_step in bounded pieces.
struct SceneData {
  std::vector<ShapeRange> shapes;
  std::vector<std::uint32_t> instanced_shapes;
  std::vector<std::uint32_t> particle_shape;
  std::vector<ParticleSphere> particle_sphere;
  std::vector<float> impostor_radius;
  std::array<ParticleColors, 3> colors;
  Aabb bounds;
  std::vector<ScenePage> pages;
  bool is_short_index = false;  // the pages' indices are 16-bit (half the memory to copy)
  // Per particle, for the instance stream (kept on the CPU: no GL buffer of all particles, whose
  // storage the driver would clear in one piece).
  std::vector<GpuTransform> transforms;
  std::vector<float> lines;       // container outline, 3 per vertex
  std::size_t merged_shapes = 0;  // shapes drawn as a scaled copy of another
  FrameScratch scratch;
};

// The GL objects of one mesh page: its vertex array (the vertex and index buffers and the
// shared per-instance attribute) and the bytes of storage its buffers have.
struct MeshPage {
  GLuint vertex_array = 0, vertex_buffer = 0, index_buffer = 0;
  std::size_t vertex_capacity = 0, index_capacity = 0;
};

// Most particles one step of a frame submits (step_frame), and most full-detail mesh triangles:
// about 30 ms on llvmpipe.
constexpr std::size_t kStepParticles = 12000;
constexpr std::size_t kStepTriangles = 60000;

// Particles per chunk of the frustum pass (one task on the cores).
constexpr std::size_t kFrustumChunk = 8192;

// Chunks of the frustum pass per step of a frame (about 260,000 particles: 10-20 ms).
constexpr std::size_t kFrustumChunksPerStep = 32;

// Below this many particles in view, drawing them all costs less than a depth read-back.
constexpr std::size_t kOcclusionMinParticles = 4000;

struct PackingRenderer::State {
  GLuint particle_program = 0;
  GLint u_colors = -1, u_view = -1, u_projection = -1, u_lit = -1;
  GLuint line_program = 0;
  GLint u_view_projection = -1, u_line_color = -1;
  GLuint point_program = 0;
  GLint p_view = -1, p_projection = -1, p_lit = -1;
  GLuint point_array = 0, point_buffer = 0;

  std::vector<MeshPage> mesh_pages;  // as many as the largest scene needed (kept for reuse)
  std::size_t page_count = 0;        // pages of the uploaded scene
  GLuint instance_buffer = 0;
  GLuint color_buffer = 0, color_texture = 0;
  GLuint line_array = 0, line_buffer = 0;
  GLsizei line_vertex_count = 0;

  std::vector<ShapeRange> shapes;
  std::vector<std::uint32_t> instanced_shapes;  // shapes drawn instanced (>= 2 particles)
  std::vector<std::uint32_t> particle_shape;
  std::vector<ParticleSphere> particle_sphere;
  std::array<ParticleColors, 3> colors;
  int uploaded_color = -1;  // ColorMode whose colours are in color_buffer, -1 = none
  Aabb bounds;

  // Per-frame scratch, kept to avoid reallocating.
  std::vector<Candidate> candidates;
  std::vector<Candidate> sorted;
  std::vector<std::uint64_t> sort_keys, sort_scratch;
  std::vector<std::vector<Candidate>> chunk_candidates;  // frustum pass, per chunk of particles
  std::vector<std::uint8_t> is_hidden_flag;              // occlusion test, per candidate
  std::vector<std::uint8_t> level;                       // per candidate: 0 full, 1 coarse, 2 point
  DepthPyramid depth_pyramid;
  // Per particle: not found hidden when last drawn (drawn first next frame, as occluders).
  std::vector<std::uint8_t> was_visible;
  bool has_visibility = false;    // was_visible holds a frame's result
  std::size_t visible_count = 0;  // particles set in was_visible
  std::vector<std::uint32_t> point_list;
  std::vector<GpuPoint> points;
  std::vector<float> impostor_radius;  // per particle (m)
  std::vector<GpuInstance> instance_list;
  std::vector<GpuTransform> transforms;  // per particle
  std::vector<std::uint32_t> group_counts;
  std::vector<std::uint32_t> group_start, cursor;
  std::vector<std::uint32_t> page_single_start;  // per page: its first single-use draw (+ end)
  std::vector<std::uint32_t> page_cursor;        // per page: its next single-use draw
  std::vector<GLsizei> single_counts;
  std::vector<const void*> single_offsets;
  std::vector<GLint> single_base_vertices;

  // The scene being uploaded (begin_upload / upload_step), null when none: its buffers in order
  // (per page vertices and indices, outline), the buffer and byte reached.
  std::shared_ptr<SceneData> pending;
  std::vector<UploadPiece> upload_list;
  std::size_t pending_buffer = 0, pending_offset = 0;
  std::size_t upload_total = 0, upload_done = 0;  // bytes of the upload, and copied
  std::size_t line_capacity = 0;
  std::size_t merged_shapes = 0;
  GLenum index_type = GL_UNSIGNED_INT;  // of the uploaded index buffers
  std::uintptr_t index_size = 4;        // their bytes per index
  // Points the bound vertex array's per-instance attributes (2 particle, 3 placement, 4
  // rotation) at element `first` of instance_buffer, which must be bound to GL_ARRAY_BUFFER.
  void point_instances_at(std::size_t first);
  // Whether piece pending_buffer's buffer has less storage than the piece (its capacity is set
  // when storage is allocated, so a piece needs it at most once), and the bytes a copy into it
  // of at most max_bytes (at least 1) moves: upload_step's units, which next_upload_bytes sizes.
  [[nodiscard]] bool needs_storage() const;
  [[nodiscard]] std::size_t copy_bytes(std::size_t max_bytes) const;
  // Creates the GL objects of mesh page `page` (once).
  void ensure_mesh_page(std::size_t page);
  // Frees the pending scene's copy of piece `piece` once uploaded, so the memory goes back in
  // pieces and not all in the frame that ends the upload.
  void release_piece(std::size_t piece);

  // The frame begun by begin_frame(), drawn by step_frame().
  struct Frame {
    // Next step: 5 frustum pass (a piece of it per step), 6 sort and set-up of the passes, 1
    // first pass (a piece of it per step), 2 depth read-back, 7 occlusion test, 3 rest (a piece
    // per step), 4 container outline only, 0 done.
    int step = 0;
    int width = 1, height = 1;
    RenderStyle style;
    Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
    Eigen::Matrix4f projection = Eigen::Matrix4f::Identity();
    Eigen::Matrix4f view_projection = Eigen::Matrix4f::Identity();
    // The view volume's six planes (columns), normalised.
    Eigen::Matrix<float, 4, 6> planes = Eigen::Matrix<float, 4, 6>::Zero();
    float pixel_scale = 1.0f;    // pixels per metre at view depth 1 (perspective)
    std::size_t next_chunk = 0;  // frustum pass: next chunk of particles
    bool is_orthographic = false;
    bool is_culled = false;  // occlusion culling this frame
    std::size_t first = 0;   // candidates [0, first) are drawn in the first pass
    std::size_t chunk = 0;   // candidates per step of a pass
    std::size_t cursor = 0;  // next candidate to submit in the pass under way
    std::size_t used = 0;    // mesh triangles of the first pass
    DrawStats stats;
  };
  Frame frame;

  // The frustum pass over chunks [first_chunk, last_chunk) of particles (kFrustumChunk each, on
  // all cores) into chunk_candidates; then finish_frustum joins them in order, sorts front to
  // back and sets up the drawing passes.
  void frustum_chunks(std::size_t first_chunk, std::size_t last_chunk);
  void finish_frustum();

  // The end of the next step's piece of candidates [begin, end): at most `most`, and about one
  // view of `width` x `height` pixels' worth of their bounding discs (at least one).
  [[nodiscard]] std::size_t step_end(std::size_t begin, std::size_t end, std::size_t most,
                                     int width, int height) const;

  // Draws candidates [begin, end) (front to back) with levels of detail chosen by size and at
  // most `budget` mesh triangles (0 = no limit); adds to `stats`; returns the mesh triangles.
  std::size_t submit(std::size_t begin, std::size_t end, std::size_t budget,
                     const RenderStyle& style, const Eigen::Matrix4f& view,
                     const Eigen::Matrix4f& projection, DrawStats& stats);

  // The steps of submit (renderer_submit.cpp), over candidates [begin, begin + count).
  // Hash threshold under the particle cap: particles whose mix_hash is >= it are left out.
  [[nodiscard]] std::uint64_t keep_below(std::size_t count, const RenderStyle& style,
                                         const DrawStats& stats) const;
  // Mesh triangles of candidate begin + k at its level (0 for points and left-out ones).
  [[nodiscard]] std::size_t triangles_of(std::size_t begin, std::size_t k) const;
  // Sets `level` (0 full, 1 coarse, 2 point, 3 left out) by size, cap and triangle budget;
  // returns the mesh triangles and counts the left-out candidates.
  std::size_t choose_levels(std::size_t begin, std::size_t count, std::size_t budget,
                            const RenderStyle& style, std::uint64_t keep_below_hash,
                            std::size_t& left_out);
  // Fills single_*, group_counts and point_list by level; returns the coarse particles.
  std::size_t build_draw_lists(std::size_t begin, std::size_t count);
  // Fills instance_list (element 0, then one block per (shape, level) group) and group_start;
  // returns its length.
  std::uint32_t build_instance_list(std::size_t begin, std::size_t count);
  void draw_meshes(const RenderStyle& style, const Eigen::Matrix4f& view,
                   const Eigen::Matrix4f& projection, DrawStats& stats);
  void draw_points(const RenderStyle& style, const Eigen::Matrix4f& view,
                   const Eigen::Matrix4f& projection, DrawStats& stats);

  void upload_colors(ColorMode mode) {
    const auto& source = colors[static_cast<std::size_t>(mode)].colors;
    std::vector<std::uint8_t> texels(std::max<std::size_t>(source.size(), 1) * 4, 255);
    for (std::size_t i = 0; i < source.size(); ++i) {
      texels[4 * i] = source[i].r;
      texels[4 * i + 1] = source[i].g;
      texels[4 * i + 2] = source[i].b;
    }
    glBindBuffer(GL_TEXTURE_BUFFER, color_buffer);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(texels.size()), texels.data(),
                 GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    uploaded_color = static_cast<int>(mode);
  }
};

}  // namespace aggpack
