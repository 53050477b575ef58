// `aggpack render --mesomodel-cut AXIS=VALUE`: the section of a packing's concrete mesomodel
// (issue 16, item 7), drawn in software on core/raster.h (mesh/mesomodel_cut.h): no OpenGL.

#include <fmt/core.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/raster.h"
#include "aggpack/io/native.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/mesh/mesomodel_cut.h"
#include "aggpack/pack/container.h"
#include "aggpack/pack/resources.h"
#include "commands.h"
#include "progress.h"

namespace aggpack::cli {

void render_mesomodel_cut(const MesomodelCutRequest& request) {
  const CutPlane plane = parse_cut_plane(request.plane, "--mesomodel-cut");
  const std::array<std::pair<const char*, double>, 3> lengths = {
      {{"--itz", request.meso.itz_thickness},
       {"--aggregate-size", request.meso.aggregate_size},
       {"--mortar-size", request.meso.mortar_size}}};
  for (const auto& [flag, value] : lengths) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InvalidInput(flag, format_value(value), ">= 0 (m)");
    }
  }
  validate(request.meso);
  if (request.width < 200) {
    throw InvalidInput("--size", request.size_text,
                       "a width of at least 200 pixels with --mesomodel-cut");
  }
  const std::string output =
      request.output.empty()
          ? std::filesystem::path(request.input).replace_extension(".png").string()
          : request.output;
  const Overwrite overwrite = request.is_forced ? Overwrite::kAllow : Overwrite::kForbid;
  check_writable(output, overwrite);  // fail before the (slow) meshing
  const Packing packing = read_packing(request.input);
  // A plane outside the container is refused before meshing; cut_mesomodel checks it against
  // the mesh's nodes again (for a cylinder, the circumscribed prism).
  const Aabb box = packing.container.bounds();
  const double lowest = box.lower[plane.axis];
  const double highest = box.upper[plane.axis];
  if (!(plane.value >= lowest && plane.value <= highest)) {
    throw InvalidInput(
        "--mesomodel-cut", request.plane,
        fmt::format("{} in [{}, {}] m (the container's extent along {})", axis_name(plane.axis),
                    format_value(lowest), format_value(highest), axis_name(plane.axis)));
  }
  announce_heavy_run(estimate_mesomodel(static_cast<double>(packing.particles.size()), 0.0));
  MesoReport report;
  const MesoMesh mesh = build_mesomodel(packing, request.meso, &report);
  const std::vector<CutPolygon> polygons =
      cut_mesomodel(mesh, plane.axis, plane.value, "--mesomodel-cut");
  const CutImageOptions options{
      .width = request.width,
      .is_tinted = request.is_tinted,
      .has_edges = true,
      .subtitle = fmt::format("{} aggregates, {}, {} tetrahedra", mesh.particle_count,
                              mesh.itz_thickness > 0.0
                                  ? fmt::format("ITZ {:g} mm", mesh.itz_thickness * 1e3)
                                  : "no ITZ",
                              mesh.tetrahedra.size())};
  const Raster raster = draw_mesomodel_cut(polygons, plane.axis, plane.value, options);
  write_png(output, raster);
  const std::array<double, 3> areas = cut_phase_areas(polygons);
  const double total = areas[0] + areas[1] + areas[2];
  fmt::print(
      "wrote {} ({}x{}, mesomodel cut {}: {} tetrahedra, {} section polygons; aggregate {:.1f} "
      "%, ITZ {:.1f} %, mortar {:.1f} % of the section)\n",
      output, raster.width(), raster.height(), request.plane, mesh.tetrahedra.size(),
      polygons.size(), 100.0 * areas[2] / total, 100.0 * areas[1] / total,
      100.0 * areas[0] / total);
}

}  // namespace aggpack::cli
