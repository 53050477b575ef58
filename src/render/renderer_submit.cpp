// PackingRenderer::State::submit: levels of detail, draw lists and draw calls for a run of
// front-to-back candidates.

#include "renderer_state.h"

namespace aggpack {

namespace {

// A well-mixed 32-bit hash of an index (Wellons' lowbias32).
std::uint32_t mix_hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace

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

  std::size_t left_out = 0;
  const std::size_t mesh_triangles =
      choose_levels(begin, count, budget, style, keep_below(count, style, stats), left_out);
  const std::size_t coarse = build_draw_lists(begin, count);
  stats.particles_drawn += count - left_out;
  stats.point_particles += point_list.size();
  stats.coarse_particles += coarse;
  stats.triangles += mesh_triangles;
  const std::uint32_t next = build_instance_list(begin, count);

  if (next > 1 || !single_counts.empty()) draw_meshes(style, view, projection, stats);
  if (!point_list.empty()) draw_points(style, view, projection, stats);
  return mesh_triangles;
}

// Over the particle cap: thin the particles evenly over the picture (not the farthest: that
// cuts the pile with a plane) and the same ones from frame to frame: keep a particle when a
// hash of its index falls below the fraction that fits (a mixing hash: the golden-ratio
// sequence would pick particles of one colour, as colours follow it).
std::uint64_t PackingRenderer::State::keep_below(std::size_t count, const RenderStyle& style,
                                                 const DrawStats& stats) const {
  std::uint64_t threshold = std::uint64_t{1} << 32;
  if (style.max_particles > 0) {
    const std::size_t room = style.max_particles > stats.particles_drawn
                                 ? style.max_particles - stats.particles_drawn
                                 : 0;
    if (room < count) {
      threshold = static_cast<std::uint64_t>(static_cast<double>(room) /
                                             static_cast<double>(count) * 4294967296.0);
    }
  }
  return threshold;
}

std::size_t PackingRenderer::State::triangles_of(std::size_t begin, std::size_t k) const {
  const ShapeRange& range = shapes[particle_shape[candidates[begin + k].particle]];
  if (level[k] >= 2) return 0;
  return static_cast<std::size_t>((level[k] == 1 ? range.coarse_count : range.full_count) / 3);
}

// Level of detail: full, coarse or point by projected size; then, over the triangle budget,
// the smallest particles become points. 3: left out (particle cap).
std::size_t PackingRenderer::State::choose_levels(std::size_t begin, std::size_t count,
                                                  std::size_t budget, const RenderStyle& style,
                                                  std::uint64_t keep_below_hash,
                                                  std::size_t& left_out) {
  level.assign(count, 0);
  std::size_t mesh_triangles = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const float pixels = candidates[begin + k].pixels;
    if (mix_hash(candidates[begin + k].particle) >= keep_below_hash) {
      level[k] = 3;
      ++left_out;
      continue;
    }
    if (pixels < style.point_below_pixels) {
      level[k] = 2;
    } else if (pixels < style.coarse_below_pixels) {
      level[k] = 1;
    }
    mesh_triangles += triangles_of(begin, k);
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
      mesh_triangles -= triangles_of(begin, k);
      level[k] = 2;
    }
  }
  return mesh_triangles;
}

// Draw lists: single-use shapes in one multi-draw per mesh page, instanced shapes by (shape,
// level), points in one draw; each in front-to-back order.
std::size_t PackingRenderer::State::build_draw_lists(std::size_t begin, std::size_t count) {
  const std::size_t shape_count = shapes.size();
  // Two entries per shape, used by the instanced shapes only (zeroing all of them costs 8 MB a
  // step at 10^6 shapes; the vector is sized when the scene is prepared).
  group_counts.resize(2 * shape_count);
  for (std::uint32_t shape : instanced_shapes) {
    group_counts[2 * shape] = 0;
    group_counts[2 * shape + 1] = 0;
  }
  page_single_start.assign(page_count + 1, 0);
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
      ++page_single_start[range.page + 1];
    }
  }
  for (std::size_t page = 0; page < page_count; ++page) {
    page_single_start[page + 1] += page_single_start[page];
  }
  const std::size_t singles = page_single_start[page_count];
  single_counts.resize(singles);
  single_offsets.resize(singles);
  single_base_vertices.resize(singles);
  page_cursor.assign(page_single_start.begin(), page_single_start.end());
  for (std::size_t k = 0; k < count; ++k) {
    const ShapeRange& range = shapes[particle_shape[candidates[begin + k].particle]];
    const std::uint8_t lod = level[k];
    if (lod >= 2 || range.instances >= 2) continue;
    const std::uint32_t at = page_cursor[range.page]++;
    single_counts[at] = lod == 1 ? range.coarse_count : range.full_count;
    single_offsets[at] = reinterpret_cast<const void*>(
        static_cast<std::uintptr_t>(lod == 1 ? range.coarse_offset : range.full_offset) *
        index_size);
    single_base_vertices[at] = range.base_vertex;
  }
  return coarse;
}

// Instance list: element 0 stays 0 (what single-use shapes read through the per-instance
// attribute), then one block per (shape, level) group.
std::uint32_t PackingRenderer::State::build_instance_list(std::size_t begin, std::size_t count) {
  group_start.resize(2 * shapes.size());  // the instanced shapes' entries, all set below
  std::uint32_t next = 1;
  for (std::uint32_t shape : instanced_shapes) {
    for (std::size_t lod = 0; lod < 2; ++lod) {
      group_start[2 * shape + lod] = next;
      next += group_counts[2 * shape + lod];
    }
  }
  instance_list.resize(next);
  instance_list[0] = GpuInstance{};  // the identity, with particle 0 (single-use meshes)
  // Only the instanced shapes' entries (a copy of all of group_start: 8 MB a step at 10^6 shapes).
  cursor.resize(group_start.size());
  for (std::uint32_t shape : instanced_shapes) {
    cursor[2 * shape] = group_start[2 * shape];
    cursor[2 * shape + 1] = group_start[2 * shape + 1];
  }
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t particle = candidates[begin + k].particle;
    const std::uint32_t shape = particle_shape[particle];
    if (level[k] >= 2 || shapes[shape].instances < 2) continue;
    instance_list[cursor[2 * shape + level[k]]++] = {transforms[particle], particle};
  }
  return next;
}

void PackingRenderer::State::draw_meshes(const RenderStyle& style, const Eigen::Matrix4f& view,
                                         const Eigen::Matrix4f& projection, DrawStats& stats) {
  glUseProgram(particle_program);
  glUniformMatrix4fv(u_view, 1, GL_FALSE, view.data());
  glUniformMatrix4fv(u_projection, 1, GL_FALSE, projection.data());
  glUniform1i(u_lit, style.is_wireframe ? 0 : 1);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, color_texture);
  glUniform1i(u_colors, 0);
  if (style.is_wireframe) {
    glDisable(GL_CULL_FACE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, instance_buffer);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instance_list.size() * sizeof(GpuInstance)),
               instance_list.data(), GL_STREAM_DRAW);
  // Each page's vertex array reads the per-instance attributes from instance_buffer (element 0
  // unless an instanced draw points them elsewhere).
  std::size_t bound_page = page_count;
  auto bind_page = [&](std::size_t page) {
    if (page == bound_page) return;
    if (bound_page < page_count) point_instances_at(0);
    glBindVertexArray(mesh_pages[page].vertex_array);
    bound_page = page;
  };
  for (std::size_t page = 0; page < page_count; ++page) {
    const std::uint32_t first = page_single_start[page];
    const std::uint32_t end = page_single_start[page + 1];
    if (first == end) continue;
    bind_page(page);
    glMultiDrawElementsBaseVertex(GL_TRIANGLES, single_counts.data() + first, index_type,
                                  single_offsets.data() + first, static_cast<GLsizei>(end - first),
                                  single_base_vertices.data() + first);
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
      bind_page(range.page);
      point_instances_at(group_start[group]);
      const GLsizei index_count = lod == 1 ? range.coarse_count : range.full_count;
      const GLuint offset = lod == 1 ? range.coarse_offset : range.full_offset;
      glDrawElementsInstancedBaseVertex(
          GL_TRIANGLES, index_count, index_type,
          reinterpret_cast<const void*>(static_cast<std::uintptr_t>(offset) * index_size),
          instances, range.base_vertex);
      ++stats.draw_calls;
      // Hand what is set up to the rasteriser threads now and then (see the impostors).
      unflushed += static_cast<std::size_t>(index_count / 3) * static_cast<std::size_t>(instances);
      if (unflushed >= kFlushTriangles) {
        glFlush();
        unflushed = 0;
      }
    }
  }
  if (bound_page < page_count) point_instances_at(0);
  glBindVertexArray(0);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glDisable(GL_CULL_FACE);
}

void PackingRenderer::State::draw_points(const RenderStyle& style, const Eigen::Matrix4f& view,
                                         const Eigen::Matrix4f& projection, DrawStats& stats) {
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

}  // namespace aggpack
