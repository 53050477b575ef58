// run_isolated: work that aborts, crashes, throws, exits or hangs in a worker process fails alone;
// every other item's result arrives, in item order, whatever the number of workers.

#include "aggpack/core/isolated.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"

namespace aggpack {
namespace {

std::string square(std::size_t i) { return std::to_string(i * i); }

TEST(RunIsolated, ResultsInItemOrderForAnyWorkerCount) {
  for (const int workers : {1, 2, 3, 7}) {
    const auto outcomes = run_isolated(100, square, {.workers = workers});
    ASSERT_EQ(outcomes.size(), 100U);
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      EXPECT_TRUE(outcomes[i].is_done) << outcomes[i].failure;
      EXPECT_EQ(outcomes[i].bytes, square(i));
      EXPECT_TRUE(outcomes[i].failure.empty());
    }
  }
  EXPECT_TRUE(run_isolated(0, square).empty());
}

TEST(RunIsolated, LargeResultsStreamThroughThePipe) {
  // Larger than a pipe's buffer (64 KiB), so the parent must read while workers write.
  const auto work = [](std::size_t i) {
    return std::string(3'000'000 + i, static_cast<char>('a' + i));
  };
  const auto outcomes = run_isolated(5, work, {.workers = 2});
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    ASSERT_TRUE(outcomes[i].is_done);
    EXPECT_EQ(outcomes[i].bytes, work(i));
  }
}

TEST(RunIsolated, AbortCrashThrowAndExitFailOnlyTheirItem) {
  const auto work = [](std::size_t i) -> std::string {
    switch (i) {
      case 3:
        std::abort();  // what TetGen's failed assertions do
      case 4:
        std::raise(SIGSEGV);
        break;
      case 7:
        throw std::runtime_error("bad item 7");
      case 8:
        ::_exit(3);
      default:
        break;
    }
    return square(i);
  };
  for (const int workers : {1, 2}) {
    // Every item is counted once as it settles, the failed ones too, in the calling process.
    std::vector<std::size_t> settled;
    const auto outcomes = run_isolated(
        12, work, {.workers = workers, .on_settled = [&](std::size_t done, std::size_t count) {
                     EXPECT_EQ(count, 12U);
                     settled.push_back(done);
                   }});
    ASSERT_EQ(settled.size(), 12U);
    for (std::size_t k = 0; k < settled.size(); ++k) EXPECT_EQ(settled[k], k + 1);
    ASSERT_EQ(outcomes.size(), 12U);
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      const bool is_bad = i == 3 || i == 4 || i == 7 || i == 8;
      EXPECT_EQ(outcomes[i].is_done, !is_bad) << i;
      if (!is_bad) {
        EXPECT_EQ(outcomes[i].bytes, square(i));
      }
    }
    EXPECT_EQ(outcomes[3].failure, "died of signal 6 (Aborted)");
    // The sanitized build's handler may turn the segfault into an abort: a signal either way.
    EXPECT_EQ(outcomes[4].failure.rfind("died of signal ", 0), 0U) << outcomes[4].failure;
    EXPECT_EQ(outcomes[7].failure, "threw: bad item 7");
    EXPECT_EQ(outcomes[8].failure, "exited with code 3");
  }
}

TEST(RunIsolated, HangingItemIsStoppedAtTheTimeLimit) {
  // Item 1 never returns; the others take microseconds, far below the limit.
  const auto work = [](std::size_t i) -> std::string {
    if (i == 1) {
      for (;;) ::pause();
    }
    return square(i);
  };
  const auto outcomes = run_isolated(4, work, {.workers = 1, .time_limit = 2.0});
  EXPECT_FALSE(outcomes[1].is_done);
  EXPECT_EQ(outcomes[1].failure, "timed out after 2 s");
  for (const std::size_t i : {0U, 2U, 3U}) {
    EXPECT_TRUE(outcomes[i].is_done) << outcomes[i].failure;
    EXPECT_EQ(outcomes[i].bytes, square(i));
  }
}

TEST(RunIsolated, DoesNotForkWhileASectionWithoutForkIsOpen) {
  // A ticker thread's section: the worker may not be forked until it is closed (the test cannot
  // prove that it would fork at once without the section, only that it waits with it).
  auto section = section_without_fork();
  auto running =
      std::async(std::launch::async, [] { return run_isolated(3, square, {.workers = 1}); });
  EXPECT_EQ(running.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout)
      << "a worker was forked inside a section without fork";
  section.unlock();
  const auto outcomes = running.get();
  ASSERT_EQ(outcomes.size(), 3U);
  for (std::size_t i = 0; i < outcomes.size(); ++i) EXPECT_EQ(outcomes[i].bytes, square(i));
}

// Threads of process `pid` (the "Threads:" line of /proc/PID/status), 0 if unknown.
int thread_count(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string word;
  while (status >> word) {
    if (word == "Threads:") {
      int count = 0;
      status >> count;
      return count;
    }
  }
  return 0;
}

TEST(RunIsolated, ForksWithNoThreadPoolWorkerAlive) {
  // A parallel loop leaves TBB's workers alive; one of them still freeing its task when a child is
  // forked leaves the child the allocator's lock (a sanitized run hung so). The worker, asked
  // how many threads its parent has, must answer one: the parent's own.
  std::atomic<int> most_threads = 0;
  parallel_for_index(0, 64, [&](std::size_t) {
    std::vector<double> scratch(1000, 1.0);
    most_threads = std::max(most_threads.load(), thread_count(::getpid()));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  });
  if (concurrency() > 1) {
    EXPECT_GT(most_threads.load(), 1) << "the loop ran on one thread";
  }
  const auto outcomes = run_isolated(
      1, [](std::size_t) { return std::to_string(thread_count(::getppid())); }, {.workers = 1});
  ASSERT_TRUE(outcomes.front().is_done) << outcomes.front().failure;
  EXPECT_EQ(outcomes.front().bytes, "1");
}

TEST(RunIsolated, RejectsBadOptions) {
  EXPECT_THROW(run_isolated(1, square, {.workers = -1}), InvalidInput);
  EXPECT_THROW(run_isolated(1, square, {.time_limit = 0.0}), InvalidInput);
  EXPECT_THROW(run_isolated(1, square, {.time_limit = 1e9}), InvalidInput);
}

}  // namespace
}  // namespace aggpack
