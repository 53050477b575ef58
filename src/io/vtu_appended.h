#pragma once
// The VTK XML unstructured grid (.vtu) file layout shared by export_vtu.cpp and
// mesomodel_vtu.cpp; not a public header.

#include <cstdint>
#include <functional>
#include <ostream>
#include <span>
#include <string_view>

namespace aggpack::detail {

/// One array of a .vtu file, stored raw in the <AppendedData> block. `write` streams exactly
/// `bytes` bytes (little-endian values) to the file.
struct VtuArray {
  const char* type;  ///< VTK type name: "Float64", "Int64", "UInt8"...
  const char* name;
  int components;
  std::uint64_t bytes;
  std::function<void(std::ostream&)> write;
};

/// What a .vtu file holds: the Points array, the three cell arrays (connectivity, offsets,
/// types) and the cell data arrays, `scalars` naming the active one.
struct VtuFile {
  std::string_view comment;  ///< text of the <!-- --> line after the XML declaration
  std::uint64_t points = 0;
  std::uint64_t cells = 0;
  const VtuArray& point_coordinates;
  std::span<const VtuArray, 3> cell_arrays;
  std::span<const VtuArray> cell_data;
  std::string_view scalars;
};

/// Writes the whole file, binary: every array raw in one <AppendedData> block, each preceded by
/// its byte count (UInt64, header_type="UInt64"). The XML header with all array offsets is known
/// from the byte counts up front, so the arrays stream one after another.
void write_vtu_appended(const VtuFile& file, std::ostream& out);

}  // namespace aggpack::detail
