// Seed ensembles of the repose test: seed lists, Student t quantiles, statistics, JSON and CSV
// (the PNG is in repose_output.cpp, next to the side view's drawing code).

#include "aggpack/sim/ensemble.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/sim/distributed.h"

namespace aggpack {

namespace {

// Continued fraction of the regularized incomplete beta function (Numerical Recipes, betacf).
double beta_continued_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  const double qab = a + b;
  const double qap = a + 1.0;
  const double qam = a - 1.0;
  double c = 1.0;
  double d = 1.0 - qab * x / qap;
  if (std::fabs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::fabs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::fabs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::fabs(delta - 1.0) < 1e-15) break;
  }
  return h;
}

// I_x(a, b).
double incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                                a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(a, b, x) / a;
  return 1.0 - front * beta_continued_fraction(b, a, 1.0 - x) / b;
}

// P(T <= t) for t >= 0.
double student_t_cdf(double t, double dof) {
  return 1.0 - 0.5 * incomplete_beta(0.5 * dof, 0.5, dof / (dof + t * t));
}

}  // namespace

double student_t_quantile(double p, double dof) {
  if (!(p > 0.0 && p < 1.0)) throw InvalidInput("t quantile p", format_value(p), "(0, 1)");
  if (!(dof >= 1.0) || !std::isfinite(dof)) {
    throw InvalidInput("t quantile degrees of freedom", format_value(dof), ">= 1, finite");
  }
  if (p == 0.5) return 0.0;
  if (p < 0.5) return -student_t_quantile(1.0 - p, dof);
  double high = 1.0;
  while (student_t_cdf(high, dof) < p && high < 1e12) high *= 2.0;
  double low = 0.0;
  for (int k = 0; k < 200 && high - low > 1e-13 * std::max(1.0, high); ++k) {
    const double middle = 0.5 * (low + high);
    (student_t_cdf(middle, dof) < p ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

EnsembleStatistics ensemble_statistics(const std::vector<double>& values, double confidence) {
  require_in_range("confidence", confidence, 1e-9, 1.0 - 1e-9);
  EnsembleStatistics s;
  s.count = values.size();
  if (s.count == 0) return s;
  double sum = 0.0;
  for (const double v : values) sum += v;
  s.mean = sum / static_cast<double>(s.count);
  if (s.count < 2) return s;
  double squares = 0.0;
  for (const double v : values) squares += (v - s.mean) * (v - s.mean);
  const auto n = static_cast<double>(s.count);
  s.std_dev = std::sqrt(squares / (n - 1.0));
  s.t_quantile = student_t_quantile(0.5 + 0.5 * confidence, n - 1.0);
  s.half_width = s.t_quantile * s.std_dev / std::sqrt(n);
  s.has_interval = true;
  return s;
}

EnsembleResult summarize_ensemble(std::vector<EnsembleSeed> seeds) {
  EnsembleResult ensemble;
  ensemble.seeds = std::move(seeds);
  std::vector<double> angles;
  for (const auto& s : ensemble.seeds) {
    if (s.is_valid) angles.push_back(s.angle_degrees);
  }
  ensemble.statistics = ensemble_statistics(angles);
  return ensemble;
}

void write_ensemble_json(const std::string& path, const ReposeOptions& base,
                         const EnsembleResult& ensemble) {
  nlohmann::ordered_json json;
  json["aggpack_version"] = AGGPACK_VERSION;
  json["options"] = {
      {"alpha", base.alpha},
      {"radius_m", base.radius},
      {"edge_length_m", base.edge_length},
      {"friction", base.physics.friction},
      {"wall_friction", base.physics.wall_friction.value_or(base.physics.friction)},
      {"trough_length_m", base.trough_length},
      {"trough_width_m", base.width()},
      {"note", "each seed's full options and result are in seed-<k>/repose.json"},
  };
  auto seeds = nlohmann::ordered_json::array();
  for (const auto& s : ensemble.seeds) {
    seeds.push_back({{"seed", s.seed},
                     {"valid", s.is_valid},
                     {"angle_degrees", s.angle_degrees},
                     {"r_squared", s.r_squared},
                     {"at_rest", s.is_at_rest},
                     {"particles", s.particle_count},
                     {"error", s.error}});
  }
  json["seeds"] = seeds;
  const EnsembleStatistics& st = ensemble.statistics;
  const auto or_null = [&](double value) {
    return st.has_interval ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
  };
  json["statistics"] = {
      {"seeds_total", ensemble.seeds.size()},
      {"seeds_used", st.count},
      {"seeds_failed", ensemble.failed_count()},
      {"mean_angle_degrees", st.count > 0 ? nlohmann::ordered_json(st.mean) : nullptr},
      {"std_dev_degrees", or_null(st.std_dev)},
      {"confidence", 0.95},
      {"t_quantile", or_null(st.t_quantile)},
      {"ci_half_width_degrees", or_null(st.half_width)},
      {"ci_lower_degrees", or_null(st.lower())},
      {"ci_upper_degrees", or_null(st.upper())},
  };
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  file.stream() << json.dump(2) << '\n';
  file.commit();
}

void write_ensemble_csv(const std::string& path, const EnsembleResult& ensemble) {
  const auto number = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    return std::string(buffer);
  };
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  auto& out = file.stream();
  out << "seed,angle_deg,r_squared,valid,at_rest,particles,error\n";
  for (const auto& s : ensemble.seeds) {
    std::string error;
    for (const char c : s.error) error += c == '"' ? std::string("\"\"") : std::string(1, c);
    out << s.seed << ',' << (s.is_valid ? number(s.angle_degrees) : std::string()) << ','
        << (s.is_valid ? number(s.r_squared) : std::string()) << ',' << (s.is_valid ? 1 : 0) << ','
        << (s.is_at_rest ? 1 : 0) << ',' << s.particle_count << ','
        << (error.empty() ? std::string() : "\"" + error + "\"") << '\n';
  }
  const EnsembleStatistics& st = ensemble.statistics;
  const auto row = [&](const char* name, bool has_value, double value) {
    out << name << ',' << (has_value ? number(value) : std::string()) << ",,,,,\n";
  };
  row("seeds_used", true, static_cast<double>(st.count));
  row("mean", st.count > 0, st.mean);
  row("std_dev", st.has_interval, st.std_dev);
  row("ci95_lower", st.has_interval, st.lower());
  row("ci95_upper", st.has_interval, st.upper());
  file.commit();
}

}  // namespace aggpack
