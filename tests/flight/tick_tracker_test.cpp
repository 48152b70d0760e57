// The tick tracker (gyro/tick_tracker.hpp): lost ticks bridged, anything else one tick.
#include <gtest/gtest.h>

#include "gyro/tick_tracker.hpp"

namespace gyro {
namespace {

constexpr std::uint64_t kGap = 8;

TEST(TickTracker, ConsecutiveTicksAreOneTickUnflagged) {
  TickTracker t;
  for (std::uint64_t k = 0; k < 5; ++k) {
    const ElapsedTicks e = t.advance(100 + k, kGap);
    EXPECT_EQ(e.ticks, 1u);
    EXPECT_EQ(e.flags, 0u);
  }
}

TEST(TickTracker, AJumpUpToTheGapIsBridgedAsLostTicks) {
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  const ElapsedTicks e = t.advance(11 + kGap, kGap);
  EXPECT_EQ(e.ticks, kGap);
  EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickSkipped));
  EXPECT_EQ(t.advance(12 + kGap, kGap).flags, 0u);
}

TEST(TickTracker, AJumpPastTheGapIsOneTickFlaggedInvalid) {
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  const ElapsedTicks e = t.advance(12 + kGap, kGap);
  EXPECT_EQ(e.ticks, 1u);
  EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickInvalid));
}

TEST(TickTracker, RepeatsAndStepsBackAreOneTickFlaggedInvalid) {
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  EXPECT_EQ(t.advance(11, kGap).flags, static_cast<std::uint32_t>(kTickInvalid));
  EXPECT_EQ(t.advance(12, kGap).flags, 0u) << "resynchronised to the repeat";
  const ElapsedTicks back = t.advance(5, kGap);
  EXPECT_EQ(back.ticks, 1u);
  EXPECT_EQ(back.flags, static_cast<std::uint32_t>(kTickInvalid));
}

TEST(TickTracker, NoJumpIsBridgedRightAfterAnUntrustedCount) {
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(10, kGap);  // untrusted
  const ElapsedTicks e = t.advance(12, kGap);
  EXPECT_EQ(e.ticks, 1u);
  EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickInvalid));
  (void)t.advance(13, kGap);  // followed by one: trusted again
  EXPECT_EQ(t.advance(15, kGap).ticks, 2u);
}

TEST(TickTracker, TheFirstCallIsOneTickWhateverItsCount) {
  TickTracker t;
  const ElapsedTicks e = t.advance(123456, kGap);
  EXPECT_EQ(e.ticks, 1u);
  EXPECT_EQ(e.flags, 0u);
  EXPECT_EQ(t.advance(123458, kGap).flags, static_cast<std::uint32_t>(kTickSkipped));
}

}  // namespace
}  // namespace gyro
