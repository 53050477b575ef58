// LS-DYNA .k, ANSYS APDL, OBJ and the YADE script. Debian has no LS-DYNA or ANSYS, so their files
// are checked by strict parsers of the documented layout (fixed columns, command syntax) plus the
// geometry (positive tetrahedra summing to each particle's volume); OBJ is read back by meshio;
// the YADE script is executed by Python against a stand-in of YADE's API.

#include <map>
#include <set>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/mesh/tetrahedra.h"
#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

std::uint64_t column(const std::string& line, std::size_t begin, std::size_t width) {
  return std::stoull(line.substr(begin, width));
}

// Per particle (1-based): summed tetrahedron volume; and the count of non-positive tetrahedra.
struct VolumeCheck {
  std::map<std::uint64_t, double> volume;
  std::size_t non_positive = 0;
};

void expect_volumes(const Packing& packing, const VolumeCheck& check) {
  EXPECT_EQ(check.non_positive, 0U);
  ASSERT_EQ(check.volume.size(), packing.particles.size());
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const double expected = test::particle_volume(packing, i);
    EXPECT_NEAR(check.volume.at(i + 1), expected, 1e-7 * expected) << "particle " << i + 1;
  }
}

TEST(LsDynaExport, FixedColumnsPartsAndVolumes) {
  const Packing packing = test::grid_packing(3, 2, 1, 61);
  ScratchFolder folder;
  const ExportSummary summary =
      write(packing, folder.file("model.k"), {.material = {.density = 2500.0}});
  std::istringstream in(test::read_text(folder.file("model.k")));
  std::string line;
  std::string block;
  std::map<std::uint64_t, Vec3> nodes;
  std::set<std::uint64_t> parts;
  VolumeCheck check;
  std::size_t elements = 0;
  std::vector<std::string> part_lines;
  std::string material_line;
  bool is_first = true;
  while (std::getline(in, line)) {
    if (is_first) {
      EXPECT_EQ(line, "*KEYWORD");
      is_first = false;
    }
    if (line.empty() || line[0] == '$') continue;
    if (line[0] == '*') {
      block = line;
      part_lines.clear();
      continue;
    }
    if (block == "*MAT_ELASTIC_TITLE" && line.find(',') != std::string::npos) material_line = line;
    if (block == "*PART") {
      part_lines.push_back(line);
      if (part_lines.size() == 2) {
        EXPECT_EQ(part_lines[0], "P" + std::to_string(column(line, 0, 10)));
        EXPECT_EQ(column(line, 10, 10), 1U);  // section
        EXPECT_EQ(column(line, 20, 10), 1U);  // material
        parts.insert(column(line, 0, 10));
      }
    } else if (block == "*NODE") {
      ASSERT_EQ(line.size(), 72U) << line;
      nodes[column(line, 0, 8)] =
          Vec3(std::stod(line.substr(8, 16)), std::stod(line.substr(24, 16)),
               std::stod(line.substr(40, 16)));
    } else if (block == "*ELEMENT_SOLID") {
      ASSERT_EQ(line.size(), 80U) << line;
      EXPECT_EQ(column(line, 0, 8), ++elements);
      const std::uint64_t part = column(line, 8, 8);
      EXPECT_EQ(parts.count(part), 1U);
      std::array<Vec3, 4> corners;
      for (int k = 0; k < 4; ++k) corners[k] = nodes.at(column(line, 16 + 8 * k, 8));
      for (int k = 4; k < 8; ++k) {
        EXPECT_EQ(column(line, 16 + 8 * k, 8), column(line, 16 + 8 * 3, 8));  // degenerate n4
      }
      const double v = tetra_volume(corners[0], corners[1], corners[2], corners[3]);
      if (!(v > 0)) ++check.non_positive;
      check.volume[part] += v;
    }
  }
  EXPECT_EQ(material_line, "1,2500,5e+10,0.2");
  EXPECT_EQ(parts.size(), packing.particles.size());
  EXPECT_EQ(nodes.size(), summary.nodes);
  EXPECT_EQ(elements, summary.elements);
  EXPECT_EQ(block, "*END");
  // Coordinates carry 9 significant digits in the 16-column field.
  expect_volumes(packing, check);
}

TEST(AnsysExport, NodeAndElementCommandsWithComponents) {
  const Packing packing = test::grid_packing(2, 2, 1, 62);
  ScratchFolder folder;
  const ExportSummary summary = write(packing, folder.file("model.mac"));
  std::istringstream in(test::read_text(folder.file("model.mac")));
  std::string line;
  std::map<std::uint64_t, Vec3> nodes;
  std::vector<std::array<std::uint64_t, 4>> elements;
  std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> components;
  std::pair<std::uint64_t, std::uint64_t> selected;
  std::set<std::string> commands;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '!') continue;
    const auto fields = test::split(line, ',');
    commands.insert(fields[0]);
    if (fields[0] == "N") {
      ASSERT_EQ(fields.size(), 5U);
      nodes[std::stoull(fields[1])] =
          Vec3(std::stod(fields[2]), std::stod(fields[3]), std::stod(fields[4]));
    } else if (fields[0] == "EN") {
      ASSERT_EQ(fields.size(), 6U);
      EXPECT_EQ(std::stoull(fields[1]), elements.size() + 1);
      elements.push_back({std::stoull(fields[2]), std::stoull(fields[3]), std::stoull(fields[4]),
                          std::stoull(fields[5])});
    } else if (fields[0] == "ESEL") {
      selected = {std::stoull(fields[4]), std::stoull(fields[5])};
    } else if (fields[0] == "CM" && fields[2] == "ELEM") {
      components[fields[1]] = selected;
    }
  }
  for (const char* command :
       {"/PREP7", "ET", "MP", "TYPE", "MAT", "N", "EN", "ESEL", "CM", "NSEL", "ALLSEL"}) {
    EXPECT_EQ(commands.count(command), 1U) << command;
  }
  EXPECT_EQ(nodes.size(), summary.nodes);
  EXPECT_EQ(elements.size(), summary.elements);
  ASSERT_EQ(components.size(), packing.particles.size());
  VolumeCheck check;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const auto [first, last] = components.at("P" + std::to_string(i + 1));
    for (auto e = first; e <= last; ++e) {
      const auto& t = elements.at(e - 1);
      const double v = tetra_volume(nodes.at(t[0]), nodes.at(t[1]), nodes.at(t[2]), nodes.at(t[3]));
      if (!(v > 0)) ++check.non_positive;
      check.volume[i + 1] += v;
    }
  }
  expect_volumes(packing, check);
}

TEST(ObjExport, MeshioReadsVerticesAndFaces) {
  const Packing packing = test::grid_packing(2, 2, 1, 63, /*share_shapes=*/true);
  ScratchFolder folder;
  const ExportSummary summary = write(packing, folder.file("p.obj"));
  const std::string text = test::read_text(folder.file("p.obj"));
  EXPECT_NE(text.find("\no P1\nv "), std::string::npos);
  EXPECT_NE(text.find("\no P4\nv "), std::string::npos);
  AGGPACK_REQUIRE_READER("meshio");
  const auto result = test::run_python(folder, R"(
import sys, meshio
mesh = meshio.read(sys.argv[1])
print(len(mesh.points), sum(len(b.data) for b in mesh.cells), mesh.cells[0].type)
print(repr(mesh.points[0].tolist()))
)",
                                       folder.file("p.obj"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = test::split(result.output, '\n');
  EXPECT_EQ(lines[0],
            std::to_string(summary.nodes) + " " + std::to_string(summary.elements) + " triangle");
  // meshio reads exactly the file's numbers (Python's repr and the file are both shortest
  // round-trip forms; compared as doubles), and they are the placed particle's vertex (the
  // exporter transforms with its own arithmetic: equal to the last bits or so).
  const std::size_t v = text.find("\nv ");
  ASSERT_NE(v, std::string::npos);
  const auto in_file = test::split(text.substr(v + 3, text.find('\n', v + 1) - v - 3), ' ');
  const auto numbers = test::split(lines[1].substr(1, lines[1].size() - 2), ',');
  ASSERT_EQ(numbers.size(), 3U);
  ASSERT_EQ(in_file.size(), 3U);
  const Vec3 first = packing.placed(0).vertices()[0];
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(std::stod(numbers[axis]), std::stod(in_file[axis]));
    EXPECT_NEAR(std::stod(in_file[axis]), first[axis], 1e-15 * first.norm());
  }
}

// A stand-in for the parts of YADE's API the script uses, so the script really runs.
constexpr const char* kYadeStub = R"(
import sys, types
calls = {"bodies": [], "materials": []}
class PolyhedraMat:
    def __init__(self, **kwargs):
        self.kwargs = kwargs
class _List:
    def __init__(self, key):
        self.key = key
    def append(self, item):
        calls[self.key].append(item)
class _O:
    bodies = _List("bodies")
    materials = _List("materials")
yade = types.ModuleType("yade")
utils = types.ModuleType("yade.polyhedra_utils")
def polyhedra(material, size=None, seed=None, v=[], mask=1, fixed=False, color=None):
    assert isinstance(material, PolyhedraMat)
    return [tuple(float(c) for c in p) for p in v]
utils.polyhedra = polyhedra
yade.polyhedra_utils = utils
sys.modules["yade"] = yade
sys.modules["yade.polyhedra_utils"] = utils
source = open(sys.argv[1]).read()
compile(source, sys.argv[1], "exec")
exec(source, {"PolyhedraMat": PolyhedraMat, "O": _O})
material = calls["materials"][0].kwargs
print(len(calls["bodies"]), material["density"], material["young"], material["poisson"])
print(" ".join(str(len(body)) for body in calls["bodies"]))
print(repr(calls["bodies"][0][0]))
)";

TEST(YadeExport, ScriptRunsAndRebuildsEveryParticle) {
  const Packing packing = test::grid_packing(3, 1, 1, 64);
  ScratchFolder folder;
  write(packing, folder.file("rebuild.py"),
        {.material = {.density = 1200.0, .youngs_modulus = 3e9, .poisson_ratio = 0.35}});
  const auto result = test::run_python(folder, kYadeStub, folder.file("rebuild.py"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const auto lines = test::split(result.output, '\n');
  ASSERT_GE(lines.size(), 3U);
  EXPECT_EQ(lines[0], "3 1200 3000000000.0 0.35");
  std::string counts;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    counts += (i ? " " : "") + std::to_string(packing.placed(i).vertex_count());
  }
  EXPECT_EQ(lines[1], counts);
  const auto numbers = test::split(lines[2].substr(1, lines[2].size() - 2), ',');
  ASSERT_EQ(numbers.size(), 3U);
  // The exporter transforms with its own arithmetic: equal to the placed vertex to the last bits.
  const Vec3 first = packing.placed(0).vertices()[0];
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(std::stod(numbers[axis]), first[axis], 1e-15 * first.norm());
  }
}

}  // namespace
}  // namespace aggpack
