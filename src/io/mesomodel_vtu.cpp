// The mesomodel as a VTK XML unstructured grid (io/mesomodel_files.h), raw appended binary in
// the layout of vtu_appended.h (as export_vtu.cpp writes it). Cells in MesoLayout order, cell
// data "phase" (UInt8, MesoPhase code: 0 mortar, 1 ITZ, 2 aggregate) and "particle" (UInt32,
// 1-based particle of aggregate and ITZ cells, 0 for the mortar). A cohesive ITZ's wedges are
// VTK_WEDGE cells of zero volume, their triangles reversed for VTK's order (the first triangle's
// right-hand normal points away from the second).

#include "export_detail.h"
#include "mesomodel_detail.h"
#include "vtu_appended.h"

namespace aggpack {

namespace {

constexpr std::uint8_t kVtkTetra = 10;
constexpr std::uint8_t kVtkWedge = 13;
// CohesiveWedge (Abaqus order: the first triangle's normal points to the second) to VTK_WEDGE.
constexpr std::array<int, 6> kVtkWedgeOrder = {0, 2, 1, 3, 5, 4};

}  // namespace

MesoFileSummary write_mesomodel_vtu(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options) {
  validate(options);
  if (options.is_quadratic) throw InvalidInput("quadratic", "true for .vtu", ".inp only (C3D10)");
  validate(mesh);
  check_writable(path, options.overwrite);
  const detail::MesoLayout layout = detail::make_layout(mesh);
  const double scale = length_scale(options.units);
  const std::uint64_t points = mesh.nodes.size();
  const std::uint64_t cells = layout.order.size();
  // offsets[i]: one past cell i's last connectivity entry.
  std::vector<std::int64_t> offsets(cells);
  std::int64_t end = 0;
  for (std::uint64_t i = 0; i < cells; ++i) {
    end += static_cast<std::int64_t>(detail::element_nodes(mesh, layout.order[i]).size());
    offsets[i] = end;
  }
  auto is_wedge = [&](std::uint64_t i) { return layout.order[i] >= mesh.tetrahedra.size(); };
  // Streams items [0, count) in chunks; format(i, buffer) appends item i's bytes.
  constexpr std::size_t kChunk = 4096;
  auto chunked = [](std::uint64_t count, auto format) {
    return [count, format](std::ostream& out) {
      detail::stream_items(
          (count + kChunk - 1) / kChunk, out, [&](std::size_t c, std::string& buffer) {
            const std::uint64_t first = c * kChunk;
            const std::uint64_t last = std::min<std::uint64_t>(count, first + kChunk);
            for (std::uint64_t i = first; i < last; ++i) format(i, buffer);
          });
    };
  };
  const detail::VtuArray point_coordinates{
      "Float64", "Points", 3, 24 * points,
      chunked(points, [&](std::uint64_t i, std::string& buffer) {
        for (int axis = 0; axis < 3; ++axis) {
          detail::append_bytes(buffer, mesh.nodes[i][axis] * scale);  // exact when scale is 1
        }
      })};
  const detail::VtuArray cell_arrays[] = {
      {"Int64", "connectivity", 1, 8 * static_cast<std::uint64_t>(end),
       chunked(cells,
               [&](std::uint64_t i, std::string& buffer) {
                 const auto nodes = detail::element_nodes(mesh, layout.order[i]);
                 for (std::size_t k = 0; k < nodes.size(); ++k) {
                   const std::uint32_t node = is_wedge(i) ? nodes[kVtkWedgeOrder[k]] : nodes[k];
                   detail::append_bytes(buffer, static_cast<std::int64_t>(node));
                 }
               })},
      {"Int64", "offsets", 1, 8 * cells,
       chunked(cells, [&](std::uint64_t i,
                          std::string& buffer) { detail::append_bytes(buffer, offsets[i]); })},
      {"UInt8", "types", 1, cells,
       chunked(cells,
               [&](std::uint64_t i, std::string& buffer) {
                 buffer += static_cast<char>(is_wedge(i) ? kVtkWedge : kVtkTetra);
               })},
  };
  const detail::VtuArray cell_data[] = {
      {"UInt8", "phase", 1, cells,
       chunked(cells,
               [&](std::uint64_t i, std::string& buffer) {
                 buffer += static_cast<char>(detail::element_phase(mesh, layout.order[i]));
               })},
      {"UInt32", "particle", 1, 4 * cells,
       chunked(cells,
               [&](std::uint64_t i, std::string& buffer) {
                 detail::append_bytes(buffer, detail::element_particle(mesh, layout.order[i]));
               })},
  };
  detail::write_atomically(path, options.overwrite, [&](std::ostream& out) {
    detail::write_vtu_appended(
        {.comment = "aggpack " AGGPACK_VERSION
                    " concrete mesomodel: phase 0 mortar, 1 ITZ, 2 aggregate; particle from 1, "
                    "0 = mortar",
         .points = points,
         .cells = cells,
         .point_coordinates = point_coordinates,
         .cell_arrays = cell_arrays,
         .cell_data = cell_data,
         .scalars = "phase"},
        out);
  });
  return {.format = ExportFormat::kVtu, .nodes = points, .elements = cells};
}

}  // namespace aggpack
