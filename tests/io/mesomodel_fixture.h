#pragma once
// A synthetic concrete mesomodel for the file writers' tests: a cube of n x n x n cells, each cut
// into the 6 tetrahedra of the Kuhn triangulation (the same in every cell, so neighbouring cells
// share faces: the mesh is conforming), every cell given a phase and a particle by the caller.

#include <algorithm>
#include <array>
#include <functional>
#include <utility>

#include "aggpack/mesh/mesomodel.h"

namespace aggpack::test {

/// Phase and 1-based particle (0 for the mortar) of cell (i, j, k).
using CellPhase = std::function<std::pair<MesoPhase, std::uint32_t>(int i, int j, int k)>;

/// The cube [0, size]^3 of n^3 cells, 6 n^3 positive tetrahedra, (n + 1)^3 nodes.
inline MesoMesh cube_mesomodel(int n, double size, std::uint32_t particle_count,
                               const CellPhase& cell_phase) {
  MesoMesh mesh;
  const int m = n + 1;
  auto node = [&](int i, int j, int k) { return static_cast<std::uint32_t>(i + m * (j + m * k)); };
  for (int k = 0; k < m; ++k) {
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        mesh.nodes.emplace_back(size * i / n, size * j / n, size * k / n);
      }
    }
  }
  std::array<int, 3> permutation = {0, 1, 2};
  std::vector<std::array<int, 3>> permutations;
  do {
    permutations.push_back(permutation);
  } while (std::next_permutation(permutation.begin(), permutation.end()));
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const auto [phase, particle] = cell_phase(i, j, k);
        for (const auto& p : permutations) {
          // Kuhn: walk from corner (0,0,0) to (1,1,1) one axis at a time, in order p.
          std::array<int, 3> at = {i, j, k};
          Tetrahedron t;
          t[0] = node(at[0], at[1], at[2]);
          for (int step = 0; step < 3; ++step) {
            ++at[p[step]];
            t[step + 1] = node(at[0], at[1], at[2]);
          }
          if (tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]) <
              0) {
            std::swap(t[1], t[2]);
          }
          mesh.tetrahedra.push_back(t);
          mesh.phase.push_back(phase);
          mesh.particle.push_back(particle);
        }
      }
    }
  }
  mesh.particle_count = particle_count;
  mesh.container.shape = BoxContainer{.length = size, .width = size, .depth = size};
  mesh.bounds = mesh.container.bounds();
  return mesh;
}

}  // namespace aggpack::test
