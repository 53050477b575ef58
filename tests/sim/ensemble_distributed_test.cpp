// Ensembles and sweeps in parts (issue 15 item 6): `--case K --of N` shares, run records,
// `aggpack merge` giving byte for byte the single-process folder, and its refusals (missing runs,
// records of another configuration, edited records, bad --case / --of); the ensemble.seeds key.

#include "aggpack/sim/distributed.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"
#include "support/cli_test.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

TEST(RunShare, ParsesAndValidatesCaseAndOf) {
  const RunShare whole = parse_run_share(std::nullopt, std::nullopt);
  EXPECT_FALSE(whole.is_split());
  EXPECT_TRUE(whole.owns(0) && whole.owns(7));
  const RunShare second = parse_run_share("2", "3");
  EXPECT_EQ(second.worker, 2U);
  EXPECT_EQ(second.of, 3U);
  // Round robin: runs 1, 4, 7 (0-based) belong to worker 2 of 3.
  std::vector<std::size_t> owned;
  for (std::size_t i = 0; i < 9; ++i) {
    if (second.owns(i)) owned.push_back(i);
  }
  EXPECT_EQ(owned, (std::vector<std::size_t>{1, 4, 7}));
  const auto rejected = [](std::optional<std::string> k, std::optional<std::string> n,
                           const std::string& start, const std::string& part) {
    try {
      parse_run_share(k, n);
      ADD_FAILURE() << "accepted --case " << k.value_or("-") << " --of " << n.value_or("-");
    } catch (const InvalidInput& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.rfind(start, 0), 0U) << message;
      EXPECT_NE(message.find(part), std::string::npos) << message;
    }
  };
  rejected("0", "2", "invalid --case = 0", "[1, 2]");
  rejected("3", "2", "invalid --case = 3", "[1, 2]");
  rejected("-1", "2", "invalid --case = -1", "[1, 2]");
  rejected("1.5", "2", "invalid --case = 1.5", "[1, 2]");
  rejected("1", "0", "invalid --of = 0", "[1, 100000]");
  rejected("1", "100001", "invalid --of = 100001", "[1, 100000]");
  rejected("1", "x", "invalid --of = x", "[1, 100000]");
  rejected("1", std::nullopt, "invalid --case = 1", "only with --of");
  rejected(std::nullopt, "2", "invalid --of = 2", "only with --case");
}

TEST(RunShare, SeedListsFormatBackAndHashesTellTextsApart) {
  EXPECT_EQ(format_seed_list({1, 2, 3, 4, 9}), "1-4,9");
  EXPECT_EQ(format_seed_list({7, 8, 2}), "7-8,2");
  EXPECT_EQ(format_seed_list({5}), "5");
  EXPECT_EQ(format_seed_list({}), "");
  for (const std::string text : {"1-16", "3,1-2", "1-4,9,11-12"}) {
    EXPECT_EQ(format_seed_list(parse_seed_list(text)), text);
  }
  EXPECT_EQ(config_hash("").size(), 16U);
  EXPECT_EQ(config_hash("a = 1\n"), config_hash("a = 1\n"));
  EXPECT_NE(config_hash("a = 1\n"), config_hash("a = 2\n"));
  // Comments (key documentation) do not count; values, also with a '#' in a string, do.
  EXPECT_EQ(config_hash("a = 1  # the a\n"), config_hash("a = 1\n"));
  EXPECT_NE(config_hash("a = \"x # y\"\n"), config_hash("a = \"x\"\n"));
}

TEST(EnsembleSeedsKey, ConfigKeyGivesTheSeedListAndWritesItBack) {
  const SweepOptions options = parse_sweep_config("[ensemble]\nseeds = \"1-3,7\"\n");
  EXPECT_EQ(options.seeds, (std::vector<std::uint64_t>{1, 2, 3, 7}));
  EXPECT_NE(resolved_sweep_config(options).find("seeds = \"1-3,7\""), std::string::npos);
  EXPECT_TRUE(parse_sweep_config("").seeds.empty());
  EXPECT_EQ(resolved_sweep_config(parse_sweep_config("")).find("[ensemble]"), std::string::npos);
  try {
    with_sweep_key_names([] { parse_sweep_config("[ensemble]\nseeds = \"4-2\"\n"); });
    ADD_FAILURE() << "accepted seeds 4-2";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("ensemble.seeds"), std::string::npos) << error.what();
  }
}

// The golden CLI test's tiny trough (120 particles, short rest times): about a second per run.
const std::string kTinyCase = test::source_dir() + "/tests/cli/cases/repose/trough.toml";

class DistributedCli : public test::CliTest {
 protected:
  DistributedCli() : CliTest("aggpack_dist_") {}
  [[nodiscard]] std::string path(const std::string& name) const {
    return (folder_ / name).string();
  }
  // Every file under `root` (relative path -> bytes).
  [[nodiscard]] static std::map<std::string, std::string> tree(const fs::path& root) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (entry.is_regular_file()) {
        files[fs::relative(entry.path(), root).string()] = test::file_text(entry.path());
      }
    }
    return files;
  }
  void expect_same_tree(const std::string& a, const std::string& b) const {
    const auto left = tree(path(a));
    const auto right = tree(path(b));
    std::vector<std::string> left_names;
    std::vector<std::string> right_names;
    for (const auto& [name, bytes] : left) left_names.push_back(name);
    for (const auto& [name, bytes] : right) right_names.push_back(name);
    ASSERT_EQ(left_names, right_names);
    for (const auto& [name, bytes] : left) {
      EXPECT_FALSE(bytes.empty()) << name;
      EXPECT_TRUE(bytes == right.at(name)) << name << " differs between " << a << " and " << b;
    }
  }
};

TEST_F(DistributedCli, TwoWorkersAndMergeGiveTheSingleProcessEnsemble) {
  const std::string common = "repose " + kTinyCase + " --seeds 3,1-2,5 --width 64 --progress none";
  const auto single = run(common + " -j 2 -o single");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  for (const char* worker : {"1", "2"}) {
    const auto part = run(common + " -j 1 --case " + std::string(worker) + " --of 2 -o parts");
    ASSERT_EQ(part.exit_code, 0) << part.err;
    EXPECT_NE(part.out.find("2 of 4 runs done"), std::string::npos) << part.out;
  }
  // Workers write their runs only: no summary before the merge.
  EXPECT_FALSE(fs::exists(path("parts/ensemble.json")));
  EXPECT_TRUE(fs::exists(path("parts/runs/seed-5.json")));
  EXPECT_TRUE(fs::exists(path("parts/seed-2/repose.json")));
  // ensemble.png at the workers' --width 64 (from their records).
  const auto merged = run("merge parts");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  EXPECT_NE(merged.out.find("merge: ensemble of 4 seeds"), std::string::npos) << merged.out;
  // ensemble.json|csv|png, runs/*.json and seed-<k>/*: the same files, the same bytes.
  expect_same_tree("single", "parts");
  EXPECT_EQ(tree(path("single")).size(), 3U + 4U + 4U * 4U);
  // The printed table and statistics too (the first and last lines name the command/folder).
  const auto table = [](const std::string& text) {
    return text.substr(text.find('\n') + 1, text.rfind("wrote") - text.find('\n') - 1);
  };
  EXPECT_EQ(table(single.out), table(merged.out));
  // -o: the summary elsewhere, the same bytes.
  const auto elsewhere = run("merge parts -o summary");
  ASSERT_EQ(elsewhere.exit_code, 0) << elsewhere.err;
  EXPECT_EQ(test::file_text(path("summary/ensemble.csv")),
            test::file_text(path("single/ensemble.csv")));
  // An existing summary is kept unless -f.
  EXPECT_NE(run("merge parts").exit_code, 0);
  EXPECT_EQ(run("merge parts -f").exit_code, 0);
  EXPECT_TRUE(test::same_bytes(test::file_text(path("parts/ensemble.png")),
                               test::file_text(path("single/ensemble.png"))));
  // --width overrides it.
  EXPECT_EQ(run("merge parts -f --width 100").exit_code, 0);
  EXPECT_NE(test::file_text(path("parts/ensemble.png")),
            test::file_text(path("single/ensemble.png")));
}

TEST_F(DistributedCli, ThreeWorkersAndMergeGiveTheSingleProcessSweep) {
  const std::string common = "sweep " + kTinyCase +
                             " --set sweep.alphas=[0.5,0.7] --set sweep.frictions=[0.3] "
                             "--seeds 1-2 --width 64 --progress none --no-plot";
  const auto single = run(common + " -j 2 -o single");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  for (const char* worker : {"3", "1", "2"}) {
    const auto part = run(common + " -j 1 --case " + std::string(worker) + " --of 3 -o parts");
    ASSERT_EQ(part.exit_code, 0) << part.err;
  }
  EXPECT_FALSE(fs::exists(path("parts/sweep.csv")));
  const auto merged = run("merge parts --no-plot");
  ASSERT_EQ(merged.exit_code, 0) << merged.err;
  // sweep.csv, sweep.gp, cases/*.json|png and runs/*.json.
  expect_same_tree("single", "parts");
  EXPECT_EQ(tree(path("single")).size(), 2U + 3U * 4U);
  EXPECT_NE(test::file_text(path("parts/sweep.csv")).find("\n0.7,0.3,"), std::string::npos);
}

TEST_F(DistributedCli, MergeRefusesMissingRunsOtherConfigurationsAndEditedRecords) {
  const std::string common = "repose " + kTinyCase + " --seeds 1-3 --width 64 --progress none";
  ASSERT_EQ(run(common + " --case 1 --of 2 -o parts").exit_code, 0);
  // Worker 2 (seed 2) has not run.
  const auto incomplete = run("merge parts");
  EXPECT_NE(incomplete.exit_code, 0);
  EXPECT_EQ(incomplete.err.rfind("aggpack: error: invalid merge parts = 2 of 3 runs", 0), 0U)
      << incomplete.err;
  EXPECT_NE(incomplete.err.find("missing seed 2 (run 2)"), std::string::npos) << incomplete.err;
  EXPECT_EQ(incomplete.err.find('\n'), incomplete.err.size() - 1) << incomplete.err;
  EXPECT_FALSE(fs::exists(path("parts/ensemble.json")));
  // A worker with another configuration refuses the folder before running.
  const auto other = run(common + " --mu 0.4 --case 2 --of 2 -o parts");
  EXPECT_NE(other.exit_code, 0);
  EXPECT_EQ(other.err.rfind("aggpack: error: invalid -o parts = a folder holding", 0), 0U)
      << other.err;
  EXPECT_FALSE(fs::exists(path("parts/runs/seed-2.json")));
  // A record of another configuration copied in: merge names both files.
  ASSERT_EQ(run(common + " --mu 0.4 --case 2 --of 2 -o stray").exit_code, 0);
  fs::copy_file(path("stray/runs/seed-2.json"), path("parts/runs/seed-2.json"));
  const auto mixed = run("merge parts");
  EXPECT_NE(mixed.exit_code, 0);
  EXPECT_NE(mixed.err.find("records of one plan only"), std::string::npos) << mixed.err;
  EXPECT_NE(mixed.err.find("seed-2.json"), std::string::npos) << mixed.err;
  EXPECT_FALSE(fs::exists(path("parts/ensemble.json")));
  // An edited record (its configuration no longer matches its hash).
  std::string text = test::file_text(path("stray/runs/seed-2.json"));
  text.replace(text.find("friction = 0.4"), 14, "friction = 0.3");
  {
    std::ofstream out(path("parts/runs/seed-2.json"), std::ios::binary | std::ios::trunc);
    out << text;
  }
  const auto edited = run("merge parts");
  EXPECT_NE(edited.exit_code, 0);
  EXPECT_NE(edited.err.find("does not match its configuration"), std::string::npos) << edited.err;
  // The right worker completes the folder.
  fs::remove(path("parts/runs/seed-2.json"));
  ASSERT_EQ(run(common + " --case 2 --of 2 -o parts").exit_code, 0);
  EXPECT_EQ(run("merge parts").exit_code, 0);
  EXPECT_TRUE(fs::exists(path("parts/ensemble.json")));
  // No run records at all.
  fs::create_directories(path("empty/runs"));
  const auto empty = run("merge empty");
  EXPECT_NE(empty.exit_code, 0);
  EXPECT_NE(empty.err.find("none found"), std::string::npos) << empty.err;
}

#ifdef AGGPACK_HAS_MPI
// `mpirun -n 2 aggpack sweep`: rank r runs --case r+1 --of 2, rank 0 merges after both are done.
// Built with MPI, mpirun must work (the test fails, not skips, without it).
TEST_F(DistributedCli, MpirunWithTwoRanksGivesTheSingleProcessSweep) {
  const std::string common = "sweep " + kTinyCase +
                             " --set sweep.alphas=[0.5] --set sweep.frictions=[0.2,0.4] "
                             "--seeds 1-2 --width 64 --progress none --no-plot -j 1";
  const auto single = run(common + " -o single");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  // As root (containers, CI) OpenMPI needs both variables; --oversubscribe: 2 ranks on any CPU.
  const auto mpi = run(common + " -o ranks",
                       "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                       "OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -n 2");
  ASSERT_EQ(mpi.exit_code, 0) << mpi.out << mpi.err;
  EXPECT_NE(mpi.out.find("worker 1 of 2"), std::string::npos) << mpi.out;
  EXPECT_NE(mpi.out.find("worker 2 of 2"), std::string::npos) << mpi.out;
  EXPECT_NE(mpi.out.find("merge: sweep of 2 cases x 2 seeds"), std::string::npos) << mpi.out;
  expect_same_tree("single", "ranks");
}
#endif

TEST_F(DistributedCli, BadCaseAndOfGiveOneLineErrorsAndNoFolder) {
  const std::string common = "repose " + kTinyCase + " --seeds 1-2 --progress none -o bad";
  for (const std::string flags :
       {"--case 0 --of 2", "--case 3 --of 2", "--case x --of 2", "--case 1 --of 0",
        "--case 1 --of 100001", "--case 1", "--of 2"}) {
    const auto bad = run(common + " " + flags);
    EXPECT_NE(bad.exit_code, 0) << flags;
    EXPECT_EQ(bad.err.rfind("aggpack: error: invalid --", 0), 0U) << bad.err;
    EXPECT_EQ(bad.err.find('\n'), bad.err.size() - 1) << bad.err;
    EXPECT_FALSE(fs::exists(path("bad"))) << flags;
  }
  const auto single = run("repose " + kTinyCase + " --case 1 --of 2 -o bad");
  EXPECT_NE(single.exit_code, 0);
  EXPECT_NE(single.err.find("only with a seed ensemble"), std::string::npos) << single.err;
  const auto sweep = run("sweep " + kTinyCase + " --case 4 --of 3 -o bad");
  EXPECT_EQ(
      sweep.err.rfind("aggpack: error: invalid --case = 4 (allowed: a whole number in [1, 3]", 0),
      0U)
      << sweep.err;
  EXPECT_FALSE(fs::exists(path("bad")));
}

TEST_F(DistributedCli, EnsembleSeedsKeyRunsTheEnsembleAndTheFlagOverridesIt) {
  const std::string common = "repose " + kTinyCase + " --width 64 --progress none";
  ASSERT_EQ(run(common + " --set 'ensemble.seeds=\"1-2\"' -o key").exit_code, 0);
  ASSERT_EQ(run(common + " --seeds 1-2 -o flag").exit_code, 0);
  EXPECT_EQ(test::file_text(path("key/ensemble.csv")), test::file_text(path("flag/ensemble.csv")));
  EXPECT_FALSE(test::file_text(path("key/ensemble.csv")).empty());
  ASSERT_EQ(run(common + " --set 'ensemble.seeds=\"1-2\"' --seeds 2 -o over").exit_code, 0);
  EXPECT_TRUE(fs::exists(path("over/seed-2")));
  EXPECT_FALSE(fs::exists(path("over/seed-1")));
  const auto bad = run(common + " --set 'ensemble.seeds=\"5-1\"' -o bad");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("ensemble.seeds"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace aggpack
