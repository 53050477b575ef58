// LS-DYNA keyword file (.k): one elastic material, one solid section (ELFORM 10, 1-point
// tetrahedron), one *PART per particle, *NODE and *ELEMENT_SOLID in the classic fixed columns
// (ids 8 wide, coordinates 16 wide). A tetrahedron is written as a degenerate solid: n1 n2 n3 n4
// n4 n4 n4 n4, LS-DYNA's convention.

#include <cstdio>

#include "export_detail.h"

namespace aggpack::detail {

namespace {

constexpr std::uint64_t kMaxDynaId = 99999999;  // 8-column id fields
constexpr int kDynaCardWidth = 10;              // columns of a standard keyword card field

}  // namespace

void write_lsdyna_mesh(const ExportModel& model, std::ostream& out, const std::string& comments) {
  require_ids_fit(model, kMaxDynaId, "LS-DYNA");
  const MaterialOptions& material = model.options().material;
  std::string head = "*KEYWORD\n" + comments + "*TITLE\naggpack " AGGPACK_VERSION " packing, ";
  head += std::to_string(model.size()) + " particles\n";
  char line[160];
  std::snprintf(line, sizeof line, "$ coordinates in metres times %.17g; part i = particle i\n",
                model.options().scale);
  head += line;
  head += "*MAT_ELASTIC_TITLE\n" + material.name + "\n$#     mid        ro         e        pr\n";
  // Free format (comma separated); a field may not be wider than its fixed column (10).
  head += "1,";
  append_number_fitting(head, material.density, kDynaCardWidth);
  head += ',';
  append_number_fitting(head, material.youngs_modulus, kDynaCardWidth);
  head += ',';
  append_number_fitting(head, material.poisson_ratio, kDynaCardWidth);
  head += "\n*SECTION_SOLID\n$#   secid    elform\n         1        10\n";
  out << head;
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    buffer += "*PART\nP" + std::to_string(model.particle_number(k)) + '\n';
    append_field(buffer, static_cast<std::uint64_t>(model.particle_number(k)), 10);
    buffer += "         1         1\n";
  });
  out << "*NODE\n$#   nid               x               y               z      tc      rc\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    std::uint64_t id = model.node_offset(k) + 1;
    for (const Vec3& node : nodes) {
      append_field(buffer, id++, 8);
      for (int axis = 0; axis < 3; ++axis) append_field(buffer, node[axis], 16);
      buffer += "       0       0\n";
    }
  });
  out << "*ELEMENT_SOLID\n"
         "$#   eid     pid      n1      n2      n3      n4      n5      n6      n7      n8\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Tetrahedron> scratch;
    const std::uint64_t first_node = model.node_offset(k) + 1;
    const auto part = static_cast<std::uint64_t>(model.particle_number(k));
    std::uint64_t id = model.element_offset(k) + 1;
    for (const auto& t : model.tetrahedra(k, scratch)) {
      append_field(buffer, id++, 8);
      append_field(buffer, part, 8);
      for (int n = 0; n < 8; ++n) append_field(buffer, first_node + t[std::min(n, 3)], 8);
      buffer += '\n';
    }
  });
}

void write_lsdyna(const ExportModel& model, std::ostream& out) {
  write_lsdyna_mesh(model, out, "");
  out << "*END\n";
}

}  // namespace aggpack::detail
