#pragma once
// OpenGL 3.3 core drawing of a Packing, shared by aggpack-gui and headless PNG rendering.
//
// A shape used by several particles is uploaded once (vertices + triangle indices, in its local
// frame) and drawn instanced: each frame streams the drawn instances' transforms (translation,
// scale, unit quaternion) as per-instance attributes. A shape used once is uploaded in world
// coordinates. Colours are a buffer texture (4 bytes a particle): no OpenGL buffer holds 32 or
// 64 bytes for every particle, whose storage the driver would clear in one piece (at 10^6
// particles that one step took up to 135 ms in the window). Facet normals come from
// screen-space derivatives in the fragment shader, so facets are lit flat without duplicating
// vertices per triangle.
//
// The software renderer (llvmpipe) pays per primitive, so particles outside the view are skipped
// (frustum test of the bounding sphere) and the rest are drawn front to back. Particles
// that cover few pixels are drawn with a coarse 24-triangle version of their shape or as one
// shaded point (an impostor), and a triangle budget turns the smallest ones into points first.
// With many particles in view, particles hidden behind others are skipped: those seen last
// frame are drawn first, the depth buffer is read back, and the rest are drawn only if part of
// their bounding sphere could show (exact: the picture is the same as drawing all).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "aggpack/geom/vec.h"
#include "aggpack/pack/packing.h"
#include "aggpack/render/camera.h"
#include "aggpack/render/colors.h"

namespace aggpack {

/// How a packing is drawn. Colours are 8-bit sRGB.
struct RenderStyle {
  ColorMode color = ColorMode::kParticle;  ///< particle colouring
  bool is_wireframe = false;               ///< draw triangle edges only (unlit), no faces
  bool show_container = true;              ///< draw the container's outline
  Rgb background = {236, 238, 242};        ///< clear colour
  Rgb container_color = {40, 44, 52};      ///< outline colour
  /// Particles whose projected diameter is below this many pixels are drawn with the coarse
  /// shape (24 triangles through the shape's support points in 14 directions). 0 = always full
  /// detail. >= 0.
  double coarse_below_pixels = 12.0;
  /// Particles whose projected diameter is below this many pixels are drawn as one shaded disc
  /// (a point sprite of their volume-equivalent size). 0 = never. >= 0.
  double point_below_pixels = 0.0;
  /// Most triangles to submit per frame; when the visible particles need more, the smallest on
  /// screen are drawn as points instead. 0 = no limit.
  std::size_t triangle_budget = 0;
  /// Skip particles hidden behind nearer ones (exact: tested against the depth read back after
  /// drawing the particles seen last frame; off in wireframe).
  bool is_occlusion_culled = true;
  /// Most particles to draw per frame, for light frames while the view moves: over it, an even
  /// thinning of the particles in view is drawn (the same particles frame to frame). 0 = all.
  std::size_t max_particles = 0;
};

/// What one draw() did (for the GUI's status line and benchmarks).
struct DrawStats {
  std::size_t particles_in_frustum = 0;  ///< particles inside the view volume
  std::size_t particles_drawn = 0;       ///< of those, drawn (not hidden behind others)
  std::size_t coarse_particles = 0;      ///< of those drawn, with the coarse shape
  std::size_t point_particles = 0;       ///< of those drawn, as points
  std::size_t triangles = 0;             ///< triangles submitted
  std::size_t draw_calls = 0;            ///< OpenGL draw calls issued
  // Where the time went on the calling thread (s). llvmpipe rasterises on worker threads, so
  // these do not add up to the frame: the read-back also waits for the first pass to finish.
  double frustum_sort_seconds = 0.0;    ///< frustum test, projection, front-to-back sort
  double submit_seconds = 0.0;          ///< draw lists, uploads and draw calls
  double depth_readback_seconds = 0.0;  ///< glReadPixels of depth (waits) and the pyramid
  double occlusion_test_seconds = 0.0;  ///< testing the other particles against the pyramid

  /// Adds another frame's counts and times (for sums over frames).
  DrawStats& operator+=(const DrawStats& other) {
    particles_in_frustum += other.particles_in_frustum;
    particles_drawn += other.particles_drawn;
    coarse_particles += other.coarse_particles;
    point_particles += other.point_particles;
    triangles += other.triangles;
    draw_calls += other.draw_calls;
    frustum_sort_seconds += other.frustum_sort_seconds;
    submit_seconds += other.submit_seconds;
    depth_readback_seconds += other.depth_readback_seconds;
    occlusion_test_seconds += other.occlusion_test_seconds;
    return *this;
  }
};

/// Everything PackingRenderer draws from a packing (shape meshes, per-particle transforms,
/// bounding spheres, colours in every mode), computed without OpenGL. Opaque.
struct SceneData;

/// Builds the scene data of `packing` on the calling thread, which may be any thread (no
/// OpenGL): an interactive program calls it on a worker so the window stays live. Shapes that
/// are scaled copies of another shape (same triangles, vertices in proportion) share its mesh
/// and are drawn instanced with the scale in their transform. `progress` (optional) is called
/// now and then with the fraction done in [0, 1]; when `cancel` (optional) becomes true the
/// function returns null. The meshes go into pages of at most `mesh_page_bytes` of vertices and
/// of indices each (whole shapes; a larger shape has a page of its own), one OpenGL buffer pair
/// per page: the driver clears a new buffer's storage, so an upload step allocates only a page's
/// worth, never hundreds of MB (0 = the default, 4 MB).
/// \throw InvalidInput if a particle refers to a shape that does not exist.
std::shared_ptr<SceneData> prepare_scene(const Packing& packing,
                                         const std::function<void(double)>& progress = {},
                                         const std::atomic<bool>* cancel = nullptr,
                                         std::size_t mesh_page_bytes = 0);

/// Draws one packing with OpenGL 3.3 core. Construct, use and destroy it only while the same
/// OpenGL 3.3 (or later) core context is current on the calling thread.
class PackingRenderer {
 public:
  /// Compiles the shaders and creates the buffers.
  /// \throw Error (kIoError) if the current context lacks OpenGL 3.3 or a shader fails.
  PackingRenderer();
  ~PackingRenderer();
  PackingRenderer(const PackingRenderer&) = delete;
  PackingRenderer& operator=(const PackingRenderer&) = delete;

  /// Uploads `packing`: every distinct shape once and the particles' colours; keeps the
  /// particles' transforms for the instanced draws. Replaces what was uploaded before.
  /// The packing is not kept. Same as begin_upload(prepare_scene(packing)) followed by
  /// upload_step until done.
  /// \throw InvalidInput if a particle refers to a shape that does not exist.
  void set_packing(const Packing& packing);

  /// Starts uploading a prepared scene (not null) in pieces; until upload_step returns true the
  /// renderer must not draw (begin_frame / draw throw Error), and an unfinished frame is dropped.
  /// The accessors below describe the last completed scene until then. A new begin_upload
  /// replaces an unfinished one.
  /// \throw LimitExceeded if the driver's buffer textures cannot hold the particles.
  void begin_upload(std::shared_ptr<SceneData> scene);
  /// One unit of the pending upload: allocates one buffer's storage (the driver may clear it), or
  /// copies at most `max_bytes` (at least 1) into it, or, after the last copy, puts the scene in
  /// use. Returns true when the whole scene is uploaded and in use (true at once when nothing is
  /// pending).
  bool upload_step(std::size_t max_bytes);
  /// Bytes the next upload_step(max_bytes) allocates or copies (putting the scene in use counts
  /// as its colour buffer, 4 bytes per particle), 0 when nothing is pending: what a caller with a
  /// time budget weighs against the cost per byte it has measured.
  [[nodiscard]] std::size_t next_upload_bytes(std::size_t max_bytes) const;
  /// Whether begin_upload's scene is not completely uploaded yet.
  [[nodiscard]] bool is_upload_pending() const;
  /// Fraction of the pending upload done, in [0, 1] (1 when none is pending).
  [[nodiscard]] double upload_progress() const;

  /// Draws into the currently bound framebuffer (clears it first), viewport (0, 0, width,
  /// height) in pixels (> 0).
  DrawStats draw(const Camera& camera, int width, int height, const RenderStyle& style);

  /// The same frame as draw(), in steps, so an interactive caller can keep its event loop
  /// running while a heavy frame is drawn (the frustum test, about 260,000 particles per step;
  /// the front-to-back sort; the particles seen last frame, in pieces of at most 12,000 and in
  /// two at least when there are many; the depth read-back and occlusion test; the rest, in
  /// pieces). begin_frame() clears the bound framebuffer; each step_frame() call does the next
  /// step and returns true once the frame is complete. The caller may draw elsewhere between steps
  /// but must bind the same framebuffer again before each step. A new begin_frame() abandons an
  /// unfinished frame.
  void begin_frame(const Camera& camera, int width, int height, const RenderStyle& style);
  bool step_frame();
  /// Whether a frame was begun and is not complete yet.
  [[nodiscard]] bool is_frame_pending() const;
  /// What the last (or the current) frame did so far.
  [[nodiscard]] const DrawStats& frame_stats() const;

  /// Bounds of the container and every particle (m); empty before set_packing of a packing
  /// with particles or a container.
  [[nodiscard]] const Aabb& scene_bounds() const;
  /// Colours and scale range of the uploaded packing in `mode` (for legends).
  [[nodiscard]] const ParticleColors& colors(ColorMode mode) const;
  /// Number of particles / distinct shapes uploaded.
  [[nodiscard]] std::size_t particle_count() const;
  [[nodiscard]] std::size_t shape_count() const;
  /// Of the shapes, how many are drawn with another shape's mesh (scaled copies of it).
  [[nodiscard]] std::size_t merged_shape_count() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace aggpack
