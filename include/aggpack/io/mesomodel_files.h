#pragma once
// Files of the concrete mesomodel (mesh/mesomodel.h; issue 16, items 1 and 4): one conforming
// tetrahedral mesh of aggregate, ITZ and mortar written as
//  - .inp (Abaqus / CalculiX): nodes, C3D4 or C3D10 elements, element sets per phase and per
//    aggregate, a material and solid section per phase, node sets of the specimen's faces and an
//    optional uniaxial compression step;
//  - .msh (Gmsh 4.1 ASCII): a volume entity per aggregate, per ITZ shell and for the mortar, each
//    in the physical group of its phase (AGGREGATE, ITZ, MORTAR);
//  - .vtu (VTK XML unstructured grid, raw binary): cell data "phase" (UInt8, MesoPhase code) and
//    "particle" (UInt32, 1-based, 0 = mortar).
// Every format writes the elements in the same order, so element i (1-based) is the same
// tetrahedron in all three: the aggregates particle by particle, then the ITZ shells particle by
// particle, then the mortar, each group in the mesh's order (docs/mesomodel.md, "Files").
// Units are SI (m, Pa, kg/m^3) unless MesoFileOptions::units asks for mm (mm, N, t, s, MPa).

#include <array>
#include <cstdint>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/io/export.h"
#include "aggpack/mesh/mesomodel.h"

namespace aggpack {

/// Linear elastic constants of one phase.
struct PhaseMaterial {
  double youngs_modulus = 0.0;  ///< Pa, in (0, 1e13]
  double poisson_ratio = 0.0;   ///< in (-1, 0.5)
  double density = 0.0;         ///< kg/m^3, in (0, 1e5]
};

/// The three phases' materials. Defaults: typical normal-strength concrete (docs/mesomodel.md,
/// "Materials", gives the sources). All three Poisson ratios are equal by default: then the Voigt
/// and Reuss averages of the phases' Young's moduli (voigt_reuss_bounds) bound the specimen's
/// effective Young's modulus rigorously.
struct MesoMaterials {
  PhaseMaterial aggregate{.youngs_modulus = 60e9, .poisson_ratio = 0.2, .density = 2700.0};
  PhaseMaterial itz{.youngs_modulus = 15e9, .poisson_ratio = 0.2, .density = 2000.0};
  PhaseMaterial mortar{.youngs_modulus = 25e9, .poisson_ratio = 0.2, .density = 2200.0};

  [[nodiscard]] const PhaseMaterial& of(MesoPhase phase) const;
};

/// Throws InvalidInput naming the field ("materials.itz.youngs_modulus"), its value and the
/// allowed range unless every constant is usable.
void validate(const MesoMaterials& materials);

/// The optional uniaxial compression step of the .inp: the bottom face held in z, the top face
/// moved down by strain x height, the sides free; two bottom nodes remove the rigid motions in x,
/// y and about z (statically determinate, so they add no stress).
struct CompressionStep {
  /// Nominal strain (shortening / height), in [0, 0.1]; 0 = no step.
  double strain = 0.0;
};

/// Units of the written file. The mesh and the materials are always given in SI; kMillimetre
/// writes the consistent mm, N, t (tonne), s, MPa system that Abaqus and CalculiX users often
/// prefer: coordinates x 1000, Young's moduli in MPa (x 1e-6), densities in t/mm^3 (x 1e-12).
/// CalculiX refuses an element whose Jacobian determinant (6 x volume for a tetrahedron) is below
/// 1e-20 in the file's units ("nonpositive jacobian"), i.e. a tetrahedron under 1.7e-21 m^3 in
/// metres - the ITZ's slivers can be that small - but under 1.7e-30 m^3 in millimetres.
enum class MesoUnits : std::uint8_t { kMetre, kMillimetre };

/// Length of one metre in the file's units (1 or 1000).
double length_scale(MesoUnits units);

/// CalculiX's solver for the .inp's steps (the compression step, a periodic box's six load cases).
/// kDirect: ccx's default (SPOOLES in Debian's calculix-ccx), exact to round-off. kIterative:
/// `*STATIC, SOLVER=ITERATIVE CHOLESKY`, a preconditioned conjugate gradient with ccx's fixed
/// tolerance: measured on a 23,000-node RVE 6.4x less CPU than SPOOLES, the stiffness's diagonal
/// within 3e-5 and its off-diagonal terms within 0.3 % of the direct solution (docs/mesomodel.md).
/// CalculiX only: Abaqus has no SOLVER parameter on *STATIC.
enum class MesoSolver : std::uint8_t { kDirect, kIterative };

/// How to write a mesomodel file.
struct MesoFileOptions {
  MesoMaterials materials;
  CompressionStep step;
  /// Units of coordinates (all formats) and of materials and the step (.inp).
  MesoUnits units = MesoUnits::kMetre;
  /// .inp only: CalculiX's solver for its steps.
  MesoSolver solver = MesoSolver::kDirect;
  /// .inp only: 10-node tetrahedra (C3D10, straight-sided: a node at the middle of every edge).
  bool is_quadratic = false;
  /// .inp only: element sets AGG<k> and ITZ<k> for every particle k (1-based) that has elements.
  bool has_particle_sets = true;
  /// Whether an existing output may be replaced (--force). A non-regular file never is.
  Overwrite overwrite = Overwrite::kForbid;
};

/// Throws InvalidInput naming the field unless the options are usable.
void validate(const MesoFileOptions& options);

/// Throws InvalidInput naming the field ("mesh.phase size", "mesh.tetrahedra[i]", ...) unless the
/// mesh is consistent: per-tetrahedron phase and particle arrays of the right size, node numbers
/// in range, particle ids in 1..particle_count for aggregate and ITZ tetrahedra and 0 for mortar,
/// a container box with positive height.
void validate(const MesoMesh& mesh);

/// The format named by the output's extension, case-insensitive: a row of export_formats() with a
/// mesomodel writer (FormatInfo::write_mesomodel: .inp, .msh, .vtu).
/// \throw InvalidInput "invalid output = 'x.stl' (allowed: .inp, .msh, .vtu)"
ExportFormat mesomodel_format(const std::string& path);

/// What was written.
struct MesoFileSummary {
  ExportFormat format = ExportFormat::kAbaqus;  ///< kAbaqus (.inp), kGmsh (.msh) or kVtu
  std::uint64_t nodes = 0;                      ///< including mid-side nodes of C3D10
  std::uint64_t elements = 0;                   ///< tetrahedra
};

/// Writes the mesh in the format of the path's extension, atomically (temporary file + rename;
/// nothing is left behind on failure). Checks options, mesh and the output's writability before
/// any work. \throw InvalidInput (extension, options, mesh; C3D10 asked for .msh or .vtu), IoError
/// (existing output without Overwrite::kAllow, a non-regular file, unwritable folder, disk full).
MesoFileSummary write_mesomodel(const std::string& path, const MesoMesh& mesh,
                                const MesoFileOptions& options = {});

/// The three writers (write_mesomodel checks the extension and calls the row's). Same contract.
MesoFileSummary write_mesomodel_inp(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options = {});
MesoFileSummary write_mesomodel_msh(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options = {});
MesoFileSummary write_mesomodel_vtu(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options = {});

/// Volume fractions of the phases (from the tetrahedra) and the Voigt (sum f_i E_i) and Reuss
/// (1 / sum f_i / E_i) averages of their Young's moduli. With equal Poisson ratios these bound the
/// specimen's effective Young's modulus (upper, lower): the Voigt and Reuss stiffness tensors
/// are then isotropic with these Young's moduli and the common Poisson ratio.
struct MesoModulusBounds {
  double fractions[3] = {0.0, 0.0, 0.0};  ///< index = MesoPhase code
  double voigt = 0.0;                     ///< Pa
  double reuss = 0.0;                     ///< Pa
};
MesoModulusBounds voigt_reuss_bounds(const MesoMesh& mesh, const MesoMaterials& materials);

/// A 6x6 stiffness in Voigt order (11, 22, 33, 23, 13, 12; engineering shear strains), Pa.
using VoigtStiffness = std::array<std::array<double, 6>, 6>;

/// The homogenised stiffness of a periodic box (every axis periodic) from the .dat CalculiX wrote
/// for the .inp that write_mesomodel made of `mesh` with `options` (its six steps, the totals of
/// RF over XMAX, YMAX and ZMAX; docs/mesomodel.md, "Periodic RVE"): column k is the box's mean
/// stress in step k over the step's strain; a shear stress is the mean of its two faces' values.
/// \throw InvalidInput when the text lacks a step's totals (naming the step and the set).
VoigtStiffness periodic_stiffness_from_dat(const std::string& dat, const MesoMesh& mesh,
                                           const MesoFileOptions& options);

}  // namespace aggpack
