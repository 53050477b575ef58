#include "aggpack/pack/grading.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/packing.h"

namespace aggpack {

namespace {

// Number-density exponent of the Fuller curve: volume density ~ d^(q-1), so number density
// ~ d^(q-1) / d^3 = d^(a-1) with a = q - 3.
double fuller_number_exponent(const Grading& grading) { return grading.exponent - 3.0; }

// Sieve table renormalised to the fraction above the smallest sieve: P~_k in [0, 1].
std::vector<double> sieve_fractions(const Grading& grading) {
  const double first = grading.sieve.front().percent_passing;
  std::vector<double> fractions;
  fractions.reserve(grading.sieve.size());
  for (const auto& row : grading.sieve) {
    fractions.push_back((row.percent_passing - first) / (100.0 - first));
  }
  return fractions;
}

// Number weight of sieve interval k (volume density uniform in d on [d0, d1], so number density
// ~ 1/d^3): dP / (d1 - d0) * integral of d^-3 = dP / (d1 - d0) * (d0^-2 - d1^-2) / 2.
double sieve_interval_weight(double fraction, double d0, double d1) {
  return fraction / (d1 - d0) * (1.0 / (d0 * d0) - 1.0 / (d1 * d1)) / 2.0;
}

std::vector<double> sieve_weights(const Grading& grading) {
  const auto fractions = sieve_fractions(grading);
  std::vector<double> weights;
  for (std::size_t k = 0; k + 1 < grading.sieve.size(); ++k) {
    weights.push_back(sieve_interval_weight(fractions[k + 1] - fractions[k], grading.sieve[k].size,
                                            grading.sieve[k + 1].size));
  }
  return weights;
}

}  // namespace

std::string to_string(GradingKind kind) {
  switch (kind) {
    case GradingKind::kUniform:
      return "uniform";
    case GradingKind::kFuller:
      return "fuller";
    case GradingKind::kSieve:
      return "sieve";
  }
  return "unknown";
}

void validate(const Grading& grading) {
  switch (grading.kind) {
    case GradingKind::kUniform:
      require_positive("grading.radius_min", grading.radius_min);
      require_positive("grading.radius_max", grading.radius_max);
      if (grading.radius_max < grading.radius_min) {
        throw InvalidInput(
            "grading.radius_max", format_value(grading.radius_max),
            {Sentence::kAtLeastKey, {"grading.radius_min", format_value(grading.radius_min)}});
      }
      return;
    case GradingKind::kFuller:
      require_positive("grading.size_min", grading.size_min);
      require_positive("grading.size_max", grading.size_max);
      if (!(grading.size_max > grading.size_min)) {
        throw InvalidInput(
            "grading.size_max", format_value(grading.size_max),
            {Sentence::kAboveKey, {"grading.size_min", format_value(grading.size_min)}});
      }
      if (!std::isfinite(grading.exponent) || grading.exponent <= 0.0 || grading.exponent > 10.0) {
        throw InvalidInput("grading.exponent", format_value(grading.exponent), "(0, 10]");
      }
      return;
    case GradingKind::kSieve: {
      const auto& rows = grading.sieve;
      if (rows.size() < 2) {
        throw InvalidInput("grading.sieve", std::to_string(rows.size()) + " rows",
                           Wording{Sentence::kSieveRows, {}});
      }
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const std::string prefix = "grading.sieve[" + std::to_string(k) + "]";
        require_positive(prefix + ".size", rows[k].size);
        require_in_range(prefix + ".percent_passing", rows[k].percent_passing, 0.0, 100.0);
        if (k > 0 && !(rows[k].size > rows[k - 1].size)) {
          throw InvalidInput(
              prefix + ".size", format_value(rows[k].size),
              Wording{Sentence::kSieveSizesIncrease, {format_value(rows[k - 1].size)}});
        }
        if (k > 0 && rows[k].percent_passing < rows[k - 1].percent_passing) {
          throw InvalidInput(
              prefix + ".percent_passing", format_value(rows[k].percent_passing),
              Wording{Sentence::kSievePassingRises, {format_value(rows[k - 1].percent_passing)}});
        }
      }
      if (rows.back().percent_passing != 100.0) {
        throw InvalidInput("grading.sieve[" + std::to_string(rows.size() - 1) + "].percent_passing",
                           format_value(rows.back().percent_passing),
                           Wording{Sentence::kSieveLastPassesAll, {}});
      }
      if (rows.front().percent_passing >= 100.0) {
        throw InvalidInput("grading.sieve[0].percent_passing",
                           format_value(rows.front().percent_passing),
                           Wording{Sentence::kSieveFirstRetains, {}});
      }
      return;
    }
  }
  throw InvalidInput("grading.kind", std::to_string(static_cast<int>(grading.kind)),
                     "uniform, fuller or sieve");
}

double smallest_size(const Grading& grading) {
  switch (grading.kind) {
    case GradingKind::kUniform:
      return 2.0 * grading.radius_min;
    case GradingKind::kFuller:
      return grading.size_min;
    case GradingKind::kSieve: {
      // The lower end of the first interval that holds material.
      const auto& rows = grading.sieve;
      for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
        if (rows[k + 1].percent_passing > rows[k].percent_passing) return rows[k].size;
      }
      return rows.front().size;
    }
  }
  return 0.0;
}

double largest_size(const Grading& grading) {
  switch (grading.kind) {
    case GradingKind::kUniform:
      return 2.0 * grading.radius_max;
    case GradingKind::kFuller:
      return grading.size_max;
    case GradingKind::kSieve: {
      const auto& rows = grading.sieve;
      for (std::size_t k = rows.size() - 1; k > 0; --k) {
        if (rows[k].percent_passing > rows[k - 1].percent_passing) return rows[k].size;
      }
      return rows.back().size;
    }
  }
  return 0.0;
}

double passing_fraction(const Grading& grading, double size) {
  const double lo = smallest_size(grading);
  const double hi = largest_size(grading);
  if (size >= hi) return 1.0;
  if (size < lo) return 0.0;
  switch (grading.kind) {
    case GradingKind::kUniform: {
      const double r = size / 2.0;
      const double r0 = grading.radius_min;
      const double r1 = grading.radius_max;
      return (std::pow(r, 4) - std::pow(r0, 4)) / (std::pow(r1, 4) - std::pow(r0, 4));
    }
    case GradingKind::kFuller: {
      const double q = grading.exponent;
      return (std::pow(size, q) - std::pow(lo, q)) / (std::pow(hi, q) - std::pow(lo, q));
    }
    case GradingKind::kSieve: {
      const auto& rows = grading.sieve;
      const auto fractions = sieve_fractions(grading);
      for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
        if (size <= rows[k + 1].size) {
          const double t = (size - rows[k].size) / (rows[k + 1].size - rows[k].size);
          return fractions[k] + std::clamp(t, 0.0, 1.0) * (fractions[k + 1] - fractions[k]);
        }
      }
      return 1.0;
    }
  }
  return 0.0;
}

double sample_size(const Grading& grading, double u) {
  u = std::clamp(u, 0.0, 1.0);
  switch (grading.kind) {
    case GradingKind::kUniform:
      return 2.0 * (grading.radius_min + u * (grading.radius_max - grading.radius_min));
    case GradingKind::kFuller: {
      const double lo = grading.size_min;
      const double hi = grading.size_max;
      const double a = fuller_number_exponent(grading);
      // Inverse of the number CDF F(d) = (d^a - lo^a) / (hi^a - lo^a); log-uniform when a = 0.
      double d = 0.0;
      if (std::abs(a) < 1e-12) {
        d = lo * std::pow(hi / lo, u);
      } else {
        const double la = std::pow(lo, a);
        d = std::pow(la + u * (std::pow(hi, a) - la), 1.0 / a);
      }
      return std::clamp(d, lo, hi);
    }
    case GradingKind::kSieve: {
      const auto weights = sieve_weights(grading);
      double total = 0.0;
      for (double w : weights) total += w;
      double target = u * total;
      std::size_t k = 0;
      for (; k + 1 < weights.size(); ++k) {
        if (weights[k] > 0.0 && target < weights[k]) break;
        target -= weights[k];
      }
      while (k > 0 && weights[k] <= 0.0) --k;  // last interval may be empty: step back
      const double d0 = grading.sieve[k].size;
      const double d1 = grading.sieve[k + 1].size;
      const double v = weights[k] > 0.0 ? std::clamp(target / weights[k], 0.0, 1.0) : 0.5;
      // Inverse CDF of the 1/d^3 number density on [d0, d1].
      const double inv0 = 1.0 / (d0 * d0);
      const double inv1 = 1.0 / (d1 * d1);
      return std::clamp(1.0 / std::sqrt(inv0 - v * (inv0 - inv1)), d0, d1);
    }
  }
  return 0.0;
}

double mean_cubed_size(const Grading& grading) {
  switch (grading.kind) {
    case GradingKind::kUniform: {
      const double r0 = grading.radius_min;
      const double r1 = grading.radius_max;
      if (r1 == r0) return 8.0 * r0 * r0 * r0;
      return 8.0 * (std::pow(r1, 4) - std::pow(r0, 4)) / (4.0 * (r1 - r0));
    }
    case GradingKind::kFuller: {
      const double lo = grading.size_min;
      const double hi = grading.size_max;
      const double q = grading.exponent;
      const double a = q - 3.0;
      if (std::abs(a) < 1e-12) return (hi * hi * hi - lo * lo * lo) / (3.0 * std::log(hi / lo));
      return a * (std::pow(hi, q) - std::pow(lo, q)) / (q * (std::pow(hi, a) - std::pow(lo, a)));
    }
    case GradingKind::kSieve: {
      // E_n[d^3] = (integral of the volume density) / (integral of volume density / d^3) = 1 / W.
      double total = 0.0;
      for (double w : sieve_weights(grading)) total += w;
      return 1.0 / total;
    }
  }
  return 0.0;
}

std::uint32_t size_class(const Grading& grading, double size) {
  if (grading.kind != GradingKind::kSieve) return 0;
  const auto& rows = grading.sieve;
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
    if (size <= rows[k + 1].size) return static_cast<std::uint32_t>(k);
  }
  return static_cast<std::uint32_t>(rows.size() - 2);
}

std::vector<double> report_sizes(const Grading& grading, int count) {
  if (grading.kind == GradingKind::kSieve) {
    std::vector<double> sizes;
    for (const auto& row : grading.sieve) sizes.push_back(row.size);
    return sizes;
  }
  const double lo = smallest_size(grading);
  const double hi = largest_size(grading);
  if (!(hi > lo)) return {hi};
  count = std::max(count, 2);
  std::vector<double> sizes(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    sizes[static_cast<std::size_t>(k)] =
        lo * std::pow(hi / lo, static_cast<double>(k) / (count - 1));
  }
  sizes.back() = hi;  // exact, so the largest particles pass the top sieve
  return sizes;
}

std::vector<GradingPoint> achieved_grading(const Packing& packing, const Grading& grading,
                                           const std::vector<double>& sizes) {
  validate(grading);
  const std::vector<double> sieve = sizes.empty() ? report_sizes(grading) : sizes;
  std::vector<double> shape_volume(packing.shapes.size(), -1.0);
  // Volume per particle (exact), and the total, summed in particle order.
  std::vector<std::pair<double, double>> size_volume;
  size_volume.reserve(packing.particles.size());
  double total = 0.0;
  for (const auto& particle : packing.particles) {
    double& volume = shape_volume[particle.shape];
    if (volume < 0.0) volume = mass_properties(packing.shapes[particle.shape]).volume;
    const double v = volume * particle.scale * particle.scale * particle.scale;
    size_volume.emplace_back(2.0 * particle.control_radius, v);
    total += v;
  }
  std::vector<GradingPoint> points;
  for (double size : sieve) {
    double passing = 0.0;
    for (const auto& [d, v] : size_volume) {
      if (d <= size) passing += v;
    }
    points.push_back({.size = size,
                      .target_percent = 100.0 * passing_fraction(grading, size),
                      .achieved_percent = total > 0.0 ? 100.0 * passing / total : 0.0});
  }
  return points;
}

}  // namespace aggpack
