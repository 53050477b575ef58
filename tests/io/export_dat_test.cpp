// rock.dat: exact layout on a known body, then a parse of a random packing checking numbering,
// orientation and that each particle's tetrahedra sum to its polyhedron volume.

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/mesh/tetrahedra.h"
#include "export_fixture.h"
#include "support/paths.h"
#include "support/poly_file.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

struct RockDat {
  std::vector<Vec3> nodes;                               // index = id - 1
  std::vector<std::array<std::uint64_t, 4>> tetrahedra;  // 1-based node ids
};

// A strict reader of the documented layout: node lines "id, x, y, z" (ids 1, 2, ... in order),
// then tetrahedron lines "id, n1, n2, n3, n4" (ids 1, 2, ...); nothing else.
RockDat parse_rock_dat(const std::string& path) {
  RockDat dat;
  std::istringstream in(test::read_text(path));
  std::string line;
  while (std::getline(in, line)) {
    const auto fields = test::split(line, ',');
    if (fields.size() == 4) {
      EXPECT_TRUE(dat.tetrahedra.empty()) << "node line after a tetrahedron line";
      EXPECT_EQ(std::stoull(fields[0]), dat.nodes.size() + 1);
      dat.nodes.emplace_back(std::stod(fields[1]), std::stod(fields[2]), std::stod(fields[3]));
    } else if (fields.size() == 5) {
      EXPECT_EQ(std::stoull(fields[0]), dat.tetrahedra.size() + 1);
      std::array<std::uint64_t, 4> tet{};
      for (int k = 0; k < 4; ++k) {
        tet[k] = std::stoull(fields[k + 1]);
        EXPECT_GE(tet[k], 1U);
        EXPECT_LE(tet[k], dat.nodes.size());
      }
      dat.tetrahedra.push_back(tet);
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
  }
  return dat;
}

TEST(RockDatExport, ExactLayoutForAUnitOctahedron) {
  Packing packing;
  packing.shapes.push_back(make_octahedron({1, 1, 1, 1, 1, 1}));
  Particle particle;
  particle.pose.position = Vec3(10, 0, 0);
  packing.particles.push_back(particle);
  ScratchFolder folder;
  write(packing, folder.file("rock.dat"));
  const std::string text = test::read_text(folder.file("rock.dat"));
  // Vertex order of make_octahedron: +x, -x, +y, -y, +z, -z; then the centroid.
  const std::string nodes =
      "1, 11, 0, 0\n2, 9, 0, 0\n3, 10, 1, 0\n4, 10, -1, 0\n5, 10, 0, 1\n6, 10, 0, -1\n"
      "7, 10, 0, 0\n";
  ASSERT_EQ(text.substr(0, nodes.size()), nodes);
  const RockDat dat = parse_rock_dat(folder.file("rock.dat"));
  ASSERT_EQ(dat.tetrahedra.size(), 8U);
  double volume = 0;
  for (const auto& t : dat.tetrahedra) {
    EXPECT_EQ(t[3], 7U);  // every tetrahedron of the fan ends at the centroid
    const double v = tetra_volume(dat.nodes[t[0] - 1], dat.nodes[t[1] - 1], dat.nodes[t[2] - 1],
                                  dat.nodes[t[3] - 1]);
    EXPECT_NEAR(v, 1.0 / 6.0, 1e-15);
    volume += v;
  }
  EXPECT_NEAR(volume, 4.0 / 3.0, 1e-14);
}

// Particles follow one another: particle i owns the next `counts[i]` tetrahedra, which use only
// nodes after the previous particle's. Each particle's tetrahedra must be positive and sum to its
// polyhedron volume.
void expect_particle_volumes(const Packing& packing, const RockDat& dat,
                             const std::vector<std::size_t>& counts) {
  std::size_t tet = 0;
  std::uint64_t previous_nodes_end = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const double expected = test::particle_volume(packing, i);
    double volume = 0;
    std::uint64_t nodes_end = previous_nodes_end;
    for (std::size_t e = 0; e < counts[i]; ++e, ++tet) {
      ASSERT_LT(tet, dat.tetrahedra.size());
      const auto& t = dat.tetrahedra[tet];
      EXPECT_GT(std::min({t[0], t[1], t[2], t[3]}), previous_nodes_end);
      const double v = tetra_volume(dat.nodes[t[0] - 1], dat.nodes[t[1] - 1], dat.nodes[t[2] - 1],
                                    dat.nodes[t[3] - 1]);
      EXPECT_GT(v, 0.0) << "tetrahedron " << tet + 1 << " not positively oriented";
      volume += v;
      nodes_end = std::max({nodes_end, t[0], t[1], t[2], t[3]});
    }
    previous_nodes_end = nodes_end;
    EXPECT_NEAR(volume, expected, 1e-12 * expected) << "particle " << i + 1;
  }
  EXPECT_EQ(tet, dat.tetrahedra.size());
  EXPECT_EQ(previous_nodes_end, dat.nodes.size());
}

TEST(RockDatExport, FanVolumesMatchEveryParticle) {
  const Packing packing = test::grid_packing(3, 3, 2, 21, /*share_shapes=*/true);
  ScratchFolder folder;
  const ExportSummary summary = write(packing, folder.file("rock.dat"));
  const RockDat dat = parse_rock_dat(folder.file("rock.dat"));
  EXPECT_EQ(summary.nodes, dat.nodes.size());
  EXPECT_EQ(summary.elements, dat.tetrahedra.size());
  std::size_t expected_nodes = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    expected_nodes += packing.placed(i).vertex_count() + 1;
  }
  EXPECT_EQ(dat.nodes.size(), expected_nodes);
  std::vector<std::size_t> counts;
  for (const auto& particle : packing.particles) {
    counts.push_back(packing.shapes[particle.shape].triangle_count());
  }
  expect_particle_volumes(packing, dat, counts);
}

#ifdef AGGPACK_HAS_TETGEN
TEST(RockDatExport, TetGenVolumesMatchEveryParticle) {
  const Packing packing = test::grid_packing(2, 2, 1, 22);
  ScratchFolder folder;
  const TetOptions tetgen{.method = TetMethod::kTetGen, .max_volume = 1e-5};
  const ExportSummary summary = write(packing, folder.file("rock.dat"), {.tetrahedra = tetgen});
  const RockDat dat = parse_rock_dat(folder.file("rock.dat"));
  EXPECT_EQ(summary.elements, dat.tetrahedra.size());
  std::vector<std::size_t> counts;
  std::size_t fan_total = 0;
  for (const auto& particle : packing.particles) {
    counts.push_back(tetgen_mesh(packing.shapes[particle.shape], tetgen).tetrahedra.size());
    fan_total += packing.shapes[particle.shape].triangle_count();
  }
  EXPECT_GT(dat.tetrahedra.size(), fan_total);  // refined beyond the fan
  expect_particle_volumes(packing, dat, counts);
}

// Shapes on which TetGen aborts (tests/mesh/fixtures/tetgen-abort) are written as centroid fans
// and reported with every particle that uses them; the rest of the file is TetGen's.
TEST(RockDatExport, ShapesTetGenAbortsOnAreFansAndReported) {
  Packing packing = test::grid_packing(3, 2, 1, 23);
  const std::string fixtures = test::source_dir() + "/tests/mesh/fixtures/";
  packing.shapes[1] = test::read_poly(fixtures + "tetgen-abort/s00324.poly");
  packing.shapes[3] = test::read_poly(fixtures + "tetgen-abort/s00336.poly");
  packing.particles[4].shape = 1;  // shape 1 twice: particles P2 and P5
  ScratchFolder folder;
  const TetOptions tetgen{.method = TetMethod::kTetGen};
  const ExportSummary summary = write(packing, folder.file("rock.dat"), {.tetrahedra = tetgen});
  EXPECT_EQ(summary.tetgen_shapes, 5U);  // shape 4 is no particle's any more
  ASSERT_EQ(summary.tetgen_fallbacks.size(), 2U);
  EXPECT_EQ(summary.tetgen_fallbacks[0].shape, 1U);
  EXPECT_EQ(summary.tetgen_fallbacks[0].particles, (std::vector<std::uint64_t>{2, 5}));
  EXPECT_EQ(summary.tetgen_fallbacks[1].shape, 3U);
  EXPECT_EQ(summary.tetgen_fallbacks[1].particles, (std::vector<std::uint64_t>{4}));
  for (const auto& fallback : summary.tetgen_fallbacks) {
    EXPECT_EQ(fallback.failure, "TetGen died of signal 6 (Aborted)");
  }
  const RockDat dat = parse_rock_dat(folder.file("rock.dat"));
  EXPECT_EQ(summary.elements, dat.tetrahedra.size());
  std::vector<std::size_t> counts;
  for (const auto& particle : packing.particles) {
    const ConvexPolyhedron& body = packing.shapes[particle.shape];
    const bool is_fan = particle.shape == 1 || particle.shape == 3;
    counts.push_back(is_fan ? body.triangle_count() : tetgen_mesh(body, tetgen).tetrahedra.size());
  }
  expect_particle_volumes(packing, dat, counts);
}
#endif

}  // namespace
}  // namespace aggpack
