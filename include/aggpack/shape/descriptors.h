#pragma once
// Measured shape descriptors of a particle (paper Eq. 1 and Eq. 2, plus common size measures).

#include <cstddef>
#include <string>
#include <vector>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack {

/// Shape descriptors of one particle. Lengths in metres, areas in m^2, volumes in m^3.
struct ShapeDescriptors {
  double volume = 0;
  double surface_area = 0;
  /// Eq. 1: SI = (4 pi / S) (3 V / (4 pi))^(2/3); 1 for a sphere.
  double sphericity = 0;
  /// Eq. 2: alpha = V / V_b, V_b the volume of the sphere with the same surface; = SI^(3/2).
  double measured_alpha = 0;
  std::size_t vertex_count = 0;
  std::size_t edge_count = 0;
  std::size_t face_count = 0;
  /// Extents along the principal axes of inertia, sorted: long >= intermediate >= short.
  double long_dimension = 0;
  double intermediate_dimension = 0;
  double short_dimension = 0;
  double elongation = 0;  ///< intermediate / long, in (0, 1]
  double flatness = 0;    ///< short / intermediate, in (0, 1]
  /// Largest distance from the centroid to a vertex (radius of the centroid-centred sphere that
  /// encloses the particle).
  double circumscribed_radius = 0;
  /// Radius of the smallest sphere enclosing the particle (geom/enclosing_sphere.h): half the
  /// circumscribed diameter a measurement of a real particle gives. <= circumscribed_radius.
  double enclosing_radius = 0;
  double equivalent_diameter = 0;  ///< diameter of the sphere of equal volume
  double longest_edge = 0;
};

/// Eq. 1: sphericity SI = (4 pi / S) (3 V / (4 pi))^(2/3) of a body of volume V (m^3) and
/// surface area S (m^2); 1 for a sphere. Precondition: V > 0, S > 0.
double sphericity(double volume, double surface_area);

/// Eq. 2: measured alpha = V / V_b, V_b the volume of the sphere with the body's surface area;
/// computed as SI^(3/2) (the same number). Precondition: V > 0, S > 0.
double measured_alpha(double volume, double surface_area);

/// Diameter (m) of the sphere of volume `volume` (m^3): cbrt(6 V / pi).
double equivalent_diameter(double volume);

/// Measures a particle. \throw InvalidInput if the body has no positive volume.
ShapeDescriptors describe(const ConvexPolyhedron& body);

/// Mean, standard deviation (sample, n-1), minimum and maximum of one descriptor over a family.
struct SummaryStatistics {
  double mean = 0;
  double standard_deviation = 0;
  double minimum = 0;
  double maximum = 0;
  std::size_t count = 0;
};

SummaryStatistics summarize(const std::vector<double>& values);

/// summarize() one value at a time (Welford's update), for families too large to keep every
/// value in memory. Add the values in a fixed order for a reproducible result.
class RunningSummary {
 public:
  void add(double value);
  [[nodiscard]] SummaryStatistics result() const;

 private:
  SummaryStatistics stats_;
  double squares_ = 0.0;  // sum of squared deviations from the running mean
};

/// V / V_circumscribed: the volume over that of the particle's smallest enclosing sphere (the
/// paper's Table 1 ratio as measured on a real particle); 0 for an empty body.
double enclosed_volume_ratio(const ShapeDescriptors& descriptors);

/// Names and accessors of the numeric descriptors, in CSV column order.
struct DescriptorColumn {
  const char* name;
  const char* unit;
  double (*get)(const ShapeDescriptors&);
};
const std::vector<DescriptorColumn>& descriptor_columns();

}  // namespace aggpack
