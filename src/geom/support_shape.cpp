// SupportShape: a polyhedron prepared for fast support queries (hull vertices only, SIMD scans,
// hill-climbing over the hull adjacency on large shapes).
#include "aggpack/geom/overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "aggpack/core/error.h"
#include "gjk.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace aggpack {

namespace {

// Hull-vertex reduction drops a vertex when it is within this fraction of the shape's size from
// the hull of its neighbours (it then changes no support value by more than that).
constexpr double kRedundantVertex = 1e-14;
// A hull vertex whose incident face normals span R^3 by less than this (max |det| of three unit
// normals) has a nearly flat cone; a hill-climb ending there is confirmed by a scan, because a
// rounding-level "no better neighbour" says little about far vertices at such a vertex.
constexpr double kBluntVertex = 1e-3;

// Largest |det| of three unit normals: 0 when they all lie in one plane (the vertex is not a
// corner), up to 1 for three orthogonal faces.
double corner_sharpness(const std::vector<Vec3>& normals) {
  double sharpness = 0.0;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    for (std::size_t j = i + 1; j < normals.size(); ++j) {
      const Vec3 cross = normals[i].cross(normals[j]);
      for (std::size_t k = j + 1; k < normals.size(); ++k) {
        sharpness = std::max(sharpness, std::abs(cross.dot(normals[k])));
      }
    }
  }
  return sharpness;
}

#if defined(__x86_64__) && defined(__GNUC__)
#define AGGPACK_HAS_AVX2_SCAN 1
// Keeps, per lane, the larger value (the lower index on ties).
__attribute__((target("avx2"), always_inline)) inline void merge_avx2(__m256d& value,
                                                                      __m256d& index,
                                                                      __m256d other_value,
                                                                      __m256d other_index) {
  const __m256d take = _mm256_or_pd(_mm256_cmp_pd(other_value, value, _CMP_GT_OQ),
                                    _mm256_and_pd(_mm256_cmp_pd(other_value, value, _CMP_EQ_OQ),
                                                  _mm256_cmp_pd(other_index, index, _CMP_LT_OQ)));
  value = _mm256_blendv_pd(value, other_value, take);
  index = _mm256_blendv_pd(index, other_index, take);
}

// Eight vertices per step in two independent groups of four lanes. Same operations in the same
// order as the SSE2 loop (no FMA), so both give bit-identical answers.
__attribute__((target("avx2"))) std::uint32_t scan_avx2(const double* x, const double* y,
                                                        const double* z, std::uint32_t stride,
                                                        const Vec3& direction) {
  const __m256d dx = _mm256_set1_pd(direction.x());
  const __m256d dy = _mm256_set1_pd(direction.y());
  const __m256d dz = _mm256_set1_pd(direction.z());
  const __m256d step = _mm256_set1_pd(8.0);
  __m256d index_low = _mm256_set_pd(3.0, 2.0, 1.0, 0.0);
  __m256d index_high = _mm256_set_pd(7.0, 6.0, 5.0, 4.0);
  __m256d best_low = _mm256_set1_pd(-std::numeric_limits<double>::infinity());
  __m256d best_high = best_low;
  __m256d best_index_low = index_low;
  __m256d best_index_high = index_high;
  for (std::uint32_t i = 0; i < stride; i += 8) {
    const __m256d value_low =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, _mm256_loadu_pd(x + i)),
                                    _mm256_mul_pd(dy, _mm256_loadu_pd(y + i))),
                      _mm256_mul_pd(dz, _mm256_loadu_pd(z + i)));
    const __m256d value_high =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, _mm256_loadu_pd(x + i + 4)),
                                    _mm256_mul_pd(dy, _mm256_loadu_pd(y + i + 4))),
                      _mm256_mul_pd(dz, _mm256_loadu_pd(z + i + 4)));
    const __m256d is_greater_low = _mm256_cmp_pd(value_low, best_low, _CMP_GT_OQ);
    const __m256d is_greater_high = _mm256_cmp_pd(value_high, best_high, _CMP_GT_OQ);
    best_low = _mm256_blendv_pd(best_low, value_low, is_greater_low);
    best_high = _mm256_blendv_pd(best_high, value_high, is_greater_high);
    best_index_low = _mm256_blendv_pd(best_index_low, index_low, is_greater_low);
    best_index_high = _mm256_blendv_pd(best_index_high, index_high, is_greater_high);
    index_low = _mm256_add_pd(index_low, step);
    index_high = _mm256_add_pd(index_high, step);
  }
  // Branchless tournament over the lanes (larger value, lower index on ties): data-dependent
  // branches here cost more than the whole scan when they mispredict.
  merge_avx2(best_low, best_index_low, best_high, best_index_high);
  merge_avx2(best_low, best_index_low, _mm256_permute2f128_pd(best_low, best_low, 1),
             _mm256_permute2f128_pd(best_index_low, best_index_low, 1));
  merge_avx2(best_low, best_index_low, _mm256_permute_pd(best_low, 0x5),
             _mm256_permute_pd(best_index_low, 0x5));
  return static_cast<std::uint32_t>(_mm256_cvtsd_f64(best_index_low));
}

bool has_avx2() {
  static const bool is_supported = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return is_supported;
}
#endif

}  // namespace

SupportShape::SupportShape(const ConvexPolyhedron& body, SupportSearch search) {
  if (body.is_empty()) throw InvalidInput("support shape", "empty polyhedron", ">= 4 vertices");
  const auto& vertices = body.vertices();
  const auto& triangles = body.triangles();
  const auto vertex_total = static_cast<std::uint32_t>(vertices.size());
  (void)body.edges();  // throws InvalidInput unless a closed 2-manifold
  const auto all_neighbours = body.vertex_neighbours();
  bounding_radius_ = aggpack::bounding_radius(body);

  std::vector<std::vector<Vec3>> incident_normals(vertex_total);
  inner_radius_ = aggpack::inner_radius(body);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Vec3 scaled = body.face_normal_scaled(f);
    const double twice_area = scaled.norm();
    if (!(twice_area > 0.0)) continue;  // a zero-area triangle constrains nothing
    const Vec3 normal = scaled / twice_area;
    for (auto index : triangles[f]) incident_normals[index].push_back(normal);
  }

  // Hull vertices: a vertex in the hull of its neighbours (on an edge or face of the hull) is
  // never needed by a support query. Distance point-to-hull by the same GJK.
  std::vector<std::uint32_t> hull_index(vertex_total, kNoHint);
  std::vector<std::uint32_t> kept;
  std::vector<Vec3> link;
  const double redundancy = kRedundantVertex * bounding_radius_;
  for (std::uint32_t i = 0; i < vertex_total; ++i) {
    link.clear();
    for (auto n : all_neighbours[i]) link.push_back(vertices[n]);
    bool is_redundant = false;
    if (link.size() >= 2) {
      const std::array<Vec3, 1> point = {vertices[i]};
      const GjkResult run = run_gjk(
          PointsSupport{link.data(), static_cast<std::uint32_t>(link.size())},
          PointsSupport{point.data(), 1}, Mat3::Identity(), Vec3::Zero(), redundancy, redundancy);
      is_redundant = run.outcome != GjkOutcome::kSeparated;
    }
    if (!is_redundant) {
      hull_index[i] = static_cast<std::uint32_t>(kept.size());
      kept.push_back(i);
    }
  }
  if (kept.size() < 4) {  // only for degenerate (flat) input; keep everything
    kept.clear();
    for (std::uint32_t i = 0; i < vertex_total; ++i) {
      hull_index[i] = i;
      kept.push_back(i);
    }
  }
  count_ = static_cast<std::uint32_t>(kept.size());
  stride_ = (count_ + 7u) & ~7u;  // whole steps of the widest scan
  coordinates_.assign(3 * static_cast<std::size_t>(stride_), 0.0);
  for (std::uint32_t slot = 0; slot < stride_; ++slot) {
    const Vec3& p = vertices[kept[std::min(slot, count_ - 1)]];
    for (int axis = 0; axis < 3; ++axis) coordinates_[axis * stride_ + slot] = p[axis];
  }

  // Adjacency between hull vertices: neighbours in the mesh, reached through dropped vertices.
  // It contains every edge of the hull (an edge of the hull is a chain of mesh edges whose inner
  // vertices were dropped), which is all hill-climbing needs.
  neighbour_offsets_.assign(1, 0);
  is_blunt_.assign(count_, 0);
  std::vector<std::uint8_t> visited(vertex_total, 0);
  std::vector<std::uint32_t> stack;
  std::vector<std::uint32_t> touched;
  for (std::uint32_t slot = 0; slot < count_; ++slot) {
    const std::uint32_t origin = kept[slot];
    stack.assign(all_neighbours[origin].begin(), all_neighbours[origin].end());
    touched.assign(1, origin);
    visited[origin] = 1;
    const std::size_t first = neighbours_.size();
    while (!stack.empty()) {
      const std::uint32_t current = stack.back();
      stack.pop_back();
      if (visited[current] != 0) continue;
      visited[current] = 1;
      touched.push_back(current);
      if (hull_index[current] != kNoHint) {
        neighbours_.push_back(hull_index[current]);
      } else {
        for (auto n : all_neighbours[current]) {
          if (visited[n] == 0) stack.push_back(n);
        }
      }
    }
    for (auto t : touched) visited[t] = 0;
    std::sort(neighbours_.begin() + static_cast<std::ptrdiff_t>(first), neighbours_.end());
    neighbour_offsets_.push_back(static_cast<std::uint32_t>(neighbours_.size()));
    is_blunt_[slot] = corner_sharpness(incident_normals[origin]) < kBluntVertex ? 1 : 0;
  }
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 direction = Vec3::Zero();
    direction[axis] = 1.0;
    axis_extremes_[2 * axis] = scan(direction);
    axis_extremes_[2 * axis + 1] = scan(-direction);
  }
  uses_hill_climbing_ = search == SupportSearch::kHillClimb ||
                        (search == SupportSearch::kAuto && count_ > kHillClimbMinVertices);
}

std::uint32_t SupportShape::scan(const Vec3& direction) const {
  const double* x = coordinates_.data();
  const double* y = x + stride_;
  const double* z = y + stride_;
#if defined(AGGPACK_HAS_AVX2_SCAN)
  if (has_avx2()) return std::min(scan_avx2(x, y, z, stride_, direction), count_ - 1);
#endif
#if defined(__SSE2__)
  // Four vertices per step (SSE2 is in every x86-64), in two independent pairs of lanes so the
  // compare-and-select chains overlap. Each lane keeps its first maximum; lanes are merged
  // preferring the lower index, so the answer is the first maximum overall, as in the scalar
  // loop. Padding repeats the last vertex, which can only tie with it.
  const __m128d dx = _mm_set1_pd(direction.x());
  const __m128d dy = _mm_set1_pd(direction.y());
  const __m128d dz = _mm_set1_pd(direction.z());
  const __m128d step = _mm_set1_pd(4.0);
  __m128d index_low = _mm_set_pd(1.0, 0.0);
  __m128d index_high = _mm_set_pd(3.0, 2.0);
  __m128d best_low = _mm_set1_pd(-std::numeric_limits<double>::infinity());
  __m128d best_high = best_low;
  __m128d best_index_low = index_low;
  __m128d best_index_high = index_high;
  const auto dot = [&](std::uint32_t i) {
    return _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(dx, _mm_loadu_pd(x + i)), _mm_mul_pd(dy, _mm_loadu_pd(y + i))),
        _mm_mul_pd(dz, _mm_loadu_pd(z + i)));
  };
  const auto select = [](__m128d mask, __m128d if_true, __m128d if_false) {
    return _mm_or_pd(_mm_and_pd(mask, if_true), _mm_andnot_pd(mask, if_false));
  };
  for (std::uint32_t i = 0; i < stride_; i += 4) {
    const __m128d value_low = dot(i);
    const __m128d value_high = dot(i + 2);
    const __m128d is_greater_low = _mm_cmpgt_pd(value_low, best_low);
    const __m128d is_greater_high = _mm_cmpgt_pd(value_high, best_high);
    best_low = select(is_greater_low, value_low, best_low);
    best_high = select(is_greater_high, value_high, best_high);
    best_index_low = select(is_greater_low, index_low, best_index_low);
    best_index_high = select(is_greater_high, index_high, best_index_high);
    index_low = _mm_add_pd(index_low, step);
    index_high = _mm_add_pd(index_high, step);
  }
  // Branchless tournament over the lanes, as in scan_avx2.
  const auto merge = [&select](__m128d& value, __m128d& index, __m128d other_value,
                               __m128d other_index) {
    const __m128d take =
        _mm_or_pd(_mm_cmpgt_pd(other_value, value),
                  _mm_and_pd(_mm_cmpeq_pd(other_value, value), _mm_cmplt_pd(other_index, index)));
    value = select(take, other_value, value);
    index = select(take, other_index, index);
  };
  merge(best_low, best_index_low, best_high, best_index_high);
  merge(best_low, best_index_low, _mm_shuffle_pd(best_low, best_low, 1),
        _mm_shuffle_pd(best_index_low, best_index_low, 1));
  return std::min(static_cast<std::uint32_t>(_mm_cvtsd_f64(best_index_low)), count_ - 1);
#else
  std::uint32_t best = 0;
  double best_value = direction.x() * x[0] + direction.y() * y[0] + direction.z() * z[0];
  for (std::uint32_t i = 1; i < count_; ++i) {
    const double value = direction.x() * x[i] + direction.y() * y[i] + direction.z() * z[i];
    if (value > best_value) {
      best_value = value;
      best = i;
    }
  }
  return best;
#endif
}

std::uint32_t SupportShape::climb(const Vec3& direction, std::uint32_t start) const {
  if (start >= count_) {
    int axis = 0;
    if (std::abs(direction.y()) > std::abs(direction.x())) axis = 1;
    if (std::abs(direction.z()) > std::abs(direction[axis])) axis = 2;
    start = axis_extremes_[2 * axis + (direction[axis] < 0.0 ? 1 : 0)];
  }
  const double* x = coordinates_.data();
  const double* y = x + stride_;
  const double* z = y + stride_;
  std::uint32_t current = start;
  double current_value =
      direction.x() * x[current] + direction.y() * y[current] + direction.z() * z[current];
  // Steepest ascent; strictly increasing, so it ends. On a convex polytope a vertex with no
  // better neighbour along the hull edges is a global maximum.
  for (;;) {
    std::uint32_t best = current;
    for (std::uint32_t k = neighbour_offsets_[current]; k < neighbour_offsets_[current + 1]; ++k) {
      const std::uint32_t n = neighbours_[k];
      const double value = direction.x() * x[n] + direction.y() * y[n] + direction.z() * z[n];
      if (value > current_value) {
        current_value = value;
        best = n;
      }
    }
    if (best == current) break;
    current = best;
  }
  return is_blunt_[current] != 0 ? scan(direction) : current;
}

std::uint32_t SupportShape::support(const Vec3& direction, std::uint32_t start) const {
  return uses_hill_climbing_ ? climb(direction, start) : scan(direction);
}

}  // namespace aggpack
