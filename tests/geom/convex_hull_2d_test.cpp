// convex_hull_2d against hulls known exactly.

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "aggpack/geom/convex_hull_2d.h"

namespace aggpack {
namespace {

using Point = std::array<double, 2>;

TEST(ConvexHull2d, SquareWithInnerEdgeAndRepeatedPointsIsItsFourCornersCounterClockwise) {
  // Corners, a repeated corner, the centre and a point on an edge (collinear: dropped).
  const std::vector<Point> points = {{1, 1}, {0, 0}, {1, 0},   {0.5, 0.5},
                                     {0, 1}, {0, 0}, {0.5, 0}, {1, 1}};
  const std::vector<Point> expected = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(convex_hull_2d(points), expected);
}

TEST(ConvexHull2d, FewerThanThreeDistinctPointsComeBackSortedWithoutDuplicates) {
  EXPECT_EQ(convex_hull_2d({}), std::vector<Point>{});
  EXPECT_EQ(convex_hull_2d({{2, 3}, {2, 3}}), (std::vector<Point>{{2, 3}}));
  EXPECT_EQ(convex_hull_2d({{1, 0}, {0, 5}, {1, 0}}), (std::vector<Point>{{0, 5}, {1, 0}}));
}

TEST(ConvexHull2d, HullOfAHexagonAndInteriorPointsIsTheHexagon) {
  // A regular hexagon (exact corners at 60-degree steps) with points strictly inside.
  std::vector<Point> points = {{0.1, 0.2}, {-0.3, 0.1}, {0.0, -0.4}};
  const double h = 0.86602540378443865;  // sqrt(3) / 2
  const std::vector<Point> hexagon = {{-1, 0}, {-0.5, -h}, {0.5, -h}, {1, 0}, {0.5, h}, {-0.5, h}};
  points.insert(points.end(), hexagon.rbegin(), hexagon.rend());
  EXPECT_EQ(convex_hull_2d(points), hexagon);  // from the lowest x, counter-clockwise
}

}  // namespace
}  // namespace aggpack
