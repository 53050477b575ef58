#include "quality_verdict.h"

#include <fmt/core.h>

#include <cmath>
#include <cstdio>

namespace aggpack::cli {

// Thresholds: kPoorDihedralDegrees (10 deg, the mesh module's "poorly shaped"); below it, what
// solvers are known to take. What CalculiX refuses is a Jacobian below 1e-20 in the file's units
// (docs/mesomodel.md), so a flat tetrahedron of a small particle written in metres can stop it
// where millimetres (--scale 1000) do not. A degenerate tetrahedron (no volume: infinite aspect
// ratio) stops every solver.
Verdict tet_quality_verdict(const TetQuality& quality, const TetOptions& tetrahedra, double scale) {
  const bool is_tetgen = tetrahedra.method == TetMethod::kTetGen;
  if (!std::isfinite(quality.max_aspect_ratio) || !(quality.min_dihedral_degrees > 0.0)) {
    return {true,
            "degenerate tetrahedra (no volume): solvers stop on them (CalculiX: nonpositive "
            "jacobian); please report it with the input file"};
  }
  if (quality.min_dihedral_degrees >= kPoorDihedralDegrees) {
    return {false,
            fmt::format("fine for solvers: no tetrahedron below {} deg", kPoorDihedralDegrees)};
  }
  const std::string why =
      !is_tetgen                   ? "the centroid fan: flat over small or steep surface triangles"
      : tetrahedra.is_surface_kept ? "TetGen keeps the surface triangles: flat where --radius-edge "
                                     "would split one"
                                   : "TetGen's --radius-edge bound does not remove slivers";
  const std::string better = !is_tetgen                   ? "--tet-method tetgen --split-surface"
                             : tetrahedra.is_surface_kept ? "--split-surface"
                                                          : "a smaller --radius-edge";
  if (quality.min_dihedral_degrees >= kSolvedDihedralDegrees) {
    return {false,
            fmt::format(
                "as expected ({}); solvers run such meshes (CalculiX down to {} deg{}); "
                "better-shaped: {}",
                why, kSolvedDihedralDegrees,
                scale < 100.0 ? "; in mm, --scale 1000, if it reports a nonpositive jacobian" : "",
                better)};
  }
  return {true, fmt::format("smallest angle {:.3g} deg, below the {} deg CalculiX is known to "
                            "solve ({}); if the solver stops on a jacobian, write in mm "
                            "(--scale 1000) or use {}",
                            quality.min_dihedral_degrees, kSolvedDihedralDegrees, why, better)};
}

Verdict mesomodel_verdict(const MesoReport& report) {
  std::string problems;
  const auto add_problem = [&problems](const std::string& text) {
    problems += (problems.empty() ? "" : "; ") + text;
  };
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    const MesoPhaseReport& p = report.phases[static_cast<int>(phase)];
    if (p.expected_volume <= 0.0) continue;
    const double error = std::abs(p.meshed_volume - p.expected_volume) / p.expected_volume;
    if (!(error <= 1e-6)) {
      add_problem(fmt::format("{} volume off its exact value by {:.2e} (expected ~1e-14)",
                              phase_set_name(phase), error));
    }
  }
  if (report.relabelled_tetrahedra > 0) {
    add_problem(fmt::format("{} tetrahedra relabelled by the phase check (expected 0)",
                            report.relabelled_tetrahedra));
  }
  if (!problems.empty()) problems += "; please report it with the input file";
  // The angles, per phase that has tetrahedra (a cohesive ITZ has none): below what CalculiX is
  // known to solve, or degenerate (0, NaN, an infinite aspect ratio), is a warning.
  std::string angles;
  const auto add_angle = [&angles](const std::string& text) {
    angles += (angles.empty() ? "" : "; ") + text;
  };
  const auto quality_of = [&report](MesoPhase phase) -> const TetQuality& {
    return report.phases[static_cast<int>(phase)].quality;
  };
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    const TetQuality& q = quality_of(phase);
    if (q.tetrahedra == 0) continue;
    if (!std::isfinite(q.max_aspect_ratio) || !(q.min_dihedral_degrees > 0.0)) {
      add_angle(fmt::format("degenerate {} tetrahedra (no volume): solvers stop on them",
                            phase_set_name(phase)));
    } else if (q.min_dihedral_degrees < kSolvedDihedralDegrees) {
      add_angle(
          fmt::format("smallest {} angle {:.3g} deg, below the {} deg CalculiX is known to "
                      "solve",
                      phase_set_name(phase), q.min_dihedral_degrees, kSolvedDihedralDegrees));
    }
  }
  if (!angles.empty()) {
    problems += (problems.empty() ? "" : "; ") + angles +
                "; if the solver stops on a nonpositive jacobian, see docs/mesomodel.md, "
                "\"Quality, honestly\"";
  }
  if (!problems.empty()) return {true, "mesomodel: " + problems};
  // What explains the angles below kPoorDihedralDegrees, phase by phase.
  const bool has_itz = report.phases[static_cast<int>(MesoPhase::kItz)].expected_volume > 0.0 &&
                       quality_of(MesoPhase::kItz).tetrahedra > 0;
  const auto is_poor = [&quality_of](MesoPhase phase) {
    const TetQuality& q = quality_of(phase);
    return q.tetrahedra > 0 && q.min_dihedral_degrees < kPoorDihedralDegrees;
  };
  std::string reasons;
  const auto add_reason = [&reasons](const std::string& text) {
    reasons += (reasons.empty() ? "" : "; ") + text;
  };
  if (has_itz && is_poor(MesoPhase::kItz)) {
    add_reason(
        "ITZ tetrahedra are flat by design (the layer is thin over the aggregate's "
        "triangles)");
  }
  if (is_poor(MesoPhase::kMortar)) {
    add_reason(fmt::format("the mortar's smallest angles sit in the thin gaps between {} and walls",
                           has_itz ? "layers" : "aggregates"));
  }
  if (is_poor(MesoPhase::kAggregate)) {
    add_reason("aggregate tetrahedra follow the particles' surface triangles");
  }
  if (reasons.empty()) {
    return {false,
            fmt::format("fine for solvers: no tetrahedron below {} deg", kPoorDihedralDegrees)};
  }
  return {false, "as expected: " + reasons + " (docs/mesomodel.md, \"Quality, honestly\")"};
}

void print_verdict(const std::string& label, const Verdict& verdict) {
  if (verdict.is_warning) {
    std::fprintf(stderr, "aggpack: warning: %s\n", verdict.text.c_str());
  } else {
    fmt::print("{}{}\n", label, verdict.text);
  }
}

}  // namespace aggpack::cli
