// The thread team that steps the simulator's devices: every part runs exactly once per run(),
// run() returns only when all are done, an exception in any part reaches the caller, and the
// team can be run many times and destroyed while idle.
#include "ibs/sim/fork_join.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace ibs::sim {
namespace {

TEST(ForkJoin, EveryPartRunsOncePerRunAndRunWaitsForAll) {
  constexpr unsigned kParts = 4;
  std::vector<std::uint64_t> counts(kParts, 0);  // each part writes only its own entry
  std::uint64_t rounds = 0;
  ForkJoin team(kParts, [&](unsigned part) {
    // Some work of different length per part, so that parts finish at different times.
    volatile std::uint64_t spin = 0;
    for (unsigned i = 0; i < 200 * (part + 1); ++i) spin = spin + i;
    ++counts[part];
  });
  EXPECT_EQ(team.parts(), kParts);
  for (; rounds < 2000; ++rounds) {
    team.run();
    // Every part has finished this round before run() returned.
    for (unsigned p = 0; p < kParts; ++p) ASSERT_EQ(counts[p], rounds + 1) << "part " << p;
  }
}

TEST(ForkJoin, OnePartRunsOnTheCallingThread) {
  unsigned runs = 0;
  ForkJoin team(1, [&](unsigned part) {
    EXPECT_EQ(part, 0U);
    ++runs;
  });
  team.run();
  team.run();
  EXPECT_EQ(runs, 2U);
  EXPECT_EQ(team.parts(), 1U);
}

TEST(ForkJoin, AnExceptionInAPartReachesTheCallerAndTheTeamGoesOn) {
  std::atomic<int> calls{0};
  bool fail = true;
  ForkJoin team(3, [&](unsigned part) {
    ++calls;
    if (fail && part == 2) throw std::runtime_error("part 2 failed");
  });
  try {
    team.run();
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "part 2 failed");
  }
  EXPECT_EQ(calls.load(), 3);
  fail = false;
  EXPECT_NO_THROW(team.run());
  EXPECT_EQ(calls.load(), 6);
}

}  // namespace
}  // namespace ibs::sim
