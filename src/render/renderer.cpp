// OpenGL 3.3 core drawing of a Packing. See renderer.h for the approach; comments here say why.

#include "aggpack/render/renderer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

namespace aggpack {

namespace {

// One particle (for shapes used once: its index) or 0 (instanced shapes: the particle index
// comes from the per-instance attribute). The shader adds both, so one program serves both paths.
struct GpuVertex {
  float x, y, z;
  std::uint32_t particle;
};

// Where a shape's data lives in the shared vertex and index buffers.
struct ShapeRange {
  GLint base_vertex = 0;
  GLuint full_offset = 0;  // first index (not bytes)
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

constexpr const char* kParticleVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in uint a_particle;
layout(location = 2) in uint a_instance;
uniform samplerBuffer u_transforms;  // four texels per particle: rows of [scale * R | t], radius
uniform samplerBuffer u_colors;      // one normalised RGBA8 texel per particle
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_view_position;
flat out vec3 v_color;
void main() {
  int id = int(a_particle + a_instance);
  vec4 p = vec4(a_position, 1.0);
  vec3 world = vec3(dot(texelFetch(u_transforms, 4 * id), p),
                    dot(texelFetch(u_transforms, 4 * id + 1), p),
                    dot(texelFetch(u_transforms, 4 * id + 2), p));
  vec4 view = u_view * vec4(world, 1.0);
  v_view_position = view.xyz;
  v_color = texelFetch(u_colors, id).rgb;
  gl_Position = u_projection * view;
}
)";

// Flat facet normal from screen-space derivatives of the view position: exact per triangle
// (position is linear across a triangle) and needs no per-face vertices. Two lights fixed to the
// camera (key from the upper left, weaker fill from the lower right) plus ambient, and a small
// specular term so neighbouring facets of similar orientation still read as separate.
#define AGGPACK_SHADE_GLSL                                                                   \
  "vec3 shade(vec3 color, vec3 n) {\n"                                                       \
  "  vec3 key = normalize(vec3(-0.45, 0.6, 0.65));\n"                                        \
  "  vec3 fill = normalize(vec3(0.55, -0.35, 0.55));\n"                                      \
  "  float diffuse = 0.28 + 0.62 * max(dot(n, key), 0.0) + 0.22 * max(dot(n, fill), 0.0);\n" \
  "  vec3 half_vector = normalize(key + vec3(0.0, 0.0, 1.0));\n"                             \
  "  float power = max(dot(n, half_vector), 0.0);\n"                                         \
  "  power *= power; power *= power; power *= power; power *= power; power *= power;\n"      \
  "  float specular = 0.22 * power;\n"                                                       \
  "  return color * diffuse + vec3(specular);\n"                                             \
  "}\n"

constexpr const char* kParticleFragmentShader = "#version 330 core\n" AGGPACK_SHADE_GLSL R"(
in vec3 v_view_position;
flat in vec3 v_color;
uniform int u_lit;
out vec4 fragment;
void main() {
  vec3 color = v_color;
  if (u_lit != 0) color = shade(color, normalize(cross(dFdx(v_view_position), dFdy(v_view_position))));
  fragment = vec4(color, 1.0);
}
)";

// Impostor for particles a few pixels across: one view-facing triangle circumscribing a disc of
// the volume-equivalent radius, shaded as a ball with the same lights as the facets. One
// triangle, not a point sprite: llvmpipe expands wide points into two triangles on a slow path.
// Per-impostor data comes as vertex attributes (repeated on the triangle's three vertices), not
// buffer-texture fetches, which llvmpipe runs far slower in vertex shaders.
constexpr const char* kPointVertexShader = R"(#version 330 core
layout(location = 0) in vec4 a_sphere;  // centre (m), impostor radius (m)
layout(location = 1) in vec4 a_color;   // normalised RGBA8
uniform mat4 u_view;
uniform mat4 u_projection;
flat out vec3 v_color;
out vec2 v_disc;  // position in units of the disc radius
void main() {
  // Corners of the equilateral triangle whose inscribed circle is the unit circle.
  const vec2 corners[3] = vec2[3](vec2(0.0, 2.0), vec2(-1.7320508, -1.0), vec2(1.7320508, -1.0));
  v_disc = corners[gl_VertexID % 3];
  vec4 view = u_view * vec4(a_sphere.xyz, 1.0);
  // Bring the billboard forward by the radius so it is not hidden inside neighbouring facets.
  view.xyz += vec3(v_disc * a_sphere.w, 0.0) + normalize(-view.xyz) * a_sphere.w * 0.5;
  v_color = a_color.rgb;
  gl_Position = u_projection * view;
}
)";

// One point of the impostor stream.
struct GpuPoint {
  float x, y, z, radius;
  std::uint8_t r, g, b, a;
};

constexpr const char* kPointFragmentShader = "#version 330 core\n" AGGPACK_SHADE_GLSL R"(
flat in vec3 v_color;
in vec2 v_disc;
uniform int u_lit;
out vec4 fragment;
void main() {
  vec2 q = v_disc;
  float r2 = dot(q, q);
  if (r2 > 1.0) discard;
  vec3 color = u_lit != 0 ? shade(v_color, vec3(q, sqrt(1.0 - r2))) : v_color;
  fragment = vec4(color, 1.0);
}
)";

constexpr const char* kLineVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * vec4(a_position, 1.0); }
)";

constexpr const char* kLineFragmentShader = R"(#version 330 core
uniform vec3 u_color;
out vec4 fragment;
void main() { fragment = vec4(u_color, 1.0); }
)";

[[noreturn]] void throw_gl(const std::string& message) { throw IoError("OpenGL: " + message); }

GLuint compile_shader(GLenum type, const char* source) {
  const GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint is_compiled = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &is_compiled);
  if (is_compiled == 0) {
    std::array<char, 2048> log{};
    glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteShader(shader);
    throw_gl(std::string("shader compilation failed: ") + log.data());
  }
  return shader;
}

GLuint link_program(const char* vertex_source, const char* fragment_source) {
  const GLuint vertex = compile_shader(GL_VERTEX_SHADER, vertex_source);
  const GLuint fragment = compile_shader(GL_FRAGMENT_SHADER, fragment_source);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint is_linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &is_linked);
  if (is_linked == 0) {
    std::array<char, 2048> log{};
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteProgram(program);
    throw_gl(std::string("shader link failed: ") + log.data());
  }
  return program;
}

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

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A well-mixed 32-bit hash of an index (Wellons' lowbias32).
std::uint32_t mix_hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// Unsigned key that orders like the float (negative values first).
std::uint32_t float_order_key(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

// Sorts 64-bit keys by their upper 32 bits, ties in their present order, with two 16-bit radix
// passes: linear in the count, where std::sort on 10^5 keys cost several milliseconds a frame.
void sort_by_high_word(std::vector<std::uint64_t>& keys, std::vector<std::uint64_t>& scratch) {
  const std::size_t n = keys.size();
  scratch.resize(n);
  std::array<std::uint32_t, 65536> counts;
  for (int shift : {32, 48}) {
    counts.fill(0u);
    for (std::size_t c = 0; c < n; ++c) ++counts[(keys[c] >> shift) & 0xffffu];
    std::uint32_t sum = 0;
    for (auto& count : counts) {
      const std::uint32_t here = count;
      count = sum;
      sum += here;
    }
    for (std::size_t c = 0; c < n; ++c) scratch[counts[(keys[c] >> shift) & 0xffffu]++] = keys[c];
    keys.swap(scratch);
  }
}

// Sorts by near_depth, ties in their present order.
void sort_front_to_back(std::vector<Candidate>& candidates, std::vector<std::uint64_t>& keys,
                        std::vector<std::uint64_t>& key_scratch, std::vector<Candidate>& scratch) {
  const std::size_t n = candidates.size();
  keys.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    keys[c] = (static_cast<std::uint64_t>(float_order_key(candidates[c].near_depth)) << 32) | c;
  }
  sort_by_high_word(keys, key_scratch);
  scratch.resize(n);
  for (std::size_t c = 0; c < n; ++c) scratch[c] = candidates[keys[c] & 0xffffffffu];
  candidates.swap(scratch);
}

// Occlusion test against the depth buffer: the drawn depth read back and reduced to a pyramid
// of maxima (each level halves the resolution), so a screen rectangle is tested with a few
// texels of the level where it spans at most four.
class DepthPyramid {
 public:
  // Reads the depth of the bound framebuffer's pixels (0, 0) to (width, height) (window depth in
  // [0, 1]) and builds the levels.
  void build(int width, int height) {
    widths_.assign(1, width);
    heights_.assign(1, height);
    levels_.resize(1);
    levels_[0].resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, levels_[0].data());
    int w = width, h = height;
    for (std::size_t level = 1; w > 1 || h > 1; ++level) {
      const int nw = (w + 1) / 2, nh = (h + 1) / 2;
      if (levels_.size() <= level) levels_.emplace_back();
      const std::vector<float>& fine = levels_[level - 1];
      std::vector<float>& coarse = levels_[level];
      coarse.resize(static_cast<std::size_t>(nw) * static_cast<std::size_t>(nh));
      for (int y = 0; y < nh; ++y) {
        const float* row0 = fine.data() + static_cast<std::size_t>(2 * y) * w;
        const float* row1 = fine.data() + static_cast<std::size_t>(std::min(2 * y + 1, h - 1)) * w;
        float* out = coarse.data() + static_cast<std::size_t>(y) * nw;
        for (int x = 0; x < nw; ++x) {
          const int x1 = std::min(2 * x + 1, w - 1);
          out[x] = std::max(std::max(row0[2 * x], row0[x1]), std::max(row1[2 * x], row1[x1]));
        }
      }
      widths_.push_back(nw);
      heights_.push_back(nh);
      w = nw;
      h = nh;
    }
    levels_.resize(widths_.size());
  }

  // True if every pixel of the square of half-width `radius` about (x, y) (pixels, lower-left
  // origin; the part outside the image is ignored) holds a depth nearer than `depth`.
  [[nodiscard]] bool is_hidden(float x, float y, float radius, float depth) const {
    const int ix0 = std::max(0, static_cast<int>(std::floor(x - radius)));
    const int iy0 = std::max(0, static_cast<int>(std::floor(y - radius)));
    const int ix1 = std::min(widths_[0] - 1, static_cast<int>(std::floor(x + radius)));
    const int iy1 = std::min(heights_[0] - 1, static_cast<int>(std::floor(y + radius)));
    if (ix0 > ix1 || iy0 > iy1) return false;
    // A well hidden particle is hidden at a coarse level already (a small, cache-friendly
    // array); otherwise test the level where the square spans <= 8 texels.
    if (is_hidden_at(level_spanning(ix0, iy0, ix1, iy1, 2), ix0, iy0, ix1, iy1, depth)) return true;
    // Texels of the fine level that meet the disc of `radius` (the square's corners hold
    // neighbours' gaps more often than not).
    const std::size_t level = level_spanning(ix0, iy0, ix1, iy1, 8);
    const int w = widths_[level];
    const float size = static_cast<float>(1 << level);
    const float radius2 = radius * radius;
    const std::vector<float>& texels = levels_[level];
    for (int ty = iy0 >> level; ty <= iy1 >> level; ++ty) {
      const float dy = std::max({0.0f, ty * size - y, y - (ty + 1) * size});
      if (!(dy * dy < radius2)) continue;
      // The texels of this row within `half` of x across: tx * size - x < half and
      // x - (tx + 1) * size < half. Widened by a hundredth of a texel against rounding, so it
      // never tests fewer texels than the disc meets (more only makes the test more cautious).
      const float half = std::sqrt(radius2 - dy * dy) + 0.01f * size;
      const int tx0 = std::max(ix0 >> level, static_cast<int>(std::floor((x - half) / size)));
      const int tx1 = std::min(ix1 >> level, static_cast<int>(std::ceil((x + half) / size)) - 1);
      const float* row = texels.data() + static_cast<std::size_t>(ty) * w;
      for (int tx = tx0; tx <= tx1; ++tx) {
        if (!(row[tx] < depth)) return false;
      }
    }
    return true;
  }

 private:
  // The finest level where pixels [x0, x1] x [y0, y1] span at most `span` texels each way.
  [[nodiscard]] std::size_t level_spanning(int x0, int y0, int x1, int y1, int span) const {
    std::size_t level = 0;
    while (level + 1 < levels_.size() &&
           ((x1 >> level) - (x0 >> level) >= span || (y1 >> level) - (y0 >> level) >= span)) {
      ++level;
    }
    return level;
  }

  [[nodiscard]] bool is_hidden_at(std::size_t level, int x0, int y0, int x1, int y1,
                                  float depth) const {
    const int w = widths_[level];
    const std::vector<float>& texels = levels_[level];
    for (int y = y0 >> level; y <= y1 >> level; ++y) {
      const float* row = texels.data() + static_cast<std::size_t>(y) * w;
      for (int x = x0 >> level; x <= x1 >> level; ++x) {
        if (!(row[x] < depth)) return false;
      }
    }
    return true;
  }

 private:
  std::vector<std::vector<float>> levels_;
  std::vector<int> widths_, heights_;
};

}  // namespace

// Below this many particles in view, drawing them all costs less than a depth read-back.
constexpr std::size_t kOcclusionMinParticles = 4000;

struct PackingRenderer::State {
  GLuint particle_program = 0;
  GLint u_transforms = -1, u_colors = -1, u_view = -1, u_projection = -1, u_lit = -1;
  GLuint line_program = 0;
  GLint u_view_projection = -1, u_line_color = -1;
  GLuint point_program = 0;
  GLint p_view = -1, p_projection = -1, p_lit = -1;
  GLuint point_array = 0, point_buffer = 0;

  GLuint vertex_array = 0;
  GLuint vertex_buffer = 0;
  GLuint index_buffer = 0;
  GLuint instance_buffer = 0;
  GLuint transform_buffer = 0, transform_texture = 0;
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
  std::vector<std::uint32_t> instance_list;
  std::vector<std::uint32_t> group_counts;
  std::vector<std::uint32_t> group_start, cursor;
  std::vector<GLsizei> single_counts;
  std::vector<const void*> single_offsets;
  std::vector<GLint> single_base_vertices;

  // The frame begun by begin_frame(), drawn by step_frame().
  struct Frame {
    // Next step: 1 first pass (or its nearer half), 5 the first pass's farther half, 2 read-back
    // + occlusion test, 3 rest, 4 container outline only, 0 done.
    int step = 0;
    int width = 1, height = 1;
    RenderStyle style;
    Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
    Eigen::Matrix4f projection = Eigen::Matrix4f::Identity();
    bool is_orthographic = false;
    bool is_culled = false;  // occlusion culling this frame
    std::size_t first = 0;   // candidates [0, first) are drawn in the first pass
    std::size_t split = 0;   // ... in two steps, [0, split) and [split, first)
    std::size_t used = 0;    // mesh triangles of the first pass
    DrawStats stats;
  };
  Frame frame;

  // Draws candidates [begin, end) (front to back) with levels of detail chosen by size and at
  // most `budget` mesh triangles (0 = no limit); adds to `stats`; returns the mesh triangles.
  std::size_t submit(std::size_t begin, std::size_t end, std::size_t budget,
                     const RenderStyle& style, const Eigen::Matrix4f& view,
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

PackingRenderer::PackingRenderer() : state_(std::make_unique<State>()) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 3 || (major == 3 && minor < 3)) {
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    throw_gl(std::string("need a 3.3 core context, have ") + (version ? version : "none"));
  }
  State& s = *state_;
  s.particle_program = link_program(kParticleVertexShader, kParticleFragmentShader);
  s.u_transforms = glGetUniformLocation(s.particle_program, "u_transforms");
  s.u_colors = glGetUniformLocation(s.particle_program, "u_colors");
  s.u_view = glGetUniformLocation(s.particle_program, "u_view");
  s.u_projection = glGetUniformLocation(s.particle_program, "u_projection");
  s.u_lit = glGetUniformLocation(s.particle_program, "u_lit");
  s.line_program = link_program(kLineVertexShader, kLineFragmentShader);
  s.u_view_projection = glGetUniformLocation(s.line_program, "u_view_projection");
  s.u_line_color = glGetUniformLocation(s.line_program, "u_color");
  s.point_program = link_program(kPointVertexShader, kPointFragmentShader);
  s.p_view = glGetUniformLocation(s.point_program, "u_view");
  s.p_projection = glGetUniformLocation(s.point_program, "u_projection");
  s.p_lit = glGetUniformLocation(s.point_program, "u_lit");
  glGenVertexArrays(1, &s.point_array);
  glGenBuffers(1, &s.point_buffer);
  glBindVertexArray(s.point_array);
  glBindBuffer(GL_ARRAY_BUFFER, s.point_buffer);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(GpuPoint), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(GpuPoint),
                        reinterpret_cast<const void*>(offsetof(GpuPoint, r)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  glGenVertexArrays(1, &s.vertex_array);
  glGenBuffers(1, &s.vertex_buffer);
  glGenBuffers(1, &s.index_buffer);
  glGenBuffers(1, &s.instance_buffer);
  glGenBuffers(1, &s.transform_buffer);
  glGenBuffers(1, &s.color_buffer);
  glGenTextures(1, &s.transform_texture);
  glGenTextures(1, &s.color_texture);
  glGenVertexArrays(1, &s.line_array);
  glGenBuffers(1, &s.line_buffer);

  glBindVertexArray(s.vertex_array);
  glBindBuffer(GL_ARRAY_BUFFER, s.vertex_buffer);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(GpuVertex),
                         reinterpret_cast<const void*>(offsetof(GpuVertex, particle)));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s.index_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, s.instance_buffer);
  const std::uint32_t zero = 0;
  glBufferData(GL_ARRAY_BUFFER, sizeof(zero), &zero, GL_STREAM_DRAW);
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
  glVertexAttribDivisor(2, 1);
  glBindVertexArray(0);

  glBindVertexArray(s.line_array);
  glBindBuffer(GL_ARRAY_BUFFER, s.line_buffer);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);

  // Empty texel stores so the samplers are valid before the first packing; nothing to draw yet.
  set_packing(Packing{});
  s.line_vertex_count = 0;
  s.bounds = Aabb{};
}

PackingRenderer::~PackingRenderer() {
  State& s = *state_;
  glDeleteProgram(s.particle_program);
  glDeleteProgram(s.line_program);
  glDeleteProgram(s.point_program);
  glDeleteBuffers(1, &s.point_buffer);
  glDeleteVertexArrays(1, &s.point_array);
  const std::array<GLuint, 7> buffers = {s.vertex_buffer,
                                         s.index_buffer,
                                         s.instance_buffer,
                                         s.transform_buffer,
                                         s.color_buffer,
                                         s.line_buffer,
                                         0};
  glDeleteBuffers(6, buffers.data());
  const std::array<GLuint, 2> textures = {s.transform_texture, s.color_texture};
  glDeleteTextures(2, textures.data());
  const std::array<GLuint, 2> arrays = {s.vertex_array, s.line_array};
  glDeleteVertexArrays(2, arrays.data());
}

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
    range.inner_radius = range.radius;
    for (std::size_t face = 0; face < shape.triangle_count(); ++face) {
      const Vec3 normal = shape.face_normal(face);
      const double distance = normal.dot(shape.vertices()[shape.triangles()[face][0]]);
      range.inner_radius = std::max(0.0, std::min(range.inner_radius, distance));
    }
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
  const Container& container = packing.container;
  if (container.kind == ContainerKind::kCylinder) {
    constexpr int kSegments = 96;
    for (int k = 0; k < kSegments; ++k) {
      const double a0 = 2.0 * M_PI * k / kSegments, a1 = 2.0 * M_PI * (k + 1) / kSegments;
      for (double z : {0.0, container.height}) {
        add_segment(Vec3(container.radius * std::cos(a0), container.radius * std::sin(a0), z),
                    Vec3(container.radius * std::cos(a1), container.radius * std::sin(a1), z));
      }
      if (k % (kSegments / 4) == 0) {
        add_segment(Vec3(container.radius * std::cos(a0), container.radius * std::sin(a0), 0.0),
                    Vec3(container.radius * std::cos(a0), container.radius * std::sin(a0),
                         container.height));
      }
    }
  } else {
    const Aabb box = container.bounds();
    if (!box.is_empty()) {
      auto corner = [&box](int c) {
        return Vec3((c & 1) ? box.upper.x() : box.lower.x(),
                    (c & 2) ? box.upper.y() : box.lower.y(),
                    (c & 4) ? box.upper.z() : box.lower.z());
      };
      for (int c = 0; c < 8; ++c) {
        for (int bit : {1, 2, 4}) {
          if ((c & bit) == 0) add_segment(corner(c), corner(c | bit));
        }
      }
    }
  }
  s.line_vertex_count = static_cast<GLsizei>(lines.size() / 3);
  glBindBuffer(GL_ARRAY_BUFFER, s.line_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(lines.size() * sizeof(float)), lines.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

std::size_t PackingRenderer::State::submit(std::size_t begin, std::size_t end, std::size_t budget,
                                           const RenderStyle& style, const Eigen::Matrix4f& view,
                                           const Eigen::Matrix4f& projection, DrawStats& stats) {
  if (begin >= end) return 0;
  const auto start = std::chrono::steady_clock::now();
  struct AddTime {
    std::chrono::steady_clock::time_point start;
    double& total;
    ~AddTime() { total += seconds_since(start); }
  } add_time{start, stats.submit_seconds};
  const std::size_t count = end - begin;

  // Over the particle cap: thin the particles evenly over the picture (not the farthest: that
  // cuts the pile with a plane) and the same ones from frame to frame: keep a particle when a
  // hash of its index falls below the fraction that fits (a mixing hash: the golden-ratio
  // sequence would pick particles of one colour, as colours follow it).
  std::uint64_t keep_below = std::uint64_t{1} << 32;
  if (style.max_particles > 0) {
    const std::size_t room = style.max_particles > stats.particles_drawn
                                 ? style.max_particles - stats.particles_drawn
                                 : 0;
    if (room < count) {
      keep_below = static_cast<std::uint64_t>(static_cast<double>(room) /
                                              static_cast<double>(count) * 4294967296.0);
    }
  }

  // Level of detail: full, coarse or point by projected size; then, over the triangle budget,
  // the smallest particles become points. 3: left out (particle cap).
  level.assign(count, 0);
  auto triangles_of = [&](std::size_t k) -> std::size_t {
    const ShapeRange& range = shapes[particle_shape[candidates[begin + k].particle]];
    if (level[k] >= 2) return 0;
    return static_cast<std::size_t>((level[k] == 1 ? range.coarse_count : range.full_count) / 3);
  };
  std::size_t mesh_triangles = 0;
  std::size_t left_out = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const float pixels = candidates[begin + k].pixels;
    if (mix_hash(candidates[begin + k].particle) >= keep_below) {
      level[k] = 3;
      ++left_out;
      continue;
    }
    if (pixels < style.point_below_pixels) {
      level[k] = 2;
    } else if (pixels < style.coarse_below_pixels) {
      level[k] = 1;
    }
    mesh_triangles += triangles_of(k);
  }
  if (budget == 1) {
    // Impostors only (no particle has a single triangle): no order needed.
    for (std::size_t k = 0; k < count; ++k) {
      if (level[k] != 3) level[k] = 2;
    }
    mesh_triangles = 0;
  } else if (budget > 0 && mesh_triangles > budget) {
    // Smallest first (ties: nearest first), as 64-bit keys: pixels are >= 0, so their float
    // bits order like the values.
    sort_keys.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      sort_keys[k] =
          (static_cast<std::uint64_t>(float_order_key(candidates[begin + k].pixels)) << 32) | k;
    }
    sort_by_high_word(sort_keys, sort_scratch);
    for (std::uint64_t key : sort_keys) {
      if (mesh_triangles <= budget) break;
      const auto k = static_cast<std::size_t>(key & 0xffffffffu);
      if (level[k] == 3) continue;
      mesh_triangles -= triangles_of(k);
      level[k] = 2;
    }
  }

  // Draw lists: single-use shapes in one multi-draw, instanced shapes by (shape, level),
  // points in one draw; all in front-to-back order.
  const std::size_t shape_count = shapes.size();
  group_counts.assign(2 * shape_count, 0);
  single_counts.clear();
  single_offsets.clear();
  single_base_vertices.clear();
  point_list.clear();
  std::size_t coarse = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t particle = candidates[begin + k].particle;
    const std::uint32_t shape = particle_shape[particle];
    const ShapeRange& range = shapes[shape];
    const std::uint8_t lod = level[k];
    if (lod == 3) continue;
    if (lod == 2) {
      point_list.push_back(particle);
      continue;
    }
    coarse += lod;
    if (range.instances >= 2) {
      ++group_counts[2 * shape + lod];
    } else {
      single_counts.push_back(lod == 1 ? range.coarse_count : range.full_count);
      single_offsets.push_back(reinterpret_cast<const void*>(
          static_cast<std::uintptr_t>(lod == 1 ? range.coarse_offset : range.full_offset) * 4u));
      single_base_vertices.push_back(range.base_vertex);
    }
  }
  stats.particles_drawn += count - left_out;
  stats.point_particles += point_list.size();
  stats.coarse_particles += coarse;
  stats.triangles += mesh_triangles;

  // Instance list: element 0 stays 0 (what single-use shapes read through the per-instance
  // attribute), then one block per (shape, level) group.
  group_start.assign(2 * shape_count, 0);
  std::uint32_t next = 1;
  for (std::uint32_t shape : instanced_shapes) {
    for (std::size_t lod = 0; lod < 2; ++lod) {
      group_start[2 * shape + lod] = next;
      next += group_counts[2 * shape + lod];
    }
  }
  instance_list.assign(next, 0);
  cursor = group_start;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t particle = candidates[begin + k].particle;
    const std::uint32_t shape = particle_shape[particle];
    if (level[k] >= 2 || shapes[shape].instances < 2) continue;
    instance_list[cursor[2 * shape + level[k]]++] = particle;
  }

  if (next > 1 || !single_counts.empty()) {
    glUseProgram(particle_program);
    glUniformMatrix4fv(u_view, 1, GL_FALSE, view.data());
    glUniformMatrix4fv(u_projection, 1, GL_FALSE, projection.data());
    glUniform1i(u_lit, style.is_wireframe ? 0 : 1);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_BUFFER, transform_texture);
    glUniform1i(u_transforms, 0);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_BUFFER, color_texture);
    glUniform1i(u_colors, 1);
    if (style.is_wireframe) {
      glDisable(GL_CULL_FACE);
      glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    } else {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glFrontFace(GL_CCW);
    }
    glBindVertexArray(vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, instance_buffer);
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(instance_list.size() * sizeof(std::uint32_t)),
                 instance_list.data(), GL_STREAM_DRAW);
    glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
    if (!single_counts.empty()) {
      glMultiDrawElementsBaseVertex(
          GL_TRIANGLES, single_counts.data(), GL_UNSIGNED_INT, single_offsets.data(),
          static_cast<GLsizei>(single_counts.size()), single_base_vertices.data());
      ++stats.draw_calls;
    }
    // GL 3.3 has no base instance: point the per-instance attribute at each group's block.
    constexpr std::size_t kFlushTriangles = 16384;
    std::size_t unflushed = 0;
    for (std::uint32_t shape : instanced_shapes) {
      const ShapeRange& range = shapes[shape];
      for (std::size_t lod = 0; lod < 2; ++lod) {
        const std::size_t group = 2 * shape + lod;
        const auto instances = static_cast<GLsizei>(group_counts[group]);
        if (instances == 0) continue;
        glVertexAttribIPointer(
            2, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t),
            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(group_start[group]) * 4u));
        const GLsizei index_count = lod == 1 ? range.coarse_count : range.full_count;
        const GLuint offset = lod == 1 ? range.coarse_offset : range.full_offset;
        glDrawElementsInstancedBaseVertex(
            GL_TRIANGLES, index_count, GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(offset) * 4u), instances,
            range.base_vertex);
        ++stats.draw_calls;
        // Hand what is set up to the rasteriser threads now and then (see the impostors).
        unflushed +=
            static_cast<std::size_t>(index_count / 3) * static_cast<std::size_t>(instances);
        if (unflushed >= kFlushTriangles) {
          glFlush();
          unflushed = 0;
        }
      }
    }
    glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
    glBindVertexArray(0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_CULL_FACE);
  }

  if (!point_list.empty()) {
    // Three vertices per impostor (not instanced: llvmpipe runs its whole vertex pipeline once
    // per instance, which costs more than the copies).
    glUseProgram(point_program);
    glUniformMatrix4fv(p_view, 1, GL_FALSE, view.data());
    glUniformMatrix4fv(p_projection, 1, GL_FALSE, projection.data());
    glUniform1i(p_lit, style.is_wireframe ? 0 : 1);
    const auto& particle_colors = colors[static_cast<std::size_t>(style.color)].colors;
    points.resize(3 * point_list.size());
    for (std::size_t k = 0; k < point_list.size(); ++k) {
      const std::uint32_t particle = point_list[k];
      const ParticleSphere& sphere = particle_sphere[particle];
      const Rgb color =
          particle < particle_colors.size() ? particle_colors[particle] : Rgb{255, 255, 255};
      const GpuPoint point = {sphere.x, sphere.y, sphere.z, impostor_radius[particle],
                              color.r,  color.g,  color.b,  255};
      points[3 * k] = point;
      points[3 * k + 1] = point;
      points[3 * k + 2] = point;
    }
    glBindVertexArray(point_array);
    glBindBuffer(GL_ARRAY_BUFFER, point_buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(GpuPoint)),
                 points.data(), GL_STREAM_DRAW);
    // In chunks with a flush before each, so llvmpipe's rasteriser threads start on one chunk
    // while this thread sets up the next (it rasterises only what was flushed).
    constexpr std::size_t kChunk = 3 * 2048;
    for (std::size_t first = 0; first < points.size(); first += kChunk) {
      glFlush();
      glDrawArrays(GL_TRIANGLES, static_cast<GLint>(first),
                   static_cast<GLsizei>(std::min(kChunk, points.size() - first)));
    }
    glBindVertexArray(0);
    ++stats.draw_calls;
  }
  return mesh_triangles;
}

DrawStats PackingRenderer::draw(const Camera& camera, int width, int height,
                                const RenderStyle& style) {
  begin_frame(camera, width, height, style);
  while (!step_frame()) {
  }
  return state_->frame.stats;
}

void PackingRenderer::begin_frame(const Camera& camera, int width, int height,
                                  const RenderStyle& style) {
  State& s = *state_;
  State::Frame& f = s.frame;
  f = State::Frame{};
  f.style = style;
  DrawStats& stats = f.stats;
  width = std::max(width, 1);
  height = std::max(height, 1);
  f.width = width;
  f.height = height;
  if (s.uploaded_color != static_cast<int>(style.color)) s.upload_colors(style.color);

  f.view = camera.view_matrix();
  f.projection = camera.projection_matrix(static_cast<double>(width) / static_cast<double>(height));
  const Eigen::Matrix4f& view = f.view;
  const Eigen::Matrix4f view_projection = f.projection * view;
  f.is_orthographic = camera.is_orthographic();

  glViewport(0, 0, width, height);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glClearColor(style.background.r / 255.0f, style.background.g / 255.0f,
               style.background.b / 255.0f, 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);

  auto start = std::chrono::steady_clock::now();
  // 1. Frustum: keep a particle unless its bounding sphere is wholly outside a plane of the
  //    view volume (planes from the combined matrix, Gribb-Hartmann).
  std::array<Eigen::Vector4f, 6> planes;
  for (int k = 0; k < 3; ++k) {
    planes[static_cast<std::size_t>(2 * k)] = view_projection.row(3) + view_projection.row(k);
    planes[static_cast<std::size_t>(2 * k + 1)] = view_projection.row(3) - view_projection.row(k);
  }
  for (auto& plane : planes) plane /= plane.head<3>().norm();
  const Eigen::Vector4f depth_row = -view.row(2);
  const float pixel_scale = static_cast<float>(camera.pixels_per_metre(1.0, height));
  const bool is_orthographic = f.is_orthographic;
  // Pixels per metre at a view depth; perspective shrinks with depth.
  auto pixels_per_metre = [&](float depth) {
    return is_orthographic ? pixel_scale : pixel_scale / std::max(depth, 1e-9f);
  };
  const std::size_t particle_count = s.particle_shape.size();
  // Whether particle i is in view, and its candidate record if so.
  auto make_candidate = [&](std::size_t i, Candidate& candidate) {
    const ParticleSphere& sphere = s.particle_sphere[i];
    const Eigen::Vector4f centre(sphere.x, sphere.y, sphere.z, 1.0f);
    bool is_inside = true;
    for (const auto& plane : planes) {
      if (plane.dot(centre) < -sphere.radius) {
        is_inside = false;
        break;
      }
    }
    if (!is_inside) return false;
    const Eigen::Vector4f clip = view_projection * centre;
    candidate.particle = static_cast<std::uint32_t>(i);
    candidate.depth = depth_row.dot(centre);
    candidate.near_depth = candidate.depth - sphere.radius;
    const bool is_in_front = is_orthographic || candidate.near_depth > 0.0f;
    candidate.pixels = is_in_front ? 2.0f * sphere.radius * pixels_per_metre(candidate.depth)
                                   : std::numeric_limits<float>::infinity();
    // The outline of the bounding sphere: orthographic, a disc of the projected radius; in
    // perspective an ellipse stretched by 1 / cos^2 of the off-axis angle (cos = depth /
    // distance) whose centre moves outward by a second-order amount that 2 % and half a pixel
    // cover.
    candidate.footprint = sphere.radius * pixel_scale;
    if (!is_orthographic && is_in_front) {
      const float distance = (view * centre).head<3>().norm();
      const float sine = std::min(sphere.radius / std::max(distance, 1e-9f), 0.99f);
      candidate.footprint = pixel_scale * sphere.radius * distance /
                            (candidate.depth * candidate.depth * std::sqrt(1.0f - sine * sine));
    }
    candidate.footprint = 1.02f * candidate.footprint + 0.5f;
    const float w = clip.w() > 1e-9f ? clip.w() : 1e-9f;
    candidate.screen_x = (clip.x() / w + 1.0f) * 0.5f * static_cast<float>(width);
    candidate.screen_y = (clip.y() / w + 1.0f) * 0.5f * static_cast<float>(height);
    return true;
  };
  // In chunks of consecutive particles on all cores (the rasteriser is idle at the start of a
  // frame), joined in chunk order: the same list as one loop would make.
  constexpr std::size_t kChunk = 8192;
  const std::size_t chunk_count = (particle_count + kChunk - 1) / kChunk;
  s.chunk_candidates.resize(std::max(s.chunk_candidates.size(), chunk_count));
  parallel_for_index(0, chunk_count, [&](std::size_t chunk) {
    std::vector<Candidate>& out = s.chunk_candidates[chunk];
    out.clear();
    Candidate candidate;
    for (std::size_t i = chunk * kChunk; i < std::min(particle_count, (chunk + 1) * kChunk); ++i) {
      if (make_candidate(i, candidate)) out.push_back(candidate);
    }
  });
  s.candidates.clear();
  for (std::size_t chunk = 0; chunk < chunk_count; ++chunk) {
    s.candidates.insert(s.candidates.end(), s.chunk_candidates[chunk].begin(),
                        s.chunk_candidates[chunk].end());
  }
  // Front to back: lets the rasteriser's early depth test reject hidden fragments. Not for a
  // frame of impostors only (budget 1): their fragment shader discards, which turns the early
  // test off, so the order would buy nothing (the depth test still gives the same picture).
  if (style.triangle_budget != 1) {
    sort_front_to_back(s.candidates, s.sort_keys, s.sort_scratch, s.sorted);
  }
  const std::size_t in_frustum = s.candidates.size();
  stats.particles_in_frustum = in_frustum;
  stats.frustum_sort_seconds = seconds_since(start);

  // 2. Draw, with occlusion culling when it can pay: llvmpipe pays per primitive, and in a
  //    packing of many small particles the view sees only the first few layers. Particles not
  //    hidden last frame are drawn first; the depth they leave is read back, and the others
  //    are drawn only if some pixel under their bounding sphere lies behind the sphere's nearest
  //    point. Exact (never drops a particle that would show), whatever last frame was.
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  f.is_culled = style.is_occlusion_culled && !style.is_wireframe && samples <= 1 &&
                in_frustum >= kOcclusionMinParticles;
  if (s.was_visible.size() != particle_count) {
    s.was_visible.assign(particle_count, 0);
    s.has_visibility = false;
  }
  // A thinned light frame (particle cap) skips the culling, whose read-back and test cost more
  // than drawing the few particles; it keeps the last full frame's visible set for the next
  // (culling is exact with any set; a recent one only makes it faster).
  // Not thinned when last frame's visible set fits under the cap: culling then draws about that
  // many, all of what shows, where a thinning of everything in view would look sparse.
  const bool is_thinned =
      style.max_particles > 0 && in_frustum > style.max_particles &&
      !(f.is_culled && s.has_visibility && s.visible_count <= style.max_particles);
  f.first = in_frustum;
  if (!f.is_culled || is_thinned) {
    f.is_culled = false;
    if (!is_thinned) s.has_visibility = false;
  } else if (s.has_visibility) {
    // First the particles seen last frame (all of them when there is no last frame).
    f.first = static_cast<std::size_t>(
        std::stable_partition(s.candidates.begin(), s.candidates.end(),
                              [&](const Candidate& c) { return s.was_visible[c.particle] != 0; }) -
        s.candidates.begin());
  }
  // A large first pass in two steps (nearer half first, with the first claim on the triangle
  // budget), so no step is much longer than the others.
  f.split = f.is_culled && f.first >= 2 * kOcclusionMinParticles ? f.first / 2 : f.first;
  f.step = 1;
}

bool PackingRenderer::step_frame() {
  State& s = *state_;
  State::Frame& f = s.frame;
  DrawStats& stats = f.stats;
  const RenderStyle& style = f.style;
  if (f.step == 0) return true;  // no frame begun, or finished
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  const std::size_t in_frustum = stats.particles_in_frustum;
  // The triangle budget left after `used` mesh triangles (0 = no limit; 1 when used up: the rest
  // are points).
  auto budget_after = [&](std::size_t used) -> std::size_t {
    if (style.triangle_budget == 0) return 0;
    return used < style.triangle_budget ? style.triangle_budget - used : 1;
  };
  if (f.step == 1) {
    // Everything (no culling), or the particles seen last frame (or the nearer half of them).
    f.used = s.submit(0, f.split, style.triangle_budget, style, f.view, f.projection, stats);
    f.step = f.split < f.first ? 5 : f.is_culled ? 2 : 4;
    return false;
  }
  if (f.step == 5) {
    f.used += s.submit(f.split, f.first, budget_after(f.used), style, f.view, f.projection, stats);
    f.step = 2;
    return false;
  }
  if (f.step == 2) {
    auto start = std::chrono::steady_clock::now();
    s.depth_pyramid.build(f.width, f.height);
    stats.depth_readback_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const Eigen::Matrix4f& projection = f.projection;
    // Window depth of a view depth (both projections map view depth alone to window depth).
    auto window_depth = [&](float depth) {
      const float clip_z = -projection(2, 2) * depth + projection(2, 3);
      const float clip_w = -projection(3, 2) * depth + projection(3, 3);
      return 0.5f * clip_z / clip_w + 0.5f;
    };
    auto is_hidden = [&](const Candidate& c) {
      if (!f.is_orthographic && !(c.near_depth > 1e-6f)) return false;
      return s.depth_pyramid.is_hidden(c.screen_x, c.screen_y, c.footprint,
                                       window_depth(c.near_depth));
    };
    // Seen now: the first group unless hidden behind the rest of it, the others unless hidden.
    // The tests run on all cores (the rasteriser has finished the first pass).
    s.is_hidden_flag.resize(in_frustum);
    parallel_for_index(0, (in_frustum + 1023) / 1024, [&](std::size_t block) {
      for (std::size_t c = 1024 * block; c < std::min(in_frustum, 1024 * (block + 1)); ++c) {
        s.is_hidden_flag[c] = is_hidden(s.candidates[c]) ? 1 : 0;
      }
    });
    std::fill(s.was_visible.begin(), s.was_visible.end(), std::uint8_t{0});
    s.visible_count = 0;
    for (std::size_t c = 0; c < f.first; ++c) {
      if (s.is_hidden_flag[c] != 0) continue;
      s.was_visible[s.candidates[c].particle] = 1;
      ++s.visible_count;
    }
    std::size_t kept = f.first;
    for (std::size_t c = f.first; c < in_frustum; ++c) {
      if (s.is_hidden_flag[c] != 0) continue;
      s.was_visible[s.candidates[c].particle] = 1;
      s.candidates[kept++] = s.candidates[c];
    }
    s.visible_count += kept - f.first;
    s.candidates.resize(kept);
    s.has_visibility = true;
    stats.occlusion_test_seconds = seconds_since(start);
    f.step = 3;
    return false;
  }
  if (f.step == 3) {
    // Budget used up: the newly seen are points this frame (and first next frame).
    s.submit(f.first, s.candidates.size(), budget_after(f.used), style, f.view, f.projection,
             stats);
  }

  if (style.show_container && s.line_vertex_count > 0) {
    const Eigen::Matrix4f view_projection = f.projection * f.view;
    glUseProgram(s.line_program);
    glUniformMatrix4fv(s.u_view_projection, 1, GL_FALSE, view_projection.data());
    glUniform3f(s.u_line_color, style.container_color.r / 255.0f, style.container_color.g / 255.0f,
                style.container_color.b / 255.0f);
    glBindVertexArray(s.line_array);
    glDrawArrays(GL_LINES, 0, s.line_vertex_count);
    glBindVertexArray(0);
    ++stats.draw_calls;
  }
  glUseProgram(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  f.step = 0;
  return true;
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
