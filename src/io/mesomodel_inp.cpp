// The mesomodel as an Abaqus / CalculiX input file (io/mesomodel_files.h): a flat model (no parts)
// that ccx and Abaqus/Standard both read. Elements are written group by group (MesoLayout), so
// every element set is one GENERATE range.

#include <algorithm>
#include <cstdio>

#include "export_detail.h"
#include "mesomodel_detail.h"

namespace aggpack {

namespace {

using detail::append_number;

constexpr int kSetEntriesPerLine = 16;  // Abaqus reads at most 16 entries a line
constexpr std::size_t kChunk = 512;     // nodes or elements formatted per parallel item

void append_real(std::string& out, double value) {
  append_number_fitting(out, value, kFeNumberWidth);
}

void append_generated_set(const std::string& name, std::uint64_t first, std::uint64_t last,
                          std::string& out) {
  out += "*ELSET, ELSET=" + name + ", GENERATE\n";
  append_number(out, first);
  out += ", ";
  append_number(out, last);
  out += ", 1\n";
}

// Boundary triangles of the mesh: faces of exactly one tetrahedron (sorted node triples).
std::vector<std::array<std::uint32_t, 3>> boundary_triangles(const std::vector<Tetrahedron>& tets) {
  std::vector<std::array<std::uint32_t, 3>> faces;
  faces.reserve(4 * tets.size());
  for (const Tetrahedron& t : tets) {
    for (const auto& f : kTetraFaces) {
      std::array<std::uint32_t, 3> face = {t[f[0]], t[f[1]], t[f[2]]};
      std::sort(face.begin(), face.end());
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<std::uint32_t, 3>> boundary;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j] == faces[i]) ++j;
    if (j - i == 1) boundary.push_back(faces[i]);
    i = j;
  }
  return boundary;
}

// Node sets BOTTOM, TOP and SIDES (index = SpecimenFace code): face_nodes(), and for C3D10 the
// mid-side node of every edge of a boundary triangle on that face. A boundary triangle lies on
// the bottom when its three corners do, on the top likewise, else on a side facet (a triangle
// with its corners on two side facets - across a corner of the bottom, say - is not on a side).
std::array<std::vector<std::uint32_t>, 3> face_node_sets(const MesoMesh& mesh,
                                                         const std::vector<Tetrahedron>& tets,
                                                         const QuadraticTopology& quadratic) {
  std::array<std::vector<std::uint32_t>, 3> sets;
  for (const SpecimenFace face : {SpecimenFace::kBottom, SpecimenFace::kTop, SpecimenFace::kSide}) {
    sets[static_cast<int>(face)] = face_nodes(mesh, face);
  }
  if (quadratic.midside_edges.empty()) return sets;
  auto is_in = [](const std::vector<std::uint32_t>& set, std::uint32_t node) {
    return std::binary_search(set.begin(), set.end(), node);
  };
  std::array<std::vector<std::array<std::uint32_t, 2>>, 3> face_edges;
  for (const auto& t : boundary_triangles(tets)) {
    int face = static_cast<int>(SpecimenFace::kSide);
    for (const SpecimenFace flat : {SpecimenFace::kBottom, SpecimenFace::kTop}) {
      const auto& set = sets[static_cast<int>(flat)];
      if (is_in(set, t[0]) && is_in(set, t[1]) && is_in(set, t[2])) face = static_cast<int>(flat);
    }
    face_edges[face].push_back({t[0], t[1]});
    face_edges[face].push_back({t[0], t[2]});
    face_edges[face].push_back({t[1], t[2]});
  }
  const auto corner_count = static_cast<std::uint32_t>(mesh.nodes.size());
  for (int face = 0; face < 3; ++face) {
    auto& edges = face_edges[face];
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (std::size_t e = 0; e < quadratic.midside_edges.size(); ++e) {
      std::array<std::uint32_t, 2> edge = quadratic.midside_edges[e];
      if (edge[0] > edge[1]) std::swap(edge[0], edge[1]);
      if (std::binary_search(edges.begin(), edges.end(), edge)) {
        sets[face].push_back(corner_count + static_cast<std::uint32_t>(e));
      }
    }
  }
  return sets;  // still sorted: mid-side nodes follow the corners, in edge order
}

void append_heading(const MesoMesh& mesh, const MesoFileOptions& options, const char* type,
                    std::uint64_t nodes, std::string& out) {
  char line[512];
  std::snprintf(line, sizeof line,
                "*HEADING\naggpack %s concrete mesomodel: %u aggregates, %zu %s elements%s%s%s, "
                "%llu nodes\n",
                AGGPACK_VERSION, mesh.particle_count, mesh.tetrahedra.size(), type,
                mesh.cohesive.empty() ? "" : " and ",
                mesh.cohesive.empty() ? "" : std::to_string(mesh.cohesive.size()).c_str(),
                mesh.cohesive.empty() ? "" : " COH3D6 cohesive ITZ elements",
                static_cast<unsigned long long>(nodes));
  out += line;
  const bool is_mm = options.units == MesoUnits::kMillimetre;
  out += is_mm ? "** Written by aggpack (docs/mesomodel.md). Units: mm, N, t, s, MPa. ITZ "
               : "** Written by aggpack (docs/mesomodel.md). Units: m, N, kg, s, Pa. ITZ ";
  out += mesh.cohesive.empty() ? "thickness " : "constitutive thickness ";
  append_real(out, mesh.itz_thickness * length_scale(options.units));
  out += is_mm ? " mm.\n" : " m.\n";
  if (!mesh.cohesive.empty()) {
    out +=
        "** The ITZ is zero-thickness COH3D6 elements on every aggregate surface (nodes 1-3 on\n"
        "** the aggregate, 4-6 their copies on the mortar), traction-separation response with\n"
        "** K_nn = E_ITZ and K_ss = K_tt = G_ITZ over the constitutive thickness above.\n";
  }
  out += "** Element sets: AGGREGATE, ITZ (when the mesh has an ITZ), MORTAR";
  if (options.has_particle_sets) out += "; per particle k (from 1) AGG<k> and ITZ<k>";
  out +=
      ".\n"
      "** Elements are numbered aggregates first (particle by particle), then the ITZ shells,\n"
      "** then the mortar. Node sets: ALLNODES, BOTTOM (z min), TOP (z max), SIDES.\n"
      "** One material and solid section per phase (MAT_AGGREGATE, MAT_ITZ, MAT_MORTAR).\n";
  if (options.step.strain > 0.0 && !(mesh.periodic[0] || mesh.periodic[1] || mesh.periodic[2])) {
    out +=
        "** Step: uniaxial compression, BOTTOM held in z, TOP moved by -strain x height in z,\n"
        "** sides free; effective E = (sum of RF3 over TOP / top area) / strain.\n";
  }
}

// Materials in the file's units: E / s^2 (N per length unit squared), rho / s^4 (the mass unit
// that keeps F = m a in N: kg x s), s being the length scale.
// A cohesive ITZ's material is a traction-separation law whose nominal strain is the opening
// over the constitutive thickness T0 (*COHESIVE SECTION, THICKNESS=SPECIFIED): with T0 the ITZ
// thickness, K_nn = E and K_ss = K_tt = G = E / (2 (1 + nu)) make the wedge as stiff as a layer
// of that thickness loaded across it (normal) or along it (shear), and its mass density x T0 x
// area that of the layer.
void append_materials(const MesoMaterials& materials, double scale, const MesoMesh& mesh,
                      const detail::MesoLayout& layout, std::string& out) {
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    if (layout.phase_begin(phase) == layout.phase_end(phase)) continue;  // no such elements
    const std::string name = phase_set_name(phase);
    const PhaseMaterial& material = materials.of(phase);
    const double modulus = material.youngs_modulus / (scale * scale);
    const bool is_cohesive = phase == MesoPhase::kItz && layout.is_cohesive;
    out += "*MATERIAL, NAME=MAT_" + name +
           (is_cohesive ? "\n*ELASTIC, TYPE=TRACTION\n" : "\n*ELASTIC\n");
    append_real(out, modulus);
    out += ", ";
    if (is_cohesive) {
      const double shear = modulus / (2.0 * (1.0 + material.poisson_ratio));
      append_real(out, shear);
      out += ", ";
      append_real(out, shear);
    } else {
      append_real(out, material.poisson_ratio);
    }
    out += "\n*DENSITY\n";
    append_real(out, material.density / (scale * scale * scale * scale));
    if (is_cohesive) {
      out += ",\n*COHESIVE SECTION, ELSET=" + name + ", MATERIAL=MAT_" + name +
             ", RESPONSE=TRACTION SEPARATION, THICKNESS=SPECIFIED\n";
      append_real(out, mesh.itz_thickness * scale);
      out += ",\n";
    } else {
      out += ",\n*SOLID SECTION, ELSET=" + name + ", MATERIAL=MAT_" + name + "\n";
    }
  }
}

// Bottom nodes A and B that, held in x and y (A) and in y (B), remove the rigid motions in x, y
// and about z and nothing else (three scalar constraints on three rigid modes): A is the bottom
// node with the smallest (y, x), B the one farthest from A in x (then closest in y).
std::array<std::uint32_t, 2> anchor_nodes(const MesoMesh& mesh,
                                          const std::vector<std::uint32_t>& bottom_nodes) {
  // Corner nodes only (the mid-side nodes of C3D10, numbered after them, are not in mesh.nodes).
  const auto corners = static_cast<long>(
      std::lower_bound(bottom_nodes.begin(), bottom_nodes.end(), mesh.nodes.size()) -
      bottom_nodes.begin());
  const std::vector<std::uint32_t> bottom(bottom_nodes.begin(), bottom_nodes.begin() + corners);
  if (bottom.size() < 2) {
    throw InvalidInput("mesh bottom face", std::to_string(bottom.size()) + " nodes",
                       "at least 2 nodes (for the compression step)");
  }
  auto key = [&](std::uint32_t n) { return std::pair(mesh.nodes[n].y(), mesh.nodes[n].x()); };
  const std::uint32_t a =
      *std::min_element(bottom.begin(), bottom.end(),
                        [&](std::uint32_t p, std::uint32_t q) { return key(p) < key(q); });
  const Vec3& pa = mesh.nodes[a];
  auto score = [&](std::uint32_t n) {
    return std::pair(std::abs(mesh.nodes[n].x() - pa.x()), -std::abs(mesh.nodes[n].y() - pa.y()));
  };
  const std::uint32_t b =
      *std::max_element(bottom.begin(), bottom.end(),
                        [&](std::uint32_t p, std::uint32_t q) { return score(p) < score(q); });
  if (!(std::abs(mesh.nodes[b].x() - pa.x()) > 0.0)) {
    throw InvalidInput("mesh bottom face", "all nodes at x = " + format_value(pa.x()),
                       "nodes spread in x (for the compression step)");
  }
  return {a, b};
}

void append_step(const MesoMesh& mesh, const CompressionStep& step, double scale, MesoSolver solver,
                 const std::vector<std::uint32_t>& bottom, std::string& out) {
  const auto [a, b] = anchor_nodes(mesh, bottom);
  const double height = (mesh.bounds.upper.z() - mesh.bounds.lower.z()) * scale;
  out += "*BOUNDARY\nBOTTOM, 3, 3, 0.\n";
  append_number(out, static_cast<std::uint64_t>(a) + 1);
  out += ", 1, 2, 0.\n";
  append_number(out, static_cast<std::uint64_t>(b) + 1);
  out += ", 2, 2, 0.\n*STEP\n";
  out += detail::static_line(solver);
  out += "*BOUNDARY\nTOP, 3, 3, ";
  append_real(out, -step.strain * height);
  out += "\n*NODE PRINT, NSET=TOP, TOTALS=YES\nRF\n*NODE FILE\nU, RF\n*EL FILE\nS, E\n*END STEP\n";
}

}  // namespace

const char* detail::static_line(MesoSolver solver) {
  return solver == MesoSolver::kIterative ? "*STATIC, SOLVER=ITERATIVE CHOLESKY\n" : "*STATIC\n";
}

void detail::append_node_set(const std::string& name, const std::vector<std::uint32_t>& nodes,
                             std::string& out) {
  out += "*NSET, NSET=" + name + "\n";
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    append_number(out, static_cast<std::uint64_t>(nodes[i]) + 1);
    out += (i + 1) % kSetEntriesPerLine == 0 || i + 1 == nodes.size() ? ",\n" : ", ";
  }
}

MesoFileSummary write_mesomodel_inp(const std::string& path, const MesoMesh& mesh,
                                    const MesoFileOptions& options) {
  validate(options);
  validate(mesh);
  if (options.is_quadratic && !mesh.cohesive.empty()) {
    throw InvalidInput("quadratic", "true with a cohesive ITZ",
                       "linear elements (COH3D6 joins the faces of C3D4, not of C3D10)");
  }
  if (options.is_quadratic && (mesh.periodic[0] || mesh.periodic[1] || mesh.periodic[2])) {
    throw InvalidInput("quadratic", "true with container.periodic",
                       Wording{Sentence::kPeriodicLinear, {}});
  }
  check_writable(path, options.overwrite);
  const detail::MesoLayout layout = detail::make_layout(mesh);
  // C3D10 (no cohesive elements then): the tetrahedra in layout order, with mid-side nodes.
  std::vector<Tetrahedron> tets;
  QuadraticTopology quadratic;
  std::vector<Vec3> nodes = mesh.nodes;
  if (options.is_quadratic) {
    tets.resize(mesh.tetrahedra.size());
    for (std::size_t i = 0; i < tets.size(); ++i) tets[i] = mesh.tetrahedra[layout.order[i]];
    quadratic = quadratic_topology(tets, static_cast<std::uint32_t>(mesh.nodes.size()));
    append_midside_nodes(quadratic, nodes);
  }
  if (options.units != MesoUnits::kMetre) {
    for (Vec3& node : nodes) node *= length_scale(options.units);
  }
  const char* type = options.is_quadratic ? "C3D10" : "C3D4";
  const auto face_sets = face_node_sets(mesh, tets, quadratic);
  const std::vector<std::uint32_t>& bottom = face_sets[static_cast<int>(SpecimenFace::kBottom)];
  std::string tail;  // everything after the elements; built first so that bad input writes nothing
  auto element_set_name = [&](std::size_t g) {
    const MesoPhase phase = layout.group_phase(g);
    if (phase == MesoPhase::kMortar || !options.has_particle_sets) {
      return std::string(phase_set_name(phase));
    }
    return std::string(phase == MesoPhase::kAggregate ? "AGG" : "ITZ") +
           std::to_string(layout.group_particle(g));
  };
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz}) {
    const std::uint64_t begin = layout.phase_begin(phase);
    const std::uint64_t end = layout.phase_end(phase);
    if (begin == end || !options.has_particle_sets) continue;  // none, or named on *ELEMENT
    append_generated_set(phase_set_name(phase), begin + 1, end, tail);
  }
  using detail::append_node_set;
  append_node_set("BOTTOM", bottom, tail);
  append_node_set("TOP", face_sets[static_cast<int>(SpecimenFace::kTop)], tail);
  append_node_set("SIDES", face_sets[static_cast<int>(SpecimenFace::kSide)], tail);
  const double scale = length_scale(options.units);
  append_materials(options.materials, scale, mesh, layout, tail);
  const bool is_periodic_mesh = mesh.periodic[0] || mesh.periodic[1] || mesh.periodic[2];
  std::string periodic_heading;
  if (is_periodic_mesh) {
    // The load cases' strain: --strain, else 1e-3 (linear elastic: any size gives the tensor).
    const double strain = options.step.strain > 0.0 ? options.step.strain : 1e-3;
    detail::append_periodic_model(mesh, nodes.size(), scale, strain, options.solver,
                                  periodic_heading, tail);
  } else if (options.step.strain > 0.0) {
    append_step(mesh, options.step, scale, options.solver, bottom, tail);
  }

  detail::write_atomically(path, options.overwrite, [&](std::ostream& out) {
    std::string head;
    append_heading(mesh, options, type, nodes.size(), head);
    head += periodic_heading;
    head += "*NODE, NSET=ALLNODES\n";
    out << head;
    const std::size_t node_chunks = (nodes.size() + kChunk - 1) / kChunk;
    detail::stream_items(node_chunks, out, [&](std::size_t c, std::string& buffer) {
      const std::size_t first = c * kChunk;
      const std::size_t last = std::min(nodes.size(), first + kChunk);
      const std::vector<Vec3> chunk(nodes.begin() + static_cast<long>(first),
                                    nodes.begin() + static_cast<long>(last));
      detail::append_node_lines(buffer, "", ", ", first + 1, chunk, kFeNumberWidth);
    });
    for (std::size_t g = 0; g < layout.group_count(); ++g) {
      const std::uint64_t begin = layout.group_offsets[g];
      const std::uint64_t end = layout.group_offsets[g + 1];
      if (begin == end) continue;
      out << "*ELEMENT, TYPE=" << (layout.is_cohesive_group(g) ? "COH3D6" : type)
          << ", ELSET=" << element_set_name(g) << '\n';
      const std::size_t chunks = (end - begin + kChunk - 1) / kChunk;
      detail::stream_items(chunks, out, [&](std::size_t c, std::string& buffer) {
        const std::uint64_t first = begin + c * kChunk;
        const std::uint64_t last = std::min<std::uint64_t>(end, first + kChunk);
        for (std::uint64_t e = first; e < last; ++e) {
          append_number(buffer, e + 1);
          auto append_nodes = [&](const auto& element) {
            for (const std::uint32_t node : element) {
              buffer += ", ";
              append_number(buffer, static_cast<std::uint64_t>(node) + 1);
            }
          };
          if (options.is_quadratic) {
            append_nodes(quadratic.tetrahedra[e]);
          } else {
            append_nodes(detail::element_nodes(mesh, layout.order[e]));
          }
          buffer += '\n';
        }
      });
    }
    out << tail;
  });
  return {.format = ExportFormat::kAbaqus,
          .nodes = nodes.size() + (is_periodic_mesh ? 3 : 0),  // + the reference nodes
          .elements = layout.order.size()};
}

}  // namespace aggpack
