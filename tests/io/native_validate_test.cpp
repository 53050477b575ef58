// validate_packing, the content check read_packing ends with: exact small cases for the shape
// topology and geometry rules and for the value ranges (docs/formats.md, "Native packing file").

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/io/native.h"

namespace aggpack {
namespace {

// Regular-ish tetrahedron, outward counter-clockwise triangles, volume 1/6.
std::vector<Vec3> tetra_vertices() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; }
std::vector<Triangle> tetra_triangles() { return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}; }

Packing packing_of(const ConvexPolyhedron& shape) {
  Packing packing;
  packing.container = {.shape = BoxContainer{.length = 2, .width = 2, .depth = 2}};
  packing.shapes.push_back(shape);
  Particle p;
  p.shape = 0;
  p.pose.position = Vec3(1, 1, 1);
  p.control_radius = 0.5;
  packing.particles.push_back(p);
  return packing;
}

// The message validate_packing throws, or "" if it accepts.
std::string problem(const Packing& packing) {
  try {
    validate_packing(packing, "x.h5");
  } catch (const FormatError& error) {
    return error.what();
  }
  return "";
}

TEST(ValidatePacking, AcceptsATetrahedron) {
  EXPECT_EQ(problem(packing_of({tetra_vertices(), tetra_triangles()})), "");
}

TEST(ValidatePacking, RejectsOneFlippedTriangle) {
  auto triangles = tetra_triangles();
  std::swap(triangles[3][1], triangles[3][2]);  // (1, 3, 2): clockwise seen from outside
  EXPECT_EQ(problem(packing_of({tetra_vertices(), triangles})),
            "x.h5: /shapes/triangles (shape 0, rows 0-3): edge 1-2 runs the same way in triangles "
            "0 and 3: not consistently oriented (a flipped triangle)");
}

TEST(ValidatePacking, RejectsANonManifoldEdge) {
  // Two tetrahedra glued along the edge 0-1: that edge is in four triangles.
  std::vector<Vec3> vertices = {{0, 0, 0},     {1, 0, 0},    {0.5, 1, 0},
                                {0.5, 0.5, 1}, {0.5, -1, 0}, {0.5, -0.5, -1}};
  std::vector<Triangle> triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
                                     {0, 4, 1}, {0, 1, 5}, {0, 5, 4}, {1, 4, 5}};
  EXPECT_EQ(problem(packing_of({vertices, triangles})),
            "x.h5: /shapes/triangles (shape 0, rows 0-7): edge 0-1 is shared by 4 triangles: not "
            "a 2-manifold (each edge needs exactly 2)");
}

TEST(ValidatePacking, RejectsAnOpenSurface) {
  auto triangles = tetra_triangles();
  triangles[3] = triangles[2];  // one face twice, one missing
  const std::string message = problem(packing_of({tetra_vertices(), triangles}));
  EXPECT_NE(message.find("x.h5: /shapes/triangles (shape 0, rows 0-3): edge "), std::string::npos)
      << message;
}

TEST(ValidatePacking, RejectsAZeroAreaTriangle) {
  // The tetrahedron with its edge 0-1 split at vertex 4: the face (0, 2, 1) becomes two triangles
  // and the face (0, 1, 3) stays, so the sliver (0, 4, 1) closes the surface with zero area.
  std::vector<Vec3> vertices = tetra_vertices();
  vertices.push_back({0.5, 0, 0});
  const std::vector<Triangle> triangles = {{0, 2, 4}, {4, 2, 1}, {0, 1, 3},
                                           {0, 3, 2}, {1, 2, 3}, {0, 4, 1}};
  EXPECT_EQ(problem(packing_of({vertices, triangles})),
            "x.h5: /shapes/triangles (shape 0, rows 0-5): triangle 5 has zero area (degenerate)");
}

TEST(ValidatePacking, RejectsAMirroredShape) {
  auto vertices = tetra_vertices();
  for (auto& v : vertices) v = -v;  // point reflection: every triangle now turns clockwise
  const std::string message = problem(packing_of({vertices, tetra_triangles()}));
  EXPECT_EQ(message,
            "x.h5: /shapes/triangles (shape 0, rows 0-3): volume -0.1666666667 m^3 is not "
            "positive: the triangles turn clockwise seen from outside (inside out, e.g. mirrored)");
}

TEST(ValidatePacking, RejectsAConcaveShapeAndAcceptsWithinTolerance) {
  // Octahedron with the +x apex pushed through to x = -0.2: closed, oriented, positive volume,
  // but dented.
  std::vector<Vec3> vertices = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const ConvexPolyhedron octahedron = make_octahedron({1, 1, 1, 1, 1, 1});
  ASSERT_EQ(octahedron.vertices(), vertices);
  EXPECT_EQ(problem(packing_of(octahedron)), "");
  vertices[0] = {-0.2, 0, 0};
  const std::string dented = problem(packing_of({vertices, octahedron.triangles()}));
  EXPECT_EQ(dented,
            "x.h5: /shapes/vertices (shape 0, rows 0-5): vertex 3 lies 0.3849001795 m outside the "
            "plane of triangle 0: not convex (tolerance 3e-06 m)");
  // A vertex pushed out of a face plane by 1e-7 of the size (tolerance 1e-6) is accepted.
  vertices = tetra_vertices();
  vertices.push_back({0.25, 0.25, 1e-7});  // just inside the face z = 0 ...
  std::vector<Triangle> triangles = {{0, 2, 4}, {2, 1, 4}, {1, 0, 4},
                                     {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_EQ(problem(packing_of({vertices, triangles})), "");
  vertices[4].z() = 1e-3;  // ... and dented into the body
  EXPECT_NE(problem(packing_of({vertices, triangles})).find("not convex"), std::string::npos);
}

TEST(ValidatePacking, RejectsValuesOutsideTheDocumentedRanges) {
  const Packing good = packing_of({tetra_vertices(), tetra_triangles()});
  auto with = [&](auto edit) {
    Packing packing = good;
    edit(packing);
    return problem(packing);
  };
  EXPECT_EQ(with([](Packing& p) { p.particles[0].scale = 2e6; }),
            "x.h5: /particles/scale[0] = 2000000: outside [1e-09, 1000000]");
  // The scale is in range, but the particle it makes is not.
  auto scaled_tetra = [](double factor, double scale) {
    Packing packing =
        packing_of(ConvexPolyhedron(tetra_vertices(), tetra_triangles()).scaled(factor));
    packing.particles[0].scale = scale;
    return problem(packing);
  };
  EXPECT_EQ(scaled_tetra(0.1, 2e-9),
            "x.h5: /particles/scale[0] = 2e-09: makes shape 0 3.464101615e-10 m across with "
            "coordinates up to 2e-10 m; allowed: at least 1e-09 m across, coordinates up to "
            "1000000 m");
  EXPECT_NE(scaled_tetra(10, 2e5).find("coordinates up to 2000000 m; allowed"), std::string::npos);
  EXPECT_EQ(scaled_tetra(1, 1e-9), "");
  EXPECT_EQ(with([](Packing& p) { p.particles[0].pose.rotation = Quat(1.01, 0, 0, 0); }),
            "x.h5: /particles/rotation[0]: |q|^2 = 1.0201, not a unit quaternion (tolerance "
            "1e-06)");
  EXPECT_EQ(with([](Packing& p) { p.particles[0].pose.position.y() = -1.5e6; }),
            "x.h5: /particles/position[0] = (1, -1500000, 1): outside [-1000000, 1000000] m");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(with([&](Packing& p) { p.particles[0].pose.position.x() = nan; }),
            "x.h5: /particles/position[0] = (nan, 1, 1): outside [-1000000, 1000000] m");
  EXPECT_EQ(with([&](Packing& p) { p.particles[0].scale = nan; }),
            "x.h5: /particles/scale[0] = nan: outside [1e-09, 1000000]");
  EXPECT_EQ(with([&](Packing& p) { p.container.get_if<BoxContainer>()->depth = nan; }),
            "x.h5: /container/depth = nan: outside [1e-09, 1000000] m (a box needs it > 0)");
  EXPECT_EQ(with([](Packing& p) { p.particles[0].control_radius = -1; }),
            "x.h5: /particles/control_radius[0] = -1: outside [0, 1000000] m");
  EXPECT_EQ(with([](Packing& p) { p.particles[0].shape = 1; }),
            "x.h5: /particles/shape[0] = 1: no such shape (the file has 1)");
  EXPECT_EQ(with([](Packing& p) { p.container.shape = CylinderContainer{.radius = 0}; }),
            "x.h5: /container/radius = 0: outside [1e-09, 1000000] m (a cylinder needs it > 0)");
  EXPECT_EQ(with([](Packing& p) { p.container.wall_gap = -0.1; }),
            "x.h5: /container/wall_gap = -0.1: outside [0, 1000000] m");
  // An empty packing is valid (unused sizes in a file:
  // NativeFileTest.ContainerFieldsFollowTheKindList).
  EXPECT_EQ(with([](Packing& p) { p.particles.clear(); }), "");
  // Far from the origin and large, but every product stays finite.
  EXPECT_EQ(with([](Packing& p) {
              p.particles[0].scale = 1e6 / 1.0;
              p.particles[0].pose.position = Vec3(-1e6, 1e6, 1e6);
            }),
            "");
}

// write_packing stores what it is given; read_packing refuses it with the same message.
TEST(ValidatePacking, ReadPackingUsesTheSameCheck) {
  auto triangles = tetra_triangles();
  std::swap(triangles[3][1], triangles[3][2]);
  const Packing packing = packing_of({tetra_vertices(), triangles});
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("aggpack_validate_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  write_packing(packing, path);
  std::string message;
  try {
    read_packing(path);
  } catch (const FormatError& error) {
    message = error.what();
  }
  std::filesystem::remove(path);
  EXPECT_EQ(message, path + problem(packing).substr(4));
}

}  // namespace
}  // namespace aggpack
