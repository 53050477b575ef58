// Abaqus/Explicit deck (--deck abaqus). Debian has no Abaqus, so the deck is checked by a strict
// reader of the keyword syntax: every keyword and parameter is one the deck may use, every set,
// surface, material, amplitude and interaction it names is defined, every data field has at most
// 20 characters; and by the model: steps, gravity, friction, the baffle's velocity, and rigid
// walls (normals inward) that enclose every particle node, the baffle ahead of the particles.

#include <set>

#include "aggpack/io/export.h"
#include "deck_fixture.h"

namespace aggpack {
namespace {

using test::InpBlock;
using test::ScratchFolder;

// Keyword -> the parameters it may carry in this deck.
const std::map<std::string, std::set<std::string>>& known_keywords() {
  static const std::map<std::string, std::set<std::string>> known = {
      {"*HEADING", {}},
      {"*NODE", {"NSET"}},
      {"*ELEMENT", {"TYPE", "ELSET"}},
      {"*NSET", {"NSET", "GENERATE"}},
      {"*ELSET", {"ELSET", "GENERATE"}},
      {"*SURFACE", {"TYPE", "NAME"}},
      {"*MATERIAL", {"NAME"}},
      {"*DENSITY", {}},
      {"*ELASTIC", {}},
      {"*SOLID SECTION", {"ELSET", "MATERIAL"}},
      {"*RIGID BODY", {"ELSET", "REF NODE"}},
      {"*BOUNDARY", {"TYPE", "AMPLITUDE"}},
      {"*AMPLITUDE", {"NAME"}},
      {"*SURFACE INTERACTION", {"NAME"}},
      {"*FRICTION", {}},
      {"*STEP", {"NAME", "NLGEOM"}},
      {"*DYNAMIC", {"EXPLICIT"}},
      {"*DLOAD", {}},
      {"*CONTACT", {}},
      {"*CONTACT INCLUSIONS", {"ALL EXTERIOR"}},
      {"*CONTACT PROPERTY ASSIGNMENT", {}},
      {"*OUTPUT", {"FIELD", "HISTORY", "TIME INTERVAL"}},
      {"*NODE OUTPUT", {"NSET"}},
      {"*ELEMENT OUTPUT", {"ELSET"}},
      {"*ENERGY OUTPUT", {}},
      {"*END STEP", {}},
  };
  return known;
}

bool is_number(const std::string& text) {
  if (text.empty()) return false;
  std::size_t used = 0;
  try {
    std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

TEST(AbaqusDeck, KeywordsSetsNumbersAndTroughGeometry) {
  const Packing packing = test::pile_near_floor(3, 2, 2, 0.001, 81);
  ScratchFolder folder;
  ExportOptions options;
  options.deck = {.kind = DeckKind::kAbaqus,
                  .friction = 0.3,
                  .baffle_speed = 0.25,
                  .settle_time = 0.7,
                  .rest_time = 0.4};
  write(packing, folder.file("deck.inp"), options);
  const std::string text = test::read_text(folder.file("deck.inp"));
  EXPECT_EQ(text.rfind("** aggpack ", 0), 0U) << "the header comes first";
  for (const char* said :
       {"Run: abaqus job=", "mu_s = 0.3", "Step SETTLE, 0.7 s", "[--friction]"}) {
    EXPECT_NE(text.find(said), std::string::npos) << said;
  }
  const std::vector<InpBlock> blocks = test::parse_inp_blocks(text);

  std::set<std::string> node_sets;
  std::set<std::string> element_sets;
  std::set<std::string> names;  // materials, amplitudes, interactions, surfaces
  std::map<std::uint64_t, Vec3> nodes;
  std::map<std::string, std::vector<std::vector<std::uint64_t>>> elements;  // elset -> elements
  std::vector<std::string> steps;
  for (const InpBlock& block : blocks) {
    ASSERT_EQ(known_keywords().count(block.keyword), 1U)
        << "unknown keyword " << block.keyword << " at line " << block.line;
    for (const auto& [name, value] : block.parameters) {
      EXPECT_EQ(known_keywords().at(block.keyword).count(name), 1U)
          << block.keyword << " parameter " << name << " at line " << block.line;
    }
    for (const auto& fields : block.data) {
      if (block.keyword == "*HEADING") break;  // free text
      for (const std::string& field : fields) {
        EXPECT_LE(field.size(), 20U) << block.keyword << " field '" << field << "'";
      }
    }
    const auto& p = block.parameters;
    if (block.keyword == "*NODE") {
      if (p.count("NSET")) node_sets.insert(p.at("NSET"));
      for (const auto& f : block.data) {
        ASSERT_EQ(f.size(), 4U);
        nodes[std::stoull(f[0])] = Vec3(std::stod(f[1]), std::stod(f[2]), std::stod(f[3]));
      }
    } else if (block.keyword == "*ELEMENT") {
      element_sets.insert(p.at("ELSET"));
      const std::size_t corners = p.at("TYPE") == "C3D4" || p.at("TYPE") == "R3D4" ? 4 : 0;
      ASSERT_EQ(corners, 4U) << p.at("TYPE");
      for (const auto& f : block.data) {
        ASSERT_EQ(f.size(), corners + 1);
        std::vector<std::uint64_t> ids;
        for (std::size_t k = 1; k < f.size(); ++k) ids.push_back(std::stoull(f[k]));
        elements[p.at("ELSET")].push_back(ids);
      }
    } else if (block.keyword == "*NSET") {
      node_sets.insert(p.at("NSET"));
    } else if (block.keyword == "*ELSET") {
      for (const auto& f : block.data) {
        for (const std::string& member : f) {
          if (!is_number(member)) {
            EXPECT_EQ(element_sets.count(member), 1U) << member;
          }
        }
      }
      element_sets.insert(p.at("ELSET"));
    } else if (block.keyword == "*SURFACE") {
      for (const auto& f : block.data) EXPECT_EQ(element_sets.count(f[0]), 1U) << f[0];
      names.insert(p.at("NAME"));
    } else if (block.keyword == "*MATERIAL" || block.keyword == "*AMPLITUDE" ||
               block.keyword == "*SURFACE INTERACTION") {
      names.insert(p.at("NAME"));
    } else if (block.keyword == "*STEP") {
      steps.push_back(p.at("NAME"));
    }
    // References.
    for (const char* key : {"ELSET"}) {
      if (p.count(key) && block.keyword != "*ELEMENT" && block.keyword != "*ELSET") {
        EXPECT_EQ(element_sets.count(p.at(key)), 1U) << block.keyword << " " << p.at(key);
      }
    }
    if (p.count("REF NODE")) {
      EXPECT_EQ(node_sets.count(p.at("REF NODE")), 1U);
    }
    if (p.count("MATERIAL")) {
      EXPECT_EQ(names.count(p.at("MATERIAL")), 1U);
    }
    if (p.count("AMPLITUDE")) {
      EXPECT_EQ(names.count(p.at("AMPLITUDE")), 1U);
    }
    if (block.keyword == "*NODE OUTPUT" && p.count("NSET")) {
      EXPECT_EQ(node_sets.count(p.at("NSET")), 1U);
    }
    if (block.keyword == "*DLOAD") {
      for (const auto& f : block.data) EXPECT_EQ(element_sets.count(f[0]), 1U) << f[0];
    }
    if (block.keyword == "*BOUNDARY") {
      for (const auto& f : block.data) EXPECT_EQ(node_sets.count(f[0]), 1U) << f[0];
    }
    if (block.keyword == "*CONTACT PROPERTY ASSIGNMENT") {
      ASSERT_EQ(block.data.size(), 1U);
      ASSERT_EQ(block.data[0].size(), 3U);
      EXPECT_EQ(names.count(block.data[0][2]), 1U) << block.data[0][2];
    }
  }
  for (const auto& [set, list] : elements) {
    for (const auto& element : list) {
      for (std::uint64_t id : element) EXPECT_EQ(nodes.count(id), 1U) << set << " node " << id;
    }
  }
  EXPECT_EQ(steps, (std::vector<std::string>{"SETTLE", "BAFFLE", "REST"}));

  // The model's values, block by block within each step.
  std::string step;
  std::map<std::string, double> step_time;
  std::map<std::string, double> baffle_velocity;
  double friction = -1;
  Vec3 gravity = Vec3::Zero();
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const InpBlock& block = blocks[b];
    if (block.keyword == "*STEP") step = block.parameters.at("NAME");
    if (block.keyword == "*DYNAMIC") {
      EXPECT_EQ(block.parameters.count("EXPLICIT"), 1U);
      step_time[step] = std::stod(block.data.at(0).at(1));
    }
    if (block.keyword == "*FRICTION") friction = std::stod(block.data.at(0).at(0));
    if (block.keyword == "*DLOAD") {
      const auto& f = block.data.at(0);
      ASSERT_EQ(f.at(1), "GRAV");
      gravity = std::stod(f[2]) * Vec3(std::stod(f[3]), std::stod(f[4]), std::stod(f[5]));
    }
    if (block.keyword == "*BOUNDARY" && block.parameters.count("TYPE")) {
      EXPECT_EQ(block.parameters.at("TYPE"), "VELOCITY");
      for (const auto& f : block.data) {
        if (f.at(0) == "BAFFLE_REF" && f.at(1) == "1") baffle_velocity[step] = std::stod(f.at(3));
      }
    }
  }
  const double length = packing.container.get_if<BoxContainer>()->length;
  EXPECT_DOUBLE_EQ(step_time["SETTLE"], 0.7);
  EXPECT_DOUBLE_EQ(step_time["BAFFLE"], length / 0.25);  // trough 2 x the container, to the end
  EXPECT_DOUBLE_EQ(step_time["REST"], 0.4);
  EXPECT_DOUBLE_EQ(friction, 0.3);
  EXPECT_EQ(gravity, Vec3(0, 0, -9.81));
  EXPECT_DOUBLE_EQ(baffle_velocity["SETTLE"], 0.0);
  EXPECT_DOUBLE_EQ(baffle_velocity["BAFFLE"], 0.25);
  EXPECT_DOUBLE_EQ(baffle_velocity["REST"], 0.0);

  // Geometry: every wall's plane has every particle node on its inner side (the side its normal
  // points to), the baffle's too; walls are the floor, y = 0 and y = width, x = 0 and the end.
  ASSERT_EQ(elements.count("WALLS"), 0U);  // WALLS is a set of the per-wall sets
  std::vector<Vec3> particle_nodes;
  for (const auto& [set, list] : elements) {
    if (set.rfind('P', 0) != 0) continue;
    for (const auto& element : list) {
      for (std::uint64_t id : element) particle_nodes.push_back(nodes.at(id));
    }
  }
  ASSERT_FALSE(particle_nodes.empty());
  std::map<std::string, Vec3> normals;
  for (const char* wall : {"FLOOR", "WALL_Y0", "WALL_Y1", "WALL_X0", "WALL_X1", "BAFFLE"}) {
    ASSERT_EQ(elements[wall].size(), 1U) << wall;
    const auto& quad = elements[wall][0];
    const Vec3 a = nodes.at(quad[0]);
    const Vec3 normal =
        (nodes.at(quad[1]) - a).cross(nodes.at(quad[2]) - a).normalized();  // R3D4 normal
    normals[wall] = normal;
    for (const Vec3& node : particle_nodes) {
      EXPECT_GE((node - a).dot(normal), -1e-12) << wall << " cuts a particle";
    }
  }
  EXPECT_TRUE(normals["FLOOR"].isApprox(Vec3(0, 0, 1)));
  EXPECT_TRUE(normals["BAFFLE"].isApprox(Vec3(-1, 0, 0)));
  EXPECT_TRUE(normals["WALL_X1"].isApprox(Vec3(-1, 0, 0)));
  EXPECT_DOUBLE_EQ(nodes.at(elements["BAFFLE"][0][0]).x(), length);
  EXPECT_DOUBLE_EQ(nodes.at(elements["WALL_X1"][0][0]).x(), 2 * length);
}

}  // namespace
}  // namespace aggpack
