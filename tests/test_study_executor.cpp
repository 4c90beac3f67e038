// SPDX-License-Identifier: BSD-3-Clause
// study/run_all.hpp: every run taken once, progress counted, cancellation stops handing out runs, and a result that
// crosses ranks as bytes keeps every bit.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>
#include <vector>

#include "study/run_all.hpp"

namespace imcol::study {
namespace {

TEST(StudyExecutor, ThreadsTakeEveryRunOnceWithProgress) {
  std::vector<int> taken(50, 0);
  std::vector<std::size_t> reported;
  Hooks hooks;
  hooks.progress = [&](std::size_t done, std::size_t total) {
    EXPECT_EQ(total, 50u);
    reported.push_back(done);
  };
  const bool all = run_all<double>(threads(2), 50, [](std::size_t i) { return 0.5 * double(i); },
                                   [&](std::size_t i, double&& x) {
                                     EXPECT_EQ(x, 0.5 * double(i));
                                     ++taken[i];
                                     return true;
                                   }, hooks);
  EXPECT_TRUE(all);
  for (int c : taken) EXPECT_EQ(c, 1);
  ASSERT_EQ(reported.size(), 50u);
  for (std::size_t k = 0; k < reported.size(); ++k) EXPECT_EQ(reported[k], k + 1);
}

TEST(StudyExecutor, CancelStopsHandingOutRuns) {
  std::atomic<int> ran{0};
  std::size_t taken = 0;
  Hooks hooks;
  hooks.cancelled = [&] { return taken >= 3; };
  const bool all = run_all<int>(threads(1), 100, [&](std::size_t i) { ++ran; return int(i); },
                                [&](std::size_t, int&&) { ++taken; return true; }, hooks);
  EXPECT_FALSE(all);
  EXPECT_EQ(taken, 3u);  // one thread: no run in flight when the third is taken
  EXPECT_EQ(ran.load(), 3);
}

TEST(StudyExecutor, CancelledBeforeStartRunsNothing) {
  Hooks hooks;
  hooks.cancelled = [] { return true; };
  int ran = 0;
  EXPECT_FALSE(run_all<int>(threads(2), 10, [&](std::size_t) { ++ran; return 0; }, [](std::size_t, int&&) { return true; }, hooks));
  EXPECT_EQ(ran, 0);
}

TEST(StudyExecutor, BytesAcrossRanksKeepEveryBit) {
  // A distribute that runs in this process but passes every result through its bytes, as the MPI one does.
  Executor ex = threads(2);
  std::size_t crossed = 0;
  ex.distribute = [&](std::size_t n, int jobs, const std::function<std::string(std::size_t)>& work,
                      const std::function<bool(std::size_t, std::string, int)>& done) {
    run_parallel(n, jobs, work, [&](std::size_t i, std::string b) {
      ++crossed;
      return done(i, std::move(b), 1);
    });
  };
  std::vector<double> got(20, 0);
  run_all<double>(ex, 20, [](std::size_t i) { return std::nextafter(1.0 / 3.0 * double(i + 1), 2.0); },
                  [&](std::size_t i, double&& x) { got[i] = x; return true; });
  EXPECT_EQ(crossed, 20u);
  for (std::size_t i = 0; i < 20; ++i) EXPECT_EQ(got[i], std::nextafter(1.0 / 3.0 * double(i + 1), 2.0));
}

}  // namespace
}  // namespace imcol::study
