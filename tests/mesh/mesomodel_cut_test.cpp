// The mesomodel cut (mesh/mesomodel_cut.h) on a synthetic MesoMesh: a cube of n^3 cells, each cut
// into the 6 Kuhn tetrahedra (conforming across cells), one phase per cell. Exact section areas
// per phase, planes through nodes and faces counted once, errors, and the PNG's pixels.

#include "aggpack/mesh/mesomodel_cut.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <stdlib.h>  // mkdtemp

#include "aggpack/core/error.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

namespace aggpack {
namespace {

constexpr int kCells = 4;      // cells per side
constexpr double kSide = 0.1;  // m
constexpr double kCell = kSide / kCells;

// Phase of cell (i, j, k): a fixed pattern with all three phases in every layer along every axis.
MesoPhase cell_phase(int i, int j, int k) { return static_cast<MesoPhase>((i + 2 * j + k) % 3); }
std::uint32_t cell_index(int i, int j, int k) {
  return static_cast<std::uint32_t>(i + kCells * (j + kCells * k));
}

MesoMesh kuhn_cube() {
  MesoMesh mesh;
  auto node = [](int i, int j, int k) {
    return static_cast<std::uint32_t>(i + (kCells + 1) * (j + (kCells + 1) * k));
  };
  for (int k = 0; k <= kCells; ++k) {
    for (int j = 0; j <= kCells; ++j) {
      for (int i = 0; i <= kCells; ++i) mesh.nodes.emplace_back(i * kCell, j * kCell, k * kCell);
    }
  }
  for (int k = 0; k < kCells; ++k) {
    for (int j = 0; j < kCells; ++j) {
      for (int i = 0; i < kCells; ++i) {
        std::array<int, 3> order{0, 1, 2};
        do {  // the path from corner (0,0,0) to (1,1,1) stepping along order[0], [1], [2]
          std::array<int, 3> at{i, j, k};
          Tetrahedron tet{};
          tet[0] = node(at[0], at[1], at[2]);
          for (int step = 0; step < 3; ++step) {
            ++at[static_cast<std::size_t>(order[static_cast<std::size_t>(step)])];
            tet[static_cast<std::size_t>(step) + 1] = node(at[0], at[1], at[2]);
          }
          const Vec3& a = mesh.nodes[tet[0]];
          const double det =
              (mesh.nodes[tet[1]] - a).cross(mesh.nodes[tet[2]] - a).dot(mesh.nodes[tet[3]] - a);
          if (det < 0.0) std::swap(tet[2], tet[3]);
          mesh.tetrahedra.push_back(tet);
          const MesoPhase phase = cell_phase(i, j, k);
          mesh.phase.push_back(phase);
          mesh.particle.push_back(phase == MesoPhase::kMortar ? 0 : cell_index(i, j, k) + 1);
        } while (std::next_permutation(order.begin(), order.end()));
      }
    }
  }
  mesh.particle_count = kCells * kCells * kCells;
  mesh.container.shape = BoxContainer{.length = kSide, .width = kSide, .depth = kSide};
  mesh.bounds = mesh.container.bounds();
  return mesh;
}

// The exact section of layer `layer` (cell index along `axis`) per phase.
std::array<double, 3> layer_areas(int axis, int layer) {
  std::array<double, 3> areas{};
  for (int a = 0; a < kCells; ++a) {
    for (int b = 0; b < kCells; ++b) {
      std::array<int, 3> cell{};
      const auto uv = cut_plane_axes(axis);
      cell[static_cast<std::size_t>(axis)] = layer;
      cell[static_cast<std::size_t>(uv[0])] = a;
      cell[static_cast<std::size_t>(uv[1])] = b;
      areas[static_cast<std::size_t>(cell_phase(cell[0], cell[1], cell[2]))] += kCell * kCell;
    }
  }
  return areas;
}

void expect_areas(const std::vector<CutPolygon>& polygons, const std::array<double, 3>& expected) {
  const std::array<double, 3> areas = cut_phase_areas(polygons);
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_NEAR(areas[p], expected[p], 1e-12 * kSide * kSide) << "phase " << p;
  }
  EXPECT_NEAR(areas[0] + areas[1] + areas[2], kSide * kSide, 1e-12 * kSide * kSide);
  for (const CutPolygon& polygon : polygons) {
    EXPECT_GE(polygon.points.size(), 3U);
    EXPECT_LE(polygon.points.size(), 4U);
    EXPECT_GT(polygon_area(polygon.points), 0.0);  // counter-clockwise, not degenerate
  }
}

TEST(MesomodelCut, SectionAreaPerPhaseIsExactBetweenNodes) {
  const MesoMesh mesh = kuhn_cube();
  for (int axis = 0; axis < 3; ++axis) {
    for (int layer = 0; layer < kCells; ++layer) {
      for (const double fraction : {0.5, 0.123, 0.999}) {
        const double value = (layer + fraction) * kCell;
        SCOPED_TRACE(std::string(axis_name(axis)) + "=" + std::to_string(value));
        const auto polygons = cut_mesomodel(mesh, axis, value);
        expect_areas(polygons, layer_areas(axis, layer));
        for (const CutPolygon& polygon : polygons) {
          const std::uint32_t cell = polygon.tetrahedron / 6;
          const std::array<int, 3> ijk{static_cast<int>(cell % kCells),
                                       static_cast<int>(cell / kCells % kCells),
                                       static_cast<int>(cell / kCells / kCells)};
          EXPECT_EQ(ijk[static_cast<std::size_t>(axis)], layer);
          EXPECT_EQ(polygon.phase, mesh.phase[polygon.tetrahedron]);
          EXPECT_EQ(polygon.particle, mesh.particle[polygon.tetrahedron]);
        }
      }
    }
  }
}

// A plane through a layer of nodes holds whole tetrahedron faces (z = k h is a face of the Kuhn
// tetrahedra) and edges: each face is drawn once, by the layer below (the limit from below), and
// at the lowest plane by the layer above.
TEST(MesomodelCut, PlaneThroughNodesAndFacesCountsEachFaceOnce) {
  const MesoMesh mesh = kuhn_cube();
  for (int axis = 0; axis < 3; ++axis) {
    for (int plane = 0; plane <= kCells; ++plane) {
      SCOPED_TRACE(std::string(axis_name(axis)) + " plane " + std::to_string(plane));
      const int layer = plane == 0 ? 0 : plane - 1;
      const auto polygons = cut_mesomodel(mesh, axis, plane * kCell);
      expect_areas(polygons, layer_areas(axis, layer));
      // A Kuhn cube cell has 2 of its 6 tetrahedra with a face on each cell face.
      EXPECT_EQ(polygons.size(), static_cast<std::size_t>(2 * kCells * kCells));
    }
  }
}

// Moving the interior nodes keeps the mesh a tiling of the cube: the section of any plane is the
// whole square, to rounding.
TEST(MesomodelCut, TotalAreaIsTheSquareForRandomPlanesOfAJitteredMesh) {
  MesoMesh mesh = kuhn_cube();
  std::mt19937_64 random(16);
  std::uniform_real_distribution<double> jitter(-0.1 * kCell, 0.1 * kCell);
  for (Vec3& node : mesh.nodes) {
    for (int c = 0; c < 3; ++c) {
      if (node[c] > 0.0 && node[c] < kSide) node[c] += jitter(random);
    }
  }
  std::uniform_real_distribution<double> where(0.0, kSide);
  for (int trial = 0; trial < 60; ++trial) {
    const int axis = trial % 3;
    const double value = where(random);
    const auto areas = cut_phase_areas(cut_mesomodel(mesh, axis, value));
    EXPECT_NEAR(areas[0] + areas[1] + areas[2], kSide * kSide, 1e-12 * kSide * kSide)
        << axis_name(axis) << "=" << value;
  }
}

TEST(MesomodelCut, BadPlanesAreRefusedNamingTheKeyValueAndRange) {
  const MesoMesh mesh = kuhn_cube();
  try {
    (void)cut_mesomodel(mesh, 2, 0.2, "--mesomodel-cut");
    FAIL() << "a plane above the mesh was accepted";
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("--mesomodel-cut"), std::string::npos) << message;
    EXPECT_NE(message.find("z=0.2"), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 0.1]"), std::string::npos) << message;
  }
  EXPECT_THROW((void)cut_mesomodel(mesh, 0, -1e-9), InvalidInput);
  EXPECT_THROW((void)cut_mesomodel(mesh, 1, std::nan("")), InvalidInput);
  EXPECT_THROW((void)cut_mesomodel(mesh, 3, 0.05), InvalidInput);
  EXPECT_THROW((void)cut_mesomodel(MesoMesh{}, 2, 0.0), InvalidInput);
  EXPECT_THROW((void)draw_mesomodel_cut({}, 2, 0.05), InvalidInput);
}

TEST(MesomodelCut, PlaneTextParsesOrNamesTheFlag) {
  const CutPlane plane = parse_cut_plane("y=0.05", "--mesomodel-cut");
  EXPECT_EQ(plane.axis, 1);
  EXPECT_EQ(plane.value, 0.05);
  EXPECT_EQ(parse_cut_plane("x=-1e-3", "k").axis, 0);
  EXPECT_EQ(parse_cut_plane("z=2", "k").value, 2.0);
  for (const std::string bad :
       {"z=abc", "w=0.1", "z=", "z", "z=nan", "z=inf", "z=0.1m", "=0.1", "z:0.1", "Z=0.1"}) {
    try {
      (void)parse_cut_plane(bad, "--mesomodel-cut");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InvalidInput& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find("--mesomodel-cut"), std::string::npos) << message;
      EXPECT_NE(message.find("x, y or z"), std::string::npos) << message;
    }
  }
}

TEST(MesomodelCut, PictureHasThePhaseColoursAtKnownPixels) {
  const MesoMesh mesh = kuhn_cube();
  std::string pattern = (std::filesystem::temp_directory_path() / "aggpack_cut_XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::filesystem::path folder = pattern;
  const std::string path = (folder / "cut.png").string();
  const int layer = 1;
  const double value = (layer + 0.5) * kCell;
  write_mesomodel_cut_png(path, mesh, 2, value,
                          {.width = 400, .is_tinted = false, .has_edges = true, .subtitle = ""});
  int width = 0;
  int height = 0;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(data, nullptr);
  const std::vector<std::uint8_t> pixels(data, data + static_cast<std::size_t>(width * height * 3));
  stbi_image_free(data);
  // The plot is 320 x 320 pixels (a square section), 80 pixels a cell; title and legend add 180.
  const int plot = 400 - 2 * kCutImageMargin;
  ASSERT_EQ(width, 400);
  ASSERT_EQ(height, kCutImageTitle + plot + 110);
  const double cell_pixels = plot / static_cast<double>(kCells);
  auto at = [&](double x, double y) {
    const auto px = static_cast<std::size_t>(x);
    const auto py = static_cast<std::size_t>(y);
    const std::size_t i = 3 * (py * static_cast<std::size_t>(width) + px);
    return Rgb{pixels[i], pixels[i + 1], pixels[i + 2]};
  };
  for (int i = 0; i < kCells; ++i) {
    for (int j = 0; j < kCells; ++j) {
      // Inside cell (i, j) the section's edges lie on x = y, x = 0.5 and y = 0.5 (cell units):
      // (0.25, 0.75) is 20 pixels from each.
      const double x = kCutImageMargin + (i + 0.25) * cell_pixels;
      const double y = kCutImageTitle + (kCells - j - 0.75) * cell_pixels;  // v (y) up
      const MesoPhase phase = cell_phase(i, j, layer);
      EXPECT_EQ(at(x, y), mesomodel_cut_colour(phase, 0, false)) << "cell " << i << ", " << j;
      // The element edge x = 0.5 is drawn, one pixel wide, a darker shade of the fill.
      const double edge_x = kCutImageMargin + (i + 0.5) * cell_pixels;
      const Rgb fill = mesomodel_cut_colour(phase, 0, false);
      bool has_edge = false;
      for (int dx = -1; dx <= 1; ++dx) {
        const Rgb seen = at(edge_x + dx, y);
        has_edge = has_edge || (seen[0] < fill[0] && seen[1] < fill[1] && seen[2] < fill[2]);
      }
      EXPECT_TRUE(has_edge) << "cell " << i << ", " << j;
    }
  }
  // Three clearly different phase colours; tinted aggregates differ from one another.
  const Rgb mortar = mesomodel_cut_colour(MesoPhase::kMortar, 0, false);
  const Rgb itz = mesomodel_cut_colour(MesoPhase::kItz, 0, false);
  const Rgb stone = mesomodel_cut_colour(MesoPhase::kAggregate, 0, false);
  EXPECT_NE(mortar, itz);
  EXPECT_NE(itz, stone);
  EXPECT_NE(stone, mortar);
  std::vector<Rgb> tints;
  for (std::uint32_t id = 1; id <= 8; ++id) {  // consecutive ids: most differ
    tints.push_back(mesomodel_cut_colour(MesoPhase::kAggregate, id, true));
  }
  std::sort(tints.begin(), tints.end());
  EXPECT_GE(std::unique(tints.begin(), tints.end()) - tints.begin(), 6);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace aggpack
