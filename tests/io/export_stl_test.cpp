// STL export: exact round trip through read_stl, outward normals, per-particle folders, and
// Debian's admesh as the independent reader (closed, no fixes needed, volume = sum of particles).

#include <map>
#include <regex>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "aggpack/io/stl.h"
#include "export_fixture.h"
#include "support/readers.h"

namespace aggpack {
namespace {

using test::ScratchFolder;

// Parses admesh's report: the "Final" column of the facet table and the processing statistics.
std::map<std::string, double> admesh_report(const std::string& path) {
  const auto result = test::run_command("admesh " + path);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::map<std::string, double> values;
  const std::regex facets(R"(Number of facets\s*:\s*(\d+)\s+(\d+))");
  const std::regex disconnected(R"(Total disconnected facets\s*:\s*(\d+)\s+(\d+))");
  const std::regex volume(R"(Volume\s*:\s*([-0-9.eE+]+))");
  const std::regex parts(R"(Number of parts\s*:\s*(\d+))");
  std::smatch match;
  if (std::regex_search(result.output, match, facets)) values["facets"] = std::stod(match[2]);
  if (std::regex_search(result.output, match, disconnected)) {
    values["disconnected"] = std::stod(match[2]);
  }
  if (std::regex_search(result.output, match, volume)) values["volume"] = std::stod(match[1]);
  if (std::regex_search(result.output, match, parts)) values["parts"] = std::stod(match[1]);
  for (const char* key : {"Degenerate facets", "Edges fixed", "Facets removed", "Facets added",
                          "Facets reversed", "Backwards edges", "Normals fixed"}) {
    const std::regex line(std::string(key) + R"(\s*:\s*(\d+))");
    if (std::regex_search(result.output, match, line)) values[key] = std::stod(match[1]);
  }
  return values;
}

void expect_admesh_clean(const std::map<std::string, double>& report, double facets, double parts,
                         double volume) {
  ASSERT_EQ(report.count("volume"), 1U) << "admesh output not understood";
  EXPECT_EQ(report.at("facets"), facets);
  EXPECT_EQ(report.at("parts"), parts);
  EXPECT_EQ(report.at("disconnected"), 0);
  for (const char* key : {"Degenerate facets", "Edges fixed", "Facets removed", "Facets added",
                          "Facets reversed", "Backwards edges", "Normals fixed"}) {
    EXPECT_EQ(report.at(key), 0) << key;
  }
  EXPECT_NEAR(report.at("volume"), volume, 2e-6 * volume);
}

TEST(StlExport, BinaryRoundTripMatchesPlacedParticles) {
  const Packing packing = test::grid_packing(3, 2, 2, 5);
  ScratchFolder folder;
  const std::string path = folder.file("packing.stl");
  const ExportSummary summary = write(packing, path);
  EXPECT_EQ(summary.format, ExportFormat::kStl);
  EXPECT_EQ(summary.files, 1U);
  const StlMesh mesh = read_stl(path);
  std::size_t facet = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const ConvexPolyhedron body = packing.placed(i);
    const Vec3 centre = mass_properties(body).centroid;
    for (std::size_t f = 0; f < body.triangle_count(); ++f, ++facet) {
      ASSERT_LT(facet, mesh.triangles.size());
      for (int v = 0; v < 3; ++v) {
        const Vec3 expected = body.vertices()[body.triangles()[f][v]];
        EXPECT_NEAR((mesh.triangles[facet][v] - expected).norm(), 0.0, 1e-6);
      }
      // Outward: the normal points away from the particle's centre, and it is a unit vector.
      const Vec3 middle =
          (mesh.triangles[facet][0] + mesh.triangles[facet][1] + mesh.triangles[facet][2]) / 3.0;
      EXPECT_GT(mesh.normals[facet].dot(middle - centre), 0.0);
      EXPECT_NEAR(mesh.normals[facet].norm(), 1.0, 1e-6);
    }
  }
  EXPECT_EQ(facet, mesh.triangles.size());
  EXPECT_EQ(summary.elements, mesh.triangles.size());
}

TEST(StlExport, AsciiAndBinaryAgreeAndScaleToMillimetres) {
  const Packing packing = test::grid_packing(2, 2, 1, 8);
  ScratchFolder folder;
  write(packing, folder.file("a.stl"), {.scale = 1000.0, .stl_encoding = StlEncoding::kAscii});
  write(packing, folder.file("b.stl"), {.scale = 1000.0});
  const StlMesh ascii = read_stl(folder.file("a.stl"));
  const StlMesh binary = read_stl(folder.file("b.stl"));
  ASSERT_EQ(ascii.triangles.size(), binary.triangles.size());
  EXPECT_EQ(test::read_text(folder.file("a.stl")).rfind("solid aggpack\n", 0), 0U);
  const Vec3 first = packing.placed(0).vertices()[packing.shapes[0].triangles()[0][0]] * 1000.0;
  EXPECT_NEAR((ascii.triangles[0][0] - first).norm(), 0.0, 1e-4);
  for (std::size_t t = 0; t < ascii.triangles.size(); ++t) {
    for (int v = 0; v < 3; ++v) {
      EXPECT_NEAR((ascii.triangles[t][v] - binary.triangles[t][v]).norm(), 0.0, 1e-4);
    }
  }
}

TEST(StlExport, AdmeshFindsClosedPartsWithTheParticleVolume) {
  AGGPACK_REQUIRE_READER("admesh");
  const Packing packing = test::grid_packing(3, 2, 2, 3);
  double total = 0;
  std::size_t facets = 0;
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    total += test::particle_volume(packing, i);
    facets += packing.placed(i).triangle_count();
  }
  ScratchFolder folder;
  // Millimetres: admesh prints volumes with 6 decimals, too few for m^3.
  for (auto encoding : {StlEncoding::kBinary, StlEncoding::kAscii}) {
    const std::string path = folder.file(encoding == StlEncoding::kAscii ? "a.stl" : "b.stl");
    write(packing, path, {.scale = 1000.0, .stl_encoding = encoding});
    expect_admesh_clean(admesh_report(path), static_cast<double>(facets),
                        static_cast<double>(packing.particles.size()), total * 1e9);
  }
}

TEST(StlExport, PerParticleFolderHasOneClosedFilePerParticle) {
  const Packing packing = test::grid_packing(2, 2, 2, 4, /*share_shapes=*/true);
  ScratchFolder folder;
  const std::string path = folder.file("prints");
  const ExportSummary summary = write(packing, path, {.scale = 1000.0, .is_per_particle = true});
  EXPECT_EQ(summary.files, packing.particles.size());
  std::vector<std::string> expected;
  for (std::size_t i = 1; i <= packing.particles.size(); ++i) {
    expected.push_back("P00000" + std::to_string(i) + ".stl");
  }
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, expected);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"prints"});  // no staging folder left
  AGGPACK_REQUIRE_READER("admesh");
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const std::string file = path + "/" + expected[i];
    EXPECT_EQ(read_stl(file).triangles.size(), packing.placed(i).triangle_count());
    expect_admesh_clean(admesh_report(file),
                        static_cast<double>(packing.placed(i).triangle_count()), 1,
                        test::particle_volume(packing, i) * 1e9);
  }
  // An existing folder is kept without overwrite, replaced as a whole with it.
  const auto before = test::read_text(path + "/" + expected[0]);
  EXPECT_THROW(write(packing, path, {.is_per_particle = true}), IoError);
  EXPECT_EQ(test::read_text(path + "/" + expected[0]), before);
  std::ofstream(path + "/stale.txt") << "old";
  const Packing smaller = test::grid_packing(1, 1, 1, 9);
  write(smaller, path, {.overwrite = Overwrite::kAllow, .is_per_particle = true});
  names.clear();
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(names, std::vector<std::string>{"P000001.stl"});
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"prints"});
}

TEST(StlExport, SameBytesForAnyThreadCountAndRepeatedRuns) {
  const Packing packing = test::grid_packing(4, 4, 3, 2);
  ScratchFolder folder;
  write(packing, folder.file("a.stl"), {.stl_encoding = StlEncoding::kAscii});
  write(packing, folder.file("b.stl"), {.stl_encoding = StlEncoding::kAscii});
  EXPECT_EQ(test::read_text(folder.file("a.stl")), test::read_text(folder.file("b.stl")));
}

}  // namespace
}  // namespace aggpack
