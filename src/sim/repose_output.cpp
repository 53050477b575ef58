// Output of the repose test: JSON result, profile CSV and the side-view PNG.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/raster.h"
#include "aggpack/geom/convex_hull_2d.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"

namespace aggpack {

namespace {

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

}  // namespace

void write_repose_json(const std::string& path, const ReposeOptions& options,
                       const ReposeResult& result) {
  nlohmann::ordered_json json;
  json["aggpack_version"] = AGGPACK_VERSION;
  json["engine"] = to_string(options.engine);
  json["options"] = {
      {"trough_length_m", options.trough_length},
      {"trough_width_m", options.width()},
      {"width_factor", options.width_factor},
      {"trough_height_m", options.trough_height},
      {"baffle_position_m", options.baffle_position},
      {"baffle_thickness_m", options.baffle_thickness},
      {"baffle_speed_m_per_s", options.baffle_speed},
      {"alpha", options.alpha},
      {"radius_m", options.radius},
      {"edge_length_m", options.edge_length},
      {"fill_height_m", options.fill_height},
      {"seed", options.seed},
      {"density_kg_per_m3", options.physics.density},
      {"friction", options.physics.friction},
      {"wall_friction", options.physics.wall_friction.value_or(options.physics.friction)},
      {"restitution", options.physics.restitution},
      {"rolling_friction", options.physics.rolling_friction},
      {"time_step_s", result.time_step},
      {"solver_iterations", options.physics.solver_iterations},
      {"solver", to_string(options.physics.solver)},
      {"solver_block_contacts", options.physics.solver_block_contacts},
      {"solver_block_sweeps", options.physics.solver_block_sweeps},
      {"margin_fraction", options.physics.margin_fraction},
      {"kinetic_energy_ratio", options.rest.kinetic_energy_ratio},
      {"confirm_window_sqrt_d_over_g", options.confirm_window},
      {"confirm_angle_tolerance_degrees", options.confirm_angle_tolerance},
      {"confirm_height_tolerance_fraction_of_d", options.confirm_height_tolerance},
      {"confirm_speed_fraction_of_sqrt_g_d", options.confirm_speed},
      {"bin_width_m", result.profile.bin_width},
      {"fit_upper", options.fit_upper},
      {"fit_lower", options.fit_lower},
  };
  // particle.library: the files the fill took its shapes from (names and content hashes).
  if (options.library.is_used()) json["shape_library"] = result.initial.provenance.shape_library;
  if (options.engine == ReposeEngine::kYade) {
    // Bullet's solver settings above do not apply; YADE's contact stiffness and damping do.
    json["yade"] = {{"young_n_per_m3", result.yade_young},
                    {"damping", options.yade.damping},
                    {"iterations", result.yade_iterations}};
  }
  json["particles"] = {
      {"count", result.particle_count},
      {"solid_volume_m3", result.solid_volume},
      {"mean_measured_alpha", result.mean_measured_alpha},
      {"smallest_equivalent_diameter_m", result.smallest_size},
  };
  json["stage1"] = {
      {"at_rest", result.is_stage1_at_rest},
      {"simulated_time_s", result.stage1_time},
      {"pile_height_m", result.stage1_height},
  };
  json["stage2"] = {
      {"at_rest", result.is_stage2_at_rest},
      {"simulated_time_s", result.stage2_time},
      {"baffle_travel_m", result.baffle_travel},
      {"baffle_removed", result.is_baffle_removed},
  };
  const auto& confirmation = result.confirmation;
  json["stage2"]["confirmation"] = {
      {"window_s", confirmation.window},
      {"restarts", confirmation.restarts},
      {"restarts_by_angle", confirmation.angle_restarts},
      {"restarts_by_crest_height", confirmation.height_restarts},
      {"restarts_by_speed", confirmation.speed_restarts},
      {"angle_change_degrees", confirmation.angle_change},
      {"crest_height_change_m", confirmation.height_change},
      {"max_pile_speed99_m_per_s", confirmation.max_speed},
      {"speed_limit_m_per_s", confirmation.speed_limit},
  };
  json["final"] = {
      {"max_overlap_fraction_of_d_min", result.max_overlap_fraction},
      {"max_contact_penetration_fraction_of_d_min", result.max_contact_penetration_fraction},
      {"escaped_particles", result.escaped_particles},
  };
  if (options.engine == ReposeEngine::kYade) {
    // Measured in Bullet's world only.
    json["final"]["max_overlap_fraction_of_d_min"] = nullptr;
    json["final"]["max_contact_penetration_fraction_of_d_min"] = nullptr;
  }
  const SlopeFit& fit = result.fit;
  json["fit"] = {
      {"valid", fit.is_valid},
      {"message", fit.message},
      {"angle_degrees", fit.angle_degrees},
      {"r_squared", fit.r_squared},
      {"angle_ci95_lower_degrees", fit.angle_ci_lower},
      {"angle_ci95_upper_degrees", fit.angle_ci_upper},
      {"slope", fit.slope},
      {"intercept_m", fit.intercept},
      {"pile_height_m", fit.pile_height},
      {"x_start_m", fit.bin_count > 0 ? result.profile.centre(fit.first_bin) : 0.0},
      {"x_end_m", fit.bin_count > 0 ? result.profile.centre(fit.last_bin) : 0.0},
      {"bins", fit.bin_count},
  };
  nlohmann::ordered_json table = nlohmann::ordered_json::array();
  for (const auto& entry : result.sensitivity.entries) {
    table.push_back({{"fit_lower", entry.fit_lower},
                     {"fit_upper", entry.fit_upper},
                     {"bin_width_m", entry.bin_width},
                     {"bin_factor", entry.bin_factor},
                     {"valid", entry.is_valid},
                     {"angle_degrees", entry.angle_degrees}});
  }
  json["sensitivity"] = {
      {"max_deviation_degrees", result.sensitivity.max_deviation},
      {"max_deviation_fit_window_degrees", result.sensitivity.max_deviation_window},
      {"max_deviation_bin_width_degrees", result.sensitivity.max_deviation_bins},
      {"entries", std::move(table)},
  };
  if (options.follow_time > 0.0) {
    json["follow_up"] = {
        {"time_s", result.follow.time},
        {"valid", result.follow.fit.is_valid},
        {"angle_degrees", result.follow.fit.angle_degrees},
        {"angle_change_degrees", result.follow.fit.angle_degrees - fit.angle_degrees},
        {"pile_height_m", result.follow.fit.pile_height},
        {"pile_height_change_m", result.follow.fit.pile_height - fit.pile_height},
    };
  }
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  file.stream() << json.dump(2) << '\n';
  file.commit();
}

void write_profile_csv(const std::string& path, const ReposeResult& result) {
  AtomicFile file(path, Overwrite::kAllow, std::ios::out);
  auto& out = file.stream();
  out << "x_m,height_m,in_fit,fit_height_m\n";
  const SlopeFit& fit = result.fit;
  for (std::size_t i = 0; i < result.profile.height.size(); ++i) {
    const bool in_fit = fit.is_valid && i >= fit.first_bin && i <= fit.last_bin;
    const double x = result.profile.centre(i);
    out << number(x) << ',' << number(result.profile.height[i]) << ',' << (in_fit ? 1 : 0) << ','
        << (fit.is_valid ? number(fit.intercept + fit.slope * x) : std::string()) << '\n';
  }
  file.commit();
}

void write_side_view_png(const std::string& path, const Packing& packing,
                         const SurfaceProfile& profile, const SlopeFit& fit, int width) {
  if (width < 64 || width > 16384) {
    throw InvalidInput("width", std::to_string(width), "[64, 16384] pixels");
  }
  check_writable(path, Overwrite::kAllow);
  const Aabb bounds = packing.container.bounds();
  double top = bounds.upper.z();
  for (const double h : profile.height) top = std::max(top, h);
  const double span = bounds.extent().x();
  const double pad = 0.04 * span;
  const double scale = width / (span + 2.0 * pad);
  const int height = static_cast<int>(std::ceil((top + 2.0 * pad) * scale)) + 40;
  Raster image(width, height);
  auto px = [&](double x) { return (x - bounds.lower.x() + pad) * scale; };
  auto py = [&](double z) { return height - (z + pad) * scale; };

  // Particles from far (large y) to near, shaded by depth.
  std::vector<std::size_t> order(packing.particles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<double> depth(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) depth[i] = packing.particles[i].pose.position.y();
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return depth[a] > depth[b]; });
  const double y_span = std::max(1e-12, bounds.extent().y());
  for (const std::size_t i : order) {
    const ConvexPolyhedron body = packing.placed(i);
    std::vector<std::array<double, 2>> points;
    points.reserve(body.vertex_count());
    for (const auto& v : body.vertices()) points.push_back({px(v.x()), py(v.z())});
    const auto hull = convex_hull_2d(points);
    const double t = std::clamp((depth[i] - bounds.lower.y()) / y_span, 0.0, 1.0);
    const auto shade = [&](double near, double far) {
      return static_cast<std::uint8_t>(std::lround(near + t * (far - near)));
    };
    image.fill_convex(hull, {shade(120, 215), shade(100, 200), shade(80, 185)});
    for (std::size_t k = 0; k < hull.size(); ++k) {
      const auto& a = hull[k];
      const auto& b = hull[(k + 1) % hull.size()];
      image.line(a[0], a[1], b[0], b[1], 1, {shade(60, 150), shade(50, 140), shade(40, 130)});
    }
  }
  // Trough: floor and end walls.
  const Rgb wall{30, 30, 30};
  image.line(px(bounds.lower.x()), py(0.0), px(bounds.upper.x()), py(0.0), 3, wall);
  image.line(px(bounds.lower.x()), py(0.0), px(bounds.lower.x()), py(bounds.upper.z()), 3, wall);
  image.line(px(bounds.upper.x()), py(0.0), px(bounds.upper.x()), py(bounds.upper.z()), 3, wall);
  // Profile: blue, the bins of the fit green.
  const int dot = std::max(3, width / 400);
  for (std::size_t i = 0; i < profile.height.size(); ++i) {
    const bool in_fit = fit.is_valid && i >= fit.first_bin && i <= fit.last_bin;
    const Rgb colour = in_fit ? Rgb{0, 150, 0} : Rgb{30, 60, 220};
    const int x = static_cast<int>(std::lround(px(profile.centre(i))));
    const int y = static_cast<int>(std::lround(py(profile.height[i])));
    image.fill_rect(x - dot / 2, y - dot / 2, x - dot / 2 + dot, y - dot / 2 + dot, colour);
  }
  std::string caption;
  if (fit.is_valid) {
    // The fitted line over the slope region, extended by a third of its length each way.
    const double x0 = profile.centre(fit.first_bin);
    const double x1 = profile.centre(fit.last_bin);
    const double extra = (x1 - x0) / 3.0;
    const double a = x0 - extra;
    const double b = x1 + extra;
    // The fit's 95 % interval: the lines at its two angles through the fit's centre (thin).
    const double xm = 0.5 * (x0 + x1);
    const double zm = fit.intercept + fit.slope * xm;
    for (const double angle : {fit.angle_ci_lower, fit.angle_ci_upper}) {
      const double slope = -std::tan(angle * 3.14159265358979323846 / 180.0);
      image.line(px(a), py(zm + slope * (a - xm)), px(b), py(zm + slope * (b - xm)), 1,
                 {240, 140, 140});
    }
    image.line(px(a), py(fit.intercept + fit.slope * a), px(b), py(fit.intercept + fit.slope * b),
               std::max(2, width / 500), {220, 20, 20});
    char buffer[200];
    std::snprintf(buffer, sizeof buffer,
                  "angle of repose %.1f deg, fit 95%% CI [%.1f, %.1f]  (R^2 %.3f, %zu bins)  %zu "
                  "particles",
                  fit.angle_degrees, fit.angle_ci_lower, fit.angle_ci_upper, fit.r_squared,
                  fit.bin_count, packing.particles.size());
    caption = buffer;
  } else {
    caption = "no slope fit: " + fit.message;
  }
  image.text(caption, 10, 10, std::max(2, width / 600), {0, 0, 0});
  write_png(path, image);
}

void write_ensemble_png(const std::string& path, const EnsembleResult& ensemble, int width) {
  if (width < 64 || width > 16384) {
    throw InvalidInput("width", std::to_string(width), "[64, 16384] pixels");
  }
  check_writable(path, Overwrite::kAllow);
  const int height = std::max(48, width * 3 / 5);
  Raster image(width, height);
  const EnsembleStatistics& st = ensemble.statistics;
  // Vertical range: every valid angle and the interval, padded by a tenth (at least 1 degree).
  double low = 1e300;
  double high = -1e300;
  for (const auto& s : ensemble.seeds) {
    if (!s.is_valid) continue;
    low = std::min(low, s.angle_degrees);
    high = std::max(high, s.angle_degrees);
  }
  if (st.has_interval) {
    low = std::min(low, st.lower());
    high = std::max(high, st.upper());
  }
  if (low > high) {
    low = 0.0;
    high = 90.0;
  }
  const double pad = std::max(1.0, 0.1 * (high - low));
  low = std::floor(low - pad);
  high = std::ceil(high + pad);
  const int text_scale = std::max(1, width / 600);
  const double left = 12.0 * 6 * text_scale;
  const double right = width - 20.0;
  const double top = 30.0 * text_scale;
  const double bottom = height - 20.0 * text_scale;
  const std::size_t n = ensemble.seeds.size();
  auto px = [&](std::size_t index) {
    return left + (static_cast<double>(index) + 0.5) / static_cast<double>(n) * (right - left);
  };
  auto py = [&](double angle) { return bottom - (angle - low) / (high - low) * (bottom - top); };
  // The 95 % band, then the mean line, then the axes and the seeds.
  if (st.has_interval) {
    image.fill_rect(static_cast<int>(left), static_cast<int>(std::lround(py(st.upper()))),
                    static_cast<int>(right), static_cast<int>(std::lround(py(st.lower()))) + 1,
                    {255, 215, 215});
  }
  if (st.count > 0) image.line(left, py(st.mean), right, py(st.mean), 2, {220, 20, 20});
  const Rgb axis{30, 30, 30};
  image.line(left, top, left, bottom, 2, axis);
  image.line(left, bottom, right, bottom, 2, axis);
  for (const double tick : {low, 0.5 * (low + high), high}) {
    char label[32];
    std::snprintf(label, sizeof label, "%.1f", tick);
    image.line(left - 5, py(tick), left, py(tick), 1, axis);
    image.text(label, 4, static_cast<int>(py(tick)) - 3 * text_scale, text_scale, axis);
  }
  const int dot = std::max(5, width / 150);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = ensemble.seeds[i];
    const int x = static_cast<int>(std::lround(px(i)));
    if (s.is_valid) {
      const int y = static_cast<int>(std::lround(py(s.angle_degrees)));
      image.fill_rect(x - dot / 2, y - dot / 2, x - dot / 2 + dot, y - dot / 2 + dot,
                      {30, 60, 220});
    } else {  // a failed seed: a red cross on the axis
      image.line(x - dot, bottom - dot, x + dot, bottom + dot, 2, {200, 0, 0});
      image.line(x - dot, bottom + dot, x + dot, bottom - dot, 2, {200, 0, 0});
    }
    if (n <= 40) {
      image.text(std::to_string(s.seed), x - 3 * text_scale, static_cast<int>(bottom) + 6,
                 text_scale, axis);
    }
  }
  char caption[200];
  if (st.has_interval) {
    std::snprintf(caption, sizeof caption,
                  "angle of repose %.2f deg, sd %.2f, 95%% CI [%.2f, %.2f]  (%zu of %zu seeds)",
                  st.mean, st.std_dev, st.lower(), st.upper(), st.count, n);
  } else {
    std::snprintf(caption, sizeof caption,
                  "angle of repose %.2f deg, no interval  (%zu of %zu seeds)", st.mean, st.count,
                  n);
  }
  image.text(caption, 10, 8, text_scale, {0, 0, 0});
  write_png(path, image);
}

}  // namespace aggpack
