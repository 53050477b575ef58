// The mesomodel as Gmsh MSH 4.1 ASCII (io/mesomodel_files.h). One volume entity per element group
// of MesoLayout - entity k is aggregate k, entity n + k the ITZ of particle k, entity 2n + 1 the
// mortar - each in the physical group of its phase: 1 "MORTAR", 2 "ITZ", 3 "AGGREGATE"
// (MesoPhase code + 1). A node is listed under the entity of the first element that uses it.
// A cohesive ITZ's wedges are Gmsh prisms (type 6; nodes 1-3 the aggregate side, 4-6 the mortar
// side, Gmsh's order like Abaqus's), of zero volume.

#include <algorithm>
#include <limits>

#include "export_detail.h"
#include "mesomodel_detail.h"

namespace aggpack {

namespace {

using detail::append_number;

constexpr int kGmshTetrahedron = 4;
constexpr int kGmshPrism = 6;
constexpr std::uint32_t kUnassigned = std::numeric_limits<std::uint32_t>::max();

void append_point(std::string& out, const Vec3& point, double scale) {
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0) out += ' ';
    append_number(out, point[axis] * scale);  // exact when scale is 1
  }
}

}  // namespace

MesoFileSummary write_mesomodel_msh(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options) {
  validate(options);
  if (options.is_quadratic) throw InvalidInput("quadratic", "true for .msh", ".inp only (C3D10)");
  validate(mesh);
  check_writable(path, options.overwrite);
  const detail::MesoLayout layout = detail::make_layout(mesh);
  const double scale = length_scale(options.units);
  const std::size_t groups = layout.group_count();
  // Each node's entity (group), its blocks, and each group's bounding box.
  std::vector<std::uint32_t> node_group(mesh.nodes.size(), kUnassigned);
  std::vector<Aabb> boxes(groups);
  std::size_t last_group = 0;
  for (std::size_t g = 0; g < groups; ++g) {
    if (layout.group_size(g) > 0) last_group = g;
    for (std::uint64_t e = layout.group_offsets[g]; e < layout.group_offsets[g + 1]; ++e) {
      for (const std::uint32_t node : detail::element_nodes(mesh, layout.order[e])) {
        boxes[g].expand(mesh.nodes[node]);
        if (node_group[node] == kUnassigned) node_group[node] = static_cast<std::uint32_t>(g);
      }
    }
  }
  std::vector<std::uint64_t> node_offsets(groups + 1, 0);
  for (std::uint32_t& g : node_group) {
    if (g == kUnassigned) g = static_cast<std::uint32_t>(last_group);  // unused nodes
    ++node_offsets[g + 1];
  }
  for (std::size_t g = 0; g < groups; ++g) node_offsets[g + 1] += node_offsets[g];
  std::vector<std::uint32_t> node_order(mesh.nodes.size());
  {
    std::vector<std::uint64_t> next(node_offsets.begin(), node_offsets.end() - 1);
    for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
      node_order[next[node_group[n]]++] = static_cast<std::uint32_t>(n);
    }
  }
  std::size_t entities = 0;
  std::size_t node_blocks = 0;
  for (std::size_t g = 0; g < groups; ++g) {
    if (layout.group_size(g) > 0) ++entities;
    if (node_offsets[g + 1] > node_offsets[g]) ++node_blocks;
  }

  detail::write_atomically(path, options.overwrite, [&](std::ostream& out) {
    std::string text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n";
    std::string names;
    int physical_count = 0;
    for (const MesoPhase phase : {MesoPhase::kMortar, MesoPhase::kItz, MesoPhase::kAggregate}) {
      if (layout.phase_begin(phase) == layout.phase_end(phase)) continue;
      ++physical_count;
      names += "3 " + std::to_string(static_cast<int>(phase) + 1) + " \"" + phase_set_name(phase) +
               "\"\n";
    }
    text += std::to_string(physical_count) + "\n" + names;
    text += "$EndPhysicalNames\n$Entities\n0 0 0 " + std::to_string(entities) + "\n";
    for (std::size_t g = 0; g < groups; ++g) {
      if (layout.group_size(g) == 0) continue;
      append_number(text, static_cast<std::uint64_t>(g + 1));
      text += ' ';
      append_point(text, boxes[g].lower, scale);
      text += ' ';
      append_point(text, boxes[g].upper, scale);
      text += " 1 " + std::to_string(static_cast<int>(layout.group_phase(g)) + 1) + " 0\n";
    }
    text += "$EndEntities\n$Nodes\n" + std::to_string(node_blocks) + ' ' +
            std::to_string(mesh.nodes.size()) + " 1 " + std::to_string(mesh.nodes.size()) + '\n';
    out << text;
    for (std::size_t g = 0; g < groups; ++g) {
      const std::uint64_t begin = node_offsets[g];
      const std::uint64_t end = node_offsets[g + 1];
      if (begin == end) continue;
      // A block's entity must exist: a group without elements holds no nodes (unused nodes go to
      // the last group with elements).
      out << "3 " << (g + 1) << " 0 " << (end - begin) << '\n';
      detail::stream_items(end - begin, out, [&](std::size_t i, std::string& buffer) {
        append_number(buffer, static_cast<std::uint64_t>(node_order[begin + i]) + 1);
        buffer += '\n';
      });
      detail::stream_items(end - begin, out, [&](std::size_t i, std::string& buffer) {
        append_point(buffer, mesh.nodes[node_order[begin + i]], scale);
        buffer += '\n';
      });
    }
    const std::size_t elements = layout.order.size();
    out << "$EndNodes\n$Elements\n" << entities << ' ' << elements << " 1 " << elements << '\n';
    for (std::size_t g = 0; g < groups; ++g) {
      const std::uint64_t begin = layout.group_offsets[g];
      const std::uint64_t end = layout.group_offsets[g + 1];
      if (begin == end) continue;
      const int type = layout.is_cohesive_group(g) ? kGmshPrism : kGmshTetrahedron;
      out << "3 " << (g + 1) << ' ' << type << ' ' << (end - begin) << '\n';
      detail::stream_items(end - begin, out, [&](std::size_t i, std::string& buffer) {
        append_number(buffer, begin + i + 1);
        for (const std::uint32_t node : detail::element_nodes(mesh, layout.order[begin + i])) {
          buffer += ' ';
          append_number(buffer, static_cast<std::uint64_t>(node) + 1);
        }
        buffer += '\n';
      });
    }
    out << "$EndElements\n";
  });
  return {
      .format = ExportFormat::kGmsh, .nodes = mesh.nodes.size(), .elements = layout.order.size()};
}

}  // namespace aggpack
