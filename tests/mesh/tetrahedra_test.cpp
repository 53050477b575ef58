#include "aggpack/mesh/tetrahedra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/shape/generator.h"

namespace aggpack {
namespace {

// Every surface triangle of the body must appear exactly once as a boundary face of the mesh, and
// no other face may be flagged as boundary.
void expect_boundary_matches_surface(const TetMesh& mesh, const ConvexPolyhedron& body) {
  std::multiset<std::array<std::uint32_t, 3>> flagged;
  ASSERT_EQ(mesh.boundary_faces.size(), mesh.tetrahedra.size());
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    for (int k = 0; k < 4; ++k) {
      if ((mesh.boundary_faces[e] >> k) & 1U) {
        const auto& face = kTetraFaces[k];
        const std::uint32_t a = mesh.tetrahedra[e][face[0]];
        const std::uint32_t b = mesh.tetrahedra[e][face[1]];
        const std::uint32_t c = mesh.tetrahedra[e][face[2]];
        // A positive tetrahedron's faces have inward right-hand normals: on the surface they
        // point towards the body's centre.
        const Vec3 normal = (mesh.nodes[b] - mesh.nodes[a]).cross(mesh.nodes[c] - mesh.nodes[a]);
        const Vec3 to_centre = -mesh.nodes[a];  // bodies here have their centroid at the origin
        EXPECT_GT(normal.dot(to_centre), 0.0) << "boundary face not on the surface";
        std::array<std::uint32_t, 3> key{a, b, c};
        std::sort(key.begin(), key.end());
        flagged.insert(key);
      }
    }
  }
  std::multiset<std::array<std::uint32_t, 3>> surface;
  for (const auto& t : body.triangles()) {
    std::array<std::uint32_t, 3> key = t;
    std::sort(key.begin(), key.end());
    surface.insert(key);
  }
  EXPECT_EQ(flagged, surface);
}

TEST(TetraVolume, UnitTetrahedronIsPositive) {
  EXPECT_DOUBLE_EQ(tetra_volume(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)),
                   1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tetra_volume(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)),
                   -1.0 / 6.0);
}

TEST(CentroidFan, UnitCubeExact) {
  const ConvexPolyhedron cube = make_box(Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5));
  const TetMesh mesh = centroid_fan(cube);
  ASSERT_EQ(mesh.nodes.size(), 9U);
  ASSERT_EQ(mesh.tetrahedra.size(), 12U);
  EXPECT_NEAR(mesh.nodes[8].norm(), 0.0, 1e-15);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(mesh.nodes[i], cube.vertices()[i]);
  // Each tetrahedron is a cube face half (area 1/2) times the distance 1/2 over 3.
  for (const auto& t : mesh.tetrahedra) {
    EXPECT_NEAR(
        tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]),
        1.0 / 12.0, 1e-15);
    EXPECT_EQ(t[3], 8U);
  }
  EXPECT_NEAR(mesh_volume(mesh), 1.0, 1e-14);
  expect_boundary_matches_surface(mesh, cube);
}

TEST(CentroidFan, RegularOctahedronExact) {
  const ConvexPolyhedron octahedron = make_octahedron({1, 1, 1, 1, 1, 1});
  const TetMesh mesh = centroid_fan(octahedron);
  EXPECT_EQ(mesh.tetrahedra.size(), 8U);
  EXPECT_NEAR(mesh_volume(mesh), 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(min_tetra_volume(mesh), 1.0 / 6.0, 1e-14);
}

TEST(CentroidFan, RejectsEmptyBody) {
  EXPECT_THROW(centroid_fan(ConvexPolyhedron{}), InvalidInput);
}

TEST(CentroidFan, PositiveAndExactVolumeOverManySeeds) {
  int checked = 0;
  for (double alpha : {0.0, 0.3, 0.6, 1.0}) {
    for (double edge : {0.2, 0.1, 0.05}) {
      const GeneratorOptions options{
          .alpha = alpha, .radius_min = 0.05, .radius_max = 0.1, .edge_length = edge, .seed = 7};
      for (std::uint64_t index = 0; index < 40; ++index) {
        const ConvexPolyhedron body = generate_particle(options, index).body;
        const TetMesh mesh = centroid_fan(body);
        const double volume = mass_properties(body).volume;
        ASSERT_EQ(mesh.tetrahedra.size(), body.triangle_count());
        ASSERT_EQ(mesh.nodes.size(), body.vertex_count() + 1);
        EXPECT_GT(min_tetra_volume(mesh), 0.0) << "alpha " << alpha << " index " << index;
        EXPECT_NEAR(mesh_volume(mesh), volume, 1e-12 * volume);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 480);
  // One full boundary check (the loop above already covers orientation and volume).
  const ConvexPolyhedron body = generate_particle({.alpha = 0.5, .seed = 3}, 0).body;
  expect_boundary_matches_surface(centroid_fan(body), body);
}

#ifdef AGGPACK_HAS_TETGEN

// Sum of the areas of the flagged boundary faces, checking that each lies on the body's surface.
double boundary_area_on_surface(const TetMesh& mesh, const ConvexPolyhedron& body,
                                double tolerance) {
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    for (int k = 0; k < 4; ++k) {
      if (((mesh.boundary_faces[e] >> k) & 1U) == 0) continue;
      const auto& face = kTetraFaces[k];
      const Vec3& a = mesh.nodes[mesh.tetrahedra[e][face[0]]];
      const Vec3& b = mesh.nodes[mesh.tetrahedra[e][face[1]]];
      const Vec3& c = mesh.nodes[mesh.tetrahedra[e][face[2]]];
      // Never outside; on the surface within `tolerance` (TetGen without -Y may cut a hair in).
      const PointLocation location = locate_point(body, (a + b + c) / 3.0, tolerance);
      EXPECT_NE(location, PointLocation::kOutside);
      if (tolerance < 1e-14) {
        EXPECT_EQ(location, PointLocation::kOnBoundary);
      }
      area += 0.5 * (b - a).cross(c - a).norm();
    }
  }
  return area;
}

TEST(TetGen, MeetsVolumeBoundAndKeepsShapeOverSeeds) {
  const GeneratorOptions options{
      .alpha = 0.5, .radius_min = 0.1, .radius_max = 0.1, .edge_length = 0.06, .seed = 11};
  for (std::uint64_t index = 0; index < 20; ++index) {
    const ConvexPolyhedron body = generate_particle(options, index).body;
    const MassProperties properties = mass_properties(body);
    const double max_volume = properties.volume / 60.0;
    const TetMesh mesh = tetgen_mesh(body, {.method = TetMethod::kTetGen,
                                            .max_volume = max_volume,
                                            .radius_edge_ratio = 1.5,
                                            .is_surface_kept = false});
    for (std::size_t i = 0; i < body.vertex_count(); ++i) {
      ASSERT_EQ(mesh.nodes[i], body.vertices()[i]);
    }
    EXPECT_GT(min_tetra_volume(mesh), 0.0);
    // Without -Y TetGen merges nearly coplanar faces: close to, not exactly, the body.
    EXPECT_NEAR(mesh_volume(mesh), properties.volume, 1e-5 * properties.volume);
    EXPECT_GE(mesh.tetrahedra.size(), 60U);
    for (const auto& t : mesh.tetrahedra) {
      EXPECT_LE(
          tetra_volume(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]),
          max_volume * (1 + 1e-9));
    }
    EXPECT_NEAR(boundary_area_on_surface(mesh, body, 1e-6 * std::pow(0.1, 3)),
                properties.surface_area, 1e-5 * properties.surface_area);
  }
}

TEST(TetGen, KeptSurfaceMatchesTheBodyTriangles) {
  const GeneratorOptions options{.alpha = 0.5, .edge_length = 0.06, .seed = 13};
  for (std::uint64_t index = 0; index < 10; ++index) {
    const ConvexPolyhedron body = generate_particle(options, index).body;
    const double volume = mass_properties(body).volume;
    const TetMesh mesh = tetgen_mesh(
        body, {.method = TetMethod::kTetGen, .max_volume = volume / 30.0, .is_surface_kept = true});
    EXPECT_GT(min_tetra_volume(mesh), 0.0);
    EXPECT_NEAR(mesh_volume(mesh), volume, 1e-12 * volume);
    expect_boundary_matches_surface(mesh, body);
    EXPECT_NEAR(boundary_area_on_surface(mesh, body, 1e-15), mass_properties(body).surface_area,
                1e-12);
  }
}

TEST(TetGen, SmallerVolumeBoundGivesMoreTetrahedra) {
  const ConvexPolyhedron body = generate_particle({.alpha = 0.7, .seed = 5}, 2).body;
  const double volume = mass_properties(body).volume;
  const TetOptions coarse_options{
      .method = TetMethod::kTetGen, .max_volume = volume / 5, .is_surface_kept = false};
  TetOptions fine_options = coarse_options;
  fine_options.max_volume = volume / 1000;
  const TetMesh coarse = tetgen_mesh(body, coarse_options);
  const TetMesh fine = tetgen_mesh(body, fine_options);
  EXPECT_GT(fine.tetrahedra.size(), 3 * coarse.tetrahedra.size());
  EXPECT_GE(fine.tetrahedra.size(), 200U);
}

TEST(TetGen, DeterministicForTheSameInput) {
  const ConvexPolyhedron body = generate_particle({.alpha = 0.3, .seed = 9}, 4).body;
  const TetOptions options{.method = TetMethod::kTetGen, .max_volume = 1e-5};
  const TetMesh first = tetgen_mesh(body, options);
  const TetMesh second = tetgen_mesh(body, options);
  EXPECT_EQ(first.nodes, second.nodes);
  EXPECT_EQ(first.tetrahedra, second.tetrahedra);
}

#endif

TEST(TetOptions, RejectsBadValues) {
  EXPECT_THROW(validate(TetOptions{.max_volume = -1.0}), InvalidInput);
  EXPECT_THROW(validate(TetOptions{.radius_edge_ratio = 1.0}), InvalidInput);
  EXPECT_THROW(validate(TetOptions{.radius_edge_ratio = 20.0}), InvalidInput);
  EXPECT_NO_THROW(validate(TetOptions{}));
  try {
    validate(TetOptions{.radius_edge_ratio = 0.5});
    FAIL();
  } catch (const InvalidInput& error) {
    EXPECT_EQ(error.field(), "radius-edge ratio");
  }
}

TEST(Quadratic, MidsideNodesSharedAndVolumeKept) {
  const ConvexPolyhedron body = generate_particle({.alpha = 0.5, .seed = 1}, 0).body;
  const TetMesh linear = centroid_fan(body);
  const QuadraticTetMesh quadratic = make_quadratic(linear);
  const TetMeshCounts counts = count(linear);
  // Fan edges: the surface edges plus one spoke per vertex.
  EXPECT_EQ(counts.edges, body.edges().size() + body.vertex_count());
  EXPECT_EQ(quadratic.nodes.size(), linear.nodes.size() + counts.edges);
  ASSERT_EQ(quadratic.tetrahedra.size(), linear.tetrahedra.size());
  for (std::size_t e = 0; e < linear.tetrahedra.size(); ++e) {
    const auto& element = quadratic.tetrahedra[e];
    for (int k = 0; k < 4; ++k) EXPECT_EQ(element[k], linear.tetrahedra[e][k]);
    for (int m = 0; m < 6; ++m) {
      const Vec3 expected = 0.5 * (quadratic.nodes[element[kTetraEdges[m][0]]] +
                                   quadratic.nodes[element[kTetraEdges[m][1]]]);
      EXPECT_NEAR((quadratic.nodes[element[4 + m]] - expected).norm(), 0.0, 1e-15);
    }
  }
}

// Mid-side nodes are numbered in the order their edges are first met (tetrahedron by
// tetrahedron, kTetraEdges order): the exporters' node and element passes each derive the
// numbering and must agree, and files written before must not change. Checked against a plain
// map over fans of many shapes and, with TetGen, interior edges too.
TEST(Quadratic, EdgesNumberedInOrderOfFirstMeeting) {
  std::vector<TetMesh> meshes;
  for (std::uint64_t index = 0; index < 40; ++index) {
    meshes.push_back(centroid_fan(generate_particle({.alpha = 0.3, .seed = 21}, index).body));
  }
#ifdef AGGPACK_HAS_TETGEN
  const ConvexPolyhedron body = generate_particle({.alpha = 0.5, .seed = 13}, 1).body;
  meshes.push_back(tetgen_mesh(
      body, {.method = TetMethod::kTetGen, .max_volume = mass_properties(body).volume / 50.0}));
#endif
  for (const TetMesh& mesh : meshes) {
    const auto corners = static_cast<std::uint32_t>(mesh.nodes.size());
    const QuadraticTopology topology = quadratic_topology(mesh.tetrahedra, corners);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> numbers;
    std::vector<std::array<std::uint32_t, 2>> edges;
    ASSERT_EQ(topology.tetrahedra.size(), mesh.tetrahedra.size());
    for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
      const Tetrahedron& tet = mesh.tetrahedra[e];
      for (int m = 0; m < 6; ++m) {
        const std::uint32_t a = tet[kTetraEdges[m][0]];
        const std::uint32_t b = tet[kTetraEdges[m][1]];
        const auto [it, is_new] = numbers.try_emplace(std::minmax(a, b), corners + edges.size());
        if (is_new) edges.push_back({a, b});
        EXPECT_EQ(topology.tetrahedra[e][4 + m], it->second);
      }
      for (int k = 0; k < 4; ++k) EXPECT_EQ(topology.tetrahedra[e][k], tet[k]);
    }
    EXPECT_EQ(topology.midside_edges, edges);
    EXPECT_EQ(edges.size(), count(mesh).edges);
  }
}

}  // namespace
}  // namespace aggpack
