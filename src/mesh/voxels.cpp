// The mesomodel's phase image (mesh/voxels.h).

#include "aggpack/mesh/voxels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/geom/halfspace.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/container.h"

namespace aggpack {

namespace {

// A placed particle: its face planes, centre and reach.
struct Body {
  ConvexPolyhedron shape;
  std::vector<HalfSpace> planes;
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;  // vertices lie within this distance of centre
  Aabb bounds;
  std::uint32_t particle = 0;  // 1-based (a periodic box has images of a particle too)
};

Body make_body(ConvexPolyhedron shape, const Vec3& centre, std::uint32_t particle) {
  Body body;
  body.particle = particle;
  body.centre = centre;
  for (const Vec3& v : shape.vertices()) body.radius = std::max(body.radius, (v - centre).norm());
  body.planes = face_half_spaces(shape);
  body.bounds = shape.bounds();
  body.shape = std::move(shape);
  return body;
}

}  // namespace

double offset_shell_volume(const ConvexPolyhedron& body, double thickness) {
  const double t = thickness;
  double mean_width_integral = 0.0;  // 1/2 sum of edge length x exterior dihedral angle
  for (const Edge& edge : body.edges()) {
    const Vec3 a = body.face_normal(edge.faces[0]);
    const Vec3 b = body.face_normal(edge.faces[1]);
    const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
    const double length =
        (body.vertices()[edge.vertices[0]] - body.vertices()[edge.vertices[1]]).norm();
    mean_width_integral += 0.5 * length * angle;
  }
  const double area = mass_properties(body).surface_area;
  return area * t + mean_width_integral * t * t + 4.0 / 3.0 * std::numbers::pi * t * t * t;
}

void validate(const VoxelOptions& options) {
  if (options.resolution < 2 || options.resolution > 4096) {
    throw InvalidInput("voxels", std::to_string(options.resolution), "[2, 4096]");
  }
  if (!std::isfinite(options.itz_thickness) || options.itz_thickness < 0.0) {
    throw InvalidInput("itz_thickness", format_value(options.itz_thickness), ">= 0 (m)");
  }
}

std::array<std::uint64_t, 4> VoxelImage::phase_counts() const {
  std::array<std::uint64_t, 4> counts{};
  for (const std::uint8_t p : phase) ++counts[std::min<std::size_t>(p, 3)];
  return counts;
}

VoxelImage voxelize(const Packing& packing, const VoxelOptions& options) {
  validate(options);
  const Aabb box = packing.container.bounds();
  const Vec3 extent = box.extent();
  const double longest = extent.maxCoeff();
  if (options.itz_thickness >= 0.5 * extent.minCoeff()) {
    throw InvalidInput("itz_thickness", format_value(options.itz_thickness),
                       "[0, " + format_value(0.5 * extent.minCoeff()) +
                           ") m: half the container's "
                           "smallest side");
  }
  VoxelImage image;
  image.spacing = longest / options.resolution;
  image.origin = box.lower;
  std::uint64_t total = 1;
  for (int axis = 0; axis < 3; ++axis) {
    image.dims[axis] =
        static_cast<std::uint32_t>(std::max(1.0, std::round(extent[axis] / image.spacing)));
    total *= image.dims[axis];
  }
  // A periodic image tiles only when its voxels fill each periodic extent exactly.
  const std::array<bool, 3> periodic = periodic_axes(packing.container);
  for (int axis = 0; axis < 3; ++axis) {
    const double cells = extent[axis] / image.spacing;
    if (periodic[static_cast<std::size_t>(axis)] &&
        std::abs(cells - std::round(cells)) > 1e-9 * cells) {
      throw InvalidInput("voxels", std::to_string(options.resolution),
                         Wording{Sentence::kVoxelsTilePeriodic, {}});
    }
  }
  if (total > options.max_voxels) {
    throw LimitExceeded("voxels",
                        std::to_string(options.resolution) + " (" + std::to_string(total) +
                            " voxels, 5 bytes each)",
                        "at most " + std::to_string(options.max_voxels) + " voxels");
  }
  // An extent that is not a multiple of the spacing is covered to the nearest whole voxel; centres
  // that fall outside the container are labelled outside.
  const double t = options.itz_thickness;
  std::vector<Body> bodies;
  bodies.reserve(packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron placed = packing.placed(i);
    const Aabb reach = placed.bounds();
    // Along a periodic axis every image within t of the box (one period away at most: the
    // extents exceed twice a particle's enclosing radius), so the image tiles without seams.
    for (int shift = 0; shift < 27; ++shift) {
      Vec3 offset = Vec3::Zero();
      bool is_used = true;
      for (int axis = 0, code = shift; axis < 3; ++axis, code /= 3) {
        const int step = code % 3 == 2 ? -1 : code % 3;
        offset[axis] = step * extent[axis];
        is_used &= step == 0 || (periodic[static_cast<std::size_t>(axis)] &&
                                 reach.lower[axis] + offset[axis] < box.upper[axis] + t &&
                                 reach.upper[axis] + offset[axis] > box.lower[axis] - t);
      }
      if (!is_used) continue;
      ConvexPolyhedron shape = placed;
      if (shift != 0) {
        std::vector<Vec3> vertices = placed.vertices();
        for (Vec3& v : vertices) v += offset;
        shape = ConvexPolyhedron(std::move(vertices), placed.triangles());
      }
      bodies.push_back(make_body(std::move(shape), packing.particles[i].pose.position + offset,
                                 static_cast<std::uint32_t>(i + 1)));
    }
  }
  // Particles binned by the z range of their bounds (+ t) over the voxel layers: each layer
  // looks only at the particles that reach it.
  const std::uint32_t nz = image.dims[2];
  std::vector<std::vector<std::uint32_t>> layer_bodies(nz);
  for (std::uint32_t i = 0; i < bodies.size(); ++i) {
    const double lo = (bodies[i].bounds.lower.z() - t - box.lower.z()) / image.spacing - 0.5;
    const double hi = (bodies[i].bounds.upper.z() + t - box.lower.z()) / image.spacing - 0.5;
    const auto first = static_cast<std::int64_t>(std::max(0.0, std::ceil(lo)));
    const auto last = static_cast<std::int64_t>(std::min<double>(nz - 1, std::floor(hi)));
    for (std::int64_t k = first; k <= last; ++k) layer_bodies[k].push_back(i);
  }
  image.phase.assign(total, static_cast<std::uint8_t>(VoxelPhase::kMortar));
  image.particle.assign(total, 0);
  const std::uint32_t nx = image.dims[0];
  const std::uint32_t ny = image.dims[1];
  parallel_for_index(0, nz, [&](std::size_t k) {
    const double z = box.lower.z() + (static_cast<double>(k) + 0.5) * image.spacing;
    // The layer's particles, with their x-y bounds, for a quick reject per voxel.
    const auto& candidates = layer_bodies[k];
    for (std::uint32_t j = 0; j < ny; ++j) {
      const double y = box.lower.y() + (j + 0.5) * image.spacing;
      for (std::uint32_t i = 0; i < nx; ++i) {
        const double x = box.lower.x() + (i + 0.5) * image.spacing;
        const Vec3 p(x, y, z);
        const std::size_t index = (static_cast<std::size_t>(k) * ny + j) * nx + i;
        if (wall_clearance(packing.container, p) < 0.0) {
          image.phase[index] = static_cast<std::uint8_t>(VoxelPhase::kOutside);
          continue;
        }
        double nearest = std::numeric_limits<double>::infinity();
        std::uint32_t nearest_body = 0;
        bool is_aggregate = false;
        for (const std::uint32_t b : candidates) {
          const Body& body = bodies[b];
          const Aabb& bb = body.bounds;
          if (x < bb.lower.x() - t || x > bb.upper.x() + t || y < bb.lower.y() - t ||
              y > bb.upper.y() + t) {
            continue;
          }
          const double s = plane_excess(body.planes, p);
          if (s <= 0.0) {
            image.phase[index] = static_cast<std::uint8_t>(VoxelPhase::kAggregate);
            image.particle[index] = body.particle;
            is_aggregate = true;
            break;
          }
          if (s > t || s >= nearest) continue;
          const double d = distance_to_body(body.shape, p);
          if (d <= t && d < nearest) {
            nearest = d;
            nearest_body = body.particle;
          }
        }
        if (!is_aggregate && nearest_body != 0) {
          image.phase[index] = static_cast<std::uint8_t>(VoxelPhase::kItz);
          image.particle[index] = nearest_body;
        }
      }
    }
  });
  return image;
}

}  // namespace aggpack
