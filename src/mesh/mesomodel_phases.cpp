// The phase of every mesomodel tetrahedron, checked against the exact geometry
// (mesomodel_plc.h, relabel_by_geometry).

#include <algorithm>
#include <atomic>
#include <cmath>

#include "aggpack/core/parallel.h"
#include "mesomodel_plc.h"

namespace aggpack::detail {

namespace {

// A uniform grid of cells listing the bodies whose bounds meet them.
struct BodyGrid {
  Aabb box;
  double cell = 1.0;
  std::array<int, 3> dims{1, 1, 1};
  std::vector<std::vector<std::uint32_t>> cells;

  [[nodiscard]] std::array<int, 3> index(const Vec3& p) const {
    std::array<int, 3> at{};
    for (int axis = 0; axis < 3; ++axis) {
      const int i = static_cast<int>(std::floor((p[axis] - box.lower[axis]) / cell));
      at[axis] = std::clamp(i, 0, dims[axis] - 1);
    }
    return at;
  }
  [[nodiscard]] const std::vector<std::uint32_t>& at(const Vec3& p) const {
    const auto i = index(p);
    return cells[(static_cast<std::size_t>(i[2]) * dims[1] + i[1]) * dims[0] + i[0]];
  }
};

BodyGrid make_grid(const std::vector<PhaseBody>& bodies, const Aabb& box) {
  BodyGrid grid;
  grid.box = box;
  double largest = 0.0;
  for (const PhaseBody& body : bodies) largest = std::max(largest, body.bounds.extent().maxCoeff());
  grid.cell = std::max(largest, 1e-9 * box.extent().maxCoeff());
  for (int axis = 0; axis < 3; ++axis) {
    grid.dims[axis] =
        std::clamp(static_cast<int>(std::ceil(box.extent()[axis] / grid.cell)), 1, 256);
  }
  grid.cell = std::max(grid.cell, box.extent().maxCoeff() / 256.0);
  grid.cells.resize(static_cast<std::size_t>(grid.dims[0]) * grid.dims[1] * grid.dims[2]);
  for (std::uint32_t b = 0; b < bodies.size(); ++b) {
    const auto lo = grid.index(bodies[b].bounds.lower);
    const auto hi = grid.index(bodies[b].bounds.upper);
    for (int k = lo[2]; k <= hi[2]; ++k) {
      for (int j = lo[1]; j <= hi[1]; ++j) {
        for (int i = lo[0]; i <= hi[0]; ++i) {
          grid.cells[(static_cast<std::size_t>(k) * grid.dims[1] + j) * grid.dims[0] + i].push_back(
              b);
        }
      }
    }
  }
  return grid;
}

}  // namespace

std::size_t relabel_by_geometry(const std::vector<PhaseBody>& bodies, double margin,
                                MesoMesh& mesh) {
  const BodyGrid grid = make_grid(bodies, mesh.bounds);
  std::atomic<std::size_t> relabelled{0};
  parallel_for_index(0, mesh.tetrahedra.size(), [&](std::size_t e) {
    const Tetrahedron& tet = mesh.tetrahedra[e];
    const Vec3 c =
        0.25 * (mesh.nodes[tet[0]] + mesh.nodes[tet[1]] + mesh.nodes[tet[2]] + mesh.nodes[tet[3]]);
    MesoPhase phase = MesoPhase::kMortar;
    std::uint32_t particle = 0;
    bool is_undecided = false;  // near some aggregate's surface
    for (const std::uint32_t b : grid.at(c)) {
      const double depth = plane_excess(bodies[b].planes, c);
      if (depth < -margin) {
        phase = MesoPhase::kAggregate;
        particle = bodies[b].particle != 0 ? bodies[b].particle : b + 1;
        break;
      }
      is_undecided |= depth < margin;
    }
    if (particle == 0 && is_undecided) return;  // too close to decide: keep TetGen's
    if (mesh.phase[e] != phase || mesh.particle[e] != particle) {
      mesh.phase[e] = phase;
      mesh.particle[e] = particle;
      relabelled.fetch_add(1, std::memory_order_relaxed);
    }
  });
  return relabelled.load();
}

}  // namespace aggpack::detail
