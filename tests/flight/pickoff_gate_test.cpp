// The pickoff gate (gyro/pickoff_gate.hpp): invalid, stale and jumped readings refused; the
// jump bound widens with the ticks that passed without information.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gyro/pickoff_gate.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace pickoff_gate_test {

constexpr PickoffLimits<double> kLimits{0.5, 0.01};

PickoffReading<double> reading(double pitch, double yaw, std::uint32_t sequence) {
  PickoffReading<double> r;
  r.gimbal_angle_rad = Vector2<double>(pitch, yaw);
  r.sequence = sequence;
  r.valid = true;
  return r;
}

TEST(PickoffGate, AValidFreshReadingIsAcceptedAndKept) {
  GYRO_VERIFIES("PICK-1");
  PickoffGate<double> g;
  const PickoffVerdict v = g.accept(reading(0.1, -0.2, 1), true, 1, true, kLimits);
  EXPECT_TRUE(v.accepted);
  EXPECT_EQ(v.flags, 0u);
  EXPECT_EQ(g.measured(), Vector2<double>(0.1, -0.2));
}

TEST(PickoffGate, UnusableReadingsAreInvalidAndNotKept) {
  GYRO_VERIFIES("PICK-1", "PICK-5", "PORT-1");
  PickoffGate<double> g;
  (void)g.accept(reading(0.1, 0.1, 1), true, 1, true, kLimits);
  PickoffReading<double> unset = reading(0.1, 0.1, 2);
  unset.valid = false;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [r, port_ok] : {std::pair{reading(0.1, 0.1, 3), false}, std::pair{unset, true},
                                   std::pair{reading(nan, 0.1, 4), true}, std::pair{reading(0.1, 0.51, 5), true}}) {
    const PickoffVerdict v = g.accept(r, port_ok, 1, true, kLimits);
    EXPECT_FALSE(v.accepted);
    EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kPickoffInvalid));
  }
  EXPECT_EQ(g.measured(), Vector2<double>(0.1, 0.1));
  EXPECT_TRUE(g.accept(reading(0.1, 0.5, 6), true, 1, false, kLimits).accepted) << "the range is inclusive";
}

TEST(PickoffGate, AnUnchangedSequenceIsStale) {
  GYRO_VERIFIES("PICK-2");
  PickoffGate<double> g;
  (void)g.accept(reading(0.1, 0.1, 7), true, 1, true, kLimits);
  const PickoffVerdict v = g.accept(reading(0.1, 0.1, 7), true, 1, true, kLimits);
  EXPECT_FALSE(v.accepted);
  EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kPickoffStale));
}

// Even with sequence 0, as a driver's first conversion may carry; the same sequence again is stale.
TEST(PickoffGate, TheFirstReadingIsNeverStaleNorAJump) {
  GYRO_VERIFIES("PICK-2", "PICK-3");
  PickoffGate<double> g;
  const PickoffVerdict first = g.accept(reading(0.4, 0.0, 0), true, 1, true, kLimits);
  EXPECT_TRUE(first.accepted);
  EXPECT_EQ(first.flags, 0u);
  EXPECT_EQ(g.measured(), Vector2<double>(0.4, 0.0));
  EXPECT_EQ(g.accept(reading(0.4, 0.0, 0), true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffStale))
      << "the same sequence again is stale";
}

// A reading exactly at the range is taken; one ulp beyond it, on either axis and either side,
// is invalid and the last accepted reading stands.
TEST(PickoffGate, TheRangeIsInclusiveToTheLastBit) {
  GYRO_VERIFIES("PICK-1");
  constexpr PickoffLimits<double> limits{4e-3, 4e-3};  // the step no tighter than the range
  PickoffGate<double> g;
  std::uint32_t sequence = 1;
  (void)g.accept(reading(0.0, 0.0, sequence++), true, 1, true, limits);
  for (const Vector2<double>& edge : {Vector2<double>(4e-3, 0.0), Vector2<double>(0.0, -4e-3)}) {
    const PickoffVerdict at = g.accept(reading(edge(0), edge(1), sequence++), true, 1, true, limits);
    EXPECT_TRUE(at.accepted) << edge.transpose();
    EXPECT_EQ(at.flags, 0u) << edge.transpose();
    EXPECT_EQ(g.measured(), edge);
    const Vector2<double> beyond(std::nextafter(edge(0), 2 * edge(0)), std::nextafter(edge(1), 2 * edge(1)));
    const PickoffVerdict past = g.accept(reading(beyond(0), beyond(1), sequence++), true, 1, true, limits);
    EXPECT_FALSE(past.accepted);
    EXPECT_EQ(past.flags, static_cast<std::uint32_t>(kPickoffInvalid)) << beyond.transpose();
    EXPECT_EQ(g.measured(), edge) << "the last accepted reading stands";
  }
}

TEST(PickoffGate, AJumpIsRefusedAndDoesNotWidenTheBound) {
  GYRO_VERIFIES("PICK-3");
  PickoffGate<double> g;
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);
  EXPECT_EQ(g.accept(reading(0.0101, 0.0, 2), true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffJump));
  EXPECT_EQ(g.accept(reading(0.0101, 0.0, 3), true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffJump))
      << "a bias jump stays refused";
  EXPECT_EQ(g.accept(reading(0.0101, 0.0, 3), true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffStale))
      << "the jumped reading's sequence was recorded";
  EXPECT_EQ(g.measured(), Vector2<double>::Zero()) << "the last accepted reading stands";
}

TEST(PickoffGate, TheJumpBoundIsInclusive) {
  GYRO_VERIFIES("PICK-3");
  PickoffGate<double> g;
  constexpr PickoffLimits<double> limits{0.5, 0.125};  // exact in binary
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, limits);
  EXPECT_TRUE(g.accept(reading(0.0, -0.125, 2), true, 1, true, limits).accepted);
}

TEST(PickoffGate, TheBoundWidensWithTicksWithoutInformation) {
  GYRO_VERIFIES("PICK-3", "TICK-2");
  PickoffGate<double> g;
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);
  (void)g.accept(reading(0.0, 0.0, 1), true, 2, true, kLimits);  // stale over 2 ticks
  PickoffReading<double> unset = reading(0.0, 0.0, 2);
  unset.valid = false;
  (void)g.accept(unset, true, 1, true, kLimits);                  // invalid: 3 blind ticks
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);  // stale again: 4
  EXPECT_FALSE(g.accept(reading(0.0, 0.0601, 3), true, 2, true, kLimits).accepted) << "6 ticks: 0.06";
  EXPECT_TRUE(g.accept(reading(0.0, 0.0599, 4), true, 2, true, kLimits).accepted);
  EXPECT_EQ(g.accept(reading(0.0, 0.0801, 5), true, 2, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffJump))
      << "accepted: the blind ticks start again";
}

// Three invalid readings: the next may have moved four bounds. Accepted, the bound is one
// tick's again.
TEST(PickoffGate, InvalidReadingsWidenTheBoundUntilOneIsTaken) {
  GYRO_VERIFIES("PICK-3");
  PickoffGate<double> g;
  const double bound = kLimits.max_step_rad;
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);
  PickoffReading<double> unset = reading(0.0, 0.0, 2);
  unset.valid = false;
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(g.accept(unset, true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffInvalid));
  }
  const PickoffVerdict wide = g.accept(reading(3.5 * bound, 0.0, 3), true, 1, true, kLimits);
  EXPECT_TRUE(wide.accepted);
  EXPECT_EQ(wide.flags, 0u);
  EXPECT_EQ(g.measured()(0), 3.5 * bound);
  EXPECT_EQ(g.accept(reading(3.5 * bound + 1.5 * bound, 0.0, 4), true, 1, true, kLimits).flags,
            static_cast<std::uint32_t>(kPickoffJump));
  EXPECT_EQ(g.measured()(0), 3.5 * bound);
}

// A stale reading (the same conversion again) tells as little as an invalid one: the bound
// widens by one tick's step for each.
TEST(PickoffGate, StaleReadingsWidenTheBoundAsInvalidOnesDo) {
  GYRO_VERIFIES("PICK-3");
  PickoffGate<double> g;
  const double bound = kLimits.max_step_rad;
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits).flags, static_cast<std::uint32_t>(kPickoffStale));
  }
  const PickoffVerdict v = g.accept(reading(0.0, -3.5 * bound, 2), true, 1, true, kLimits);  // four ticks: four bounds
  EXPECT_TRUE(v.accepted);
  EXPECT_EQ(v.flags, 0u);
  EXPECT_EQ(g.measured()(1), -3.5 * bound);
}

TEST(PickoffGate, WithoutTheJumpTestTheReferenceFollows) {
  GYRO_VERIFIES("PICK-4");
  PickoffGate<double> g;
  (void)g.accept(reading(0.0, 0.0, 1), true, 1, true, kLimits);
  EXPECT_TRUE(g.accept(reading(0.3, 0.0, 2), true, 1, false, kLimits).accepted);
  EXPECT_EQ(g.measured()(0), 0.3);
}

}  // namespace pickoff_gate_test
}  // namespace gyro
