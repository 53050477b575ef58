// ANSYS APDL macro (.mac): /PREP7, one SOLID285 element type (4-node tetrahedron) and material,
// every node as N,id,x,y,z and every tetrahedron as EN,id,i,j,k,l, then one element component
// P<id> and one node component P<id>_N per particle. Run it with /INPUT or as a macro.

#include <cstdio>

#include "export_detail.h"

namespace aggpack::detail {

void write_ansys(const ExportModel& model, std::ostream& out) {
  require_ids_fit(model, 0x7FFFFFFF, "ANSYS");
  const MaterialOptions& material = model.options().material;
  std::string head = "! aggpack " AGGPACK_VERSION " packing, " + std::to_string(model.size()) +
                     " particles (material " + material.name + ")\n";
  char line[160];
  std::snprintf(line, sizeof line, "! coordinates in metres times %.17g\n", model.options().scale);
  head += line;
  head += "/PREP7\nET,1,SOLID285\nMP,EX,1,";
  append_number_fitting(head, material.youngs_modulus, kFeNumberWidth);
  head += "\nMP,PRXY,1,";
  append_number_fitting(head, material.poisson_ratio, kFeNumberWidth);
  head += "\nMP,DENS,1,";
  append_number_fitting(head, material.density, kFeNumberWidth);
  head += "\nTYPE,1\nMAT,1\n";
  out << head;
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Vec3> nodes;
    model.linear_nodes(k, nodes);
    append_node_lines(buffer, "N,", ",", model.node_offset(k) + 1, nodes, kFeNumberWidth);
  });
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    std::vector<Tetrahedron> scratch;
    append_element_lines(buffer, "EN,", ",", model.element_offset(k) + 1, model.node_offset(k) + 1,
                         model.tetrahedra(k, scratch));
  });
  stream_items(model.size(), out, [&](std::size_t k, std::string& buffer) {
    const std::string name = model.particle_name(k);
    buffer += "ESEL,S,ELEM,,";
    append_number(buffer, model.element_offset(k) + 1);
    buffer += ',';
    append_number(buffer, model.element_offset(k + 1));
    buffer += "\nCM," + name + ",ELEM\nNSEL,S,NODE,,";
    append_number(buffer, model.node_offset(k) + 1);
    buffer += ',';
    append_number(buffer, model.node_offset(k + 1));
    buffer += "\nCM," + name + "_N,NODE\n";
  });
  out << "ALLSEL,ALL\n";
}

}  // namespace aggpack::detail
