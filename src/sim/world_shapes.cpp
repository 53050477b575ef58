// World: the Bullet hull (and the exact shapes) of every distinct (shape, scale) of a packing.
#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/descriptors.h"
#include "world_impl.h"

namespace aggpack {

namespace {

constexpr double kMinSize = 1e-9;      // m, smallest equivalent diameter simulated
constexpr double kMaxSize = 1e6;       // m, largest
constexpr double kMaxSizeRatio = 1e6;  // largest / smallest in one world

}  // namespace

void World::Impl::build_shapes() {
  // One hull per distinct (stored shape, scale): a shape library reuses one stored shape at many
  // sizes, and Bullet's local scaling is a property of the shared shape, not of the body.
  std::map<std::pair<std::uint32_t, double>, std::uint32_t> keys;
  body_shape.reserve(packing.particles.size());
  for (const auto& particle : packing.particles) {
    if (particle.shape >= packing.shapes.size()) {
      throw InvalidInput("particle.shape", std::to_string(particle.shape),
                         "[0, " + std::to_string(packing.shapes.size()) + ")");
    }
    if (!(particle.scale > 0.0) || !std::isfinite(particle.scale)) {
      throw InvalidInput("particle.scale", format_value(particle.scale), "> 0");
    }
    const auto [it, is_new] = keys.try_emplace({particle.shape, particle.scale},
                                               static_cast<std::uint32_t>(shapes.size()));
    if (is_new) {
      detail::ShapeData shape;
      shape.source = particle.shape;
      shape.scale = particle.scale;
      shapes.push_back(std::move(shape));
    }
    body_shape.push_back(it->second);
  }
  for (auto& shape : shapes) {
    const ConvexPolyhedron& stored = packing.shapes[shape.source];
    const MassProperties mass = mass_properties(stored);
    if (!(mass.volume > 0.0)) {
      throw InvalidInput("shape " + std::to_string(shape.source) + " volume",
                         format_value(mass.volume), "> 0 (a closed outward mesh)");
    }
    const double s = shape.scale;
    shape.volume = mass.volume * s * s * s;
    shape.centroid = s * mass.centroid;  // in the stored (unscaled-pose) local frame, scaled
    shape.size = equivalent_diameter(shape.volume);
    // Masses, inertias and the time step (from the smallest size) must stay finite and non-zero:
    // a particle at scale 1e-200 has volume 0, a time step of 0 and made settle run forever.
    if (!(shape.size >= kMinSize && shape.size <= kMaxSize)) {
      std::size_t particle = 0;
      while (packing.particles[particle].shape != shape.source ||
             packing.particles[particle].scale != s) {
        ++particle;
      }
      throw InvalidInput(
          "particle " + std::to_string(particle) + " scale",
          format_value(s) + " (equivalent diameter " + format_value(shape.size) + " m)",
          "a size giving an equivalent diameter in [1e-9, 1e6] m");
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> eigen(mass.inertia);
    Mat3 axes = eigen.eigenvectors();
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
    shape.principal = Quat(axes).normalized();
    shape.unit_inertia = eigen.eigenvalues() * std::pow(s, 5);
  }
  std::vector<double> sizes;
  sizes.reserve(body_shape.size());
  for (const auto index : body_shape) sizes.push_back(shapes[index].size);
  std::sort(sizes.begin(), sizes.end());
  smallest_size = sizes.front();
  median_size = sizes[sizes.size() / 2];
  if (sizes.back() > kMaxSizeRatio * sizes.front()) {
    throw InvalidInput("particle sizes",
                       format_value(sizes.front()) + " to " + format_value(sizes.back()) + " m",
                       "largest / smallest <= 10^6 (Bullet's tolerances follow the median size)");
  }
  scale = 1.0 / median_size;
  margin = options.margin_fraction * smallest_size * scale;
  for (auto& shape : shapes) {
    const Mat3 to_principal = shape.principal.conjugate().toRotationMatrix();
    const ConvexPolyhedron& stored = packing.shapes[shape.source];
    std::vector<btScalar> points;
    points.reserve(3 * stored.vertex_count());
    for (const auto& v : stored.vertices()) {
      const Vec3 p = scale * (to_principal * (shape.scale * v - shape.centroid));
      points.insert(points.end(), {p.x(), p.y(), p.z()});
    }
    const int count = static_cast<int>(points.size() / 3);
    // Bullet collides the hull inflated by the margin (a body with rounded edges) and runs GJK on
    // the hull itself, needing the slower EPA only when hulls interpenetrate. So the hull is
    // scaled about the centroid by s = 1 - margin / h_min (h_min: distance from the centroid to
    // the nearest face plane): the support function of s * hull + margin is then at most that of
    // the polyhedron in every direction, i.e. the rounded body lies inside the polyhedron, touches
    // its nearest face, and is nowhere more than margin * (h_face / h_min - 1) inside a face.
    // (Moving every face in by the margin instead, btConvexHullComputer's shrink, splits each
    // vertex into several and triples the support-mapping cost.) The computer also keeps only
    // extreme points: the generator leaves many vertices on an edge or a face plane.
    btConvexHullComputer computer;
    computer.compute(points.data(), 3 * sizeof(btScalar), count, 0.0, 0.0);
    if (computer.vertices.size() < 4 || computer.faces.size() < 4) {
      throw InvalidInput("shape " + std::to_string(shape.source), "degenerate hull",
                         "a convex body with positive volume");
    }
    double nearest_face = std::numeric_limits<double>::infinity();
    for (int f = 0; f < computer.faces.size(); ++f) {
      const auto* edge = &computer.edges[computer.faces[f]];
      const btVector3 a = computer.vertices[edge->getSourceVertex()];
      const btVector3 b = computer.vertices[edge->getTargetVertex()];
      const btVector3 c = computer.vertices[edge->getNextEdgeOfFace()->getTargetVertex()];
      const btVector3 normal = (b - a).cross(c - a);
      if (normal.length2() > 0.0) nearest_face = std::min(nearest_face, normal.normalized().dot(a));
    }
    if (!(nearest_face > 2.0 * margin)) {
      throw InvalidInput("shape " + std::to_string(shape.source) + " inner radius",
                         format_value(nearest_face / scale), "> 2 x collision margin");
    }
    const btScalar factor = 1.0 - margin / nearest_face;
    btAlignedObjectArray<btVector3> scaled;
    for (int v = 0; v < computer.vertices.size(); ++v)
      scaled.push_back(factor * computer.vertices[v]);
    shape.hull =
        std::make_unique<btConvexHullShape>(&scaled[0].x(), scaled.size(), sizeof(btVector3));
    shape.hull->setMargin(margin);
    shape.exact = SupportShape(shape.scale == 1.0 ? stored : stored.scaled(shape.scale));
    shape.exact_hull =
        std::make_unique<btConvexHullShape>(points.data(), count, 3 * sizeof(btScalar));
    shape.exact_hull->optimizeConvexHull();
    shape.exact_hull->setMargin(0.0);
  }
}

}  // namespace aggpack
