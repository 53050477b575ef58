// ConvexPolyhedron: constructors of the standard bodies, adjacency, structural checks and the
// value-type transforms.

#include "aggpack/geom/convex_polyhedron.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"

namespace aggpack {
namespace {

// Every triangle's normal must point away from the body's centroid (outward) and the three
// vertices must be counter-clockwise seen from there.
void expect_outward(const ConvexPolyhedron& body) {
  const Vec3 centroid = mass_properties(body).centroid;
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 on_face = body.vertices()[body.triangles()[f][0]];
    EXPECT_GT(body.face_normal_scaled(f).dot(on_face - centroid), 0.0) << "face " << f;
  }
}

TEST(MakeBox, UnitCubeStructure) {
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  EXPECT_EQ(cube.vertex_count(), 8u);
  EXPECT_EQ(cube.triangle_count(), 12u);
  EXPECT_EQ(cube.edges().size(), 18u);
  EXPECT_TRUE(check_closed_manifold(cube).is_ok) << check_closed_manifold(cube).message;
  EXPECT_TRUE(check_convex(cube, 1e-12).is_ok) << check_convex(cube, 1e-12).message;
  expect_outward(cube);
  // Each unit normal is an axis direction; each axis direction appears on two triangles.
  std::multiset<std::string> normals;
  for (std::size_t f = 0; f < cube.triangle_count(); ++f) {
    const Vec3 n = cube.face_normal(f);
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-15);
    normals.insert(std::to_string(static_cast<int>(std::lround(n.x()))) + "," +
                   std::to_string(static_cast<int>(std::lround(n.y()))) + "," +
                   std::to_string(static_cast<int>(std::lround(n.z()))));
  }
  for (const char* axis : {"1,0,0", "-1,0,0", "0,1,0", "0,-1,0", "0,0,1", "0,0,-1"}) {
    EXPECT_EQ(normals.count(axis), 2u) << axis;
  }
  const Aabb box = cube.bounds();
  EXPECT_EQ(box.lower, Vec3::Zero());
  EXPECT_EQ(box.upper, Vec3::Ones());
  EXPECT_DOUBLE_EQ(cube.longest_edge(), std::sqrt(2.0));
}

TEST(MakeBox, RejectsEmptyOrInvertedBox) {
  EXPECT_THROW(make_box(Vec3::Zero(), Vec3(1, 0, 1)), InvalidInput);
  EXPECT_THROW(make_box(Vec3::Ones(), Vec3::Zero()), InvalidInput);
  EXPECT_THROW(make_box(Vec3::Zero(), Vec3(1, 1, std::nan(""))), InvalidInput);
}

TEST(MakeOctahedron, RegularStructureAndAdjacency) {
  const double r = 0.7;
  const auto body = make_octahedron({r, r, r, r, r, r});
  EXPECT_EQ(body.vertex_count(), 6u);
  EXPECT_EQ(body.triangle_count(), 8u);
  EXPECT_TRUE(check_closed_manifold(body).is_ok);
  EXPECT_TRUE(check_convex(body, 1e-12).is_ok);
  expect_outward(body);
  // Unit normals are (+-1, +-1, +-1) / sqrt 3.
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    const Vec3 n = body.face_normal(f);
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(std::abs(n[axis]), 1 / std::sqrt(3.0), 1e-15);
  }
  const auto edges = body.edges();
  ASSERT_EQ(edges.size(), 12u);
  for (const auto& edge : edges) {
    // No edge joins opposite vertices (0-1, 2-3, 4-5); all have length r sqrt 2.
    EXPECT_NE(edge.vertices[0] / 2, edge.vertices[1] / 2);
    EXPECT_NEAR((body.vertices()[edge.vertices[0]] - body.vertices()[edge.vertices[1]]).norm(),
                r * std::sqrt(2.0), 1e-15);
    // faces[0] runs vertices[0] -> vertices[1], faces[1] the other way.
    auto runs = [&](std::uint32_t face, std::uint32_t from, std::uint32_t to) {
      const auto& t = body.triangles()[face];
      for (int k = 0; k < 3; ++k) {
        if (t[k] == from && t[(k + 1) % 3] == to) return true;
      }
      return false;
    };
    EXPECT_TRUE(runs(edge.faces[0], edge.vertices[0], edge.vertices[1]));
    EXPECT_TRUE(runs(edge.faces[1], edge.vertices[1], edge.vertices[0]));
  }
  const auto neighbours = body.vertex_neighbours();
  ASSERT_EQ(neighbours.size(), 6u);
  for (std::uint32_t v = 0; v < 6; ++v) {
    EXPECT_EQ(neighbours[v].size(), 4u);
    EXPECT_TRUE(std::is_sorted(neighbours[v].begin(), neighbours[v].end()));
    for (auto w : neighbours[v]) EXPECT_NE(w / 2, v / 2);
  }
}

TEST(MakeOctahedron, IrregularStaysConvexAndRejectsNonPositive) {
  const auto body = make_octahedron({0.2, 1.0, 0.5, 0.9, 0.3, 0.75});
  EXPECT_TRUE(check_closed_manifold(body).is_ok);
  EXPECT_TRUE(check_convex(body, 1e-12).is_ok);
  expect_outward(body);
  EXPECT_EQ(body.vertices()[1], Vec3(-1.0, 0, 0));
  EXPECT_EQ(body.vertices()[5], Vec3(0, 0, -0.75));
  EXPECT_THROW(make_octahedron({1, 1, 0, 1, 1, 1}), InvalidInput);
  EXPECT_THROW(make_octahedron({1, 1, 1, 1, -1, 1}), InvalidInput);
  EXPECT_THROW(make_octahedron({1, 1, 1, 1, 1, INFINITY}), InvalidInput);
}

TEST(MakeRegularTetrahedron, CircumradiusAndEdges) {
  const double radius = 1.5;
  const auto body = make_regular_tetrahedron(radius);
  EXPECT_TRUE(check_closed_manifold(body).is_ok);
  EXPECT_TRUE(check_convex(body, 1e-12).is_ok);
  expect_outward(body);
  for (const auto& v : body.vertices()) EXPECT_NEAR(v.norm(), radius, 1e-15);
  const auto edges = body.edges();
  ASSERT_EQ(edges.size(), 6u);
  for (const auto& edge : edges) {
    EXPECT_NEAR((body.vertices()[edge.vertices[0]] - body.vertices()[edge.vertices[1]]).norm(),
                radius * std::sqrt(8.0 / 3.0), 1e-14);
  }
  EXPECT_THROW(make_regular_tetrahedron(0.0), InvalidInput);
}

TEST(ConvexPolyhedron, ConstructorRejectsBadInput) {
  const auto tet = make_regular_tetrahedron(1.0);
  auto field_of = [](auto make) -> std::string {
    try {
      make();
    } catch (const InvalidInput& error) {
      return error.field();
    }
    return "";
  };
  EXPECT_EQ(field_of([&] {
              return ConvexPolyhedron({tet.vertices().begin(), tet.vertices().begin() + 3},
                                      tet.triangles());
            }),
            "polyhedron.vertices");
  EXPECT_EQ(field_of([&] {
              return ConvexPolyhedron(tet.vertices(),
                                      {tet.triangles().begin(), tet.triangles().begin() + 3});
            }),
            "polyhedron.triangles");
  auto out_of_range = tet.triangles();
  out_of_range[2][1] = 4;
  EXPECT_EQ(field_of([&] { return ConvexPolyhedron(tet.vertices(), out_of_range); }),
            "polyhedron.triangles");
  auto non_finite = tet.vertices();
  non_finite[3].y() = std::nan("");
  EXPECT_EQ(field_of([&] { return ConvexPolyhedron(non_finite, tet.triangles()); }),
            "polyhedron.vertices");
  EXPECT_TRUE(ConvexPolyhedron().is_empty());
}

TEST(CheckClosedManifold, DetectsEachKindOfDefect) {
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  // One triangle flipped: its edges run the same way as their neighbours'.
  auto flipped = cube.triangles();
  std::swap(flipped[3][1], flipped[3][2]);
  const auto one_flipped = check_closed_manifold(ConvexPolyhedron(cube.vertices(), flipped));
  EXPECT_FALSE(one_flipped.is_ok);
  EXPECT_NE(one_flipped.message.find("edge"), std::string::npos) << one_flipped.message;
  EXPECT_THROW(ConvexPolyhedron(cube.vertices(), flipped).edges(), InvalidInput);
  // A hole: one triangle missing.
  auto holed = cube.triangles();
  holed.pop_back();
  EXPECT_FALSE(check_closed_manifold(ConvexPolyhedron(cube.vertices(), holed)).is_ok);
  // An unused vertex.
  auto extra = cube.vertices();
  extra.emplace_back(5, 5, 5);
  const auto unused = check_closed_manifold(ConvexPolyhedron(extra, cube.triangles()));
  EXPECT_FALSE(unused.is_ok);
  EXPECT_NE(unused.message.find("vertex 8"), std::string::npos) << unused.message;
  // A duplicated triangle pair (an edge shared by four triangles).
  auto doubled = cube.triangles();
  doubled.push_back(cube.triangles()[0]);
  doubled.push_back({cube.triangles()[0][0], cube.triangles()[0][2], cube.triangles()[0][1]});
  EXPECT_FALSE(check_closed_manifold(ConvexPolyhedron(cube.vertices(), doubled)).is_ok);
  // Two disjoint tetrahedra: closed and manifold but V - E + F = 4.
  const auto tet = make_regular_tetrahedron(1.0);
  auto vertices = tet.vertices();
  auto triangles = tet.triangles();
  for (const auto& v : tet.vertices()) vertices.push_back(v + Vec3(5, 0, 0));
  for (auto t : tet.triangles()) triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  const auto two = check_closed_manifold(ConvexPolyhedron(vertices, triangles));
  EXPECT_FALSE(two.is_ok);
  EXPECT_NE(two.message.find("V - E + F = 4"), std::string::npos) << two.message;
}

TEST(CheckConvex, DetectsDentsInversionAndFlatness) {
  const auto octahedron = make_octahedron({1, 1, 1, 1, 1, 1});
  // Pull the +z vertex inward past the equator: a dent, still a closed manifold.
  auto dented = octahedron.vertices();
  dented[4] = Vec3(0, 0, -0.5);
  const auto dent = check_convex(ConvexPolyhedron(dented, octahedron.triangles()), 1e-12);
  EXPECT_FALSE(dent.is_ok);
  // Move it only slightly inward (0.5): convex again.
  dented[4] = Vec3(0, 0, 0.5);
  EXPECT_TRUE(check_convex(ConvexPolyhedron(dented, octahedron.triangles()), 1e-12).is_ok);
  // Every triangle inside out: vertices lie in front of the faces and the volume is negative.
  auto inverted = octahedron.triangles();
  for (auto& t : inverted) std::swap(t[0], t[1]);
  EXPECT_FALSE(check_convex(ConvexPolyhedron(octahedron.vertices(), inverted), 1e-12).is_ok);
  // Cube corner (1,1,1) pushed out by e: it lies e in front of the planes of the three unmoved
  // triangles of its faces. Rejected below tolerance e, accepted above it.
  const auto cube = make_box(Vec3::Zero(), Vec3::Ones());
  auto bulged = cube.vertices();
  const double e = 1e-6;
  bulged[7] += Vec3(e, e, e);
  const ConvexPolyhedron corner(bulged, cube.triangles());
  const auto tight = check_convex(corner, 0.5 * e);
  EXPECT_FALSE(tight.is_ok);
  EXPECT_NE(tight.message.find("vertex 7"), std::string::npos) << tight.message;
  EXPECT_TRUE(check_convex(corner, 1.5 * e).is_ok);
  // A degenerate triangle has zero area.
  auto flat = octahedron.vertices();
  flat[4] = Vec3(0, 0, 0);
  flat[5] = Vec3(0, 0, 0);
  EXPECT_FALSE(check_convex(ConvexPolyhedron(flat, octahedron.triangles()), 1e-12).is_ok);
}

TEST(ConvexPolyhedron, TransformsAreValuesAndExact) {
  const auto body = make_octahedron({0.3, 0.5, 0.4, 0.6, 0.7, 0.2});
  const Vec3 offset(10, -20, 30);
  const auto moved = body.translated(offset);
  ASSERT_EQ(moved.triangles(), body.triangles());
  for (std::size_t v = 0; v < body.vertex_count(); ++v) {
    EXPECT_EQ(moved.vertices()[v], body.vertices()[v] + offset);
  }
  EXPECT_EQ(body.vertices()[0], Vec3(0.3, 0, 0));  // the original is untouched

  const Pose pose{.position = Vec3(1, 2, 3),
                  .rotation = Quat(Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 2).normalized()))};
  const auto placed = body.transformed(pose);
  for (std::size_t v = 0; v < body.vertex_count(); ++v) {
    EXPECT_NEAR((placed.vertices()[v] - pose.apply(body.vertices()[v])).norm(), 0.0, 1e-15);
    EXPECT_NEAR((pose.apply_inverse(placed.vertices()[v]) - body.vertices()[v]).norm(), 0.0, 1e-15);
  }
  EXPECT_TRUE(check_convex(placed, 1e-12).is_ok);
  EXPECT_NEAR(placed.longest_edge(), body.longest_edge(), 1e-15);

  const auto big = body.scaled(2.5);
  EXPECT_NEAR(big.longest_edge(), 2.5 * body.longest_edge(), 1e-15);
  EXPECT_THROW(body.scaled(0.0), InvalidInput);
  EXPECT_THROW(body.scaled(-1.0), InvalidInput);

  const Aabb box = body.bounds();
  EXPECT_EQ(box.lower, Vec3(-0.5, -0.6, -0.2));
  EXPECT_EQ(box.upper, Vec3(0.3, 0.4, 0.7));
  EXPECT_FALSE(box.is_empty());
  EXPECT_TRUE(Aabb{}.is_empty());
}

}  // namespace
}  // namespace aggpack
