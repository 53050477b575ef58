// Abaqus / CalculiX input file (.inp): nodes, C3D4 or C3D10 elements, per-particle node and element
// sets and an element-face surface, one material and solid section. Two layouts: a flat model
// with sets (what CalculiX reads) or one part + instance per particle (Abaqus/CAE's form).

#include <cstdio>

#include "aggpack/core/error.h"
#include "export_detail.h"

namespace aggpack::detail {

namespace {

constexpr std::uint64_t kMaxAbaqusId = 999999999;  // Abaqus labels are at most 9 digits
constexpr int kSetEntriesPerLine = 16;             // Abaqus reads at most 16 entries a line

const char* element_type(const ExportModel& model) {
  return model.mode() == ElementMode::kQuadraticTetrahedra ? "C3D10" : "C3D4";
}

void append_heading(const ExportModel& model, std::string& out) {
  const Packing& packing = model.packing();
  char line[512];
  std::snprintf(line, sizeof line,
                "*HEADING\naggpack %s packing, %zu particles, packer %s, seed %llu\n"
                "** Written by aggpack. Coordinates in metres times ",
                AGGPACK_VERSION, model.size(),
                packing.provenance.packer.empty() ? "-" : packing.provenance.packer.c_str(),
                static_cast<unsigned long long>(packing.provenance.seed));
  out += line;
  append_number_fitting(out, model.options().scale, kFeNumberWidth);
  out +=
      ". Numbers have at most 20 characters.\n"
      "** Particle i (from 1): node set Pi, element set Pi, surface Pi_SURFACE.\n";
}

// Element lines "id, n1, ..., n4|n10" for particle k, ids from first_element, nodes from
// first_node (both 1-based). `quadratic` is model.quadratic_topology(k).
void append_elements(const ExportModel& model, std::size_t k, const QuadraticTopology& quadratic,
                     std::uint64_t first_node, std::uint64_t first_element, std::string& out) {
  if (model.mode() == ElementMode::kQuadraticTetrahedra) {
    append_element_lines(out, "", ", ", first_element, first_node, quadratic.tetrahedra);
  } else {
    std::vector<Tetrahedron> scratch;
    append_element_lines(out, "", ", ", first_element, first_node, model.tetrahedra(k, scratch));
  }
}

// Node lines "id, x, y, z" for particle k: its linear nodes, then the mid-side nodes of
// `quadratic` (model.quadratic_topology(k), empty for C3D4).
void append_nodes(const ExportModel& model, std::size_t k, const QuadraticTopology& quadratic,
                  std::uint64_t first_node, std::string& out) {
  std::vector<Vec3> nodes;
  model.linear_nodes(k, nodes);
  append_midside_nodes(quadratic, nodes);
  append_node_lines(out, "", ", ", first_node, nodes, kFeNumberWidth);
}

void append_generated_set(const char* keyword, const std::string& name, std::uint64_t first,
                          std::uint64_t last, std::string& out) {
  out += keyword;
  out += name;
  out += ", GENERATE\n";
  append_number(out, first);
  out += ", ";
  append_number(out, last);
  out += ", 1\n";
}

// The particle's outer surface as element faces. A fan's tetrahedra all have their face S1 on the
// surface, so the particle's element set is enough; other meshes get one set per face number.
void append_surface(const ExportModel& model, std::size_t k, const std::string& name,
                    std::uint64_t first_element, std::string& out) {
  if (model.is_fan()) {
    out += "*SURFACE, TYPE=ELEMENT, NAME=" + name + "_SURFACE\n" + name + ", S1\n";
    return;
  }
  const std::vector<std::uint8_t>& boundary_faces = model.boundary_faces(k);
  std::string lines;
  for (int face = 0; face < 4; ++face) {
    std::string ids;
    int on_line = 0;
    for (std::size_t e = 0; e < boundary_faces.size(); ++e) {
      if (((boundary_faces[e] >> face) & 1U) == 0) continue;
      if (on_line == kSetEntriesPerLine) {
        ids += '\n';
        on_line = 0;
      } else if (on_line > 0) {
        ids += ", ";
      }
      append_number(ids, first_element + e);
      ++on_line;
    }
    if (ids.empty()) continue;
    const std::string set_name = name + "_S" + std::to_string(face + 1);
    out += "*ELSET, ELSET=" + set_name + "\n" + ids + "\n";
    lines += set_name + ", S" + std::to_string(face + 1) + "\n";
  }
  out += "*SURFACE, TYPE=ELEMENT, NAME=" + name + "_SURFACE\n" + lines;
}

void append_material(const ExportModel& model, std::string& out) {
  const MaterialOptions& material = model.options().material;
  out += "*MATERIAL, NAME=" + material.name + "\n*DENSITY\n";
  append_number_fitting(out, material.density, kFeNumberWidth);
  out += ",\n*ELASTIC\n";
  append_number_fitting(out, material.youngs_modulus, kFeNumberWidth);
  out += ", ";
  append_number_fitting(out, material.poisson_ratio, kFeNumberWidth);
  out += '\n';
}

void write_element_sets(const ExportModel& model, std::ostream& out) {
  out << "*NODE, NSET=ALLNODES\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    append_nodes(model, k, model.quadratic_topology(k), model.node_offset(k) + 1, buffer);
  });
  const std::string type = element_type(model);
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    buffer += "*ELEMENT, TYPE=";
    buffer += type;
    buffer += ", ELSET=";
    buffer += model.particle_name(k);
    buffer += '\n';
    append_elements(model, k, model.quadratic_topology(k), model.node_offset(k) + 1,
                    model.element_offset(k) + 1, buffer);
  });
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::string name = model.particle_name(k);
    append_generated_set("*NSET, NSET=", name, model.node_offset(k) + 1, model.node_offset(k + 1),
                         buffer);
    append_surface(model, k, name, model.element_offset(k) + 1, buffer);
  });
  std::string tail;
  if (model.element_count() > 0) {
    append_generated_set("*ELSET, ELSET=", "AGGREGATES", 1, model.element_count(), tail);
  } else {
    tail += "*ELSET, ELSET=AGGREGATES\n";
  }
  append_material(model, tail);
  tail += "*SOLID SECTION, ELSET=AGGREGATES, MATERIAL=" + model.options().material.name + "\n";
  out << tail;
}

void write_parts(const ExportModel& model, std::ostream& out) {
  const std::string type = element_type(model);
  const std::string& material = model.options().material.name;
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::string name = model.particle_name(k);
    const QuadraticTopology quadratic = model.quadratic_topology(k);
    buffer += "*PART, NAME=" + name + "\n*NODE\n";
    append_nodes(model, k, quadratic, 1, buffer);
    buffer += "*ELEMENT, TYPE=" + type + ", ELSET=" + name + "\n";
    append_elements(model, k, quadratic, 1, 1, buffer);
    append_generated_set("*NSET, NSET=", name, 1, model.nodes_of(k), buffer);
    buffer += "*SOLID SECTION, ELSET=" + name + ", MATERIAL=" + material + "\n";
    append_surface(model, k, name, 1, buffer);
    buffer += "*END PART\n";
  });
  out << "*ASSEMBLY, NAME=ASSEMBLY\n";
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::string name = model.particle_name(k);
    buffer += "*INSTANCE, NAME=" + name + "-1, PART=" + name + "\n*END INSTANCE\n";
  });
  std::string tail = "*END ASSEMBLY\n";
  append_material(model, tail);
  out << tail;
}

}  // namespace

void write_abaqus(const ExportModel& model, std::ostream& out) {
  require_ids_fit(model, kMaxAbaqusId, "Abaqus");
  std::string heading;
  append_heading(model, heading);
  out << heading;
  if (model.options().abaqus_layout == AbaqusLayout::kPartsInstances) {
    write_parts(model, out);
  } else {
    write_element_sets(model, out);
  }
}

}  // namespace aggpack::detail
