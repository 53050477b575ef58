#pragma once
// Running CalculiX (ccx) on an exported flat .inp: a reader of the file's nodes and generated
// node sets, and a static gravity step with every particle held at its base, checked for a clean
// run (exit 0, "Job finished", no *ERROR, no *WARNING), every node's displacement and the total
// mass ccx computes (*EL PRINT ... TOTALS=ONLY, EMAS).

#include <algorithm>
#include <cctype>
#include <map>
#include <numeric>
#include <regex>
#include <string>

#include "export_fixture.h"

namespace aggpack::test {

inline std::string upper(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

/// Node coordinates and the node range of every particle's generated node set, from a flat file.
struct FlatInp {
  std::map<std::uint64_t, Vec3> nodes;
  std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> node_sets;  // name -> [a, b]
  std::size_t elements = 0;
};

inline FlatInp parse_flat(const std::string& path) {
  FlatInp inp;
  std::istringstream in(read_text(path));
  std::string line;
  std::string block;
  std::string set_name;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind('*', 0) == 0) {
      const std::string keyword = upper(line);
      block = trim(split(keyword, ',')[0]);
      std::smatch found;
      if (block == "*NSET" && std::regex_search(keyword, found, std::regex("NSET=([A-Z0-9_]+)"))) {
        set_name = found[1];
      }
      continue;
    }
    const auto fields = split(line, ',');
    if (block == "*NODE") {
      inp.nodes[std::stoull(fields[0])] =
          Vec3(std::stod(fields[1]), std::stod(fields[2]), std::stod(fields[3]));
    } else if (block == "*ELEMENT") {
      ++inp.elements;
    } else if (block == "*NSET" && fields.size() == 3) {
      inp.node_sets[set_name] = {std::stoull(fields[0]), std::stoull(fields[1])};
    }
  }
  return inp;
}

/// What a gravity run gave.
struct CcxGravity {
  double total_mass = -1;  ///< ccx's total mass of ELSET AGGREGATES (7 significant digits)
  std::size_t fixed_nodes = 0;
};

/// Runs ccx on `model` (an exported flat .inp in `folder`) with gravity (9.81 m/s^2 along -z)
/// and, per particle, the nodes in the lowest 30% of its height fixed, at least three that span a
/// triangle (so no particle can move as a rigid body). Expects a clean run, every node's
/// displacement listed, downward on average and small; returns ccx's total mass.
inline void run_ccx_gravity(const ScratchFolder& folder, const std::string& model,
                            std::size_t particles, CcxGravity* result = nullptr) {
  const FlatInp inp = parse_flat(folder.file(model));
  ASSERT_EQ(inp.node_sets.size(), particles);
  std::string base;
  std::size_t fixed = 0;
  for (const auto& [name, range] : inp.node_sets) {
    std::vector<std::uint64_t> ids(range.second - range.first + 1);
    std::iota(ids.begin(), ids.end(), range.first);
    std::sort(ids.begin(), ids.end(), [&](std::uint64_t a, std::uint64_t b) {
      return inp.nodes.at(a).z() < inp.nodes.at(b).z();
    });
    const Vec3& lowest = inp.nodes.at(ids.front());
    const double height = inp.nodes.at(ids.back()).z() - lowest.z();
    // The nodes in the lowest 30% of the particle's height, and at least enough of its lowest
    // nodes to span a triangle (three non-collinear fixed nodes hold a body in place).
    std::size_t count = 0;
    double far = 0;
    Vec3 axis = Vec3::Zero();
    double spread = 0;
    for (const std::uint64_t id : ids) {
      const Vec3 offset = inp.nodes.at(id) - lowest;
      const bool is_low = offset.z() <= 0.3 * height;
      if (!is_low && count >= 3 && spread > 1e-3 * height * height) break;
      base += std::to_string(id) + ",\n";
      ++count;
      if (offset.norm() > far) {
        far = offset.norm();
        axis = offset / far;
      }
      spread = std::max(spread, axis.cross(offset).norm() * far);
    }
    fixed += count;
  }
  ASSERT_GE(fixed, 3 * particles);
  std::ofstream(folder.file("job.inp"))
      << "*INCLUDE, INPUT=" << model << "\n*NSET, NSET=BASE\n"
      << base
      << "*BOUNDARY\nBASE, 1, 3\n*STEP\n*STATIC\n*DLOAD\nAGGREGATES, GRAV, 9.81, 0., 0., -1.\n"
         "*NODE PRINT, NSET=ALLNODES\nU\n*EL PRINT, ELSET=AGGREGATES, TOTALS=ONLY\nEMAS\n"
         "*END STEP\n";
  const auto run = run_command("cd " + folder.path().string() + " && OMP_NUM_THREADS=1 ccx -i job");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("Job finished"), std::string::npos) << run.output;
  EXPECT_EQ(upper(run.output).find("*ERROR"), std::string::npos) << run.output;
  EXPECT_EQ(upper(run.output).find("*WARNING"), std::string::npos) << run.output;
  // The .dat file: a displacement table for ALLNODES, then the total mass of AGGREGATES.
  std::istringstream dat(read_text(folder.file("job.dat")));
  std::string line;
  std::string section;
  std::size_t listed = 0;
  double sum_z = 0;
  double largest = 0;
  double mass = -1;
  while (std::getline(dat, line)) {
    if (line.find("displacements") != std::string::npos) {
      section = "u";
      continue;
    }
    if (line.find("total mass for set") != std::string::npos) {
      section = "mass";
      continue;
    }
    if (line.find(" for set ") != std::string::npos) {
      section.clear();
      continue;
    }
    std::istringstream fields(line);
    if (section == "u") {
      std::uint64_t id = 0;
      double ux = 0;
      double uy = 0;
      double uz = 0;
      if (fields >> id >> ux >> uy >> uz) {
        ++listed;
        sum_z += uz;
        largest = std::max(largest, std::abs(uz));
      }
    } else if (section == "mass" && mass < 0) {
      fields >> mass;
    }
  }
  EXPECT_EQ(listed, inp.nodes.size());
  EXPECT_LT(sum_z, 0.0);
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(largest, 1e-3);  // stiff rock under its own weight: tiny displacements
  EXPECT_GT(mass, 0.0);
  if (result != nullptr) *result = {.total_mass = mass, .fixed_nodes = fixed};
}

}  // namespace aggpack::test
