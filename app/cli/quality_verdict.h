#pragma once
// One-line verdicts on a mesh's quality numbers (issue 36 item 4): whether they are what this
// kind of mesh is expected to have (printed on stdout) or a warning, when something is wrong
// (printed on stderr, "aggpack: warning: ...").

#include <string>

#include "aggpack/mesh/mesomodel.h"
#include "aggpack/mesh/quality.h"
#include "aggpack/mesh/tetrahedra.h"

namespace aggpack::cli {

struct Verdict {
  bool is_warning = false;
  std::string text;  ///< one line, no "warning:" prefix
};

/// Smallest angle at or below which CalculiX is known to solve a mesh: the 3,439-aggregate
/// mesomodel whose smallest dihedral was 0.017 deg (bench/RESULTS.md, "Concrete mesomodel mesh").
inline constexpr double kSolvedDihedralDegrees = 0.017;

/// The exported tetrahedra: fine (no angle below kPoorDihedralDegrees), as expected for the
/// method (down to kSolvedDihedralDegrees, naming the better-shaped option), or a warning
/// (degenerate, or below what a solver is known to take). `scale` = the export's --scale.
Verdict tet_quality_verdict(const TetQuality& quality, const TetOptions& tetrahedra, double scale);

/// A mesomodel, from its phases' quality: angles below kPoorDihedralDegrees are explained per
/// phase that has them (a flat ITZ layer, when there is one; mortar in thin gaps; aggregate
/// tetrahedra on the particles' surface triangles), none is "fine for solvers". A phase angle
/// below kSolvedDihedralDegrees or degenerate, a phase volume off its exact value (relative
/// error above 1e-6) or a relabelled tetrahedron is a warning naming the phase and the number.
Verdict mesomodel_verdict(const MesoReport& report);

/// Prints `verdict`: "<label>: <text>" on stdout, or "aggpack: warning: <text>" on stderr.
void print_verdict(const std::string& label, const Verdict& verdict);

}  // namespace aggpack::cli
