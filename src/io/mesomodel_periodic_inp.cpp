// The periodic part of a periodic mesomodel's .inp (mesomodel_detail.h): face node sets, one
// reference node per periodic axis, *EQUATION ties and the six load cases of homogenisation.

#include <cstdio>
#include <sstream>
#include <string>

#include "export_detail.h"
#include "mesomodel_detail.h"

namespace aggpack::detail {

namespace {

void append_fe_real(std::string& out, double value) {
  append_number_fitting(out, value, kFeNumberWidth);
}

// Load case k (Voigt order 11, 22, 33, 23, 13, 12): the macroscopic strain, engineering shear
// `strain` for k >= 3 (so half of it in each off-diagonal entry).
std::array<std::array<double, 3>, 3> load_case_strain(int k, double strain) {
  std::array<std::array<double, 3>, 3> e{};
  constexpr std::array<std::array<int, 2>, 6> kVoigt{
      {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  const auto [i, j] = kVoigt[static_cast<std::size_t>(k)];
  const double value = k < 3 ? strain : 0.5 * strain;
  e[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = value;
  e[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)] = value;
  return e;
}

}  // namespace

void append_periodic_model(const MesoMesh& mesh, std::uint64_t written_nodes, double scale,
                           double strain, MesoSolver solver, std::string& heading,
                           std::string& out) {
  const std::vector<PeriodicPair> pairs = periodic_pairs(mesh);
  const Vec3 extent = mesh.bounds.extent();
  const bool is_full = mesh.periodic[0] && mesh.periodic[1] && mesh.periodic[2];
  constexpr std::array<const char*, 3> kAxis{"X", "Y", "Z"};
  heading +=
      "** Periodic box (docs/mesomodel.md, \"Periodic RVE\"): node sets XMIN/XMAX, YMIN/YMAX,\n"
      "** ZMIN/ZMAX of the periodic faces; reference nodes REF_X, REF_Y, REF_Z (set REFS), one "
      "per\n"
      "** periodic axis a, whose displacement is the box's macroscopic displacement over one\n"
      "** period L_a: u(node on an upper face) = u(its image on the lower faces) + the sum of\n"
      "** u(REF_a) over the faces it was moved across (*EQUATION, the upper node dependent).\n";
  if (is_full) {
    heading +=
        "** Six steps: macroscopic strains 11, 22, 33, 23, 13, 12 (engineering shear) of the "
        "value\n"
        "** below, u(REF_a)_i = strain_ia L_a; the node at the origin is held. Every node of\n"
        "** XMAX is tied to REF_X, so the total of RF over XMAX is REF_X's reaction F_X (CalculiX\n"
        "** gives no reaction at a node without elements; Abaqus gives it at REF_X too). Column k\n"
        "** of the stiffness: sigma_ij = F_j,i L_j / V = F_j,i / area of face j, over the "
        "strain.\n";
  }
  const std::uint64_t ref_first = written_nodes + 1;
  out += "*NODE, NSET=REFS\n";
  for (int axis = 0; axis < 3; ++axis) {
    append_number(out, ref_first + static_cast<std::uint64_t>(axis));
    for (int c = 0; c < 3; ++c) {
      out += ", ";
      append_fe_real(out, scale * (mesh.bounds.upper[c] + (c == axis ? 0.1 * extent[c] : 0.0)));
    }
    out += '\n';
  }
  for (int axis = 0; axis < 3; ++axis) {
    out += "*NSET, NSET=REF_" + std::string(kAxis[static_cast<std::size_t>(axis)]) + "\n";
    append_number(out, ref_first + static_cast<std::uint64_t>(axis));
    out += ",\n";
    if (!mesh.periodic[static_cast<std::size_t>(axis)]) continue;
    for (int side = 0; side < 2; ++side) {
      const double at = side == 0 ? mesh.bounds.lower[axis] : mesh.bounds.upper[axis];
      std::vector<std::uint32_t> nodes;
      for (std::uint32_t i = 0; i < mesh.nodes.size(); ++i) {
        if (mesh.nodes[i][axis] == at) nodes.push_back(i);
      }
      append_node_set(
          kAxis[static_cast<std::size_t>(axis)] + std::string(side == 0 ? "MIN" : "MAX"), nodes,
          out);
    }
  }
  out += "*EQUATION\n";
  for (const PeriodicPair& pair : pairs) {
    for (int dof = 1; dof <= 3; ++dof) {
      std::vector<std::pair<std::uint64_t, const char*>> terms{
          {static_cast<std::uint64_t>(pair.node) + 1, "1."},
          {static_cast<std::uint64_t>(pair.image) + 1, "-1."}};
      for (int axis = 0; axis < 3; ++axis) {
        if (pair.shifted[static_cast<std::size_t>(axis)]) {
          terms.emplace_back(ref_first + static_cast<std::uint64_t>(axis), "-1.");
        }
      }
      append_number(out, terms.size());
      out += '\n';
      for (std::size_t t = 0; t < terms.size(); ++t) {  // at most 4 terms (12 entries) a line
        append_number(out, terms[t].first);
        out += ", " + std::to_string(dof) + ", " + terms[t].second;
        out += (t + 1) % 4 == 0 || t + 1 == terms.size() ? "\n" : ", ";
      }
    }
  }
  if (!is_full) return;
  std::uint32_t origin = 0;
  for (std::uint32_t i = 0; i < mesh.nodes.size(); ++i) {
    if (mesh.nodes[i] == mesh.bounds.lower) origin = i;
  }
  out += "*BOUNDARY\n";
  append_number(out, static_cast<std::uint64_t>(origin) + 1);
  out += ", 1, 3, 0.\n";
  for (int k = 0; k < 6; ++k) {
    const auto e = load_case_strain(k, strain);
    out += "*STEP\n";
    out += static_line(solver);
    out += "*BOUNDARY\n";
    for (int axis = 0; axis < 3; ++axis) {
      for (int i = 0; i < 3; ++i) {
        append_number(out, ref_first + static_cast<std::uint64_t>(axis));
        out += ", " + std::to_string(i + 1) + ", " + std::to_string(i + 1) + ", ";
        append_fe_real(out, e[static_cast<std::size_t>(i)][static_cast<std::size_t>(axis)] *
                                extent[axis] * scale);
        out += '\n';
      }
    }
    for (const char* face : {"XMAX", "YMAX", "ZMAX"}) {
      out += "*NODE PRINT, NSET=" + std::string(face) + ", TOTALS=ONLY\nRF\n";
    }
    out += "*END STEP\n";
  }
}

}  // namespace aggpack::detail

namespace aggpack {

VoigtStiffness periodic_stiffness_from_dat(const std::string& dat, const MesoMesh& mesh,
                                           const MesoFileOptions& options) {
  const double strain = options.step.strain > 0.0 ? options.step.strain : 1e-3;
  const double scale = length_scale(options.units);
  const double stress_unit = options.units == MesoUnits::kMillimetre ? 1e6 : 1.0;  // MPa -> Pa
  const Vec3 extent = mesh.bounds.extent() * scale;
  // force[step][face][component], from "total force (fx,fy,fz) for set XMAX and time  0.1E+01".
  std::array<std::array<std::array<double, 3>, 3>, 6> force{};
  std::array<std::array<bool, 3>, 6> is_found{};
  std::istringstream in(dat);
  std::string line;
  int face = -1;
  int step = -1;
  while (std::getline(in, line)) {
    const std::size_t at = line.find("total force (fx,fy,fz) for set ");
    if (at != std::string::npos) {
      const std::string rest = line.substr(at + 31);
      face = rest.rfind("XMAX", 0) == 0   ? 0
             : rest.rfind("YMAX", 0) == 0 ? 1
             : rest.rfind("ZMAX", 0) == 0 ? 2
                                          : -1;
      const std::size_t time = rest.find("time");
      step = time == std::string::npos
                 ? -1
                 : static_cast<int>(std::lround(std::atof(rest.c_str() + time + 4))) - 1;
      continue;
    }
    std::array<double, 3> f{};
    if (face >= 0 && step >= 0 && step < 6 && (std::istringstream(line) >> f[0] >> f[1] >> f[2])) {
      force[static_cast<std::size_t>(step)][static_cast<std::size_t>(face)] = f;
      is_found[static_cast<std::size_t>(step)][static_cast<std::size_t>(face)] = true;
      face = -1;
    }
  }
  constexpr std::array<std::array<int, 2>, 6> kVoigt{
      {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  VoigtStiffness stiffness{};
  for (int k = 0; k < 6; ++k) {
    for (int f = 0; f < 3; ++f) {
      if (!is_found[static_cast<std::size_t>(k)][static_cast<std::size_t>(f)]) {
        throw InvalidInput(Wording{Sentence::kText, {"dat"}},
                           Wording{Sentence::kDatStepSet,
                                   {std::to_string(k + 1), std::string(1, "XYZ"[f]) + "MAX"}},
                           Wording{Sentence::kPeriodicDatTotals, {}});
      }
    }
    // sigma_ij = F_j,i / area of face j
    const auto stress = [&](int i, int j) {
      const double area = extent.prod() / extent[j];
      return force[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)]
                  [static_cast<std::size_t>(i)] /
             area;
    };
    for (int row = 0; row < 6; ++row) {
      const auto [i, j] = kVoigt[static_cast<std::size_t>(row)];
      stiffness[static_cast<std::size_t>(row)][static_cast<std::size_t>(k)] =
          0.5 * (stress(i, j) + stress(j, i)) * stress_unit / strain;
    }
  }
  return stiffness;
}

}  // namespace aggpack
