// The tick tracker (gyro/tick_tracker.hpp): lost ticks bridged, anything else one tick.
#include <gtest/gtest.h>

#include "gyro/tick_tracker.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace tick_tracker_test {

constexpr std::uint64_t kGap = 8;

TEST(TickTracker, ConsecutiveTicksAreOneTickUnflagged) {
  GYRO_VERIFIES("TICK-1");
  TickTracker t;
  for (std::uint64_t k = 0; k < 5; ++k) {
    const ElapsedTicks e = t.advance(100 + k, kGap);
    EXPECT_EQ(e.ticks, 1u);
    EXPECT_EQ(e.flags, 0u);
  }
}

TEST(TickTracker, AJumpUpToTheGapIsBridgedAsLostTicks) {
  GYRO_VERIFIES("TICK-2");
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  const ElapsedTicks e = t.advance(11 + kGap, kGap);
  EXPECT_EQ(e.ticks, kGap);
  EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickSkipped));
  EXPECT_EQ(t.advance(12 + kGap, kGap).flags, 0u);
}

TEST(TickTracker, AJumpPastTheGapIsOneTickFlaggedInvalid) {
  GYRO_VERIFIES("TICK-3");
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  const ElapsedTicks e = t.advance(12 + kGap, kGap);
  EXPECT_EQ(e.ticks, 1u);
  EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickInvalid));
}

TEST(TickTracker, RepeatsAndStepsBackAreOneTickFlaggedInvalid) {
  GYRO_VERIFIES("TICK-3");
  TickTracker t;
  (void)t.advance(10, kGap);
  (void)t.advance(11, kGap);
  const ElapsedTicks repeat = t.advance(11, kGap);
  EXPECT_EQ(repeat.ticks, 1u) << "never a bridge of zero ticks";
  EXPECT_EQ(repeat.flags, static_cast<std::uint32_t>(kTickInvalid));
  EXPECT_EQ(t.advance(12, kGap).flags, 0u) << "resynchronised to the repeat";
  const ElapsedTicks back = t.advance(5, kGap);
  EXPECT_EQ(back.ticks, 1u);
  EXPECT_EQ(back.flags, static_cast<std::uint32_t>(kTickInvalid));
}

// A count made untrusted by a repeat or by a jump past the gap: a jump within the gap right
// after it is not believed either; a count following it by one is trusted again, and a gap
// after that is bridged.
TEST(TickTracker, NoJumpIsBridgedRightAfterAnUntrustedCount) {
  GYRO_VERIFIES("TICK-3");
  struct Case {
    std::uint64_t untrusted;  // after 10
    std::uint64_t jump;
  };
  for (const Case& c : {Case{10, 2}, Case{10 + 1000, 3}}) {
    SCOPED_TRACE(c.untrusted);
    TickTracker t;
    (void)t.advance(10, kGap);
    ASSERT_EQ(t.advance(c.untrusted, kGap).flags, static_cast<std::uint32_t>(kTickInvalid));
    const ElapsedTicks e = t.advance(c.untrusted + c.jump, kGap);
    EXPECT_EQ(e.ticks, 1u);
    EXPECT_EQ(e.flags, static_cast<std::uint32_t>(kTickInvalid));
    EXPECT_EQ(t.advance(c.untrusted + c.jump + 1, kGap).flags, 0u) << "followed by one: trusted again";
    const ElapsedTicks gap = t.advance(c.untrusted + c.jump + 3, kGap);
    EXPECT_EQ(gap.ticks, 2u);
    EXPECT_EQ(gap.flags, static_cast<std::uint32_t>(kTickSkipped));
  }
}

TEST(TickTracker, TheFirstCallIsOneTickWhateverItsCount) {
  GYRO_VERIFIES("TICK-4");
  TickTracker t;
  const ElapsedTicks e = t.advance(123456, kGap);
  EXPECT_EQ(e.ticks, 1u);
  EXPECT_EQ(e.flags, 0u);
  EXPECT_EQ(t.advance(123458, kGap).flags, static_cast<std::uint32_t>(kTickSkipped));
}

}  // namespace tick_tracker_test
}  // namespace gyro
