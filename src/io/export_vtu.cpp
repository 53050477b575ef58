// VTK XML unstructured grid (.vtu), binary: every array is stored raw in one <AppendedData>
// block, each preceded by its byte count (UInt64, header_type="UInt64"). The XML header with all
// array offsets is known from the counts up front, so the arrays stream one after another.

#include <cstdio>

#include "export_detail.h"

namespace aggpack::detail {

namespace {

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkTetra = 10;

struct ArraySpec {
  const char* type;
  const char* name;
  int components;
  std::uint64_t bytes;
};

}  // namespace

void write_vtu(const ExportModel& model, std::ostream& out) {
  const bool is_surface = model.mode() == ElementMode::kSurface;
  const std::uint64_t points = model.node_count();
  const std::uint64_t cells = model.element_count();
  const std::uint64_t corners = is_surface ? 3 : 4;
  const ArraySpec arrays[] = {
      {"Float64", "Points", 3, 24 * points},   {"Int64", "connectivity", 1, 8 * corners * cells},
      {"Int64", "offsets", 1, 8 * cells},      {"UInt8", "types", 1, cells},
      {"Int64", "particle_id", 1, 8 * cells},  {"Float64", "volume", 1, 8 * cells},
      {"Float64", "sphericity", 1, 8 * cells}, {"Float64", "alpha", 1, 8 * cells},
      {"Int32", "size_class", 1, 4 * cells},   {"Float64", "control_radius", 1, 8 * cells},
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
  std::string header =
      "<?xml version=\"1.0\"?>\n"
      "<!-- aggpack " AGGPACK_VERSION
      ": one cell block per particle, cell data per particle (particle_id from 1) -->\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  header += "    <Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" +
            std::to_string(cells) + "\">\n      <Points>\n";
  header += data_array(0);
  header += "      </Points>\n      <Cells>\n";
  for (std::size_t a = 1; a <= 3; ++a) header += data_array(a);
  header += "      </Cells>\n      <CellData Scalars=\"particle_id\">\n";
  for (std::size_t a = 4; a < std::size(arrays); ++a) header += data_array(a);
  header +=
      "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"
      "  <AppendedData encoding=\"raw\">\n   _";
  out << header;

  std::size_t current = 0;
  auto begin_array = [&]() {
    std::string size;
    append_bytes(size, arrays[current].bytes);
    out << size;
    ++current;
  };
  // Points.
  begin_array();
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    for (const Vec3& node : nodes) {
      for (int axis = 0; axis < 3; ++axis) append_bytes(buffer, node[axis]);
    }
  });
  // Connectivity (0-based global point indices).
  begin_array();
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const auto first = static_cast<std::int64_t>(model.node_offset(k));
    if (is_surface) {
      for (const auto& t : model.triangles(k)) {
        for (auto index : t) append_bytes(buffer, first + static_cast<std::int64_t>(index));
      }
    } else {
      std::vector<Tetrahedron> scratch;
      for (const auto& t : model.tetrahedra(k, scratch)) {
        for (auto index : t) append_bytes(buffer, first + static_cast<std::int64_t>(index));
      }
    }
  });
  // Offsets: the end of each cell in the connectivity array.
  begin_array();
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    auto end = static_cast<std::int64_t>(model.element_offset(k) * corners);
    for (std::uint32_t e = 0; e < model.elements_of(k); ++e) {
      end += static_cast<std::int64_t>(corners);
      append_bytes(buffer, end);
    }
  });
  // Types.
  begin_array();
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    buffer.append(model.elements_of(k), static_cast<char>(is_surface ? kVtkTriangle : kVtkTetra));
  });
  // Per-particle cell data, repeated on each of the particle's cells.
  auto per_cell = [&](auto value_of) {
    begin_array();
    stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
      const auto value = value_of(k);
      for (std::uint32_t e = 0; e < model.elements_of(k); ++e) append_bytes(buffer, value);
    });
  };
  per_cell([&](std::size_t k) { return static_cast<std::int64_t>(model.particle_number(k)); });
  per_cell([&](std::size_t k) { return model.volume(k); });
  per_cell([&](std::size_t k) { return model.sphericity(k); });
  per_cell([&](std::size_t k) { return model.alpha(k); });
  per_cell([&](std::size_t k) { return static_cast<std::int32_t>(model.size_class(k)); });
  per_cell([&](std::size_t k) { return model.control_radius(k); });
  // The newline before the closing tag matters: readers such as meshio cut the raw block there.
  out << "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace aggpack::detail
