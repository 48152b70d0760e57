// The fault monitors (gyro/fault_monitors.hpp): each condition latches safe mode once it
// persists; the input fault is flagged; the torquer's is fed by the last write.
#include <gtest/gtest.h>

#include "gyro/fault_monitors.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace fault_monitors_test {

const Vector2<double> kOver(0.0, -2e-3);  // beyond a limit of 1e-3 rad in one axis

struct Persistences {
  double residual_limit_rad{1e-3};
  std::uint32_t invalid_persistence_ticks{3};
  std::uint32_t spin_low_persistence_ticks{4};
  std::uint32_t torquer_fail_persistence_ticks{5};
  std::uint32_t input_persistence_ticks{6};
  std::uint32_t residual_persistence_ticks{7};
};

// The ticks until `monitors` latch with the same conditions each tick (0: not in 100).
template <typename Feed>
int ticks_to_fault(Feed feed) {
  FaultMonitors m;
  for (int k = 1; k <= 100; ++k) {
    if (feed(m).fault) return k;
  }
  return 0;
}

TEST(FaultMonitors, EachConditionLatchesAfterItsPersistence) {
  GYRO_VERIFIES("FAULT-1", "MODE-4");
  const Persistences p;
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) { return m.update(FaultConditions{true, false, false}, p); }), 3);
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) { return m.update(FaultConditions{false, true, false}, p); }), 4);
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) { return m.update(FaultConditions{false, false, true}, p); }), 6);
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) {
              m.torquer_written(false);
              return m.update(FaultConditions{}, p);
            }),
            5);
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) {
              (void)m.test_residual(kOver, false, p);
              return m.update(FaultConditions{}, p);
            }),
            7);
  EXPECT_EQ(ticks_to_fault([&](FaultMonitors& m) { return m.update(FaultConditions{}, p); }), 0);
}

TEST(FaultMonitors, OnlyThePersistedInputConditionIsFlagged) {
  GYRO_VERIFIES("INPUT-5");
  const Persistences p;
  FaultMonitors m;
  for (int k = 1; k < 6; ++k) EXPECT_EQ(m.update(FaultConditions{false, false, true}, p).flags, 0u);
  EXPECT_EQ(m.update(FaultConditions{false, false, true}, p).flags, static_cast<std::uint32_t>(kInputFault));
  FaultMonitors reading;
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(reading.update(FaultConditions{true, false, false}, p).flags, 0u);
}

TEST(FaultMonitors, ResettingTheResidualClearsItsFill) {
  GYRO_VERIFIES("FAULT-2");
  const Persistences p;
  FaultMonitors m;
  for (int k = 1; k < 7; ++k) EXPECT_EQ(m.test_residual(kOver, false, p), 0u);
  m.reset_residual();
  EXPECT_EQ(m.test_residual(kOver, false, p), 0u);
  EXPECT_FALSE(m.update(FaultConditions{}, p).fault);
}

TEST(FaultMonitors, AResidualOverItsLimitIsFlaggedOnceItPersists) {
  GYRO_VERIFIES("FAULT-2");
  const Persistences p;
  FaultMonitors m;
  for (int k = 1; k < 7; ++k) EXPECT_EQ(m.test_residual(kOver, false, p), 0u) << k;
  EXPECT_EQ(m.test_residual(kOver, false, p), static_cast<std::uint32_t>(kResidualFault));
  FaultMonitors at_limit;
  for (int k = 1; k <= 20; ++k) {
    EXPECT_EQ(at_limit.test_residual(Vector2<double>(-1e-3, 1e-3), false, p), 0u) << "at the limit is within it";
  }
}

TEST(FaultMonitors, SafeModeDropsTheResidualsFill) {
  GYRO_VERIFIES("FAULT-2");
  const Persistences p;
  FaultMonitors m;
  for (int k = 1; k < 7; ++k) EXPECT_EQ(m.test_residual(kOver, false, p), 0u);
  EXPECT_EQ(m.test_residual(kOver, true, p), 0u) << "not monitored in safe mode";
  for (int k = 1; k < 7; ++k) EXPECT_EQ(m.test_residual(kOver, false, p), 0u) << "the fill starts again: " << k;
  EXPECT_EQ(m.test_residual(kOver, false, p), static_cast<std::uint32_t>(kResidualFault));
}

TEST(FaultMonitors, AGoodWriteClearsTheTorquerCondition) {
  GYRO_VERIFIES("PORT-2");
  const Persistences p;
  FaultMonitors m;
  for (int k = 0; k < 4; ++k) {
    m.torquer_written(false);
    EXPECT_FALSE(m.update(FaultConditions{}, p).fault);
  }
  m.torquer_written(true);
  EXPECT_FALSE(m.update(FaultConditions{}, p).fault) << "the fill drains";
}

}  // namespace fault_monitors_test
}  // namespace gyro
