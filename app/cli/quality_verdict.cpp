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
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    const MesoPhaseReport& p = report.phases[static_cast<int>(phase)];
    if (p.expected_volume <= 0.0) continue;
    const double error = std::abs(p.meshed_volume - p.expected_volume) / p.expected_volume;
    if (!(error <= 1e-6)) {
      problems += fmt::format("{}{} volume off its exact value by {:.2e} (expected ~1e-14)",
                              problems.empty() ? "" : "; ", phase_set_name(phase), error);
    }
  }
  if (report.relabelled_tetrahedra > 0) {
    problems += fmt::format("{}{} tetrahedra relabelled by the phase check (expected 0)",
                            problems.empty() ? "" : "; ", report.relabelled_tetrahedra);
  }
  if (!problems.empty()) {
    return {true, "mesomodel: " + problems + "; please report it with the input file"};
  }
  return {false,
          "as expected: ITZ tetrahedra are flat by design (the layer is thin over the "
          "aggregate's triangles) and the mortar's smallest angles sit in the thin gaps between "
          "layers and walls (docs/mesomodel.md, \"Quality, honestly\")"};
}

void print_verdict(const std::string& label, const Verdict& verdict) {
  if (verdict.is_warning) {
    std::fprintf(stderr, "aggpack: warning: %s\n", verdict.text.c_str());
  } else {
    fmt::print("{}{}\n", label, verdict.text);
  }
}

}  // namespace aggpack::cli
