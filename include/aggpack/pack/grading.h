#pragma once
// Particle size gradings (size distributions) for the random packer.
//
// Size convention: a particle's SIZE d is its control diameter, d = 2 r, where r is the control
// radius it was grown with (every vertex lies within r of its centre, generator.h). Gradings are
// by VOLUME (= mass for one density), as in sieve analysis: P(d) is the volume fraction of all
// particles with size <= d. The packer samples particle sizes from the NUMBER density that gives
// this volume distribution, n(d) ~ P'(d) / d^3, and places them largest first.

#include <cstdint>
#include <string>
#include <vector>

namespace aggpack {

struct Packing;

enum class GradingKind {
  kUniform,  ///< control radius uniform BY NUMBER in [radius_min, radius_max] (the generator's)
  kFuller,   ///< power law (Fuller/Talbot) between size_min and size_max
  kSieve     ///< a sieve table (size, percent passing by volume)
};

/// One row of a sieve table.
struct SieveRow {
  double size = 0.0;             ///< sieve opening = control diameter d (m), > 0
  double percent_passing = 0.0;  ///< volume percent of particles with size <= `size`, [0, 100]
};

/// A size distribution. Only the fields of the chosen `kind` are used.
///
/// kFuller uses the truncated, renormalised power law (the usual choice for mesoscale concrete
/// models, where the fines below d_min belong to the mortar):
///     P(d) = (d^q - d_min^q) / (d_max^q - d_min^q),   d_min <= d <= d_max.
/// This is the classic Fuller curve (d / d_max)^q restricted to [d_min, d_max] and rescaled to
/// 100 %; q = 0.5 is Fuller-Thompson, q = 0.45 the FHWA curve.
///
/// kSieve: sizes strictly increasing, percent non-decreasing, last row 100 %. The volume passing
/// the smallest sieve is not generated (fines; treated like Fuller's d < d_min) and the rest is
/// renormalised to 100 %. Between two sieves P is linear in d (uniform volume density).
///
/// kUniform: r uniform by number in [radius_min, radius_max]; its volume curve is then
/// P(d) = (r^4 - r_min^4) / (r_max^4 - r_min^4) with r = d/2.
struct Grading {
  GradingKind kind = GradingKind::kUniform;
  double radius_min = 0.1;        ///< kUniform: smallest control radius (m), > 0
  double radius_max = 0.1;        ///< kUniform: largest control radius (m), >= radius_min
  double size_min = 0.005;        ///< kFuller: d_min, smallest control diameter (m), > 0
  double size_max = 0.02;         ///< kFuller: d_max, largest control diameter (m), > size_min
  double exponent = 0.5;          ///< kFuller: q, in (0, 10]
  std::vector<SieveRow> sieve{};  ///< kSieve: at least 2 rows (sizes in m, percent by volume)
};

/// Throws InvalidInput naming the field ("grading.radius_min", "grading.size_max",
/// "grading.exponent", "grading.sieve[2].size", ...) unless the grading is usable.
void validate(const Grading& grading);

/// Smallest and largest control diameter the grading can produce (m).
double smallest_size(const Grading& grading);
double largest_size(const Grading& grading);

/// Target volume fraction passing size d (m), in [0, 1]: 0 below the smallest size, 1 above the
/// largest.
double passing_fraction(const Grading& grading, double size);

/// Draws a control diameter (m) from the NUMBER density of the grading by inverse transform of a
/// uniform deviate u in [0, 1). Monotone in u. Precondition: validate(grading) passed.
double sample_size(const Grading& grading, double u);

/// Mean of d^3 over the number density (m^3); the expected solid volume per particle is
/// kappa * pi/6 * mean_cubed_size, with kappa = particle volume / volume of its control sphere.
double mean_cubed_size(const Grading& grading);

/// Size class of a particle of control diameter `size`: for kSieve the index of the sieve
/// interval it falls in (0 = between the two smallest sieves), otherwise 0.
std::uint32_t size_class(const Grading& grading, double size);

/// Sieve sizes to report a grading at (m, ascending): the table's sizes for kSieve; otherwise
/// `count` (>= 2) sizes evenly spaced in log(d) from the smallest to the largest size.
std::vector<double> report_sizes(const Grading& grading, int count = 9);

/// One row of an achieved-vs-target grading comparison.
struct GradingPoint {
  double size = 0.0;              ///< sieve size = control diameter (m)
  double target_percent = 0.0;    ///< target volume percent passing
  double achieved_percent = 0.0;  ///< achieved volume percent passing in the packing
};

/// Achieved grading of a packing: for each size, the percent of the packing's solid volume
/// (exact particle volumes) in particles whose control diameter 2 * control_radius <= size, next
/// to the grading's target. `sizes` empty = report_sizes(grading).
/// \throw InvalidInput if the grading is invalid.
std::vector<GradingPoint> achieved_grading(const Packing& packing, const Grading& grading,
                                           const std::vector<double>& sizes = {});

/// Human-readable name of a grading kind: "uniform", "fuller", "sieve".
std::string to_string(GradingKind kind);

}  // namespace aggpack
