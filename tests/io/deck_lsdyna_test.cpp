// LS-DYNA deck (--deck lsdyna). Debian has no LS-DYNA, so the deck is checked by a strict reader
// of the fixed-column keyword format: every keyword is one the deck may use, every card line is at
// most 80 columns and made of numbers in its 10-column fields (curve points 20, nodes 8/16,
// elements 8); every curve, part, section, material, set and node referenced is defined; and by
// the model: termination = the three stages, gravity 9.81 through curve 1, friction, a baffle
// curve whose integral is the baffle's travel, planar walls with every particle node on their
// inner side.

#include <set>

#include "aggpack/io/export.h"
#include "deck_fixture.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// The numbers of a fixed-column card: fields of the given widths (the last repeats); a blank
// field is 0. Fails the test on a field that is not a number.
std::vector<double> fields_of(const std::string& line, std::vector<std::size_t> widths,
                              const std::string& keyword) {
  std::vector<double> values;
  std::size_t at = 0;
  for (std::size_t k = 0; at < line.size(); ++k) {
    const std::size_t width = widths[std::min(k, widths.size() - 1)];
    const std::string field = test::trim(line.substr(at, width));
    at += width;
    if (field.empty()) {
      values.push_back(0.0);
      continue;
    }
    std::size_t used = 0;
    double value = NAN;
    try {
      value = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    EXPECT_EQ(used, field.size()) << keyword << ": '" << field << "' in '" << line << "'";
    values.push_back(value);
  }
  return values;
}

struct Card {
  std::string keyword;
  std::vector<std::string> lines;  // data lines (no $ comments)
};

TEST(LsDynaDeck, FixedColumnsReferencesAndTrough) {
  const Packing packing = test::pile_near_floor(2, 2, 2, 0.002, 91);
  ScratchFolder folder;
  ExportOptions options;
  options.deck = {.kind = DeckKind::kLsDyna,
                  .friction = 0.2,
                  .trough_length = packing.container.get_if<BoxContainer>()->length + 0.5,
                  .baffle_speed = 0.5,
                  .settle_time = 0.6,
                  .rest_time = 0.3};
  const ExportSummary summary = write(packing, folder.file("deck.k"), options);
  EXPECT_EQ(summary.format, ExportFormat::kLsDyna);
  std::istringstream in(test::read_text(folder.file("deck.k")));
  std::vector<Card> cards;
  std::string line;
  std::size_t header_comments = 0;
  while (std::getline(in, line)) {
    EXPECT_LE(line.size(), 80U) << line;
    if (line.rfind('$', 0) == 0) {
      if (cards.size() == 1) ++header_comments;
      continue;
    }
    if (line.rfind('*', 0) == 0) {
      cards.push_back({line, {}});
    } else {
      ASSERT_FALSE(cards.empty()) << line;
      cards.back().lines.push_back(line);
    }
  }
  ASSERT_FALSE(cards.empty());
  EXPECT_EQ(cards.front().keyword, "*KEYWORD");
  EXPECT_EQ(cards.back().keyword, "*END");
  EXPECT_GT(header_comments, 10U);  // the deck's assumptions, after *KEYWORD

  const std::set<std::string> known = {"*KEYWORD",
                                       "*TITLE",
                                       "*MAT_ELASTIC_TITLE",
                                       "*SECTION_SOLID",
                                       "*PART",
                                       "*NODE",
                                       "*ELEMENT_SOLID",
                                       "*CONTROL_TERMINATION",
                                       "*CONTROL_TIMESTEP",
                                       "*DEFINE_CURVE_TITLE",
                                       "*LOAD_BODY_Z",
                                       "*CONTACT_AUTOMATIC_SINGLE_SURFACE",
                                       "*RIGIDWALL_PLANAR",
                                       "*SECTION_SHELL",
                                       "*MAT_RIGID",
                                       "*ELEMENT_SHELL",
                                       "*SET_NODE_LIST",
                                       "*BOUNDARY_PRESCRIBED_MOTION_RIGID",
                                       "*DATABASE_GLSTAT",
                                       "*DATABASE_MATSUM",
                                       "*DATABASE_RWFORC",
                                       "*DATABASE_RCFORC",
                                       "*DATABASE_BINARY_D3PLOT",
                                       "*END"};
  std::map<std::uint64_t, Vec3> nodes;
  std::map<int, std::vector<std::pair<double, double>>> curves;
  std::map<int, std::pair<int, int>> parts;  // pid -> (section, material)
  std::set<int> sections;
  std::set<int> materials;
  std::map<int, std::vector<std::uint64_t>> node_sets;
  std::vector<std::vector<std::uint64_t>> elements;  // node ids of solids and shells
  std::vector<std::pair<Vec3, Vec3>> walls;          // tail, head
  std::vector<double> wall_friction;
  std::vector<int> wall_excluded_sets;
  double end_time = 0;
  double contact_friction = -1;
  std::vector<double> gravity;
  std::vector<double> motion;
  for (const Card& card : cards) {
    const std::string& k = card.keyword;
    ASSERT_EQ(known.count(k), 1U) << "unknown keyword " << k;
    const auto ten = [&](std::size_t i) { return fields_of(card.lines.at(i), {10}, k); };
    if (k == "*NODE") {
      for (const std::string& l : card.lines) {
        const auto f = fields_of(l, {8, 16, 16, 16, 8}, k);
        nodes[static_cast<std::uint64_t>(f[0])] = Vec3(f[1], f[2], f[3]);
      }
    } else if (k == "*ELEMENT_SOLID" || k == "*ELEMENT_SHELL") {
      for (const std::string& l : card.lines) {
        const auto f = fields_of(l, {8}, k);
        EXPECT_EQ(parts.count(static_cast<int>(f.at(1))), 1U) << l;
        std::vector<std::uint64_t> ids;
        for (std::size_t n = 2; n < f.size(); ++n) ids.push_back(static_cast<std::uint64_t>(f[n]));
        elements.push_back(ids);
      }
    } else if (k == "*PART") {
      const auto f = ten(1);
      parts[static_cast<int>(f[0])] = {static_cast<int>(f[1]), static_cast<int>(f[2])};
    } else if (k == "*SECTION_SOLID" || k == "*SECTION_SHELL") {
      sections.insert(static_cast<int>(ten(0)[0]));
      if (k == "*SECTION_SHELL") {
        EXPECT_GT(ten(1)[0], 0.0);  // thickness
      }
    } else if (k == "*MAT_ELASTIC_TITLE") {
      materials.insert(std::stoi(test::split(card.lines.at(1), ',')[0]));  // free format
    } else if (k == "*MAT_RIGID") {
      ASSERT_EQ(card.lines.size(), 3U);
      materials.insert(static_cast<int>(ten(0)[0]));
      EXPECT_EQ(ten(1), (std::vector<double>{1, 5, 7}));  // y, z and rotations fixed
    } else if (k == "*DEFINE_CURVE_TITLE") {
      const int id = static_cast<int>(ten(1)[0]);
      for (std::size_t i = 2; i < card.lines.size(); ++i) {
        const auto f = fields_of(card.lines[i], {20}, k);
        ASSERT_EQ(f.size(), 2U);
        curves[id].emplace_back(f[0], f[1]);
      }
    } else if (k == "*CONTROL_TERMINATION") {
      end_time = ten(0)[0];
    } else if (k == "*LOAD_BODY_Z") {
      gravity = ten(0);
    } else if (k == "*CONTACT_AUTOMATIC_SINGLE_SURFACE") {
      ASSERT_EQ(card.lines.size(), 3U);
      EXPECT_EQ(ten(0)[2], 5.0);  // every part
      contact_friction = ten(1)[0];
      EXPECT_EQ(ten(1)[1], contact_friction);
    } else if (k == "*RIGIDWALL_PLANAR") {
      ASSERT_EQ(card.lines.size(), 2U);
      EXPECT_EQ(ten(0)[0], 0.0);  // all nodes ...
      wall_excluded_sets.push_back(static_cast<int>(ten(0)[1]));
      const auto f = ten(1);
      walls.emplace_back(Vec3(f[0], f[1], f[2]), Vec3(f[3], f[4], f[5]));
      wall_friction.push_back(f.at(6));
    } else if (k == "*SET_NODE_LIST") {
      const int id = static_cast<int>(ten(0)[0]);
      for (std::size_t i = 1; i < card.lines.size(); ++i) {
        for (double n : ten(i)) node_sets[id].push_back(static_cast<std::uint64_t>(n));
      }
    } else if (k == "*BOUNDARY_PRESCRIBED_MOTION_RIGID") {
      motion = ten(0);
    }
  }
  // References.
  for (const auto& [pid, refs] : parts) {
    EXPECT_EQ(sections.count(refs.first), 1U) << "part " << pid;
    EXPECT_EQ(materials.count(refs.second), 1U) << "part " << pid;
  }
  for (const auto& element : elements) {
    for (std::uint64_t id : element) EXPECT_EQ(nodes.count(id), 1U) << id;
  }
  for (int set : wall_excluded_sets) EXPECT_EQ(node_sets.count(set), 1U);
  for (const auto& [set, ids] : node_sets) {
    for (std::uint64_t id : ids) EXPECT_EQ(nodes.count(id), 1U) << id;
  }
  ASSERT_EQ(parts.size(), packing.particles.size() + 1);
  ASSERT_EQ(motion.size(), 5U);
  const int baffle = static_cast<int>(packing.particles.size() + 1);
  EXPECT_EQ(motion[0], baffle);
  EXPECT_EQ(motion[1], 1.0);  // x
  EXPECT_EQ(motion[2], 0.0);  // velocity
  ASSERT_EQ(curves.count(static_cast<int>(motion[3])), 1U);
  ASSERT_EQ(gravity.size(), 2U);
  ASSERT_EQ(curves.count(static_cast<int>(gravity[0])), 1U);
  EXPECT_EQ(gravity[1], 9.81);

  // Times: termination after the three stages; the baffle's velocity integrates to its travel,
  // starting after the settle time; gravity is on throughout.
  const double travel = 0.5;  // trough length - container length
  const double baffle_time = travel / 0.5;
  EXPECT_NEAR(end_time, 0.6 + baffle_time + 0.3, 1e-6);
  const auto& velocity = curves.at(static_cast<int>(motion[3]));
  double moved = 0;
  for (std::size_t i = 1; i < velocity.size(); ++i) {
    const auto [t0, v0] = velocity[i - 1];
    const auto [t1, v1] = velocity[i];
    ASSERT_GT(t1, t0);
    moved += 0.5 * (v0 + v1) * (std::min(t1, end_time) - std::min(t0, end_time));
    if (t1 <= 0.6) {
      EXPECT_EQ(v1, 0.0);
    }
  }
  EXPECT_NEAR(moved, travel, 1e-6);
  for (const auto& [t, value] : curves.at(static_cast<int>(gravity[0]))) EXPECT_EQ(value, 1.0);
  EXPECT_GE(curves.at(static_cast<int>(gravity[0])).back().first, end_time);

  // Walls: floor, two sides, two ends, all with the deck's friction and every particle node on
  // the side the normal (tail -> head) points to.
  EXPECT_EQ(contact_friction, 0.2);
  ASSERT_EQ(walls.size(), 5U);
  for (double f : wall_friction) EXPECT_EQ(f, 0.2);
  std::set<std::uint64_t> baffle_nodes(node_sets.begin()->second.begin(),
                                       node_sets.begin()->second.end());
  for (const auto& [tail, head] : walls) {
    const Vec3 normal = (head - tail).normalized();
    for (const auto& [id, node] : nodes) {
      if (baffle_nodes.count(id) != 0) continue;
      EXPECT_GE((node - tail).dot(normal), -1e-9) << "wall through " << tail.transpose();
    }
  }
  // The baffle plate stands ahead of (beyond) every particle node.
  double particles_end = -1e9;
  for (const auto& [id, node] : nodes) {
    if (baffle_nodes.count(id) == 0) particles_end = std::max(particles_end, node.x());
  }
  for (std::uint64_t id : baffle_nodes) EXPECT_GE(nodes.at(id).x(), particles_end);
}

}  // namespace
}  // namespace aggpack
