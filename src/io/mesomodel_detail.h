#pragma once
// Internals shared by the mesomodel writers (src/io/mesomodel_*.cpp); not a public header.

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "aggpack/io/mesomodel_files.h"

namespace aggpack::detail {

/// The order every mesomodel file writes the elements in: group g holds the tetrahedra of
/// aggregate g + 1 (g < n), of ITZ shell g - n + 1 (n <= g < 2n) or the mortar (g = 2n), n being
/// mesh.particle_count; each group in the mesh's order. Element id (1-based) = position + 1.
struct MesoLayout {
  std::uint32_t particle_count = 0;
  std::vector<std::uint32_t> order;          ///< tetrahedron index by position
  std::vector<std::uint64_t> group_offsets;  ///< 2n + 2 entries: positions of group g
  [[nodiscard]] std::size_t group_count() const { return group_offsets.size() - 1; }
  [[nodiscard]] std::uint64_t group_size(std::size_t g) const {
    return group_offsets[g + 1] - group_offsets[g];
  }
  /// Phase and 1-based particle (0 for the mortar) of group g.
  [[nodiscard]] MesoPhase group_phase(std::size_t g) const;
  [[nodiscard]] std::uint32_t group_particle(std::size_t g) const;
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

}  // namespace aggpack::detail
