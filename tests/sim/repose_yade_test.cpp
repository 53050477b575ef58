// `aggpack repose --engine yade` (aggpack/sim/repose_yade.h): the real YADE (Debian's yade) runs
// a small trough end to end through the CLI; a missing yade is a one-line error naming the
// package; the particles YADE is given are exactly the fill Bullet starts from.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>

#include "aggpack/config/repose_config.h"
#include "aggpack/io/native.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/repose_yade.h"
#include "aggpack/study/repose_study.h"
#include "support/cli_test.h"
#include "support/readers.h"
#include "support/troughs.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

// 2 x 2 x 2 = 8 particles behind the baffle, few vertices (L = 2 R), short stages: a few
// thousand YADE steps.
const std::string kSmallTrough = test::small_trough("alpha = 0.9375\nedge_length = 0.01\n");

class ReposeYadeCli : public test::CliTest {
 protected:
  ReposeYadeCli() : CliTest("aggpack_repose_yade_") {}
  void write_config() const { std::ofstream(path("small.toml")) << kSmallTrough; }
};

TEST_F(ReposeYadeCli, RunsTheSmallTroughEndToEnd) {
  AGGPACK_REQUIRE_READER("yade");
  write_config();
  // YADE's scratch folder goes to TMPDIR: here one of the test's own, to see it removed.
  fs::create_directories(path("tmp"));
  const auto run = this->run("repose small.toml --engine yade --time-limit 1200 -o out",
                             "TMPDIR='" + path("tmp") + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("engine               yade: "), std::string::npos) << run.out;
  const auto json = nlohmann::json::parse(test::file_text(fs::path(path("out")) / "repose.json"));
  EXPECT_EQ(json["engine"], "yade");
  EXPECT_EQ(json["particles"]["count"], 8);
  EXPECT_GT(json["yade"]["iterations"].get<double>(), 100.0);
  // The baffle moved (it cannot pass the far wall: 0.05 - 0.005 - 0.02 m).
  const double travel = json["stage2"]["baffle_travel_m"];
  EXPECT_GT(travel, 0.005);
  EXPECT_LE(travel, 0.025 + 1e-12);
  // The pile is what the same measurement makes of YADE's final poses (final.h5): the profile's
  // crest is the highest particle point, on the floor and below the 2-layer fill's top.
  const Packing final = read_packing(path("out/final.h5"));
  ASSERT_EQ(final.particles.size(), 8U);
  double top = 0.0;
  for (std::size_t i = 0; i < final.particles.size(); ++i) {
    const Aabb box = final.placed(i).bounds();
    top = std::max(top, box.upper.z());
    EXPECT_GT(box.lower.z(), -0.001) << "particle " << i << " fell through the floor";
    EXPECT_GT(box.lower.x(), -0.001);
    EXPECT_LT(box.upper.x(), 0.05 + 0.001);
    EXPECT_GT(box.lower.y(), -0.001);
    EXPECT_LT(box.upper.y(), 0.02 + 0.001);
  }
  EXPECT_LT(top, 0.02);  // settled: below the lattice's top (2 layers of 2R = 0.02 m)
  const double crest = json["fit"]["pile_height_m"];
  EXPECT_NEAR(crest, top, 0.25 * 0.005);   // the smoothed profile's crest vs the highest point
  EXPECT_TRUE(fs::is_empty(path("tmp")));  // the scratch folder is gone
}

TEST_F(ReposeYadeCli, MissingYadeIsAOneLineErrorNamingThePackage) {
  write_config();
  const auto run = this->run("repose small.toml --engine yade -o out", "PATH=/nonexistent");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err,
            "aggpack: error: invalid physics.engine = yade (allowed: bullet, or yade with YADE "
            "installed: no program yade on PATH (Debian package yade: apt-get install yade))\n");
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(ReposeYadeCli, EngineFlagsAreChecked) {
  write_config();
  auto run = this->run("repose small.toml --engine ode -o out");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "aggpack: error: invalid --engine = ode (allowed: bullet or yade)\n");
  run = this->run("repose small.toml --engine yade --time-limit -1 -o out");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "aggpack: error: invalid --time-limit = -1 (allowed: [0, 1e7] s)\n");
  run = this->run("repose small.toml --set physics.engine=ode -o out");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("physics.engine"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(path("out")));
}

// The particles of YADE's script, parsed back: every vertex of particle k as the script lists it.
std::vector<std::vector<Vec3>> script_particles(const std::string& script) {
  std::vector<std::vector<Vec3>> particles;
  const std::size_t begin = script.find("particles = [\n");
  const std::size_t end = script.find("\n]\n", begin);
  std::istringstream lines(script.substr(begin + 14, end - begin - 14));
  const std::regex vertex(R"(\(([^,()]+), ([^,()]+), ([^,()]+)\))");
  for (std::string line; std::getline(lines, line);) {
    std::vector<Vec3> vertices;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), vertex);
         it != std::sregex_iterator(); ++it) {
      vertices.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]));
    }
    particles.push_back(vertices);
  }
  return particles;
}

TEST(ReposeYade, TheScriptHoldsBulletsFill) {
  AGGPACK_REQUIRE_READER("yade");  // run_repose_yade looks for it before it writes the script
  SweepOptions options = parse_sweep_config(kSmallTrough);
  options.base.rest.max_time = 0.05;  // the fill is all this test needs from Bullet
  options.base.confirm_window = 0.0;
  const ReposeResult bullet = run_repose(options.base, study::repose_fill(options.base));
  // The Bullet run's initial packing is what the YADE run prepares and gives its writer.
  options.base.engine = ReposeEngine::kYade;
  Packing given;
  std::string script;
  const auto capture = [&](const Packing& initial, const ReposeOptions& resolved,
                           std::ostream& out) {
    given = initial;
    std::ostringstream text;
    study::write_repose_yade_script(initial, resolved, text);
    script = text.str();
    out << "raise SystemExit(3)\n";  // stop here: the test needs the script, not the run
  };
  EXPECT_THROW(run_repose_yade(options.base, study::repose_fill(options.base), capture), Error);
  ASSERT_EQ(given.particles.size(), bullet.initial.particles.size());
  for (std::size_t i = 0; i < given.particles.size(); ++i) {
    EXPECT_EQ(given.particles[i].pose.position, bullet.initial.particles[i].pose.position);
    EXPECT_EQ(given.particles[i].pose.rotation.coeffs(),
              bullet.initial.particles[i].pose.rotation.coeffs());
    EXPECT_EQ(given.particles[i].shape, bullet.initial.particles[i].shape);
  }
  // The script's bodies are those particles' vertices, exactly (shortest round-trip numbers).
  const auto bodies = script_particles(script);
  ASSERT_EQ(bodies.size(), bullet.initial.particles.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const ConvexPolyhedron placed = bullet.initial.placed(i);
    ASSERT_EQ(bodies[i].size(), placed.vertices().size()) << "particle " << i;
    for (std::size_t v = 0; v < bodies[i].size(); ++v) {
      EXPECT_LT((bodies[i][v] - placed.vertices()[v]).norm(), 1e-15)
          << "particle " << i << " vertex " << v;
    }
  }
  EXPECT_NE(script.find("FRICTION = 0.5\n"), std::string::npos);
  EXPECT_NE(script.find("BAFFLE_POSITION = 0.02\n"), std::string::npos);
}

}  // namespace
}  // namespace aggpack
