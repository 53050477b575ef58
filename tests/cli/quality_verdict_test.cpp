// The one-line quality verdicts of `export` (tetrahedra) and `mesomodel` (issue 36 item 4): each
// branch, the thresholds at their edges, and that only real problems are warnings.

#include "quality_verdict.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace aggpack::cli {
namespace {

TetQuality quality_with_min_angle(double degrees) {
  TetQuality quality;
  quality.tetrahedra = 100;
  quality.min_dihedral_degrees = degrees;
  quality.max_aspect_ratio = 3.0;
  return quality;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(QualityVerdict, TenDegreesAndAboveIsFine) {
  const TetOptions fan;
  for (const double degrees : {10.0, 35.0}) {
    const Verdict verdict = tet_quality_verdict(quality_with_min_angle(degrees), fan, 1.0);
    EXPECT_FALSE(verdict.is_warning) << verdict.text;
    EXPECT_EQ(verdict.text, "fine for solvers: no tetrahedron below 10 deg");
  }
}

TEST(QualityVerdict, SliversDownToTheSolvedAngleAreExpectedAndNameTheBetterOption) {
  TetOptions fan;
  const Verdict fan_verdict = tet_quality_verdict(quality_with_min_angle(9.99), fan, 1.0);
  EXPECT_FALSE(fan_verdict.is_warning);
  EXPECT_TRUE(contains(fan_verdict.text, "as expected (the centroid fan")) << fan_verdict.text;
  EXPECT_TRUE(contains(fan_verdict.text, "better-shaped: --tet-method tetgen --split-surface"));
  // In metres (scale 1) the verdict suggests millimetres; at --scale 1000 it does not.
  EXPECT_TRUE(contains(fan_verdict.text, "--scale 1000"));
  EXPECT_FALSE(
      contains(tet_quality_verdict(quality_with_min_angle(1.0), fan, 1000.0).text, "--scale 1000"));
  TetOptions tetgen;
  tetgen.method = TetMethod::kTetGen;
  tetgen.is_surface_kept = true;
  const Verdict kept =
      tet_quality_verdict(quality_with_min_angle(kSolvedDihedralDegrees), tetgen, 1.0);
  EXPECT_FALSE(kept.is_warning);
  EXPECT_TRUE(contains(kept.text, "TetGen keeps the surface triangles")) << kept.text;
  EXPECT_TRUE(contains(kept.text, "better-shaped: --split-surface")) << kept.text;
  tetgen.is_surface_kept = false;
  const Verdict split = tet_quality_verdict(quality_with_min_angle(0.5), tetgen, 1.0);
  EXPECT_TRUE(contains(split.text, "better-shaped: a smaller --radius-edge")) << split.text;
}

TEST(QualityVerdict, BelowTheSolvedAngleIsAWarningWithTheAngle) {
  TetOptions tetgen;
  tetgen.method = TetMethod::kTetGen;
  const Verdict verdict = tet_quality_verdict(quality_with_min_angle(0.0123), tetgen, 1.0);
  EXPECT_TRUE(verdict.is_warning);
  EXPECT_EQ(verdict.text.rfind("smallest angle 0.0123 deg, below the 0.017 deg", 0), 0U)
      << verdict.text;
  EXPECT_TRUE(contains(verdict.text, "--scale 1000")) << verdict.text;
}

TEST(QualityVerdict, DegenerateTetrahedraAreAWarning) {
  const TetOptions fan;
  TetQuality flat = quality_with_min_angle(0.0);
  EXPECT_TRUE(tet_quality_verdict(flat, fan, 1.0).is_warning);
  TetQuality infinite = quality_with_min_angle(5.0);
  infinite.max_aspect_ratio = std::numeric_limits<double>::infinity();
  const Verdict verdict = tet_quality_verdict(infinite, fan, 1.0);
  EXPECT_TRUE(verdict.is_warning);
  EXPECT_EQ(verdict.text.rfind("degenerate tetrahedra (no volume)", 0), 0U) << verdict.text;
  // A NaN angle (no number at all) is not taken for a good mesh either.
  EXPECT_TRUE(tet_quality_verdict(quality_with_min_angle(std::numeric_limits<double>::quiet_NaN()),
                                  fan, 1.0)
                  .is_warning);
}

// The golden case's spaced lattice: exact volumes, the angles its phases had (deg).
MesoReport exact_mesomodel() {
  MesoReport report;
  for (MesoPhaseReport& phase : report.phases) {
    phase.expected_volume = 2.0e-6;
    phase.meshed_volume = 2.0e-6 * (1.0 + 1e-13);
  }
  report.phases[static_cast<int>(MesoPhase::kAggregate)].quality = quality_with_min_angle(0.628);
  report.phases[static_cast<int>(MesoPhase::kItz)].quality = quality_with_min_angle(2.389);
  report.phases[static_cast<int>(MesoPhase::kMortar)].quality = quality_with_min_angle(0.101);
  return report;
}

TetQuality& quality_of(MesoReport& report, MesoPhase phase) {
  return report.phases[static_cast<int>(phase)].quality;
}

TEST(QualityVerdict, MesomodelWithExactVolumesIsAsExpected) {
  const Verdict verdict = mesomodel_verdict(exact_mesomodel());
  EXPECT_FALSE(verdict.is_warning);
  EXPECT_EQ(verdict.text,
            "as expected: ITZ tetrahedra are flat by design (the layer is thin over the "
            "aggregate's triangles); the mortar's smallest angles sit in the thin gaps between "
            "layers and walls; aggregate tetrahedra follow the particles' surface triangles "
            "(docs/mesomodel.md, \"Quality, honestly\")");
  // A phase with no expected volume (none meshed, e.g. no ITZ) is not checked, and the ITZ
  // sentence is left out: the mortar meets the aggregates.
  MesoReport no_itz = exact_mesomodel();
  no_itz.phases[static_cast<int>(MesoPhase::kItz)] = {};
  const Verdict without = mesomodel_verdict(no_itz);
  EXPECT_FALSE(without.is_warning);
  EXPECT_FALSE(contains(without.text, "ITZ")) << without.text;
  EXPECT_TRUE(contains(without.text, "thin gaps between aggregates and walls")) << without.text;
  // A cohesive ITZ: no ITZ tetrahedra (its report has the wedges' nodes only).
  MesoReport cohesive = exact_mesomodel();
  cohesive.phases[static_cast<int>(MesoPhase::kItz)].expected_volume = 0.0;
  cohesive.phases[static_cast<int>(MesoPhase::kItz)].quality = {};
  EXPECT_FALSE(contains(mesomodel_verdict(cohesive).text, "ITZ tetrahedra")) << "no ITZ sentence";
}

TEST(QualityVerdict, MesomodelNamesOnlyThePhasesWithSlivers) {
  // Aggregate at 10 deg (kPoorDihedralDegrees) or above: its sentence is left out.
  MesoReport report = exact_mesomodel();
  quality_of(report, MesoPhase::kAggregate) = quality_with_min_angle(kPoorDihedralDegrees);
  const Verdict coarse = mesomodel_verdict(report);
  EXPECT_FALSE(coarse.is_warning);
  EXPECT_FALSE(contains(coarse.text, "aggregate tetrahedra")) << coarse.text;
  EXPECT_TRUE(contains(coarse.text, "ITZ tetrahedra are flat")) << coarse.text;
  // Every phase at 10 deg or above: fine, no excuse needed.
  for (const MesoPhase phase : {MesoPhase::kItz, MesoPhase::kMortar}) {
    quality_of(report, phase) = quality_with_min_angle(12.0);
  }
  const Verdict fine = mesomodel_verdict(report);
  EXPECT_FALSE(fine.is_warning);
  EXPECT_EQ(fine.text, "fine for solvers: no tetrahedron below 10 deg");
}

TEST(QualityVerdict, MesomodelAngleBelowWhatSolversTakeIsAWarningNamingThePhase) {
  MesoReport report = exact_mesomodel();
  // At the threshold: still expected.
  quality_of(report, MesoPhase::kMortar) = quality_with_min_angle(kSolvedDihedralDegrees);
  EXPECT_FALSE(mesomodel_verdict(report).is_warning);
  quality_of(report, MesoPhase::kMortar) = quality_with_min_angle(0.0123);
  const Verdict verdict = mesomodel_verdict(report);
  EXPECT_TRUE(verdict.is_warning);
  EXPECT_EQ(verdict.text.rfind("mesomodel: smallest MORTAR angle 0.0123 deg, below the 0.017 deg "
                               "CalculiX is known to solve",
                               0),
            0U)
      << verdict.text;
  EXPECT_TRUE(contains(verdict.text, "Quality, honestly")) << verdict.text;
  // Degenerate (no volume) or NaN: a warning too, naming the phase.
  quality_of(report, MesoPhase::kMortar) = quality_with_min_angle(1.0);
  quality_of(report, MesoPhase::kItz) =
      quality_with_min_angle(std::numeric_limits<double>::quiet_NaN());
  const Verdict nan = mesomodel_verdict(report);
  EXPECT_TRUE(nan.is_warning);
  EXPECT_TRUE(contains(nan.text, "degenerate ITZ tetrahedra")) << nan.text;
  quality_of(report, MesoPhase::kItz) = quality_with_min_angle(0.0);
  EXPECT_TRUE(mesomodel_verdict(report).is_warning);
}

TEST(QualityVerdict, MesomodelVolumeOffOrRelabelledTetrahedraAreWarnings) {
  MesoReport off = exact_mesomodel();
  off.phases[static_cast<int>(MesoPhase::kMortar)].meshed_volume = 2.0e-6 * (1.0 + 2e-6);
  const Verdict volume = mesomodel_verdict(off);
  EXPECT_TRUE(volume.is_warning);
  EXPECT_TRUE(contains(volume.text, std::string(phase_set_name(MesoPhase::kMortar)) +
                                        " volume off its exact value by 2.00e-06"))
      << volume.text;
  MesoReport relabelled = exact_mesomodel();
  relabelled.relabelled_tetrahedra = 3;
  const Verdict labels = mesomodel_verdict(relabelled);
  EXPECT_TRUE(labels.is_warning);
  EXPECT_TRUE(contains(labels.text, "3 tetrahedra relabelled by the phase check")) << labels.text;
  off.relabelled_tetrahedra = 1;
  EXPECT_TRUE(contains(mesomodel_verdict(off).text, "; 1 tetrahedra relabelled")) << "both named";
}

}  // namespace
}  // namespace aggpack::cli
