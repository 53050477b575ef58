// The angle measurement of the repose test (sim/repose.h): the pile's surface profile, the slope
// fit, re-measuring a pile, and the fit's sensitivity to its window and bin width.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/sim/ensemble.h"  // student_t_quantile
#include "aggpack/sim/repose.h"
#include "repose_detail.h"

namespace aggpack {

namespace {

// Running median over `window` bins (odd); near the ends the window shrinks symmetrically.
std::vector<double> running_median(const std::vector<double>& values, std::size_t window) {
  const std::size_t half = window / 2;
  std::vector<double> smoothed(values.size());
  std::vector<double> scratch;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::size_t reach = std::min({half, i, values.size() - 1 - i});
    scratch.assign(values.begin() + static_cast<std::ptrdiff_t>(i - reach),
                   values.begin() + static_cast<std::ptrdiff_t>(i + reach + 1));
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(reach),
                     scratch.end());
    smoothed[i] = scratch[reach];
  }
  return smoothed;
}

}  // namespace

namespace detail {

// Running-median window of the slope fit: one particle diameter (2 R) in bins, odd, >= 3, so that
// a single particle sitting high (often against a wall) is not taken for the crest.
std::size_t repose_smoothing_bins(const ReposeOptions& options, double bin_width) {
  auto smoothing = static_cast<std::size_t>(std::ceil(2.0 * options.radius / bin_width));
  return std::max<std::size_t>(3, smoothing | 1u);
}

double repose_bin_width(const ReposeOptions& options) {
  return options.bin_width > 0.0 ? options.bin_width : 0.5 * options.radius;
}

}  // namespace detail

SurfaceProfile surface_profile(const Packing& packing, double lower, double upper,
                               double bin_width) {
  require_positive("bin_width", bin_width);
  if (!(lower < upper)) {
    throw InvalidInput("profile range", format_value(lower) + " .. " + format_value(upper),
                       "lower < upper");
  }
  SurfaceProfile profile;
  profile.lower = lower;
  profile.bin_width = bin_width;
  const auto bins = static_cast<std::size_t>(std::ceil((upper - lower) / bin_width - 1e-9));
  profile.height.assign(std::max<std::size_t>(bins, 1), 0.0);
  const auto bin_of = [&](double x) -> std::ptrdiff_t {
    return static_cast<std::ptrdiff_t>(std::floor((x - lower) / bin_width));
  };
  const auto last = static_cast<std::ptrdiff_t>(profile.height.size()) - 1;
  auto raise = [&](std::ptrdiff_t bin, double z) {
    if (bin < 0 || bin > last) return;
    auto& h = profile.height[static_cast<std::size_t>(bin)];
    h = std::max(h, z);
  };
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron body = packing.placed(i);
    const auto& vertices = body.vertices();
    // The maximum of z over a convex body cut to a slab lies at a vertex inside the slab or where
    // an edge crosses one of the slab's planes.
    for (const auto& v : vertices) {
      const std::ptrdiff_t bin = bin_of(v.x());
      raise(bin, v.z());
      // Bins are closed intervals: a vertex on a bin plane belongs to both sides.
      if (lower + static_cast<double>(bin) * bin_width == v.x()) raise(bin - 1, v.z());
    }
    for (const auto& t : body.triangles()) {
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = vertices[t[static_cast<std::size_t>(k)]];
        const Vec3& b = vertices[t[static_cast<std::size_t>((k + 1) % 3)]];
        if (a.x() == b.x()) continue;
        const Vec3& left = a.x() < b.x() ? a : b;
        const Vec3& right = a.x() < b.x() ? b : a;
        for (std::ptrdiff_t plane = bin_of(left.x()) + 1; plane <= bin_of(right.x()); ++plane) {
          const double x = lower + static_cast<double>(plane) * bin_width;
          const double s = (x - left.x()) / (right.x() - left.x());
          const double z = left.z() + s * (right.z() - left.z());
          raise(plane - 1, z);  // the plane is the right edge of bin plane-1 ...
          raise(plane, z);      // ... and the left edge of bin plane
        }
      }
    }
  }
  return profile;
}

SlopeFit fit_slope(const SurfaceProfile& profile, double fit_upper, double fit_lower,
                   std::size_t smoothing_bins) {
  require_in_range("fit_upper", fit_upper, 1e-6, 1.0);
  require_in_range("fit_lower", fit_lower, 0.0, fit_upper - 1e-6);
  if (smoothing_bins < 1 || smoothing_bins % 2 == 0) {
    throw InvalidInput("smoothing_bins", std::to_string(smoothing_bins), "odd and >= 1");
  }
  SlopeFit fit;
  const std::size_t n = profile.height.size();
  if (n < 3) {
    fit.message = "profile has fewer than 3 bins";
    return fit;
  }
  const std::vector<double> smooth = running_median(profile.height, smoothing_bins);
  const auto crest =
      static_cast<std::size_t>(std::max_element(smooth.begin(), smooth.end()) - smooth.begin());
  const double top = smooth[crest];
  fit.pile_height = top;
  if (!(top > 0.0)) {
    fit.message = "empty profile";
    return fit;
  }
  // The toe: the first bin after the crest below fit_lower x crest; if the pile never gets that
  // low (it leans on the far wall), the lowest bin after the crest.
  std::size_t toe = crest + 1;
  while (toe < n && smooth[toe] >= fit_lower * top) ++toe;
  if (toe >= n) {
    toe = static_cast<std::size_t>(
        std::min_element(smooth.begin() + static_cast<std::ptrdiff_t>(crest), smooth.end()) -
        smooth.begin());
    if (smooth[toe] >= fit_upper * top) {
      fit.message = "no descending slope after the crest";
      return fit;
    }
  }
  // The slope: back from the toe while the surface stays at or below fit_upper x crest.
  std::size_t first = toe;
  while (first > crest + 1 && smooth[first - 1] <= fit_upper * top) --first;
  const std::size_t end = toe;  // exclusive
  if (end < first + 3) {
    fit.message = "slope region has fewer than 3 bins";
    fit.first_bin = first;
    fit.last_bin = end > 0 ? end - 1 : 0;
    return fit;
  }
  fit.first_bin = first;
  fit.last_bin = end - 1;
  fit.bin_count = end - first;
  double sx = 0.0;
  double sz = 0.0;
  for (std::size_t i = first; i < end; ++i) {
    sx += profile.centre(i);
    sz += profile.height[i];
  }
  const double count = static_cast<double>(fit.bin_count);
  const double mx = sx / count;
  const double mz = sz / count;
  double sxx = 0.0;
  double sxz = 0.0;
  double szz = 0.0;
  for (std::size_t i = first; i < end; ++i) {
    const double dx = profile.centre(i) - mx;
    const double dz = profile.height[i] - mz;
    sxx += dx * dx;
    sxz += dx * dz;
    szz += dz * dz;
  }
  fit.slope = sxz / sxx;
  fit.intercept = mz - fit.slope * mx;
  fit.angle_degrees = std::atan(-fit.slope) * 180.0 / std::numbers::pi;
  fit.r_squared = szz > 0.0 ? (sxz * sxz) / (sxx * szz) : 1.0;
  const double residual = std::max(0.0, szz - sxz * sxz / sxx);
  const double half_width =
      student_t_quantile(0.975, count - 2.0) * std::sqrt(residual / (count - 2.0) / sxx);
  fit.angle_ci_lower = std::atan(-(fit.slope + half_width)) * 180.0 / std::numbers::pi;
  fit.angle_ci_upper = std::atan(-(fit.slope - half_width)) * 180.0 / std::numbers::pi;
  fit.is_valid = true;
  return fit;
}

ReposeMeasurement measure_repose(const Packing& packing, const ReposeOptions& options,
                                 double bin_width, double fit_upper, double fit_lower) {
  if (!(bin_width > 0.0)) bin_width = detail::repose_bin_width(options);
  ReposeMeasurement measured;
  measured.profile = surface_profile(packing, 0.0, options.trough_length, bin_width);
  measured.fit = fit_slope(measured.profile, fit_upper, fit_lower,
                           detail::repose_smoothing_bins(options, bin_width));
  return measured;
}

ReposeMeasurement measure_repose(const Packing& packing, const ReposeOptions& options) {
  return measure_repose(packing, options, detail::repose_bin_width(options), options.fit_upper,
                        options.fit_lower);
}

namespace {
// value + delta rounded to 1e-9, so that 0.2 - 0.05 reads 0.15; the value itself when delta = 0.
double shifted(double value, double delta) {
  return delta == 0.0 ? value : std::round((value + delta) * 1e9) / 1e9;
}
}  // namespace

FitSensitivity fit_sensitivity(const Packing& packing, const ReposeOptions& options,
                               const SlopeFit& reference) {
  FitSensitivity sensitivity;
  const double bin_width = detail::repose_bin_width(options);
  for (const double factor : {0.5, 1.0, 2.0}) {
    const SurfaceProfile profile =
        surface_profile(packing, 0.0, options.trough_length, factor * bin_width);
    const std::size_t smoothing = detail::repose_smoothing_bins(options, factor * bin_width);
    for (const double dl : {-0.05, 0.0, 0.05}) {
      for (const double du : {-0.05, 0.0, 0.05}) {
        SensitivityEntry entry;
        entry.bin_width = factor * bin_width;
        entry.bin_factor = factor;
        entry.fit_lower = std::clamp(shifted(options.fit_lower, dl), 0.0, 1.0);
        entry.fit_upper = std::clamp(shifted(options.fit_upper, du), 1e-6, 1.0);
        if (entry.fit_lower < entry.fit_upper - 1e-6) {
          const SlopeFit fit = fit_slope(profile, entry.fit_upper, entry.fit_lower, smoothing);
          entry.is_valid = fit.is_valid;
          entry.angle_degrees = fit.angle_degrees;
          if (fit.is_valid && reference.is_valid) {
            const double deviation = std::abs(fit.angle_degrees - reference.angle_degrees);
            sensitivity.max_deviation = std::max(sensitivity.max_deviation, deviation);
            if (factor == 1.0) {
              sensitivity.max_deviation_window =
                  std::max(sensitivity.max_deviation_window, deviation);
            }
            if (dl == 0.0 && du == 0.0) {
              sensitivity.max_deviation_bins = std::max(sensitivity.max_deviation_bins, deviation);
            }
          }
        }
        sensitivity.entries.push_back(entry);
      }
    }
  }
  return sensitivity;
}

}  // namespace aggpack
