// A frame of PackingRenderer: frustum culling and front-to-back order (begin_frame), then the
// steps of step_frame (first pass, depth read-back and occlusion test, the rest, the outline).

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "renderer_state.h"

namespace aggpack {

namespace render_detail {

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

}  // namespace render_detail

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
  if (s.pending)
    throw Error(ErrorKind::kInvalidInput,
                "PackingRenderer: drawing while a scene is being uploaded");
  State::Frame& f = s.frame;
  f = State::Frame{};
  f.style = style;
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

  // 1. Frustum: keep a particle unless its bounding sphere is wholly outside a plane of the
  //    view volume (planes from the combined matrix, Gribb-Hartmann). The pass over the
  //    particles and the sort are the frame's first steps (step_frame), bounded work each.
  f.view_projection = view_projection;
  for (int k = 0; k < 3; ++k) {
    f.planes.col(2 * k) = (view_projection.row(3) + view_projection.row(k)).transpose();
    f.planes.col(2 * k + 1) = (view_projection.row(3) - view_projection.row(k)).transpose();
  }
  for (int k = 0; k < 6; ++k) f.planes.col(k) /= f.planes.col(k).head<3>().norm();
  f.pixel_scale = static_cast<float>(camera.pixels_per_metre(1.0, height));
  const std::size_t chunk_count = (s.particle_shape.size() + kFrustumChunk - 1) / kFrustumChunk;
  s.chunk_candidates.resize(std::max(s.chunk_candidates.size(), chunk_count));
  s.candidates.clear();
  s.sort_keys.clear();
  f.next_chunk = 0;
  f.step = 5;
}

void PackingRenderer::State::frustum_chunks(std::size_t first_chunk, std::size_t last_chunk) {
  Frame& f = frame;
  const Eigen::Matrix4f& view = f.view;
  const Eigen::Matrix4f& view_projection = f.view_projection;
  const auto& planes = f.planes;
  const Eigen::Vector4f depth_row = -view.row(2);
  const float pixel_scale = f.pixel_scale;
  const bool is_orthographic = f.is_orthographic;
  const int width = f.width, height = f.height;
  auto& s = *this;
  // Pixels per metre at a view depth; perspective shrinks with depth.
  auto pixels_per_metre = [&](float depth) {
    return is_orthographic ? pixel_scale : pixel_scale / std::max(depth, 1e-9f);
  };
  // Whether particle i is in view, and its candidate record if so.
  auto make_candidate = [&](std::size_t i, Candidate& candidate) {
    const ParticleSphere& sphere = s.particle_sphere[i];
    const Eigen::Vector4f centre(sphere.x, sphere.y, sphere.z, 1.0f);
    bool is_inside = true;
    for (int k = 0; k < 6; ++k) {
      if (planes.col(k).dot(centre) < -sphere.radius) {
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
  const std::size_t particle_count = particle_shape.size();
  // In chunks of consecutive particles on all cores (the rasteriser is idle at the start of a
  // frame), joined in chunk order: the same list as one loop would make.
  constexpr std::size_t kChunk = kFrustumChunk;
  parallel_for_index(first_chunk, last_chunk, [&](std::size_t chunk) {
    std::vector<Candidate>& out = s.chunk_candidates[chunk];
    out.clear();
    Candidate candidate;
    for (std::size_t i = chunk * kChunk; i < std::min(particle_count, (chunk + 1) * kChunk); ++i) {
      if (make_candidate(i, candidate)) out.push_back(candidate);
    }
  });
  // Joined in chunk order, with their sort keys (near depth, then the position: ties keep it).
  const bool is_sorted = f.style.triangle_budget != 1;
  for (std::size_t chunk = first_chunk; chunk < last_chunk; ++chunk) {
    for (const Candidate& c : chunk_candidates[chunk]) {
      if (is_sorted) {
        sort_keys.push_back((static_cast<std::uint64_t>(float_order_key(c.near_depth)) << 32) |
                            candidates.size());
      }
      candidates.push_back(c);
    }
  }
}

void PackingRenderer::State::finish_frustum() {
  Frame& f = frame;
  const RenderStyle& style = f.style;
  DrawStats& stats = f.stats;
  auto& s = *this;
  const std::size_t particle_count = particle_shape.size();
  // Front to back: lets the rasteriser's early depth test reject hidden fragments. Not for a
  // frame of impostors only (budget 1): their fragment shader discards, which turns the early
  // test off, so the order would buy nothing (the depth test still gives the same picture).
  if (style.triangle_budget != 1) {
    sort_by_high_word(sort_keys, sort_scratch);
    const std::size_t n = candidates.size();
    sorted.resize(n);
    for (std::size_t c = 0; c < n; ++c) sorted[c] = candidates[sort_keys[c] & 0xffffffffu];
    candidates.swap(sorted);
  }
  const std::size_t in_frustum = s.candidates.size();
  stats.particles_in_frustum = in_frustum;

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
  // A large pass in steps of at most kStepParticles (a large first pass in two at least; nearer
  // particles first, with the first claim on the triangle budget), so no step is long.
  f.chunk = f.is_culled && f.first >= 2 * kOcclusionMinParticles
                ? std::min(kStepParticles, (f.first + 1) / 2)
                : kStepParticles;
  f.cursor = 0;
  f.step = 1;
}

std::size_t PackingRenderer::State::step_end(std::size_t begin, std::size_t end, std::size_t most,
                                             int width, int height) const {
  // At most `most` candidates, about one view's worth of covered pixels (the near particles,
  // first in the order, are large on screen) and kStepTriangles mesh triangles at full detail
  // (the near ones take the triangle budget: without this the first piece drew all of it).
  const double pixel_budget = static_cast<double>(width) * static_cast<double>(height);
  double pixels = 0.0;
  std::size_t triangles = 0;
  std::size_t k = begin;
  const std::size_t last = std::min(end, begin + most);
  while (k < last) {
    const double diameter = std::min(static_cast<double>(candidates[k].pixels),
                                     static_cast<double>(std::max(width, height)));
    pixels += 0.785 * diameter * diameter;
    triangles +=
        static_cast<std::size_t>(shapes[particle_shape[candidates[k].particle]].full_count / 3);
    ++k;
    if (pixels > pixel_budget || triangles > kStepTriangles) break;
  }
  return k;
}

bool PackingRenderer::step_frame() {
  State& s = *state_;
  State::Frame& f = s.frame;
  DrawStats& stats = f.stats;
  const RenderStyle& style = f.style;
  if (f.step == 0) return true;  // no frame begun, or finished
  if (f.step == 5 || f.step == 6) {
    // The frustum pass, a bounded number of particles per step, then the sort.
    const auto start = std::chrono::steady_clock::now();
    if (f.step == 5) {
      const std::size_t chunk_count = (s.particle_shape.size() + kFrustumChunk - 1) / kFrustumChunk;
      const std::size_t last = std::min(chunk_count, f.next_chunk + kFrustumChunksPerStep);
      s.frustum_chunks(f.next_chunk, last);
      f.next_chunk = last;
      if (last == chunk_count) f.step = 6;
    } else {
      s.finish_frustum();  // on to step 1
    }
    stats.frustum_sort_seconds += seconds_since(start);
    return false;
  }
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
    // Everything (no culling), or the particles seen last frame: the next piece of them.
    const std::size_t end = s.step_end(f.cursor, f.first, f.chunk, f.width, f.height);
    f.used += s.submit(f.cursor, end, budget_after(f.used), style, f.view, f.projection, stats);
    f.cursor = end;
    if (f.cursor < f.first) return false;
    f.step = f.is_culled ? 2 : 4;
    return false;
  }
  if (f.step == 2) {
    // The read-back waits for the rasteriser to finish the first pass: a step of its own.
    const auto start = std::chrono::steady_clock::now();
    s.depth_pyramid.build(f.width, f.height);
    stats.depth_readback_seconds = seconds_since(start);
    f.step = 7;
    return false;
  }
  if (f.step == 7) {
    const auto start = std::chrono::steady_clock::now();
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
    // The newly seen, in pieces; budget used up: they are points this frame (and first next).
    if (f.cursor < f.first) f.cursor = f.first;
    const std::size_t end =
        s.step_end(f.cursor, s.candidates.size(), kStepParticles, f.width, f.height);
    f.used += s.submit(f.cursor, end, budget_after(f.used), style, f.view, f.projection, stats);
    f.cursor = end;
    if (f.cursor < s.candidates.size()) return false;
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

}  // namespace aggpack
