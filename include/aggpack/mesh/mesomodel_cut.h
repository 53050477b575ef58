#pragma once
// A planar cut through a concrete mesomodel (issue 16, item 7): every tetrahedron of a MesoMesh
// sliced by an axis-aligned plane (pure geometry, exact up to rounding), and a software picture of
// the section (phases coloured, element edges drawn thinly, legend, scale bar) on the PNG raster
// of core/raster.h. No OpenGL.
//
// Plane convention (no double counting): a node lies "below" when its coordinate is < value and
// "above" otherwise, so the section is the limit of the cuts at value - epsilon. A tetrahedron
// contributes a polygon only when it has nodes on both sides; a face lying in the plane is
// therefore drawn once, by the tetrahedron below it, and a node or edge in the plane adds nothing
// of its own. At the lowest coordinate of the mesh (nothing below) the side is flipped: the limit
// from above. The section of every plane in [min, max] of the nodes is thus the whole cross
// section of the mesh.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aggpack/core/raster.h"
#include "aggpack/mesh/mesomodel.h"

namespace aggpack {

/// The section of one tetrahedron: a triangle or a quadrilateral, convex, counter-clockwise in
/// the plane's (u, v) coordinates: x-cut (y, z), y-cut (x, z), z-cut (x, y). Metres.
struct CutPolygon {
  std::vector<std::array<double, 2>> points;  ///< 3 or 4 corners, CCW
  MesoPhase phase = MesoPhase::kMortar;
  std::uint32_t particle = 0;     ///< as MesoMesh::particle (0 = mortar)
  std::uint32_t tetrahedron = 0;  ///< index into MesoMesh::tetrahedra
};

/// "x", "y" or "z" for axis 0, 1, 2.
const char* axis_name(int axis);

/// An axis-aligned plane coordinate[axis] = value (m).
struct CutPlane {
  int axis = 2;
  double value = 0.0;
};

/// "z=0.05" (also "x=...", "y=..."; value in metres, finite) -> {2, 0.05}. \throw InvalidInput
/// naming `key` otherwise.
CutPlane parse_cut_plane(const std::string& text, const std::string& key);

/// The in-plane axes (u, v) of a cut normal to `axis`: x -> (1, 2), y -> (0, 2), z -> (0, 1).
std::array<int, 2> cut_plane_axes(int axis);

/// Sections of every tetrahedron crossed by the plane coordinate[axis] = value (see the header
/// comment for nodes in the plane), in tetrahedron order. \throw InvalidInput naming `key`
/// (e.g. "--mesomodel-cut") when axis is not 0..2, the mesh has no tetrahedra or value is not
/// within the nodes' extent along the axis [min, max].
std::vector<CutPolygon> cut_mesomodel(const MesoMesh& mesh, int axis, double value,
                                      const std::string& key = "cut plane");

/// Area of a polygon (shoelace; positive when counter-clockwise). m^2.
double polygon_area(const std::vector<std::array<double, 2>>& points);

/// Section area per phase (index = MesoPhase code). m^2.
std::array<double, 3> cut_phase_areas(const std::vector<CutPolygon>& polygons);

/// The fill colour of a phase: mortar light beige, ITZ orange-red, aggregate stone grey; with
/// `is_tinted` each aggregate's grey is lightened or darkened by up to 24 levels, a fixed function
/// of its particle id, so neighbouring aggregates are told apart.
Rgb mesomodel_cut_colour(MesoPhase phase, std::uint32_t particle, bool is_tinted);

/// Layout of the picture: the plot (the section at equal scales, centred) fills the box from
/// x = kCutImageMargin to width - kCutImageMargin and from y = kCutImageTitle down to
/// kCutImageTitle + plot height, plot height = plot width x (v extent / u extent), within
/// [20, 2 x plot width]; the legend is below it.
inline constexpr int kCutImageMargin = 40;
inline constexpr int kCutImageTitle = 70;

struct CutImageOptions {
  /// Image width in pixels, [200, 8192]; the height follows the section's aspect ratio (the plot
  /// at most 2 x as tall as wide) plus the title and legend.
  int width = 1200;
  /// Vary each aggregate's grey (mesomodel_cut_colour).
  bool is_tinted = true;
  /// Draw the element edges of the section (1 pixel, a darker shade of each polygon's fill).
  /// Skipped automatically when the mean section edge is shorter than 3 pixels (it would hide the
  /// phases); the legend then says so.
  bool has_edges = true;
  /// Extra title text after the plane, e.g. "ITZ 0.3 mm, 12345 tetrahedra" ("" = none).
  std::string subtitle;
};

/// The picture of a section: title "Mesomodel cut z = ... mm", the polygons (u right, v up,
/// equal scales), legend with each phase's name and area fraction in the section, scale bar in
/// mm. \throw InvalidInput (width, an empty section).
Raster draw_mesomodel_cut(const std::vector<CutPolygon>& polygons, int axis, double value,
                          const CutImageOptions& options = {});

/// cut_mesomodel + draw_mesomodel_cut + write_png (atomic). \throw InvalidInput as above (named
/// `key`), IoError (the file).
void write_mesomodel_cut_png(const std::string& path, const MesoMesh& mesh, int axis, double value,
                             const CutImageOptions& options = {},
                             const std::string& key = "cut plane");

}  // namespace aggpack
