#include "aggpack/shape/descriptors.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "aggpack/core/error.h"
#include "aggpack/geom/enclosing_sphere.h"

namespace aggpack {

double sphericity(double volume, double surface_area) {
  const double pi = std::numbers::pi;
  return (4.0 * pi / surface_area) * std::pow(3.0 * volume / (4.0 * pi), 2.0 / 3.0);
}

double measured_alpha(double volume, double surface_area) {
  return std::pow(sphericity(volume, surface_area), 1.5);
}

double equivalent_diameter(double volume) { return std::cbrt(6.0 * volume / std::numbers::pi); }

ShapeDescriptors describe(const ConvexPolyhedron& body) {
  ShapeDescriptors result;
  const MassProperties mass = mass_properties(body);
  if (!(mass.volume > 0.0)) {
    throw InvalidInput(Wording{Sentence::kParticleVolume, {}},
                       Wording{Sentence::kText, {format_value(mass.volume)}},
                       Wording{Sentence::kText, {"> 0"}});
  }
  result.volume = mass.volume;
  result.surface_area = mass.surface_area;
  result.sphericity = sphericity(mass.volume, mass.surface_area);
  result.measured_alpha = measured_alpha(mass.volume, mass.surface_area);
  result.vertex_count = body.vertex_count();
  result.face_count = body.triangle_count();
  result.edge_count = body.vertex_count() + body.triangle_count() - 2;  // Euler, closed genus 0

  // Principal axes of inertia; extents of the vertices along them.
  Eigen::SelfAdjointEigenSolver<Mat3> solver(mass.inertia);
  const Mat3 axes = solver.eigenvectors();
  std::array<double, 3> extents{};
  for (int axis = 0; axis < 3; ++axis) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const auto& v : body.vertices()) {
      const double t = axes.col(axis).dot(v - mass.centroid);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    extents[axis] = hi - lo;
  }
  std::sort(extents.begin(), extents.end(), std::greater<>());
  result.long_dimension = extents[0];
  result.intermediate_dimension = extents[1];
  result.short_dimension = extents[2];
  result.elongation = extents[1] / extents[0];
  result.flatness = extents[2] / extents[1];
  for (const auto& v : body.vertices()) {
    result.circumscribed_radius = std::max(result.circumscribed_radius, (v - mass.centroid).norm());
  }
  result.enclosing_radius = minimal_enclosing_sphere(body.vertices()).radius;
  result.equivalent_diameter = equivalent_diameter(mass.volume);
  result.longest_edge = body.longest_edge();
  return result;
}

SummaryStatistics summarize(const std::vector<double>& values) {
  SummaryStatistics stats;
  stats.count = values.size();
  if (values.empty()) return stats;
  stats.minimum = *std::min_element(values.begin(), values.end());
  stats.maximum = *std::max_element(values.begin(), values.end());
  // Two-pass for accuracy; sums in index order so the result is independent of threading.
  double sum = 0.0;
  for (double v : values) sum += v;
  stats.mean = sum / static_cast<double>(values.size());
  if (values.size() > 1) {
    double squares = 0.0;
    for (double v : values) squares += (v - stats.mean) * (v - stats.mean);
    stats.standard_deviation = std::sqrt(squares / static_cast<double>(values.size() - 1));
  }
  return stats;
}

void RunningSummary::add(double value) {
  if (stats_.count == 0) {
    stats_.minimum = value;
    stats_.maximum = value;
  } else {
    stats_.minimum = std::min(stats_.minimum, value);
    stats_.maximum = std::max(stats_.maximum, value);
  }
  ++stats_.count;
  const double delta = value - stats_.mean;
  stats_.mean += delta / static_cast<double>(stats_.count);
  squares_ += delta * (value - stats_.mean);
}

SummaryStatistics RunningSummary::result() const {
  SummaryStatistics stats = stats_;
  if (stats.count > 1) {
    stats.standard_deviation = std::sqrt(squares_ / static_cast<double>(stats.count - 1));
  }
  return stats;
}

double enclosed_volume_ratio(const ShapeDescriptors& descriptors) {
  const double r = descriptors.enclosing_radius;
  return r > 0.0 ? descriptors.volume / (4.0 / 3.0 * std::numbers::pi * r * r * r) : 0.0;
}

const std::vector<DescriptorColumn>& descriptor_columns() {
  static const std::vector<DescriptorColumn> columns = {
      {"volume", "m^3", [](const ShapeDescriptors& d) { return d.volume; }},
      {"surface_area", "m^2", [](const ShapeDescriptors& d) { return d.surface_area; }},
      {"sphericity", "-", [](const ShapeDescriptors& d) { return d.sphericity; }},
      {"measured_alpha", "-", [](const ShapeDescriptors& d) { return d.measured_alpha; }},
      {"vertices", "-",
       [](const ShapeDescriptors& d) { return static_cast<double>(d.vertex_count); }},
      {"edges", "-", [](const ShapeDescriptors& d) { return static_cast<double>(d.edge_count); }},
      {"faces", "-", [](const ShapeDescriptors& d) { return static_cast<double>(d.face_count); }},
      {"long", "m", [](const ShapeDescriptors& d) { return d.long_dimension; }},
      {"intermediate", "m", [](const ShapeDescriptors& d) { return d.intermediate_dimension; }},
      {"short", "m", [](const ShapeDescriptors& d) { return d.short_dimension; }},
      {"elongation", "-", [](const ShapeDescriptors& d) { return d.elongation; }},
      {"flatness", "-", [](const ShapeDescriptors& d) { return d.flatness; }},
      {"circumscribed_radius", "m",
       [](const ShapeDescriptors& d) { return d.circumscribed_radius; }},
      {"enclosing_radius", "m", [](const ShapeDescriptors& d) { return d.enclosing_radius; }},
      {"equivalent_diameter", "m", [](const ShapeDescriptors& d) { return d.equivalent_diameter; }},
      {"longest_edge", "m", [](const ShapeDescriptors& d) { return d.longest_edge; }},
      {"volume_ratio", "-", [](const ShapeDescriptors& d) { return enclosed_volume_ratio(d); }},
  };
  return columns;
}

}  // namespace aggpack
