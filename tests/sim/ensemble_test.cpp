// Seed ensembles of the repose test (issue 15 item 2): seed lists, Student t quantiles, the
// statistics on fixed numbers, and `aggpack repose --seeds` end to end (per-seed folders, JSON and
// CSV agreeing with each seed's own repose.json, the same bytes at -j 1 and -j 2, bad --seeds).

#include "aggpack/sim/ensemble.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/sim/sweep.h"
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

TEST(StudentT, QuantilesMatchTables) {
  // Two-sided 95 % (p = 0.975) values from standard t tables, and a few other levels.
  EXPECT_NEAR(student_t_quantile(0.975, 1), 12.7062047, 1e-6);
  EXPECT_NEAR(student_t_quantile(0.975, 2), 4.30265273, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 3), 3.18244631, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 9), 2.26215716, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 15), 2.13144955, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 30), 2.04227246, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.975, 1000), 1.96233908, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.95, 10), 1.81246112, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.995, 5), 4.03214298, 1e-7);
  EXPECT_NEAR(student_t_quantile(0.025, 15), -2.13144955, 1e-7);
  EXPECT_EQ(student_t_quantile(0.5, 7), 0.0);
  EXPECT_THROW(student_t_quantile(1.0, 5), InvalidInput);
  EXPECT_THROW(student_t_quantile(0.9, 0.5), InvalidInput);
}

TEST(EnsembleStatistics, MeanSdAndIntervalOfFixedNumbers) {
  // 30, 32, 31, 35, 32: mean 32, sum of squares 4 + 0 + 1 + 9 + 0 = 14, sd sqrt(14 / 4).
  const auto s = ensemble_statistics({30.0, 32.0, 31.0, 35.0, 32.0});
  EXPECT_EQ(s.count, 5U);
  EXPECT_DOUBLE_EQ(s.mean, 32.0);
  EXPECT_NEAR(s.std_dev, std::sqrt(3.5), 1e-12);
  EXPECT_NEAR(s.t_quantile, 2.77644511, 1e-7);
  EXPECT_NEAR(s.half_width, 2.77644511 * std::sqrt(3.5) / std::sqrt(5.0), 1e-7);
  EXPECT_NEAR(s.lower(), 32.0 - s.half_width, 1e-12);
  EXPECT_TRUE(s.has_interval);
  const auto one = ensemble_statistics({33.0});
  EXPECT_EQ(one.count, 1U);
  EXPECT_DOUBLE_EQ(one.mean, 33.0);
  EXPECT_FALSE(one.has_interval);
  EXPECT_EQ(ensemble_statistics({}).count, 0U);
}

TEST(SeedList, RangesListsAndMixes) {
  EXPECT_EQ(parse_seed_list("1-4"), (std::vector<std::uint64_t>{1, 2, 3, 4}));
  EXPECT_EQ(parse_seed_list("1,4,9"), (std::vector<std::uint64_t>{1, 4, 9}));
  EXPECT_EQ(parse_seed_list("7-8,2"), (std::vector<std::uint64_t>{7, 8, 2}));
  EXPECT_EQ(parse_seed_list("5"), (std::vector<std::uint64_t>{5}));
  EXPECT_EQ(parse_seed_list("1-10000").size(), 10000U);
}

void expect_rejected(const std::string& text, const std::string& part) {
  try {
    parse_seed_list(text);
    ADD_FAILURE() << "accepted " << text;
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("invalid --seeds = ", 0), 0U) << message;
    EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(SeedList, RejectsBadValuesNamingTheFlag) {
  expect_rejected("", "a range 1-16");
  expect_rejected("1,,2", "non-negative integers");
  expect_rejected("a-3", "non-negative integers");
  expect_rejected("1.5", "non-negative integers");
  expect_rejected("-3", "non-negative integers");
  expect_rejected("9-2", "9-2 is reversed");
  expect_rejected("1-3,2", "2 repeats");
  expect_rejected("1-10001", "at most 10000 seeds");
  expect_rejected("1-9999,20000,20001", "at most 10000 seeds");
  expect_rejected("0-18446744073709551615", "at most 10000 seeds");
}

// The golden CLI test's tiny trough (a few particles, short rest times): seconds per seed.
const std::string kTrough = test::source_dir() + "/tests/cli/cases/repose/trough.toml";

class EnsembleCli : public test::CliTest {
 protected:
  EnsembleCli() : CliTest("aggpack_ensemble_") {}
  [[nodiscard]] std::string path(const std::string& name) const {
    return (folder_ / name).string();
  }
};

TEST_F(EnsembleCli, PerSeedResultsStatisticsAndThreadIndependence) {
  const std::string common = "repose " + kTrough + " --seeds 3,1-2 --width 64 --progress none";
  const auto one = run(common + " -j 1 -o " + path("j1"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = run(common + " -j 2 -o " + path("j2"));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  for (const char* name : {"ensemble.json", "ensemble.csv", "ensemble.png", "seed-1/repose.json",
                           "seed-2/profile.csv", "seed-3/repose.json"}) {
    const std::string a = test::file_text(fs::path(path("j1")) / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_TRUE(test::same_bytes(a, test::file_text(fs::path(path("j2")) / name)))
        << name << " differs between -j 1 and 2";
  }
  const auto json = nlohmann::json::parse(test::file_text(fs::path(path("j1")) / "ensemble.json"));
  ASSERT_EQ(json["seeds"].size(), 3U);
  const std::vector<std::uint64_t> order = {3, 1, 2};
  std::vector<double> angles;
  std::ifstream csv(fs::path(path("j1")) / "ensemble.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "seed,angle_deg,r_squared,valid,at_rest,particles,error");
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto& seed = json["seeds"][i];
    EXPECT_EQ(seed["seed"].get<std::uint64_t>(), order[i]);
    const auto own = nlohmann::json::parse(test::file_text(
        fs::path(path("j1")) / ("seed-" + std::to_string(order[i])) / "repose.json"));
    EXPECT_EQ(own["options"]["seed"].get<std::uint64_t>(), order[i]);
    ASSERT_TRUE(seed["valid"].get<bool>()) << seed.dump();
    EXPECT_EQ(seed["angle_degrees"].get<double>(), own["fit"]["angle_degrees"].get<double>());
    angles.push_back(seed["angle_degrees"].get<double>());
    ASSERT_TRUE(std::getline(csv, line));
    EXPECT_EQ(line.substr(0, line.find(',')), std::to_string(order[i]));
    const std::string rest = line.substr(line.find(',') + 1);
    EXPECT_EQ(std::stod(rest.substr(0, rest.find(','))), angles.back()) << line;
  }
  // The seeds differ, so their angles do: the ensemble is not one run three times.
  EXPECT_TRUE(angles[0] != angles[1] || angles[1] != angles[2]);
  const auto expected = ensemble_statistics(angles);
  const auto& st = json["statistics"];
  EXPECT_EQ(st["seeds_used"].get<std::size_t>(), 3U);
  EXPECT_EQ(st["seeds_failed"].get<std::size_t>(), 0U);
  EXPECT_DOUBLE_EQ(st["mean_angle_degrees"].get<double>(), expected.mean);
  EXPECT_DOUBLE_EQ(st["std_dev_degrees"].get<double>(), expected.std_dev);
  EXPECT_NEAR(st["t_quantile"].get<double>(), 4.30265273, 1e-7);
  EXPECT_DOUBLE_EQ(st["ci_lower_degrees"].get<double>(), expected.lower());
  EXPECT_DOUBLE_EQ(st["ci_upper_degrees"].get<double>(), expected.upper());
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "seeds_used,3,,,,,");
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(std::stod(line.substr(5)), expected.mean) << line;
}

TEST_F(EnsembleCli, BadSeedsGiveOneLineErrorsAndNoFolder) {
  for (const std::string seeds : {"''", "5-2", "x", "1-20000", "1,1"}) {
    const auto bad = run("repose " + kTrough + " --seeds " + seeds + " -o " + path("bad"));
    EXPECT_NE(bad.exit_code, 0) << seeds;
    EXPECT_EQ(bad.err.rfind("aggpack: error: invalid --seeds = ", 0), 0U) << bad.err;
    EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1) << bad.err;
    EXPECT_FALSE(fs::exists(path("bad"))) << seeds;
  }
}

}  // namespace
}  // namespace aggpack
