// The STL writer (the exporter's, src/io/export_stl.cpp, as `aggpack particle` uses it) and the
// reader (src/io/stl.cpp): binary and ASCII round trips of generated particles, facet normals
// against vertex order, atomic writes, malformed files, and Debian's admesh as an independent
// reader of a written particle.

#include "aggpack/io/stl.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/shape/generator.h"
#include "support/files.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test (tests may run in parallel), removed afterwards.
class StlFolder {
 public:
  StlFolder() {
    std::string pattern = (fs::temp_directory_path() / "aggpack-stl-XXXXXX").string();
    path_ = ::mkdtemp(pattern.data());
  }
  StlFolder(const StlFolder&) = delete;
  StlFolder& operator=(const StlFolder&) = delete;
  ~StlFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] std::size_t entry_count() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(path_), fs::directory_iterator()));
  }

 private:
  fs::path path_;
};

ConvexPolyhedron particle(std::uint64_t index = 0) {
  return generate_particle(
             {.alpha = 0.4, .radius_min = 0.05, .radius_max = 0.1, .edge_length = 0.04, .seed = 9},
             index)
      .body;
}

// Writes `bodies` as they are (identity poses) through the one STL writer, write() of export.h.
void write_bodies(const std::string& path, const std::vector<ConvexPolyhedron>& bodies,
                  ExportOptions options = {.overwrite = Overwrite::kAllow}) {
  Packing packing;
  packing.shapes = bodies;
  for (std::uint32_t i = 0; i < bodies.size(); ++i) packing.particles.push_back({.shape = i});
  options.format = ExportFormat::kStl;
  write(packing, path, options);
}

// Volume of a triangle soup by the divergence theorem (independent of ConvexPolyhedron).
double soup_volume(const StlMesh& mesh) {
  double volume = 0;
  for (const auto& t : mesh.triangles) volume += t[0].dot(t[1].cross(t[2])) / 6;
  return volume;
}

// The stored triangles equal the body's (as floats for binary, to `relative` for ASCII), in the
// body's CCW order, and every stored normal is the unit normal of that order.
void expect_matches(const StlMesh& mesh, const ConvexPolyhedron& body, double scale,
                    double relative) {
  ASSERT_EQ(mesh.triangles.size(), body.triangle_count());
  ASSERT_EQ(mesh.normals.size(), body.triangle_count());
  for (std::size_t f = 0; f < body.triangle_count(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      const Vec3 expected = body.vertices()[body.triangles()[f][corner]] * scale;
      ASSERT_LE((mesh.triangles[f][corner] - expected).norm(), relative * 0.1 * scale)
          << "facet " << f;
    }
    const auto& t = mesh.triangles[f];
    const Vec3 from_order = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    ASSERT_NEAR(mesh.normals[f].norm(), 1.0, 1e-6) << "facet " << f;
    ASSERT_GT(mesh.normals[f].dot(from_order), 1 - 1e-4) << "facet " << f;
    // Outward: the growth centre (origin, scaled) is behind every facet.
    ASSERT_GT(mesh.normals[f].dot(t[0]), 0.0) << "facet " << f;
  }
}

TEST(Stl, BinaryRoundTrip) {
  StlFolder folder;
  const auto body = particle();
  const std::string path = folder.file("p.stl");
  write_bodies(path, {body});
  const std::string bytes = test::file_text(path);
  EXPECT_EQ(bytes.size(), 84 + 50 * body.triangle_count());
  EXPECT_NE(bytes.rfind("solid", 0), 0U) << "a binary header must not start with 'solid'";
  const StlMesh mesh = read_stl(path);
  expect_matches(mesh, body, 1.0, 1e-6);
  const double volume = mass_properties(body).volume;
  EXPECT_NEAR(soup_volume(mesh), volume, 1e-5 * volume);
}

TEST(Stl, AsciiRoundTrip) {
  StlFolder folder;
  const auto body = particle(1);
  const std::string path = folder.file("p.stl");
  write_bodies(path, {body}, {.overwrite = Overwrite::kAllow, .stl_encoding = StlEncoding::kAscii});
  const std::string text = test::file_text(path);
  EXPECT_EQ(text.rfind("solid aggpack\n", 0), 0U);
  EXPECT_NE(text.find("endsolid aggpack\n"), std::string::npos);
  const StlMesh mesh = read_stl(path);
  expect_matches(mesh, body, 1.0, 1e-8);
  const double volume = mass_properties(body).volume;
  EXPECT_NEAR(soup_volume(mesh), volume, 1e-8 * volume);
}

TEST(Stl, ScaleAndSeveralBodies) {
  StlFolder folder;
  const auto a = particle(2);
  const auto b = particle(3).translated(Vec3(1, 0, 0));
  const std::string path = folder.file("two.stl");
  write_bodies(path, {a, b}, {.scale = 1000.0, .overwrite = Overwrite::kAllow});
  const StlMesh mesh = read_stl(path);
  ASSERT_EQ(mesh.triangles.size(), a.triangle_count() + b.triangle_count());
  EXPECT_LE((mesh.triangles[0][0] - 1000.0 * a.vertices()[a.triangles()[0][0]]).norm(), 1e-3);
  const double volume = (mass_properties(a).volume + mass_properties(b).volume) * 1e9;
  EXPECT_NEAR(soup_volume(mesh), volume, 1e-5 * volume);
}

TEST(Stl, WriteIsAtomicAndRespectsOverwrite) {
  StlFolder folder;
  const std::string path = folder.file("keep.stl");
  test::write_file(path, "keep me");
  EXPECT_THROW(write_bodies(path, {particle()}, {.overwrite = Overwrite::kForbid}), IoError);
  EXPECT_EQ(test::file_text(path), "keep me");
  EXPECT_EQ(folder.entry_count(), 1U) << "no temporary file left behind";
  write_bodies(path, {particle()}, {.overwrite = Overwrite::kAllow});
  EXPECT_EQ(read_stl(path).triangles.size(), particle().triangle_count());
  EXPECT_EQ(folder.entry_count(), 1U);

  EXPECT_THROW(write_bodies(folder.file("missing/p.stl"), {particle()}), IoError);
  for (const double scale : {0.0, -1.0, std::nan("")}) {
    EXPECT_THROW(write_bodies(folder.file("bad.stl"), {particle()}, {.scale = scale}),
                 InvalidInput);
  }
  EXPECT_FALSE(fs::exists(folder.file("bad.stl")));
  EXPECT_EQ(folder.entry_count(), 1U);
}

TEST(StlRead, MalformedFilesAreFormatErrors) {
  StlFolder folder;
  EXPECT_THROW(read_stl(folder.file("absent.stl")), IoError);
  fs::create_directory(folder.file("folder.stl"));
  EXPECT_THROW(read_stl(folder.file("folder.stl")), IoError);

  const std::string good = folder.file("good.stl");
  write_bodies(good, {particle()});
  const std::string bytes = test::file_text(good);
  const std::string truncated = folder.file("truncated.stl");
  test::write_file(truncated, bytes.substr(0, bytes.size() - 20));
  EXPECT_THROW(read_stl(truncated), FormatError);

  const std::string ascii = folder.file("ascii.stl");
  write_bodies(ascii, {particle()},
               {.overwrite = Overwrite::kAllow, .stl_encoding = StlEncoding::kAscii});
  const std::string text = test::file_text(ascii);
  const std::string cut = folder.file("cut.stl");
  test::write_file(cut, text.substr(0, text.size() / 2));
  EXPECT_THROW(read_stl(cut), FormatError);
  const std::string no_end = folder.file("no_end.stl");
  test::write_file(no_end, text.substr(0, text.rfind("endsolid")));
  EXPECT_THROW(read_stl(no_end), FormatError);
  const std::string bad_vertex = folder.file("bad_vertex.stl");
  std::string corrupted = text;
  corrupted.replace(corrupted.find("vertex"), 6, "vortex");
  test::write_file(bad_vertex, corrupted);
  EXPECT_THROW(read_stl(bad_vertex), FormatError);

  const std::string bad_normal = folder.file("bad_normal.stl");
  corrupted = text;
  corrupted.replace(corrupted.find("normal"), 6, "nermal");
  test::write_file(bad_normal, corrupted);
  EXPECT_THROW(read_stl(bad_normal), FormatError);
  const std::string bad_loop = folder.file("bad_loop.stl");
  corrupted = text;
  corrupted.replace(corrupted.find("outer loop"), 10, "outer hoop");
  test::write_file(bad_loop, corrupted);
  EXPECT_THROW(read_stl(bad_loop), FormatError);

  const std::string garbage = folder.file("garbage.stl");
  test::write_file(garbage, std::string(200, 'x'));
  EXPECT_THROW(read_stl(garbage), FormatError);
  const std::string empty = folder.file("empty.stl");
  test::write_file(empty, "");
  EXPECT_THROW(read_stl(empty), FormatError);
}

struct CommandResult {
  int exit_code = -1;
  std::string output;
};

CommandResult run(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
    result.output.append(buffer, count);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

bool has_admesh() { return run("command -v admesh").exit_code == 0; }

// admesh's report: the "Final" facet count, parts, volume and every fix-up counter.
std::map<std::string, double> admesh(const std::string& path) {
  const auto result = run("admesh '" + path + "'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  std::map<std::string, double> values;
  std::smatch match;
  const std::string& out = result.output;
  if (std::regex_search(out, match, std::regex(R"(Number of facets\s*:\s*(\d+)\s+(\d+))"))) {
    values["facets"] = std::stod(match[2]);
  }
  if (std::regex_search(out, match, std::regex(R"(Volume\s*:\s*([-0-9.eE+]+))"))) {
    values["volume"] = std::stod(match[1]);
  }
  if (std::regex_search(out, match, std::regex(R"(Number of parts\s*:\s*(\d+))"))) {
    values["parts"] = std::stod(match[1]);
  }
  if (std::regex_search(out, match,
                        std::regex(R"(Total disconnected facets\s*:\s*(\d+)\s+(\d+))"))) {
    values["disconnected"] = std::stod(match[1]);
  }
  for (const char* key : {"Degenerate facets", "Edges fixed", "Facets removed", "Facets added",
                          "Facets reversed", "Backwards edges", "Normals fixed"}) {
    if (std::regex_search(out, match, std::regex(std::string(key) + R"(\s*:\s*(\d+))"))) {
      values[key] = std::stod(match[1]);
    }
  }
  return values;
}

// admesh must find a written particle closed, with nothing to fix, and the polyhedron's volume.
TEST(StlAdmesh, ParticleIsCleanAndHasItsVolume) {
  if (!has_admesh())
    FAIL() << "admesh not installed (Debian package admesh; a test dependency, installed by "
              "scripts/install-deps.sh)";
  StlFolder folder;
  for (const auto encoding : {StlEncoding::kBinary, StlEncoding::kAscii}) {
    for (std::uint64_t index = 0; index < 3; ++index) {
      const auto body = particle(index);
      const std::string path = folder.file("p.stl");
      // Millimetres: admesh prints volumes with 6 decimals, too few for m^3.
      write_bodies(path, {body},
                   {.scale = 1000.0, .overwrite = Overwrite::kAllow, .stl_encoding = encoding});
      const auto report = admesh(path);
      ASSERT_EQ(report.count("volume"), 1U) << "admesh output not understood";
      ASSERT_EQ(report.size(), 11U) << "admesh output not fully understood";
      EXPECT_EQ(report.at("facets"), static_cast<double>(body.triangle_count()));
      EXPECT_EQ(report.at("parts"), 1.0);
      EXPECT_EQ(report.at("disconnected"), 0.0);
      for (const char* key : {"Degenerate facets", "Edges fixed", "Facets removed", "Facets added",
                              "Facets reversed", "Backwards edges", "Normals fixed"}) {
        EXPECT_EQ(report.at(key), 0.0) << key;
      }
      const double volume = mass_properties(body).volume * 1e9;
      EXPECT_NEAR(report.at("volume"), volume, 1e-5 * volume);
    }
  }
}

// Control: the same check does notice a facet written in the wrong order.
TEST(StlAdmesh, NoticesAFlippedFacet) {
  if (!has_admesh())
    FAIL() << "admesh not installed (Debian package admesh; a test dependency, installed by "
              "scripts/install-deps.sh)";
  StlFolder folder;
  const auto body = particle();
  auto triangles = body.triangles();
  std::swap(triangles[5][1], triangles[5][2]);
  const std::string path = folder.file("flipped.stl");
  write_bodies(path, {ConvexPolyhedron(body.vertices(), triangles)},
               {.scale = 1000.0, .overwrite = Overwrite::kAllow});
  const auto report = admesh(path);
  ASSERT_EQ(report.count("Facets reversed"), 1U);
  EXPECT_GT(report.at("Facets reversed") + report.at("Backwards edges"), 0.0);
}

}  // namespace
}  // namespace aggpack
