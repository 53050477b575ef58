#pragma once
// The convex hull of points in a plane (Andrew's monotone chain).

#include <array>
#include <vector>

namespace aggpack {

/// The convex hull of `points`, counter-clockwise (x right, y up), without repeated or collinear
/// points; fewer than 3 distinct points come back sorted, duplicates removed.
std::vector<std::array<double, 2>> convex_hull_2d(std::vector<std::array<double, 2>> points);

}  // namespace aggpack
