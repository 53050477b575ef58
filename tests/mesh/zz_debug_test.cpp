#include <gtest/gtest.h>
#include <cstdio>
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/geom/halfspace.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/native.h"
namespace aggpack {
TEST(ZzDebug, PerParticle) {
  const Packing packing = read_packing("/work/tmp16/small.h5");
  MesoOptions options; options.itz_thickness = 2e-4;
  MesoReport report;
  const MesoMesh mesh = build_mesomodel(packing, options, &report);
  std::vector<double> itz(mesh.particle_count + 1, 0.0);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    if (mesh.phase[e] != MesoPhase::kItz) continue;
    const auto& t = mesh.tetrahedra[e];
    itz[mesh.particle[e]] += tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]);
  }
  const auto& box = mesh.bounds;
  std::vector<HalfSpace> walls = {{-Vec3::UnitX(), -box.lower.x()}, {Vec3::UnitX(), box.upper.x()}, {-Vec3::UnitY(), -box.lower.y()}, {Vec3::UnitY(), box.upper.y()}, {-Vec3::UnitZ(), -box.lower.z()}, {Vec3::UnitZ(), box.upper.z()}};
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron a = packing.placed(i);
    const double expected = mass_properties(mitred_offset(a, 2e-4, walls, 2e-10)).volume - mass_properties(a).volume;
    if (std::abs(itz[i + 1] - expected) > 1e-9 * expected) std::printf("particle %zu itz %.9g expected %.9g lower %.6g upper %.6g\n", i + 1, itz[i + 1], expected, a.bounds().lower.minCoeff(), a.bounds().upper.maxCoeff());
  }
}
}
