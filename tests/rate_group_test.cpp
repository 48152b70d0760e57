// RateGroup: releases, cycles, skipped ticks and overruns, as the timer interrupt and the main
// loop see them (the interrupt is played by direct release() calls).
#include <gtest/gtest.h>

#include <cstdint>

#include "gyro/rate_group.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

TEST(RateGroup, GivenNoReleaseThenNoCycleAndGivenOneThenTickZeroRunsOnce) {
  GYRO_VERIFIES("RG-1");
  RateGroup g;
  std::uint64_t tick = 99;
  EXPECT_FALSE(g.pending());
  EXPECT_FALSE(g.begin(tick));
  EXPECT_EQ(tick, 99u);
  EXPECT_FALSE(g.end());  // no cycle open: nothing counted
  EXPECT_EQ(g.telemetry().cycles, 0u);

  g.release();
  EXPECT_TRUE(g.pending());
  ASSERT_TRUE(g.begin(tick));
  EXPECT_EQ(tick, 0u);
  EXPECT_FALSE(g.pending());
  EXPECT_FALSE(g.begin(tick));  // once per release
  EXPECT_FALSE(g.end());
  EXPECT_EQ(g.telemetry().cycles, 1u);
  EXPECT_EQ(g.telemetry().overruns, 0u);
  EXPECT_EQ(g.telemetry().skipped, 0u);
}

TEST(RateGroup, GivenAnOpenCycleThenBeginIsRefusedUntilItEnds) {
  GYRO_VERIFIES("RG-1");
  RateGroup g;
  std::uint64_t tick = 99;
  g.release();
  ASSERT_TRUE(g.begin(tick));
  g.release();  // tick 1, released while tick 0 runs
  EXPECT_FALSE(g.begin(tick)) << "a cycle is open";
  EXPECT_EQ(tick, 0u);
  EXPECT_EQ(g.telemetry().released, 1u) << "nothing changed";
  EXPECT_TRUE(g.end());
  ASSERT_TRUE(g.begin(tick));
  EXPECT_EQ(tick, 1u);
}

TEST(RateGroup, GivenATickReleasedDuringTheCycleThenAnOverrunAndTheNextCycleRunsIt) {
  GYRO_VERIFIES("RG-1", "RG-2");
  RateGroup g;
  std::uint64_t tick = 0;
  g.release();
  ASSERT_TRUE(g.begin(tick));
  g.release();  // tick 1 arrives while tick 0 still runs
  EXPECT_TRUE(g.end());
  EXPECT_TRUE(g.telemetry().overrun);
  EXPECT_EQ(g.telemetry().overruns, 1u);
  ASSERT_TRUE(g.begin(tick));
  EXPECT_EQ(tick, 1u);
  EXPECT_FALSE(g.end());
  EXPECT_FALSE(g.telemetry().overrun);  // the flag is the last cycle's
  EXPECT_EQ(g.telemetry().overruns, 1u);
  EXPECT_EQ(g.telemetry().skipped, 0u);
}

TEST(RateGroup, GivenSeveralTicksReleasedDuringACycleThenTheLatestRunsAndTheOthersAreSkipped) {
  GYRO_VERIFIES("RG-1", "RG-2");
  RateGroup g;
  std::uint64_t tick = 0;
  g.release();
  ASSERT_TRUE(g.begin(tick));
  for (int i = 0; i < 3; ++i) g.release();  // ticks 1, 2, 3
  EXPECT_TRUE(g.end());
  ASSERT_TRUE(g.begin(tick));
  EXPECT_EQ(tick, 3u);
  EXPECT_FALSE(g.end());
  const RateGroupTelemetry& t = g.telemetry();
  EXPECT_EQ(t.released, 4u);
  EXPECT_EQ(t.cycles, 2u);
  EXPECT_EQ(t.skipped, 2u);  // ticks 1 and 2 never ran
  EXPECT_EQ(t.last_tick, 3u);
  EXPECT_EQ(t.overruns, 1u);
}

TEST(RateGroup, GivenTicksReleasedBeforeTheFirstCycleThenTheyAreSkipped) {
  GYRO_VERIFIES("RG-2");
  RateGroup g;
  std::uint64_t tick = 0;
  g.release();
  g.release();
  ASSERT_TRUE(g.begin(tick));
  EXPECT_EQ(tick, 1u);
  EXPECT_EQ(g.telemetry().skipped, 1u);
}

TEST(RateGroup, GivenASteadyScheduleThenEveryTickRunsWithoutOverrun) {
  GYRO_VERIFIES("RG-2");
  RateGroup g;
  std::uint64_t tick = 0;
  for (std::uint64_t k = 0; k < 10000; ++k) {
    g.release();
    ASSERT_TRUE(g.begin(tick));
    ASSERT_EQ(tick, k);
    ASSERT_FALSE(g.end());
  }
  EXPECT_EQ(g.telemetry().cycles, 10000u);
  EXPECT_EQ(g.telemetry().overruns, 0u);
  EXPECT_EQ(g.telemetry().skipped, 0u);
}

}  // namespace
}  // namespace gyro
