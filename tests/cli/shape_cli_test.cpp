// `aggpack particle` and `aggpack shapes` end to end (issue 2 items 5 and 6): STL and CSV outputs
// read back and checked against the library, byte-identical output for 1 and 2 threads, --help,
// and bad input: non-zero exit, a one-line error naming the flag, value and range, and no output
// file (an existing one left untouched without --force).

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/stl.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"
#include "support/cli_test.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::file_text;

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  return parts;
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

class ShapeCliTest : public test::CliTest {
 protected:
  ShapeCliTest() : CliTest("aggpack_shape_cli_") {}
  [[nodiscard]] fs::path file(const std::string& name) const { return folder_ / name; }
  [[nodiscard]] std::size_t entry_count() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(folder_), fs::directory_iterator()));
  }
};

// The value printed after `name` in `aggpack particle`'s report.
double reported(const std::string& report, const std::string& name) {
  for (const auto& line : split(report, '\n')) {
    if (line.rfind(name + " ", 0) == 0) return std::stod(line.substr(name.size()));
  }
  ADD_FAILURE() << name << " not in report:\n" << report;
  return std::nan("");
}

TEST_F(ShapeCliTest, ParticleWritesBinaryAndAsciiStlMatchingTheLibrary) {
  const GeneratorOptions options{
      .alpha = 0.3, .radius_min = 0.08, .radius_max = 0.08, .edge_length = 0.04, .seed = 5};
  const auto expected = generate_particle(options, 7);
  const std::string flags = "--alpha 0.3 -r 0.08 -L 0.04 --seed 5 --index 7";

  const auto binary = run("particle " + flags + " -o p.stl");
  ASSERT_EQ(binary.exit_code, 0) << binary.err;
  EXPECT_EQ(binary.err, "");
  const StlMesh mesh = read_stl(file("p.stl").string());
  EXPECT_EQ(mesh.triangles.size(), expected.body.triangle_count());
  EXPECT_EQ(reported(binary.out, "faces"), static_cast<double>(expected.body.triangle_count()));
  EXPECT_EQ(reported(binary.out, "vertices"), static_cast<double>(expected.body.vertex_count()));
  const auto d = describe(expected.body);
  EXPECT_NEAR(reported(binary.out, "volume"), d.volume, 1e-5 * d.volume);
  EXPECT_NEAR(reported(binary.out, "measured_alpha"), d.measured_alpha, 1e-5);
  EXPECT_NEAR(reported(binary.out, "control radius"), 0.08, 1e-12);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Vec3 v = expected.body.vertices()[expected.body.triangles()[f][0]];
    ASSERT_LE((mesh.triangles[f][0] - v).norm(), 1e-7);
  }

  const auto ascii = run("particle " + flags + " --ascii --scale 1000 -o a.stl");
  ASSERT_EQ(ascii.exit_code, 0) << ascii.err;
  EXPECT_EQ(file_text(file("a.stl")).rfind("solid aggpack", 0), 0U);
  const StlMesh millimetres = read_stl(file("a.stl").string());
  ASSERT_EQ(millimetres.triangles.size(), mesh.triangles.size());
  EXPECT_LE((millimetres.triangles[3][1] - 1000.0 * mesh.triangles[3][1]).norm(), 1e-3);

  // The same command gives the same bytes; another index gives another particle.
  ASSERT_EQ(run("particle " + flags + " -o again.stl").exit_code, 0);
  EXPECT_TRUE(test::same_bytes(file_text(file("p.stl")), file_text(file("again.stl"))));
  ASSERT_EQ(run("particle --alpha 0.3 -r 0.08 -L 0.04 --seed 5 --index 8 -o other.stl").exit_code,
            0);
  EXPECT_NE(file_text(file("p.stl")), file_text(file("other.stl")));
}

TEST_F(ShapeCliTest, ShapesCsvIsByteIdenticalForOneAndTwoThreads) {
  const std::string flags =
      "-n 3000 --alpha 0.6 --radius-min 0.05 --radius-max 0.1 -L 0.04 --seed 11";
  const auto one = run("shapes " + flags + " -j 1 -o one.csv");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = run("shapes " + flags + " --threads 2 -o two.csv");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const std::string csv = file_text(file("one.csv"));
  EXPECT_TRUE(test::same_bytes(csv, file_text(file("two.csv"))));
  // The printed summary is the same too, apart from the file name.
  EXPECT_EQ(one.out.substr(one.out.find('\n')), two.out.substr(two.out.find('\n')));

  // Header, one row per particle, rows in index order and equal to the library's values.
  const auto lines = split(csv, '\n');
  ASSERT_EQ(lines.size(), 3001U);
  const auto header = split(lines[0], ',');
  ASSERT_EQ(header.size(), 2 + descriptor_columns().size());
  EXPECT_EQ(header[0], "index");
  EXPECT_EQ(header[1], "control_radius");
  for (std::size_t c = 0; c < descriptor_columns().size(); ++c) {
    EXPECT_EQ(header[2 + c], descriptor_columns()[c].name);
  }
  const GeneratorOptions options{
      .alpha = 0.6, .radius_min = 0.05, .radius_max = 0.1, .edge_length = 0.04, .seed = 11};
  std::vector<double> alphas;
  for (std::size_t i = 0; i < 3000; ++i) {
    const auto row = split(lines[i + 1], ',');
    ASSERT_EQ(row.size(), header.size());
    ASSERT_EQ(row[0], std::to_string(i));
    alphas.push_back(std::stod(row[2 + 3]));  // measured_alpha
    if (i % 500 == 0) {
      // %.17g round-trips doubles exactly.
      const auto particle = generate_particle(options, i);
      const auto d = describe(particle.body);
      EXPECT_EQ(std::stod(row[1]), particle.control_radius) << "row " << i;
      for (std::size_t c = 0; c < descriptor_columns().size(); ++c) {
        EXPECT_EQ(std::stod(row[2 + c]), descriptor_columns()[c].get(d))
            << "row " << i << " " << header[2 + c];
      }
    }
  }
  // The summary's mean of measured alpha is the CSV column's mean.
  const auto stats = summarize(alphas);
  for (const auto& line : split(one.out, '\n')) {
    if (line.rfind("measured_alpha", 0) != 0) continue;
    std::istringstream fields(line.substr(std::string("measured_alpha").size()));
    double mean = 0, deviation = 0, minimum = 0, maximum = 0;
    fields >> mean >> deviation >> minimum >> maximum;
    EXPECT_NEAR(mean, stats.mean, 1e-5);
    EXPECT_NEAR(deviation, stats.standard_deviation, 1e-5);
    EXPECT_NEAR(minimum, stats.minimum, 1e-5);
    EXPECT_NEAR(maximum, stats.maximum, 1e-5);
  }
  EXPECT_NE(one.out.find("measured_alpha"), std::string::npos) << one.out;
}

TEST_F(ShapeCliTest, HelpDocumentsEveryOptionWithDefault) {
  for (const char* command : {"particle", "shapes"}) {
    const auto help = run(std::string(command) + " --help");
    ASSERT_EQ(help.exit_code, 0);
    for (const char* expected :
         {"--alpha FLOAT=0.5", "-r,--radius", "--radius-min FLOAT=0.1", "--radius-max FLOAT=0.1",
          "-L,--edge-length FLOAT=0.1", "--max-vertices UINT=20000", "--seed UINT=1", "(m)",
          "[0, 1]", "-o,--output", "-f,--force"}) {
      EXPECT_NE(help.out.find(expected), std::string::npos) << command << ": " << expected;
    }
  }
  const auto shapes = run("shapes --help");
  EXPECT_NE(shapes.out.find("-n,--count UINT=1000"), std::string::npos) << shapes.out;
  EXPECT_NE(shapes.out.find("-j,--threads INT=0"), std::string::npos) << shapes.out;
  const auto particle = run("particle --help");
  EXPECT_NE(particle.out.find("--index UINT=0"), std::string::npos) << particle.out;
  EXPECT_NE(particle.out.find("--scale FLOAT=1"), std::string::npos) << particle.out;
  EXPECT_NE(particle.out.find("--ascii"), std::string::npos) << particle.out;
}

struct BadInput {
  std::string arguments;
  std::vector<std::string> message_parts;  // all must appear in stderr
};

// Every bad input: non-zero exit, the flag and value named, nothing written.
TEST_F(ShapeCliTest, BadInputFailsWithOneLineAndNoFile) {
  const std::vector<BadInput> cases = {
      {"--alpha -0.1", {"--alpha", "-0.1", "[0, 1]"}},
      {"--alpha 1.5", {"--alpha", "1.5", "[0, 1]"}},
      {"--alpha nan", {"--alpha", "nan", "[0, 1]"}},
      {"--alpha inf", {"--alpha", "inf", "[0, 1]"}},
      {"-r 0", {"--radius", "= 0", "> 0"}},
      {"-r -0.1", {"--radius", "-0.1", "> 0"}},
      {"-r nan", {"--radius", "nan", "> 0"}},
      {"--radius inf", {"--radius", "inf", "> 0"}},
      {"--radius-min 0", {"--radius-min", "= 0", "> 0"}},
      {"--radius-max -1", {"--radius-max", "-1", "> 0"}},
      {"--radius-min 0.2 --radius-max 0.1", {"--radius-max", "0.1", ">= --radius-min = 0.2"}},
      {"-r 0.1 --radius-min 0.1", {"--radius", "not both"}},
      {"-L 0", {"--edge-length", "= 0", "> 0"}},
      {"-L -0.05", {"--edge-length", "-0.05", "> 0"}},
      {"--edge-length nan", {"--edge-length", "nan", "> 0"}},
      {"-L inf", {"--edge-length", "inf", "> 0"}},
      {"-L 1e-5", {"limit exceeded for --edge-length", "1e-05", "max_vertices is 20000"}},
      {"-L 0.01 --max-vertices 100",
       {"limit exceeded for --edge-length", "0.01", "max_vertices is 100"}},
      {"--max-vertices 5", {"invalid --max-vertices", "5", "[6, 1000000]"}},
      {"--max-vertices 2000000", {"invalid --max-vertices", "2000000", "[6, 1000000]"}},
      {"--seed -1", {"--seed", "-1", ">= 0"}},
      {"--alpha abc", {"--alpha", "abc"}},
      {"--bogus 3", {"--bogus"}},
  };
  for (const char* command : {"shapes -n 5", "particle"}) {
    for (const auto& bad : cases) {
      const std::string output =
          std::string(command).rfind("shapes", 0) == 0 ? "out.csv" : "out.stl";
      const auto result = run(std::string(command) + " " + bad.arguments + " -o " + output);
      SCOPED_TRACE(std::string(command) + " " + bad.arguments);
      EXPECT_NE(result.exit_code, 0);
      EXPECT_EQ(result.out, "");
      for (const auto& part : bad.message_parts) {
        EXPECT_NE(result.err.find(part), std::string::npos) << result.err;
      }
      // aggpack's own errors are one line; CLI11's parse errors add a "Run with --help" line.
      if (result.err.rfind("aggpack: error: ", 0) == 0) {
        EXPECT_EQ(line_count(result.err), 1U) << result.err;
      } else {
        EXPECT_LE(line_count(result.err), 2U) << result.err;
      }
      EXPECT_EQ(entry_count(), 0U) << "an output file was created";
    }
  }
  const auto zero = run("shapes -n 0 -o out.csv");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("invalid -n/--count = 0 (allowed: [1, 100000000])"), std::string::npos)
      << zero.err;
  const auto threads = run("shapes -n 5 -j -2 -o out.csv");
  EXPECT_NE(threads.exit_code, 0);
  EXPECT_NE(threads.err.find("--threads"), std::string::npos) << threads.err;
  EXPECT_EQ(entry_count(), 0U);
  const auto scale = run("particle --scale 0 -o out.stl");
  EXPECT_NE(scale.exit_code, 0);
  EXPECT_NE(scale.err.find("--scale = 0"), std::string::npos) << scale.err;
  EXPECT_EQ(entry_count(), 0U);
}

TEST_F(ShapeCliTest, ExistingOutputIsKeptWithoutForce) {
  std::ofstream(file("old.csv")) << "keep me\n";
  std::ofstream(file("old.stl")) << "keep me\n";
  const auto shapes = run("shapes -n 10 -o old.csv");
  EXPECT_EQ(shapes.exit_code, 3);
  EXPECT_NE(shapes.err.find("old.csv"), std::string::npos) << shapes.err;
  EXPECT_NE(shapes.err.find("--force"), std::string::npos) << shapes.err;
  EXPECT_EQ(line_count(shapes.err), 1U);
  EXPECT_EQ(file_text(file("old.csv")), "keep me\n");
  const auto particle = run("particle -o old.stl");
  EXPECT_EQ(particle.exit_code, 3);
  EXPECT_EQ(file_text(file("old.stl")), "keep me\n");
  EXPECT_EQ(entry_count(), 2U);

  ASSERT_EQ(run("shapes -n 10 -o old.csv --force").exit_code, 0);
  EXPECT_EQ(file_text(file("old.csv")).rfind("index,control_radius,", 0), 0U);
  ASSERT_EQ(run("particle -f -o old.stl").exit_code, 0);
  EXPECT_GT(read_stl(file("old.stl").string()).triangles.size(), 8U);
  EXPECT_EQ(entry_count(), 2U) << "no temporary files left";

  const auto missing = run("shapes -n 10 -o no/such/folder/x.csv");
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_NE(missing.err.find("no/such/folder"), std::string::npos) << missing.err;
  EXPECT_EQ(entry_count(), 2U);
}

// A cap just below the up-front vertex estimate is refused before any particle is made; at the
// estimate the run succeeds.
TEST_F(ShapeCliTest, VertexCapIsCheckedUpFront) {
  const auto cap = static_cast<std::uint32_t>(std::ceil(estimated_vertex_count(0.1, 0.02)));
  const std::string flags = "shapes -n 200 --alpha 1 -r 0.1 -L 0.02 --max-vertices ";
  const auto refused = run(flags + std::to_string(cap - 1) + " -o capped.csv");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(refused.err.rfind("aggpack: error: limit exceeded for --edge-length = 0.02", 0), 0U)
      << refused.err;
  EXPECT_EQ(line_count(refused.err), 1U);
  EXPECT_EQ(entry_count(), 0U);
  const auto accepted = run(flags + std::to_string(cap) + " -o capped.csv");
  EXPECT_EQ(accepted.exit_code, 0) << accepted.err;
  EXPECT_EQ(line_count(file_text(file("capped.csv"))), 201U);
}

}  // namespace
}  // namespace aggpack
