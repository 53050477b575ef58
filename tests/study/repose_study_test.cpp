// The study layer's calls on the golden CLI test's tiny trough (seconds per run): an ensemble's
// per-seed angles are those of separate single runs, the same every time and at any thread
// count; a failing seed is reported and left out; a sweep's case with seeds is that case's
// ensemble; cancelling skips the runs not yet started.

#include "aggpack/study/repose_study.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/verify.h"
#include "support/files.h"
#include "support/paths.h"

namespace aggpack {
namespace {

namespace fs = std::filesystem;

const std::string kStudyTrough = test::source_dir() + "/tests/cli/cases/repose/trough.toml";

TEST(ReposeStudy, EnsembleAnglesAreThoseOfSeparateRunsAndRepeat) {
  const ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  std::vector<std::uint64_t> reported;
  study::StudyControl control;
  control.on_seed = [&](const EnsembleSeed& s, const ReposeResult* result, std::size_t done,
                        std::size_t total) {
    EXPECT_NE(result, nullptr);
    EXPECT_EQ(total, 2U);
    EXPECT_EQ(done, reported.size() + 1);
    reported.push_back(s.seed);
  };
  const std::vector<std::uint64_t> order = {2, 1};
  const EnsembleResult ensemble = study::run_repose_ensemble(base, order, control);
  EXPECT_EQ(reported.size(), 2U);
  EXPECT_FALSE(ensemble.is_cancelled);
  ASSERT_EQ(ensemble.seeds.size(), 2U);
  std::vector<double> angles;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const EnsembleSeed& seed = ensemble.seeds[i];
    EXPECT_EQ(seed.seed, order[i]);
    ASSERT_TRUE(seed.is_valid) << seed.error;
    ReposeOptions single = base;
    single.seed = order[i];
    const ReposeResult alone = study::run_repose(single);
    EXPECT_EQ(seed.angle_degrees, alone.fit.angle_degrees) << "seed " << order[i];
    EXPECT_EQ(seed.r_squared, alone.fit.r_squared);
    EXPECT_EQ(seed.particle_count, alone.particle_count);
    angles.push_back(seed.angle_degrees);
  }
  EXPECT_NE(angles[0], angles[1]);  // different seeds, different piles
  const EnsembleStatistics expected = ensemble_statistics(angles);
  EXPECT_EQ(ensemble.statistics.count, 2U);
  EXPECT_DOUBLE_EQ(ensemble.statistics.mean, 0.5 * (angles[0] + angles[1]));
  EXPECT_EQ(ensemble.statistics.mean, expected.mean);
  EXPECT_EQ(ensemble.statistics.upper(), expected.upper());
  // The same again, one seed at a time: exactly the same numbers.
  const ThreadLimit one_thread(1);
  const EnsembleResult again = study::run_repose_ensemble(base, order);
  ASSERT_EQ(again.seeds.size(), 2U);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again.seeds[i].angle_degrees, ensemble.seeds[i].angle_degrees);
  }
  EXPECT_EQ(again.statistics.mean, ensemble.statistics.mean);
}

TEST(ReposeStudy, AFailingSeedIsReportedAndLeftOutOfTheStatistics) {
  const ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  std::vector<std::uint64_t> reported;
  study::StudyControl control;
  control.fill = [](const ReposeOptions& options) {
    if (options.seed == 2) throw LimitExceeded("test fill", "seed 2", "a fill that works");
    return study::repose_fill(options);
  };
  control.on_seed = [&](const EnsembleSeed& s, const ReposeResult* result, std::size_t,
                        std::size_t total) {
    EXPECT_EQ(total, 3U);
    EXPECT_EQ(result == nullptr, s.seed == 2);
    reported.push_back(s.seed);
  };
  const auto ensemble = study::run_repose_ensemble(base, {3, 2, 1}, control);
  EXPECT_EQ(reported.size(), 3U);
  ASSERT_EQ(ensemble.seeds.size(), 3U);
  EXPECT_EQ(ensemble.seeds[1].seed, 2U);
  EXPECT_FALSE(ensemble.seeds[1].is_valid);
  EXPECT_NE(ensemble.seeds[1].error.find("test fill"), std::string::npos);
  EXPECT_EQ(ensemble.statistics.count, 2U);
  EXPECT_EQ(ensemble.failed_count(), 1U);
  EXPECT_TRUE(ensemble.seeds[0].is_valid);
  EXPECT_DOUBLE_EQ(ensemble.statistics.mean,
                   0.5 * (ensemble.seeds[0].angle_degrees + ensemble.seeds[2].angle_degrees));
  const fs::path csv =
      fs::temp_directory_path() / ("aggpack_study_ens_" + std::to_string(::getpid()));
  write_ensemble_csv(csv.string(), ensemble);
  const std::string text = test::file_text(csv);
  fs::remove(csv);
  EXPECT_NE(text.find("\n2,,,0,0,0,\"limit exceeded for test fill"), std::string::npos) << text;
  EXPECT_NE(text.find("\nseeds_used,2,,,,,\n"), std::string::npos) << text;
}

TEST(ReposeStudy, SweepWithSeedsGivesEachCaseTheEnsembleStatistics) {
  SweepOptions sweep = load_sweep_config(kStudyTrough, {});
  sweep.alphas = {0.5};
  sweep.frictions = {0.3};
  sweep.seeds = {1, 9};
  std::vector<std::uint64_t> run_seeds;
  study::StudyControl control;
  control.on_run = [&](const SweepCase& c, const ReposeResult&, std::size_t, std::size_t) {
    run_seeds.push_back(c.seed);
  };
  const study::SweepResult result = study::run_sweep(sweep, control);
  EXPECT_FALSE(result.is_cancelled);
  const std::vector<SweepCase>& cases = result.cases;
  EXPECT_EQ(run_seeds.size(), 2U);
  ASSERT_EQ(cases.size(), 1U);
  ReposeOptions base = sweep.base;
  base.alpha = 0.5;
  base.physics.friction = 0.3;
  base.physics.wall_friction = 0.3;
  const auto ensemble = study::run_repose_ensemble(base, {1, 9});
  ASSERT_EQ(ensemble.statistics.count, 2U);
  EXPECT_EQ(cases[0].seed_count, 2U);
  EXPECT_EQ(cases[0].seeds_used, 2U);
  EXPECT_DOUBLE_EQ(cases[0].angle_degrees, ensemble.statistics.mean);
  EXPECT_DOUBLE_EQ(cases[0].statistics.upper(), ensemble.statistics.upper());
  const fs::path csv =
      fs::temp_directory_path() / ("aggpack_study_sweep_" + std::to_string(::getpid()));
  write_sweep_csv(csv.string(), cases);
  const std::string text = test::file_text(csv);
  fs::remove(csv);
  EXPECT_NE(text.find(",seeds,seeds_used,std_dev_deg,ci95_lower_deg,ci95_upper_deg\n"),
            std::string::npos)
      << text;
}

TEST(ReposeStudy, SweepCaseIsTheSingleRunOfItsOptions) {
  SweepOptions sweep = load_sweep_config(kStudyTrough, {});
  sweep.alphas = {0.5};
  sweep.frictions = {0.2, 0.4};
  const study::SweepResult result = study::run_sweep(sweep);
  ASSERT_EQ(result.cases.size(), 2U);
  EXPECT_EQ(result.cases[0].friction, 0.2);
  const SweepCase& c = result.cases[1];
  EXPECT_EQ(c.index, 1U);
  ReposeOptions single = sweep.base;
  single.alpha = 0.5;
  single.physics.friction = 0.4;
  single.physics.wall_friction = 0.4;
  const ReposeResult alone = study::run_repose(single);
  EXPECT_EQ(c.angle_degrees, alone.fit.angle_degrees);
  EXPECT_EQ(c.particle_count, alone.particle_count);
}

TEST(ReposeStudy, CancellingSkipsTheRunsNotYetStarted) {
  const ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  const ThreadLimit one_thread(1);  // one run at a time: the first one finishes, no other starts
  std::atomic<bool> cancel{false};
  study::StudyControl control;
  control.cancel = &cancel;
  control.on_seed = [&](const EnsembleSeed&, const ReposeResult*, std::size_t, std::size_t) {
    cancel.store(true);
  };
  const EnsembleResult ensemble = study::run_repose_ensemble(base, {1, 2, 3}, control);
  EXPECT_TRUE(ensemble.is_cancelled);
  ASSERT_EQ(ensemble.seeds.size(), 1U);
  EXPECT_EQ(ensemble.statistics.count, ensemble.seeds[0].is_valid ? 1U : 0U);
  // Cancelled before it starts: no run at all.
  SweepOptions sweep = load_sweep_config(kStudyTrough, {});
  sweep.alphas = {0.5};
  sweep.frictions = {0.2, 0.4};
  const study::SweepResult none = study::run_sweep(sweep, control);
  EXPECT_TRUE(none.is_cancelled);
  EXPECT_TRUE(none.cases.empty());
}

// The study's fill is the lattice packing with each particle turned about its site: same
// particles and sites, new orientations, still overlap-free, the same every time.
TEST(ReposeStudy, FillTurnsTheLatticeParticlesAboutTheirSites) {
  ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  const PackResult turned = study::repose_fill(base);
  base.is_orientation_random = false;
  const PackResult lattice = study::repose_fill(base);
  ASSERT_EQ(turned.packing.particles.size(), lattice.packing.particles.size());
  ASSERT_GT(turned.packing.particles.size(), 10U);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < turned.packing.particles.size(); ++i) {
    const Pose& a = turned.packing.particles[i].pose;
    const Pose& b = lattice.packing.particles[i].pose;
    EXPECT_EQ(turned.packing.particles[i].shape, lattice.packing.particles[i].shape);
    if (a.rotation.angularDistance(b.rotation) > 1e-3) ++moved;
  }
  EXPECT_EQ(moved, turned.packing.particles.size());
  const VerifyResult check = verify(turned.packing);
  EXPECT_TRUE(check.is_ok) << check.message;
  base.is_orientation_random = true;
  const PackResult again = study::repose_fill(base);
  for (std::size_t i = 0; i < again.packing.particles.size(); ++i) {
    EXPECT_EQ(again.packing.particles[i].pose.position, turned.packing.particles[i].pose.position);
  }
}

// What a run would refuse is refused before it starts, named by the field.
TEST(ReposeStudy, InputsAreCheckedBeforeTheRun) {
  ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  EXPECT_NO_THROW(study::check_repose_inputs(base));
  ReposeOptions too_large = base;
  too_large.radius = 10.0;  // no lattice site fits the fill box
  EXPECT_THROW(study::check_repose_inputs(too_large), Error);
  ReposeOptions missing = base;
  missing.library.paths = {(fs::temp_directory_path() / "aggpack-no-such-library").string()};
  try {
    study::check_repose_inputs(missing);
    FAIL() << "a missing library was accepted";
  } catch (const Error& error) {
    EXPECT_EQ(error.field(), "particle.library");
  }
  EXPECT_THROW(study::run_repose(missing), Error);
}

TEST(ReposeStudy, RejectsNoSeedsAndBadOptions) {
  const ReposeOptions base = load_sweep_config(kStudyTrough, {}).base;
  EXPECT_THROW(study::run_repose_ensemble(base, {}), InvalidInput);
  ReposeOptions bad = base;
  bad.baffle_speed = -1.0;
  EXPECT_THROW(study::run_repose_ensemble(bad, {1}), InvalidInput);
  SweepOptions sweep = load_sweep_config(kStudyTrough, {});
  sweep.frictions.clear();
  EXPECT_THROW(study::run_sweep(sweep), InvalidInput);
}

}  // namespace
}  // namespace aggpack
