// VTK XML unstructured grid (.vtu), binary, in the layout of vtu_appended.h: one cell block per
// particle, cell data per particle repeated on each of its cells.

#include "export_detail.h"
#include "vtu_appended.h"

namespace aggpack::detail {

namespace {

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkTetra = 10;

}  // namespace

void write_vtu(const ExportModel& model, std::ostream& out) {
  const bool is_surface = model.mode() == ElementMode::kSurface;
  const std::uint64_t points = model.node_count();
  const std::uint64_t cells = model.element_count();
  const std::uint64_t corners = is_surface ? 3 : 4;
  auto write_points = [&](std::ostream& o) {
    stream_items(model.size(), o, [&](std::size_t k, std::string& buffer) {
      std::vector<Vec3> nodes;
      model.linear_nodes(k, nodes);
      for (const Vec3& node : nodes) {
        for (int axis = 0; axis < 3; ++axis) append_bytes(buffer, node[axis]);
      }
    });
  };
  const VtuArray point_coordinates{"Float64", "Points", 3, 24 * points, write_points};
  const VtuArray cell_arrays[] = {
      // Connectivity (0-based global point indices).
      {"Int64", "connectivity", 1, 8 * corners * cells,
       [&](std::ostream& o) {
         stream_items(model.size(), o, [&](std::size_t k, std::string& buffer) {
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
       }},
      // Offsets: the end of each cell in the connectivity array.
      {"Int64", "offsets", 1, 8 * cells,
       [&](std::ostream& o) {
         stream_items(model.size(), o, [&](std::size_t k, std::string& buffer) {
           auto end = static_cast<std::int64_t>(model.element_offset(k) * corners);
           for (std::uint32_t e = 0; e < model.elements_of(k); ++e) {
             end += static_cast<std::int64_t>(corners);
             append_bytes(buffer, end);
           }
         });
       }},
      {"UInt8", "types", 1, cells,
       [&](std::ostream& o) {
         stream_items(model.size(), o, [&](std::size_t k, std::string& buffer) {
           buffer.append(model.elements_of(k),
                         static_cast<char>(is_surface ? kVtkTriangle : kVtkTetra));
         });
       }},
  };
  // Per-particle cell data, repeated on each of the particle's cells.
  auto per_cell = [&](const char* type, const char* name, auto value_of) {
    using Value = decltype(value_of(std::size_t{0}));
    return VtuArray{type, name, 1, sizeof(Value) * cells, [&model, value_of](std::ostream& o) {
                      stream_items(model.size(), o, [&](std::size_t k, std::string& buffer) {
                        const Value value = value_of(k);
                        for (std::uint32_t e = 0; e < model.elements_of(k); ++e) {
                          append_bytes(buffer, value);
                        }
                      });
                    }};
  };
  const VtuArray cell_data[] = {
      per_cell("Int64", "particle_id",
               [&](std::size_t k) { return static_cast<std::int64_t>(model.particle_number(k)); }),
      per_cell("Float64", "volume", [&](std::size_t k) { return model.volume(k); }),
      per_cell("Float64", "sphericity", [&](std::size_t k) { return model.sphericity(k); }),
      per_cell("Float64", "alpha", [&](std::size_t k) { return model.alpha(k); }),
      per_cell("Int32", "size_class",
               [&](std::size_t k) { return static_cast<std::int32_t>(model.size_class(k)); }),
      per_cell("Float64", "control_radius", [&](std::size_t k) { return model.control_radius(k); }),
  };
  write_vtu_appended(
      {.comment = "aggpack " AGGPACK_VERSION
                  ": one cell block per particle, cell data per particle (particle_id from 1)",
       .points = points,
       .cells = cells,
       .point_coordinates = point_coordinates,
       .cell_arrays = cell_arrays,
       .cell_data = cell_data,
       .scalars = "particle_id"},
      out);
}

}  // namespace aggpack::detail
