#pragma once
// Internals shared by the mesomodel writers (src/io/mesomodel_*.cpp); not a public header.

#include <cstdint>
#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "aggpack/io/mesomodel_files.h"

namespace aggpack::detail {

/// A mesh's elements in one numbering: its tetrahedra 0..T-1, then its cohesive wedges
/// T..T+C-1 (a cohesive mesh has no ITZ tetrahedra, validate(MesoMesh)).
[[nodiscard]] inline std::span<const std::uint32_t> element_nodes(const MesoMesh& mesh,
                                                                  std::uint32_t element) {
  if (element < mesh.tetrahedra.size()) return mesh.tetrahedra[element];
  return mesh.cohesive[element - mesh.tetrahedra.size()];
}
[[nodiscard]] inline std::uint64_t element_count(const MesoMesh& mesh) {
  return mesh.tetrahedra.size() + mesh.cohesive.size();
}
/// Phase and 1-based particle (0 for the mortar) of an element of that numbering.
[[nodiscard]] MesoPhase element_phase(const MesoMesh& mesh, std::uint32_t element);
[[nodiscard]] std::uint32_t element_particle(const MesoMesh& mesh, std::uint32_t element);

/// The order every mesomodel file writes the elements in: group g holds the elements of
/// aggregate g + 1 (g < n), of the ITZ of particle g - n + 1 (n <= g < 2n: tetrahedra of a solid
/// layer or cohesive wedges) or the mortar (g = 2n), n being mesh.particle_count; each group in
/// the mesh's order. Element id (1-based) = position + 1.
struct MesoLayout {
  std::uint32_t particle_count = 0;
  bool is_cohesive = false;                  ///< the ITZ groups hold cohesive wedges
  std::vector<std::uint32_t> order;          ///< element (element_nodes numbering) by position
  std::vector<std::uint64_t> group_offsets;  ///< 2n + 2 entries: positions of group g
  [[nodiscard]] std::size_t group_count() const { return group_offsets.size() - 1; }
  [[nodiscard]] std::uint64_t group_size(std::size_t g) const {
    return group_offsets[g + 1] - group_offsets[g];
  }
  /// Phase and 1-based particle (0 for the mortar) of group g.
  [[nodiscard]] MesoPhase group_phase(std::size_t g) const;
  [[nodiscard]] std::uint32_t group_particle(std::size_t g) const;
  /// Whether group g holds cohesive wedges (else tetrahedra).
  [[nodiscard]] bool is_cohesive_group(std::size_t g) const {
    return is_cohesive && group_phase(g) == MesoPhase::kItz;
  }
  /// First and one-past-last position of a phase's groups (they are consecutive).
  [[nodiscard]] std::uint64_t phase_begin(MesoPhase phase) const;
  [[nodiscard]] std::uint64_t phase_end(MesoPhase phase) const;
};

MesoLayout make_layout(const MesoMesh& mesh);

/// Writes a file atomically: checks writability, opens an AtomicFile, runs `write`, commits;
/// names the file and the reason on a failed write. \throw IoError
void write_atomically(const std::string& path, Overwrite overwrite,
                      const std::function<void(std::ostream&)>& write);

/// Throws IoError "write error" when `out` failed (stops long loops early on a full disk).
void require_good(const std::ostream& out);

/// Writes `name`'s node set (1-based, 16 a line).
void append_node_set(const std::string& name, const std::vector<std::uint32_t>& nodes,
                     std::string& out);

/// The line that starts a step's analysis: "*STATIC\n", with the iterative solver's parameter
/// for MesoSolver::kIterative.
const char* static_line(MesoSolver solver);

/// A periodic mesh's part of the .inp (docs/mesomodel.md, "Periodic RVE"), after the model's sets:
/// node sets XMIN ... ZMAX, reference nodes numbered from written_nodes + 1 (REF_X, REF_Y,
/// REF_Z), the *EQUATION ties of periodic_pairs(mesh) and, when every axis is periodic, the
/// origin node held and six steps of unit-direction macroscopic strains of size `strain`
/// (11, 22, 33, 23, 13, 12; engineering shear) with the reference nodes' reactions printed.
/// Coordinates and displacements are multiplied by `scale`; comment lines go to `heading`.
void append_periodic_model(const MesoMesh& mesh, std::uint64_t written_nodes, double scale,
                           double strain, MesoSolver solver, std::string& heading,
                           std::string& out);

}  // namespace aggpack::detail
