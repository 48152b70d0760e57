// The persistence monitor (gyro/persistence.hpp): a leaky count that trips at N consecutive bad
// ticks, or at an intermittent condition present in more than one tick in three; one good tick
// untrips it, and its fill is capped so that it can.
#include <gtest/gtest.h>

#include <cstdint>

#include "gyro/persistence.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace persistence_test {

TEST(PersistenceMonitor, NBadTicksInARowTripItAtTheNth) {
  GYRO_VERIFIES("FAULT-1");
  PersistenceMonitor m;
  for (std::uint32_t k = 1; k < 10; ++k) EXPECT_FALSE(m.update(true, 10)) << k;
  EXPECT_TRUE(m.update(true, 10));
}

TEST(PersistenceMonitor, TripsAboveOneBadTickInThreeOnly) {
  GYRO_VERIFIES("FAULT-1");
  const auto ticks_to_trip = [](int bad, int period, int limit) {
    PersistenceMonitor m;
    for (int k = 0; k < limit; ++k) {
      if (m.update(k % period < bad, 10)) return k + 1;
    }
    return -1;
  };
  EXPECT_EQ(ticks_to_trip(19, 20, 1000), 10) << "19 bad in 20: as fast as consecutive ones";
  EXPECT_GT(ticks_to_trip(1, 2, 1000), 0) << "one in two";
  EXPECT_LE(ticks_to_trip(1, 2, 1000), 4 * 10 + 2);
  EXPECT_EQ(ticks_to_trip(1, 3, 100000), -1) << "one in three: counted, never latched";
  EXPECT_EQ(ticks_to_trip(1, 20, 100000), -1);
}

TEST(PersistenceMonitor, OneGoodTickUntripsACappedFill) {
  GYRO_VERIFIES("FAULT-1");
  PersistenceMonitor m;
  for (int k = 0; k < 1000; ++k) (void)m.update(true, 5);
  EXPECT_EQ(m.fill(), 10u);
  EXPECT_FALSE(m.update(false, 5));
  EXPECT_TRUE(m.update(true, 5)) << "and the next bad tick trips it again";
}

}  // namespace persistence_test
}  // namespace gyro
