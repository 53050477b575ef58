#pragma once
// Shared helpers of the deck tests: a small pile resting just above a floor, and reading the
// keyword lines of an Abaqus/CalculiX deck.

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "export_fixture.h"

namespace aggpack::test {

/// nx * ny * nz grid particles (export_fixture.h) lowered so that the lowest particles' lowest
/// vertex is `gap` above the floor z = 0, layers 0.25 m apart as in grid_packing; the container
/// is the grid's box. aggpack 0.1's particles (midpoint growth, ~20 vertices at L = r): the decks
/// are run by ccx and yade in tests, whose explicit contact steps cost several times more with
/// the hull rule's finer particles (the CalculiX trough went from 95 s to over 600 s).
inline Packing pile_near_floor(int nx, int ny, int nz, double gap, std::uint64_t seed = 1) {
  Packing packing = grid_packing(nx, ny, nz, seed, false, Growth::kMidpoint);
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    double low = 1e9;
    const ConvexPolyhedron body = packing.placed(i);
    for (const Vec3& v : body.vertices()) low = std::min(low, v.z());
    const int layer = static_cast<int>(i / static_cast<std::size_t>(nx * ny));
    packing.particles[i].pose.position.z() += gap + 0.25 * layer - low;
  }
  return packing;
}

/// Upper-case copy.
inline std::string upper_case(std::string text) {
  for (auto& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

/// One keyword line of an .inp deck: the keyword ("*STEP") and its parameters (NAME -> value,
/// upper case, "" when it has no value), and the data lines that follow it.
struct InpBlock {
  std::string keyword;
  std::map<std::string, std::string> parameters;
  std::vector<std::vector<std::string>> data;  ///< trimmed comma-separated fields
  std::size_t line = 0;                        ///< 1-based line of the keyword
};

/// Splits an .inp deck into keyword blocks; comment lines (**) are dropped.
inline std::vector<InpBlock> parse_inp_blocks(const std::string& text) {
  std::vector<InpBlock> blocks;
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind('*', 0) == 0) {
      InpBlock block;
      block.line = number;
      const auto fields = split(upper_case(line), ',');
      block.keyword = trim(fields[0]);
      for (std::size_t k = 1; k < fields.size(); ++k) {
        const std::string field = trim(fields[k]);
        const auto equals = field.find('=');
        if (equals == std::string::npos) {
          block.parameters[field] = "";
        } else {
          block.parameters[trim(field.substr(0, equals))] = trim(field.substr(equals + 1));
        }
      }
      blocks.push_back(block);
      continue;
    }
    if (blocks.empty()) continue;
    std::vector<std::string> fields;
    for (const std::string& field : split(line, ',')) fields.push_back(trim(field));
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    blocks.back().data.push_back(fields);
  }
  return blocks;
}

}  // namespace aggpack::test
