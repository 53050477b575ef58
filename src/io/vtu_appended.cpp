// The .vtu layout shared by the packing and mesomodel writers (vtu_appended.h).

#include "vtu_appended.h"

#include <cstdio>
#include <string>

#include "export_detail.h"

namespace aggpack::detail {

void write_vtu_appended(const VtuFile& file, std::ostream& out) {
  std::uint64_t offset = 0;
  auto data_array = [&](const VtuArray& array) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
                  "format=\"appended\" offset=\"%llu\"/>\n",
                  array.type, array.name, array.components,
                  static_cast<unsigned long long>(offset));
    offset += 8 + array.bytes;
    return std::string(line);
  };
  std::string header = "<?xml version=\"1.0\"?>\n<!-- ";
  header += file.comment;
  header +=
      " -->\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  header += "    <Piece NumberOfPoints=\"" + std::to_string(file.points) + "\" NumberOfCells=\"" +
            std::to_string(file.cells) + "\">\n      <Points>\n";
  header += data_array(file.point_coordinates);
  header += "      </Points>\n      <Cells>\n";
  for (const VtuArray& array : file.cell_arrays) header += data_array(array);
  header += "      </Cells>\n      <CellData Scalars=\"";
  header += file.scalars;
  header += "\">\n";
  for (const VtuArray& array : file.cell_data) header += data_array(array);
  header +=
      "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"
      "  <AppendedData encoding=\"raw\">\n   _";
  out << header;

  auto stream = [&](const VtuArray& array) {
    std::string size;
    append_bytes(size, array.bytes);
    out << size;
    array.write(out);
  };
  stream(file.point_coordinates);
  for (const VtuArray& array : file.cell_arrays) stream(array);
  for (const VtuArray& array : file.cell_data) stream(array);
  // The newline before the closing tag matters: readers such as meshio cut the raw block there.
  out << "\n  </AppendedData>\n</VTKFile>\n";
}

}  // namespace aggpack::detail
