// The configuration checks of the component and the SIL stub refuse a rotor whose exact step
// over one tick is not representable, and name the field responsible (not always the tick,
// as the component's check did), in double and float.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gyro/component_config.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

template <typename T>
struct Case {
  std::function<void(T& j1, T& j2, T& j0, T& f, T& spin, T& tick)> mutate;
  const char* culprit;  // pitch_inertia, yaw_inertia, spin_inertia, friction, spin, tick
};

// Overflowing cases in `T`, each with the input responsible.
template <typename T>
std::vector<Case<T>> overflowing_cases() {
  constexpr bool kDouble = sizeof(T) == 8;
  const T tiny = kDouble ? T(5e-324) : T(1e-45);   // the smallest subnormal: 1/J is infinite
  const T small = kDouble ? T(1e-300) : T(1e-36);  // 1/J finite, the rate terms are not
  const T huge = kDouble ? T(1e300) : T(1e36);
  return {
      {[=](T& j1, T&, T&, T&, T&, T&) { j1 = tiny; }, "pitch_inertia"},
      {[=](T& j1, T&, T&, T&, T&, T&) { j1 = small; }, "pitch_inertia"},
      {[=](T&, T& j2, T&, T&, T&, T&) { j2 = tiny; }, "yaw_inertia"},
      {[=](T&, T&, T& j0, T&, T&, T&) { j0 = huge; }, "spin_inertia"},
      {[=](T&, T&, T&, T& f, T&, T&) { f = huge; }, "friction"},
      {[=](T&, T&, T&, T&, T& spin, T&) { spin = huge; }, "spin"},
      {[=](T&, T&, T&, T&, T& spin, T&) { spin = kDouble ? T(1e160) : T(1e20); }, "spin"},  // H finite, H^2 not
      {[=](T&, T&, T&, T&, T&, T& tick) { tick = huge; }, "tick"},
  };
}

template <typename T>
class ExactStepCheck : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ExactStepCheck, Scalars);

TYPED_TEST(ExactStepCheck, GivenAComponentRotorWhoseStepOverflowsWhenConfiguredThenTheFieldResponsibleIsNamed) {
  GYRO_VERIFIES("CONF-3");
  using T = TypeParam;
  for (const Case<T>& k : overflowing_cases<T>()) {
    GyroComponentConfig<T> c = SeekerExample<T>::component();
    c.cage_gain_1_s = T(0.1);  // the least the contract takes: gain * tick <= 1 would refuse a long tick
    k.mutate(c.pitch_inertia, c.yaw_inertia, c.spin_inertia, c.friction, c.nominal_spin_hz, c.tick_s);
    if (std::string(k.culprit) == "spin") c.min_spin_hz = T(0);
    const std::string expected = std::string(k.culprit) == "spin"   ? "nominal_spin_hz"
                                 : std::string(k.culprit) == "tick" ? "tick_s"
                                                                    : k.culprit;
    SCOPED_TRACE(expected);
    const ConfigCheck r = check(c);
    // Refused as an overflow, or (the contract's ranges come first) by the field's own range.
    EXPECT_TRUE(r.status == Status::kNumericalOverflow || r.relation != Relation::kNone) << to_string(r.status);
    ASSERT_NE(r.field, nullptr);
    EXPECT_EQ(std::string(r.field), expected);
  }
}

TYPED_TEST(ExactStepCheck, GivenAStubRotorWhoseStepOverflowsWhenConfiguredThenRefusedNamingTheFieldAndNothingStarts) {
  GYRO_VERIFIES("STUB-4");
  using T = TypeParam;
  for (const Case<T>& k : overflowing_cases<T>()) {
    SimulatedGyroConfig<T> c = SeekerExample<T>::stub();
    c.plant = PlantKind::kReport;  // the exact step is the report's plant's
    k.mutate(c.gyro.pitch_inertia, c.gyro.yaw_inertia, c.gyro.spin_inertia, c.gyro.friction, c.spin_hz, c.tick_s);
    const std::string expected = std::string(k.culprit) == "spin"   ? "spin_hz"
                                 : std::string(k.culprit) == "tick" ? "tick_s"
                                                                    : k.culprit;
    SCOPED_TRACE(expected);
    SimulatedGyro<T> sim;
    const ConfigCheck r = sim.configure(c);
    EXPECT_TRUE(r.status == Status::kNumericalOverflow || r.relation != Relation::kNone) << to_string(r.status);
    ASSERT_NE(r.field, nullptr);
    EXPECT_EQ(std::string(r.field), expected);
    EXPECT_EQ(sim.start(Matrix3<T>::Identity(), Vector2<T>::Zero()), Status::kNotConfigured);
  }
}

// What the check accepts, the stub advances: the largest spins either side of the limit. The
// spin's own bound (100 kHz) comes first; the exact step's limit, far beyond it, is one of the
// representation.
TEST(ExactStepCheck, GivenTheLargestSpinTheStubAcceptsThenItsFirstStepSucceeds) {
  GYRO_VERIFIES("STUB-4");
  SimulatedGyroConfig<double> c = SeekerExample<double>::stub();
  c.plant = PlantKind::kReport;  // the exact step is the report's plant's
  const auto largest_accepted = [&c](auto accepts) {
    double lo = 1e3, hi = 1e300;  // accepted, refused
    for (int i = 0; i < 200; ++i) {
      const double mid = std::sqrt(lo) * std::sqrt(hi);
      c.spin_hz = mid;
      (accepts() ? lo : hi) = mid;
    }
    return std::pair<double, double>(lo, hi);
  };
  const auto [lo, hi] = largest_accepted([&c] { return check(c).ok(); });
  c.spin_hz = lo;
  SimulatedGyro<double> sim;
  ASSERT_TRUE(sim.configure(c).ok()) << lo;
  ASSERT_EQ(sim.start(Matrix3<double>::Identity(), Vector2<double>::Zero()), Status::kOk);
  EXPECT_EQ(sim.advance(1, Matrix3<double>::Identity(), Vector2<double>::Zero()), Status::kOk) << lo;
  EXPECT_LE(lo, 1e5);
  EXPECT_GT(lo, 0.999999e5);
  c.spin_hz = hi;
  EXPECT_EQ(check(c).status, Status::kOutOfRange) << hi;
  EXPECT_STREQ(check(c).field, "spin_hz");

  const auto [step_lo, step_hi] = largest_accepted([&c] { return check_exact_step_at_start(c).ok(); });
  c.spin_hz = step_hi;
  EXPECT_EQ(check_exact_step_at_start(c).status, Status::kNumericalOverflow) << step_hi;
  EXPECT_GT(step_lo, 1e100);  // a real limit of the representation, not a tight physical one
}

TEST(ExactStepCheck, GivenTheShippedExampleGyrosThenBothChecksAccept) {
  GYRO_VERIFIES("CONF-8");
  EXPECT_TRUE(check(SeekerExample<double>::component()).ok());
  EXPECT_TRUE(check(SeekerExample<float>::component()).ok());
  EXPECT_TRUE(check(SeekerExample<double>::stub()).ok());
  EXPECT_TRUE(check(SeekerExample<float>::stub()).ok());
}

// check_exact_step itself, on each way it names the input responsible: H not representable,
// the rate terms not (the inertia, the friction or H furthest from 1, a friction of 0 the
// least extreme of all), and the step over the tick not.
TEST(ExactStepCheck, EachOverflowNamesTheInputFurthestFromOne) {
  GYRO_VERIFIES("CONF-3");
  constexpr ExactStepFields kNames{"pitch_inertia", "yaw_inertia", "spin_inertia", "friction", "spin_hz", "tick_s"};
  const auto named = [&](double j1, double f, double j0, double spin, double tick) {
    const ConfigCheck r = check_exact_step(j1, 2e-4, j0, f, spin, tick, kNames);
    EXPECT_EQ(r.status, Status::kNumericalOverflow);
    return std::string(r.field != nullptr ? r.field : "(none)");
  };
  EXPECT_TRUE(check_exact_step(2e-4, 2e-4, 3e-4, 1e-4, 100.0, 1e-3, kNames).ok());
  EXPECT_EQ(named(2e-4, 1e-4, 1e100, 1e250, 1e-3), "spin_hz");       // H = 2 pi spin J0 overflows
  EXPECT_EQ(named(2e-4, 1e-4, 1e250, 1e100, 1e-3), "spin_inertia");
  EXPECT_EQ(named(5e-324, 0.0, 3e-4, 100.0, 1e-3), "pitch_inertia");  // no friction: extremeness 0
  EXPECT_EQ(named(2e-4, 1e300, 3e-4, 100.0, 1e-3), "friction");
  EXPECT_EQ(named(2e-4, 1e-4, 3e-4, 1e160, 1e-3), "spin_hz");         // H finite, H^2 not
  EXPECT_EQ(named(2e-4, 1e-4, 3e-4, 100.0, 1e300), "tick_s");         // the step, not the rotor
}

}  // namespace
}  // namespace gyro
