// The mesomodel as a VTK XML unstructured grid (io/mesomodel_files.h), raw appended binary as
// export_vtu.cpp writes it: each array preceded by its byte count (UInt64). Cells in MesoLayout
// order, cell data "phase" (UInt8, MesoPhase code: 0 mortar, 1 ITZ, 2 aggregate) and "particle"
// (UInt32, 1-based particle of aggregate and ITZ cells, 0 for the mortar).

#include <cstdio>

#include "export_detail.h"
#include "mesomodel_detail.h"

namespace aggpack {

namespace {

constexpr std::uint8_t kVtkTetra = 10;

struct ArraySpec {
  const char* type;
  const char* name;
  int components;
  std::uint64_t bytes;
};

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
  const std::uint64_t cells = mesh.tetrahedra.size();
  const ArraySpec arrays[] = {
      {"Float64", "Points", 3, 24 * points}, {"Int64", "connectivity", 1, 32 * cells},
      {"Int64", "offsets", 1, 8 * cells},    {"UInt8", "types", 1, cells},
      {"UInt8", "phase", 1, cells},          {"UInt32", "particle", 1, 4 * cells},
  };
  std::uint64_t offsets[std::size(arrays)];
  std::uint64_t offset = 0;
  for (std::size_t a = 0; a < std::size(arrays); ++a) {
    offsets[a] = offset;
    offset += 8 + arrays[a].bytes;
  }
  auto data_array = [&](std::size_t a) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
                  "format=\"appended\" offset=\"%llu\"/>\n",
                  arrays[a].type, arrays[a].name, arrays[a].components,
                  static_cast<unsigned long long>(offsets[a]));
    return std::string(line);
  };
  detail::write_atomically(path, options.overwrite, [&](std::ostream& out) {
    std::string header =
        "<?xml version=\"1.0\"?>\n"
        "<!-- aggpack " AGGPACK_VERSION
        " concrete mesomodel: phase 0 mortar, 1 ITZ, 2 aggregate; particle from 1, 0 = mortar "
        "-->\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
    header += "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" +
              std::to_string(cells) + "\">\n      <Points>\n";
    header += data_array(0);
    header += "      </Points>\n      <Cells>\n";
    for (std::size_t a = 1; a <= 3; ++a) header += data_array(a);
    header += "      </Cells>\n      <CellData Scalars=\"phase\">\n";
    for (std::size_t a = 4; a < std::size(arrays); ++a) header += data_array(a);
    header +=
        "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"
        "  <AppendedData encoding=\"raw\">\n   _";
    out << header;
    std::size_t current = 0;
    auto begin_array = [&]() {
      std::string size;
      detail::append_bytes(size, arrays[current].bytes);
      out << size;
      ++current;
    };
    constexpr std::size_t kChunk = 4096;
    auto chunked = [&](std::uint64_t count, const auto& format) {
      detail::stream_items(
          (count + kChunk - 1) / kChunk, out, [&](std::size_t c, std::string& buffer) {
            const std::uint64_t first = c * kChunk;
            const std::uint64_t last = std::min<std::uint64_t>(count, first + kChunk);
            for (std::uint64_t i = first; i < last; ++i) format(i, buffer);
          });
    };
    begin_array();
    chunked(points, [&](std::uint64_t i, std::string& buffer) {
      for (int axis = 0; axis < 3; ++axis) {
        detail::append_bytes(buffer, mesh.nodes[i][axis] * scale);  // exact when scale is 1
      }
    });
    begin_array();
    chunked(cells, [&](std::uint64_t i, std::string& buffer) {
      for (const std::uint32_t node : mesh.tetrahedra[layout.order[i]]) {
        detail::append_bytes(buffer, static_cast<std::int64_t>(node));
      }
    });
    begin_array();
    chunked(cells, [&](std::uint64_t i, std::string& buffer) {
      detail::append_bytes(buffer, static_cast<std::int64_t>(4 * (i + 1)));
    });
    begin_array();
    chunked(cells,
            [&](std::uint64_t, std::string& buffer) { buffer += static_cast<char>(kVtkTetra); });
    begin_array();
    chunked(cells, [&](std::uint64_t i, std::string& buffer) {
      buffer += static_cast<char>(mesh.phase[layout.order[i]]);
    });
    begin_array();
    chunked(cells, [&](std::uint64_t i, std::string& buffer) {
      detail::append_bytes(buffer, mesh.particle[layout.order[i]]);
    });
    // The newline before the closing tag matters: readers such as meshio cut the raw block there.
    out << "\n  </AppendedData>\n</VTKFile>\n";
  });
  return {.format = MesoFileFormat::kVtu, .nodes = points, .elements = cells};
}

}  // namespace aggpack
