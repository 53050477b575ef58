// The printed lines of the repose commands: one run's summary, YADE's progress lines and a
// split run's worker line. Built only with AGGPACK_HAS_SIM (cmake/sim.cmake).

#ifdef AGGPACK_HAS_SIM

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "aggpack/core/text.h"
#include "sim_flags.h"

namespace aggpack::cli {

void print_repose_result(const ReposeResult& r) {
  fmt::print("particles            {} (mean measured alpha {:.3f}), solid {:.4g} m^3\n",
             r.particle_count, r.mean_measured_alpha, r.solid_volume);
  fmt::print("time step            {:.4g} s (d_min {:.4g} m)\n", r.time_step, r.smallest_size);
  if (r.yade_iterations > 0) {
    fmt::print(
        "engine               yade: {} iterations, contact stiffness {:.3g} N/m^3, {} s CPU\n",
        r.yade_iterations, r.yade_young, format_seconds(r.engine_cpu_seconds));
  }
  fmt::print("stage 1 (settle)     {:.2f} s simulated, {}, pile height {:.3f} m, {} s wall\n",
             r.stage1_time, r.is_stage1_at_rest ? "at rest" : "NOT at rest (max_time)",
             r.stage1_height, format_seconds(r.stage1_seconds));
  fmt::print(
      "stage 2 (baffle)     {:.2f} s simulated, baffle moved {:.3f} m ({}), {}, {} s wall\n",
      r.stage2_time, r.baffle_travel, r.is_baffle_removed ? "then removed" : "to the far wall",
      r.is_stage2_at_rest ? "stable" : "NOT stable (max_time)", format_seconds(r.stage2_seconds));
  if (r.yade_iterations > 0) {
    fmt::print("final pile           {} particles outside\n", r.escaped_particles);
  } else {
    fmt::print(
        "final pile           max overlap {:.3f}% of d_min, max contact penetration {:.3f}%, "
        "{} particles outside\n",
        100.0 * r.max_overlap_fraction, 100.0 * r.max_contact_penetration_fraction,
        r.escaped_particles);
  }
  if (r.fit.is_valid) {
    fmt::print(
        "angle of repose      {:.2f} deg (R^2 {:.3f}, {} bins from x = {:.3f} to {:.3f} m, "
        "pile height {:.3f} m)\n",
        r.fit.angle_degrees, r.fit.r_squared, r.fit.bin_count, r.profile.centre(r.fit.first_bin),
        r.profile.centre(r.fit.last_bin), r.fit.pile_height);
    fmt::print(
        "fit sensitivity      max deviation {:.2f} deg (fit window +-0.05: {:.2f}, bin width "
        "x0.5-2: "
        "{:.2f})\n",
        r.sensitivity.max_deviation, r.sensitivity.max_deviation_window,
        r.sensitivity.max_deviation_bins);
  } else {
    fmt::print("angle of repose      not measured: {}\n", r.fit.message);
  }
  if (r.confirmation.window > 0.0) {
    fmt::print("rest confirmation    {:.2f} s window {}, {} restarts\n", r.confirmation.window,
               r.is_stage2_at_rest ? "passed" : "not passed", r.confirmation.restarts);
  }
  if (r.follow.time > 0.0 && r.follow.fit.is_valid) {
    fmt::print("follow-up            {:.2f} s later: angle {:.2f} deg, pile height {:.3f} m\n",
               r.follow.time, r.follow.fit.angle_degrees, r.follow.fit.pile_height);
  }
}

// A YADE progress line: simulated time, the rate (simulated per wall-clock second) and a rough
// ETA from an expected length of the run (the fill's fall and quiet time, half the baffle's
// travel, the quiet time and the confirmation window), which the run may well exceed.
void print_yade_progress(const YadeProgress& p, const ReposeOptions& o) {
  const double g = std::max(1e-9, o.physics.gravity.norm());
  const double earliest = std::sqrt(2.0 * o.fill_height / g) +
                          2.0 * (o.rest.min_time + o.rest.quiet_time) +
                          (o.trough_length - o.baffle_position) / o.baffle_speed * 0.5 +
                          o.confirm_window * std::sqrt(2.0 * o.radius / g);
  const double rate = p.wall_seconds > 0.0 ? p.total_time / p.wall_seconds : 0.0;
  const std::string eta = rate > 0.0 && earliest > p.total_time
                              ? fmt::format(", ETA ~{:.0f} s", (earliest - p.total_time) / rate)
                              : std::string();
  std::fprintf(stderr,
               "yade stage %d  t = %7.3f s (total %.3f s)  kinetic energy %.3g J  %.3g "
               "simulated s per s, %.0f s wall%s\n",
               p.stage, p.time, p.total_time, p.energy, rate, p.wall_seconds, eta.c_str());
}

void print_share(const RunShare& share, std::size_t owned, std::size_t total,
                 const std::string& folder) {
  fmt::print(
      "worker {} of {}: {} of {} runs done, records in {}/runs/; when every worker is done: "
      "aggpack merge {}\n",
      share.worker, share.of, owned, total, folder, folder);
}

}  // namespace aggpack::cli

#endif  // AGGPACK_HAS_SIM
