#pragma once
// The homogenised stiffness of a periodic RVE (docs/mesomodel.md, "Periodic RVE"): CalculiX runs
// the six load cases of the mesomodel's .inp in a temporary folder, the 6x6 tensor is read back
// from its .dat, and this file adds what a user compares it with: its isotropic projection, its
// asymmetry, and the Hashin-Shtrikman bounds of the phases (Walpole's form, which holds for any
// isotropic phases, ordered or not). write_stiffness_json writes all of it.

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/io/mesomodel_files.h"

namespace aggpack {

/// Isotropic elastic constants: bulk and shear modulus (Pa), Young's modulus (Pa), Poisson ratio.
struct IsotropicModuli {
  double bulk = 0.0;
  double shear = 0.0;
  double youngs = 0.0;
  double poisson = 0.0;
};

/// The constants of bulk modulus k and shear modulus g (E = 9kg / (3k + g), nu = (3k - 2g) /
/// (6k + 2g)).
IsotropicModuli isotropic_from_bulk_shear(double bulk, double shear);

/// The stiffness of an isotropic material (Voigt order, engineering shear).
VoigtStiffness isotropic_stiffness(double youngs, double poisson);

/// The isotropic tensor nearest to `c` (the orthogonal projection onto isotropic tensors, i.e. the
/// Voigt average over orientations): k = (C11 + C22 + C33 + 2 (C12 + C13 + C23)) / 9,
/// g = (C11 + C22 + C33 - (C12 + C13 + C23) + 3 (C44 + C55 + C66)) / 15.
IsotropicModuli isotropic_projection(const VoigtStiffness& c);

/// max |C_ij - C_ji| / max |C_ij| (0 for a symmetric tensor).
double asymmetry(const VoigtStiffness& c);

/// Bounds of an isotropic mixture's effective moduli: for k and g separately, and for E through
/// them (E grows with k and with g). The phases' fractions are the mesh's.
struct HashinShtrikmanBounds {
  IsotropicModuli lower;
  IsotropicModuli upper;
};

/// The Hashin-Shtrikman bounds (Walpole's form: k with 4/3 of the smallest and largest shear
/// modulus, g with z(k, g) = g (9k + 8g) / (6 (k + 2g)) of the smallest and largest k and g) of
/// the mesh's phases with `materials`. Phases without tetrahedra are left out.
HashinShtrikmanBounds hashin_shtrikman_bounds(const MesoMesh& mesh, const MesoMaterials& materials);

/// How CalculiX runs.
struct HomogenizeOptions {
  /// Threads for ccx (OMP_NUM_THREADS); 0 = the cores aggpack may use (allowed_threads()).
  int threads = 0;
  /// Called about five times a second while ccx runs, with the load cases it has finished (0-6).
  std::function<void(int finished)> progress;
};

/// What one CalculiX run gave.
struct Homogenized {
  VoigtStiffness stiffness{};  ///< Pa, Voigt order 11 22 33 23 13 12, engineering shear
  IsotropicModuli isotropic;   ///< isotropic_projection(stiffness)
  double asymmetry = 0.0;      ///< asymmetry(stiffness)
  double strain = 0.0;         ///< the load cases' strain
  double wall_seconds = 0.0;   ///< ccx's run, from start to end
  double cpu_seconds = 0.0;    ///< ccx's user + system time
  int threads = 1;             ///< OMP_NUM_THREADS given to ccx
  MesoSolver solver = MesoSolver::kDirect;  ///< the options' solver
  std::string program;                      ///< the ccx that ran
  /// ccx's *WARNING lines (the first 5, each with the line after it), none on a clean run.
  std::vector<std::string> warnings;
};

/// What homogenize_with_calculix refuses before any work, for a box periodic along `periodic`
/// (x, y, z): CalculiX not installed, then a box not periodic in all three axes. Returns the ccx
/// to run. A front end calls it before meshing. \throw InvalidInput (field "homogenize"; value
/// "true" when ccx is not on PATH, the message naming the Debian package calculix-ccx, or "with
/// container.periodic = xy").
std::string check_homogenize(const std::array<bool, 3>& periodic);

/// Writes the periodic .inp of `mesh` with `options` in a temporary folder, runs CalculiX's ccx on
/// it and reads the stiffness from its .dat. The folder and everything in it are removed on every
/// exit path; ccx dies with aggpack.
/// \throw InvalidInput (check_homogenize(mesh.periodic)), IoError (ccx failed: its exit status and
/// its first *ERROR line or last line).
Homogenized homogenize_with_calculix(const MesoMesh& mesh, const MesoFileOptions& options,
                                     const HomogenizeOptions& run = {});

/// The JSON file of a run (docs/mesomodel.md, "Periodic RVE", lists its keys), written
/// atomically. \throw IoError (not a regular file, exists with Overwrite::kForbid, unwritable).
void write_stiffness_json(const std::string& path, const Homogenized& result, const MesoMesh& mesh,
                          const MesoMaterials& materials, Overwrite overwrite);

}  // namespace aggpack
