// PackingRenderer's GL objects: shader programs, buffers and vertex layouts (constructor,
// destructor).

#include "aggpack/core/error.h"
#include "renderer_state.h"

namespace aggpack {

namespace {

constexpr const char* kParticleVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in uint a_particle;
layout(location = 2) in uint a_instance;
layout(location = 3) in vec4 a_placement;  // per instance: translation (m), scale
layout(location = 4) in vec4 a_rotation;   // per instance: unit quaternion (x, y, z, w)
uniform samplerBuffer u_colors;      // one normalised RGBA8 texel per particle
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_view_position;
flat out vec3 v_color;
void main() {
  int id = int(a_particle + a_instance);
  // v + 2 w (q x v) + 2 q x (q x v): the unit quaternion's rotation of the scaled vertex.
  vec3 v = a_position * a_placement.w;
  vec3 u = 2.0 * cross(a_rotation.xyz, v);
  vec3 world = v + a_rotation.w * u + cross(a_rotation.xyz, u) + a_placement.xyz;
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

// "OpenGL: what": the sentence and its one value (a driver's log or version).
[[noreturn]] void throw_gl(Sentence sentence, const std::string& value) {
  throw IoError(Wording{sentence, {value}});
}

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
    throw_gl(Sentence::kOpenGlCompile, log.data());
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
    throw_gl(Sentence::kOpenGlLink, log.data());
  }
  return program;
}

}  // namespace

PackingRenderer::PackingRenderer() : state_(std::make_unique<State>()) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 3 || (major == 3 && minor < 3)) {
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    throw_gl(Sentence::kOpenGlVersion, version ? version : "none");
  }
  State& s = *state_;
  s.particle_program = link_program(kParticleVertexShader, kParticleFragmentShader);
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

  glGenBuffers(1, &s.instance_buffer);
  glGenBuffers(1, &s.color_buffer);
  glGenTextures(1, &s.color_texture);
  glGenVertexArrays(1, &s.line_array);
  glGenBuffers(1, &s.line_buffer);
  glBindBuffer(GL_ARRAY_BUFFER, s.instance_buffer);
  const GpuInstance identity;
  glBufferData(GL_ARRAY_BUFFER, sizeof(identity), &identity, GL_STREAM_DRAW);

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

void PackingRenderer::State::point_instances_at(std::size_t first) {
  // The bound vertex array's per-instance attributes, from instance_buffer (bound to
  // GL_ARRAY_BUFFER), starting at element `first`.
  const std::uintptr_t base = first * sizeof(GpuInstance);
  auto at = [base](std::size_t offset) { return reinterpret_cast<const void*>(base + offset); };
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(GpuInstance),
                         at(offsetof(GpuInstance, particle)));
  glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, sizeof(GpuInstance),
                        at(offsetof(GpuInstance, transform) + offsetof(GpuTransform, placement)));
  glVertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, sizeof(GpuInstance),
                        at(offsetof(GpuInstance, transform) + offsetof(GpuTransform, rotation)));
}

void PackingRenderer::State::ensure_mesh_page(std::size_t page) {
  while (mesh_pages.size() <= page) {
    MeshPage mesh;
    glGenVertexArrays(1, &mesh.vertex_array);
    glGenBuffers(1, &mesh.vertex_buffer);
    glGenBuffers(1, &mesh.index_buffer);
    glBindVertexArray(mesh.vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(GpuVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(GpuVertex),
                           reinterpret_cast<const void*>(offsetof(GpuVertex, particle)));
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.index_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, instance_buffer);
    for (GLuint attribute = 2; attribute <= 4; ++attribute) {
      glEnableVertexAttribArray(attribute);
      glVertexAttribDivisor(attribute, 1);
    }
    point_instances_at(0);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    mesh_pages.push_back(mesh);
  }
}

PackingRenderer::~PackingRenderer() {
  State& s = *state_;
  glDeleteProgram(s.particle_program);
  glDeleteProgram(s.line_program);
  glDeleteProgram(s.point_program);
  glDeleteBuffers(1, &s.point_buffer);
  glDeleteVertexArrays(1, &s.point_array);
  for (const MeshPage& page : s.mesh_pages) {
    const std::array<GLuint, 2> page_buffers = {page.vertex_buffer, page.index_buffer};
    glDeleteBuffers(2, page_buffers.data());
    glDeleteVertexArrays(1, &page.vertex_array);
  }
  const std::array<GLuint, 3> buffers = {s.instance_buffer, s.color_buffer, s.line_buffer};
  glDeleteBuffers(3, buffers.data());
  glDeleteTextures(1, &s.color_texture);
  glDeleteVertexArrays(1, &s.line_array);
}

}  // namespace aggpack
