#include "aggpack/shape/generator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "growing_mesh.h"

namespace aggpack {

namespace {

constexpr std::uint32_t kVertexCapLimit = 1000000;
// Safety factors of estimated_vertex_count over the sphere tiling (see there).
constexpr double kMidpointVertexMargin = 3.0;
constexpr double kHullVertexMargin = 12.0;
double vertex_margin(Growth growth) {
  return growth == Growth::kHull ? kHullVertexMargin : kMidpointVertexMargin;
}
// The hull rule drops vertices that end up inside: insertions are capped at this many times the
// vertex cap, so a run that keeps replacing its surface still ends.
constexpr std::uint32_t kInsertionsPerVertex = 4;

// The base octahedron's six directions, in make_octahedron's order (+x, -x, +y, -y, +z, -z).
const std::array<Vec3, 6> kBaseDirections = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                                             Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};

// The growing mesh of this thread, kept between particles so that growth allocates nothing once
// warm (a particle's own allocations cost as much as its growth at L = r). A callback that grows
// a particle itself (a GrowthLimit) gets a mesh of its own.
class MeshLease {
 public:
  MeshLease() {
    if (!is_busy()) {
      is_busy() = true;
      mesh_ = &shared();
    } else {
      mesh_ = &own_.emplace();
    }
  }
  ~MeshLease() {
    if (mesh_ == &shared()) is_busy() = false;
  }
  MeshLease(const MeshLease&) = delete;
  MeshLease& operator=(const MeshLease&) = delete;
  detail::GrowingMesh& operator*() const { return *mesh_; }

 private:
  static detail::GrowingMesh& shared() {
    thread_local detail::GrowingMesh mesh;
    return mesh;
  }
  static bool& is_busy() {
    thread_local bool busy = false;
    return busy;
  }
  std::optional<detail::GrowingMesh> own_;
  detail::GrowingMesh* mesh_ = nullptr;
};

// The bodies of eq3_distance and control_radius_along, which the growth loop calls twice per
// insertion: the library is compiled with -fPIC, where GCC does not inline a function with
// external linkage (it could be interposed), so the loop calls these local copies instead.
inline double eq3_radius(double alpha, double radius, double u) {
  return radius * (alpha + (1.0 - alpha) * (0.2 + 0.8 * u));
}

inline double growth_control_radius(const GrowthParams& params, const Vec3& direction) {
  if (params.form.is_sphere()) return params.radius;
  const Vec3 local = params.axes.conjugate() * direction;
  const double b = params.form.elongation;
  const double c = b * params.form.flatness;
  const double y = local.y() / b;
  const double z = local.z() / c;
  return params.radius / std::sqrt(local.x() * local.x() + y * y + z * z);
}

}  // namespace

double eq3_distance(double alpha, double radius, double u) { return eq3_radius(alpha, radius, u); }

double estimated_vertex_count(double radius, double edge_length, Growth growth) {
  // Adjacent base vertices lie on perpendicular half-axes within r, so every base edge is at most
  // sqrt(2) r: a longer L means no growth at all.
  if (edge_length >= std::sqrt(2.0) * radius * (1.0 + 1e-12)) return 6.0;
  // Sphere area / equilateral triangle area = faces; V = F/2 + 2 for a closed triangulation.
  // Growth ends with edges shorter than L, so real counts exceed this tiling. Midpoint rule:
  // measured over alpha in [0, 1] and L/r in [0.05, 1.41] they reach 2.77 times it (alpha 1, L/r
  // 1.4; 2.0 to 2.5 times for L/r <= 0.5), hence the factor 3. Hull rule: random points leave
  // edges down to min_edge_ratio x L, and the count grows slowly as L/r falls: 5.9 times the
  // tiling at L/r 0.08 with the default min_edge_ratio 0.25, 9.8 times with 0 (alpha 0, the
  // most), hence 12.
  const double faces =
      4.0 * std::numbers::pi * radius * radius / (std::sqrt(3.0) / 4.0 * edge_length * edge_length);
  return std::max(6.0, vertex_margin(growth) * (faces / 2.0 + 2.0));
}

void validate(const GrowthParams& params) {
  require_in_range("alpha", params.alpha, 0.0, 1.0);
  require_positive("radius", params.radius);
  require_positive("edge_length", params.edge_length);
  validate(params.form);
  if (params.max_vertices < 6 || params.max_vertices > kVertexCapLimit) {
    throw InvalidInput("max_vertices", std::to_string(params.max_vertices),
                       "[6, " + std::to_string(kVertexCapLimit) + "]");
  }
  const double estimate =
      estimated_vertex_count(params.radius, params.edge_length, params.form.growth);
  if (estimate > params.max_vertices) {
    // The smallest L whose estimate fits the cap (inverting estimated_vertex_count).
    const double no_growth = std::sqrt(2.0) * params.radius * (1.0 + 1e-12);
    const double half_faces = params.max_vertices / vertex_margin(params.form.growth) - 2.0;
    const double smallest =
        half_faces <= 0.0 ? no_growth
                          : std::min(no_growth, params.radius * std::sqrt(4.0 * std::numbers::pi /
                                                                          (std::sqrt(3.0) / 4.0) /
                                                                          (2.0 * half_faces)));
    throw LimitExceeded(
        "edge_length", format_value(params.edge_length),
        Wording{Sentence::kEdgeLengthForVertexCap,
                {format_value(smallest), format_value(params.radius),
                 format_value(std::round(estimate)), std::to_string(params.max_vertices)}});
  }
}

const char* growth_name(Growth growth) { return growth == Growth::kMidpoint ? "midpoint" : "hull"; }

std::optional<Growth> find_growth(std::string_view name) {
  if (name == "hull") return Growth::kHull;
  if (name == "midpoint") return Growth::kMidpoint;
  return std::nullopt;
}

void validate(const GrowthForm& form, const std::string& prefix) {
  require_in_range(prefix + "elongation", form.elongation, 0.1, 1.0);
  require_in_range(prefix + "flatness", form.flatness, 0.1, 1.0);
  require_in_range(prefix + "min_edge_ratio", form.min_edge_ratio, 0.0, 0.5);
}

double control_radius_along(const GrowthParams& params, const Vec3& direction) {
  return growth_control_radius(params, direction);
}

ConvexPolyhedron grow_aggregate(const GrowthParams& params, Rng& rng, const GrowthLimit& limit) {
  validate(params);
  // The six base vertices on the control surface's axes, at their Eq. 3 distances.
  std::array<Vec3, 6> base;
  for (std::size_t k = 0; k < 6; ++k) {
    const Vec3 direction =
        params.form.is_sphere() ? kBaseDirections[k] : Vec3(params.axes * kBaseDirections[k]);
    base[k] = eq3_radius(params.alpha, growth_control_radius(params, direction), rng.uniform()) *
              direction;
  }
  // Reserve for the estimate, not for the cap: a 20,000-vertex reservation per particle costs more
  // in page faults than the growth itself.
  const auto expected = static_cast<std::size_t>(
      std::min(estimated_vertex_count(params.radius, params.edge_length, params.form.growth) + 16.0,
               static_cast<double>(params.max_vertices) + 1.0));
  const MeshLease lease;
  detail::GrowingMesh& mesh = *lease;
  mesh.reset(
      base, params.edge_length,
      params.form.growth == Growth::kHull ? params.form.min_edge_ratio * params.edge_length : 0.0,
      expected);
  const detail::DrawDistance draw = [&](const Vec3& direction) {
    return eq3_radius(params.alpha, growth_control_radius(params, direction), rng.uniform());
  };
  const bool is_hull = params.form.growth == Growth::kHull;
  const double min_edge = params.form.min_edge_ratio * params.edge_length;
  const std::uint64_t max_insertions =
      static_cast<std::uint64_t>(kInsertionsPerVertex) * params.max_vertices;
  std::uint64_t insertions = 0;
  detail::EdgeEntry longest{};
  while (mesh.longest_edge(longest)) {
    if (mesh.vertex_count() >= params.max_vertices || insertions++ >= max_insertions) {
      throw LimitExceeded("max_vertices", std::to_string(params.max_vertices),
                          Wording{Sentence::kVertexCapReached,
                                  {format_value(std::sqrt(longest.length_squared)),
                                   format_value(params.edge_length)}});
    }
    if (is_hull) {
      // The random point keeps min_edge from both ends (the edge is longer than L >= 2 min_edge).
      const double margin = std::min(0.5, min_edge / std::sqrt(longest.length_squared));
      const double t = margin + (1.0 - 2.0 * margin) * rng.uniform();
      mesh.insert_hull(longest, t, draw, limit);
    } else {
      mesh.split_midpoint(longest, draw, limit);
    }
  }
  return mesh.release();
}

void validate(const GeneratorOptions& options) {
  require_in_range("alpha", options.alpha, 0.0, 1.0);
  require_positive("radius_min", options.radius_min);
  require_positive("radius_max", options.radius_max);
  if (options.radius_max < options.radius_min) {
    throw InvalidInput("radius_max", format_value(options.radius_max),
                       ">= radius_min = " + format_value(options.radius_min));
  }
  // The smallest edge-to-radius ratio is the hardest case for the vertex cap.
  validate(GrowthParams{.alpha = options.alpha,
                        .radius = options.radius_max,
                        .edge_length = options.edge_length,
                        .max_vertices = options.max_vertices,
                        .form = options.form});
}

GeneratedParticle generate_particle(const GeneratorOptions& options, std::uint64_t index) {
  Rng rng(options.seed, index);
  const double radius = options.radius_min == options.radius_max
                            ? options.radius_min
                            : rng.uniform(options.radius_min, options.radius_max);
  GrowthParams params{.alpha = options.alpha,
                      .radius = radius,
                      .edge_length = options.edge_length,
                      .max_vertices = options.max_vertices,
                      .form = options.form};
  return {grow_aggregate(params, rng), radius};
}

}  // namespace aggpack
