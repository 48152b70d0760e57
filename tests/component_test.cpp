// GyroComponent against the SIL stub: lifecycle, modes, closed-loop slew, refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::SeekerGyro;
using testing::Sil;

TEST(ComponentLifecycle, GivenNotActivatedThenStepIsRefusedWithoutPortTraffic) {
  Sil<double> sil;
  ASSERT_TRUE(sil.gyro.configure(SeekerGyro<double>::stub()).ok());
  ASSERT_EQ(sil.gyro.start(sil.R_earth_to_body, sil.body_rate), Status::kOk);
  EXPECT_EQ(sil.component.activate(), Status::kNotConfigured);
  EXPECT_EQ(sil.component.step(1, sil.guidance), Status::kNotConfigured);
  ASSERT_TRUE(sil.component.configure(SeekerGyro<double>::component()).ok());
  EXPECT_EQ(sil.component.mode(), GyroMode::kIdle);
  ASSERT_EQ(sil.component.activate(), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(sil.component.activate(), Status::kWrongMode);
  const ConfigCheck again = sil.component.configure(SeekerGyro<double>::component());
  EXPECT_EQ(again.status, Status::kWrongMode);
}

TEST(ComponentConfig, GivenEachBadFieldThenRefusedNamingIt) {
  using C = GyroComponentConfig<double>;
  struct Case {
    const char* field;
    void (*spoil)(C&);
    Status status;
  };
  const Case cases[] = {
      {"tick_s", [](C& c) { c.tick_s = 0; }, Status::kNonPositiveStep},
      {"tick_s", [](C& c) { c.tick_s = std::nan(""); }, Status::kNonFiniteInput},
      {"pitch_inertia", [](C& c) { c.pitch_inertia = -1; }, Status::kNonPositiveInertia},
      {"yaw_inertia", [](C& c) { c.yaw_inertia = 0; }, Status::kNonPositiveInertia},
      {"spin_inertia", [](C& c) { c.spin_inertia = 0; }, Status::kNonPositiveInertia},
      {"friction", [](C& c) { c.friction = -1e-6; }, Status::kNegativeFriction},
      {"friction", [](C& c) { c.friction = HUGE_VAL; }, Status::kNonFiniteInput},
      {"nominal_spin_hz", [](C& c) { c.nominal_spin_hz = 0; }, Status::kOutOfRange},
      {"min_spin_hz", [](C& c) { c.min_spin_hz = 500; }, Status::kOutOfRange},
      {"max_pitch_rate_rad_s", [](C& c) { c.max_pitch_rate_rad_s = 0; }, Status::kOutOfRange},
      {"max_yaw_rate_rad_s", [](C& c) { c.max_yaw_rate_rad_s = -1; }, Status::kOutOfRange},
      {"max_torque", [](C& c) { c.max_torque = 0; }, Status::kOutOfRange},
      {"cage_gain_1_s", [](C& c) { c.cage_gain_1_s = 1e4; }, Status::kOutOfRange},
      {"gimbal_cone_limit_rad", [](C& c) { c.gimbal_cone_limit_rad = 2; }, Status::kOutOfRange},
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = 0.6; }, Status::kOutOfRange},
      {"small_angle_limit_rad", [](C& c) { c.small_angle_limit_rad = 0; }, Status::kOutOfRange},
      {"pickoff_range_rad", [](C& c) { c.pickoff_range_rad = 0; }, Status::kOutOfRange},
      {"max_pickoff_step_rad", [](C& c) { c.max_pickoff_step_rad = -1; }, Status::kOutOfRange},
      {"estimator_gain", [](C& c) { c.estimator_gain = 1.5; }, Status::kOutOfRange},
      {"residual_limit_rad", [](C& c) { c.residual_limit_rad = 0; }, Status::kOutOfRange},
      {"residual_persistence_ticks", [](C& c) { c.residual_persistence_ticks = 0; }, Status::kOutOfRange},
      {"invalid_persistence_ticks", [](C& c) { c.invalid_persistence_ticks = 0; }, Status::kOutOfRange},
      {"spin_low_persistence_ticks", [](C& c) { c.spin_low_persistence_ticks = 0; }, Status::kOutOfRange},
      {"torquer_fail_persistence_ticks", [](C& c) { c.torquer_fail_persistence_ticks = 0; },
       Status::kOutOfRange},
  };
  for (const Case& k : cases) {
    Sil<double> sil;
    C c = SeekerGyro<double>::component();
    k.spoil(c);
    const ConfigCheck r = sil.component.configure(c);
    EXPECT_EQ(r.status, k.status) << k.field;
    ASSERT_NE(r.field, nullptr) << k.field;
    EXPECT_STREQ(r.field, k.field);
    EXPECT_EQ(sil.component.activate(), Status::kNotConfigured) << "a refused config is not kept";
  }
}

TEST(ComponentModes, GivenCagedThenGimbalsFollowTheTurningBody) {
  Sil<double> sil;
  sil.body_rate = Vector2<double>(0.4, -0.3);
  ASSERT_TRUE(sil.start());
  sil.run(2000);  // 1 s: the caging loop closes at 20 1/s
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  // A first-order loop following a ramp lags by rate/gain: 0.4/20 = 0.02 rad.
  EXPECT_NEAR(sil.gyro.gimbal_angle_rad()(0), 0.0, 2e-3);
  EXPECT_NEAR(sil.gyro.gimbal_angle_rad()(1), 0.0, 2e-3);
  EXPECT_EQ(sil.tm().flags & kResidualFault, 0u);
}

TEST(ComponentModes, GivenUncageRequestThenUncagingThenFreeAfterSettleTicks) {
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  sil.run(100);
  ASSERT_EQ(sil.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  EXPECT_EQ(sil.tm().torque_cmd, Vector2<double>::Zero());
  sil.run(static_cast<int>(SeekerGyro<double>::component().uncage_settle_ticks) - 1);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  sil.run(1);
  EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
  ASSERT_EQ(sil.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
}

// Mean true precession rate over `ticks` ticks of slewing at `cmd`.
Vector2<double> mean_true_rate(Sil<double>& sil, const Vector2<double>& cmd, int settle, int ticks) {
  sil.guidance.slew_rate_cmd_rad_s = cmd;
  sil.run(settle);
  Vector2<double> sum = Vector2<double>::Zero();
  for (int k = 0; k < ticks; ++k) {
    (void)sil.step();
    sum += sil.gyro.spin_axis_rate_rad_s();
  }
  return sum / ticks;
}

// With friction f the report's torque law T = (H w2, -H w1) precesses at k5, k6 instead of
// the command: the error is (f/H)(w2, -w1) to first order. The exact inverse removes it.
TEST(ComponentClosedLoop, GivenSlewCommandThenRateAchievedAndFrictionCouplingRemoved) {
  const Vector2<double> cmd(0.3, -0.2);
  const double h = angular_momentum(400.0, 3e-5), f = 4e-4;
  for (bool compensate : {true, false}) {
    GyroComponentConfig<double> c = SeekerGyro<double>::component();
    c.friction_compensation = compensate;
    Sil<double> sil;
    ASSERT_TRUE(sil.start(c));
    ASSERT_TRUE(sil.uncage());
    // Settle 0.3 s (6 time constants of nutation decay), then average over 0.2 s.
    const Vector2<double> w = mean_true_rate(sil, cmd, 600, 400);
    const Vector2<double> err = w - cmd;
    const Vector2<double> coupling((f * h * cmd(1) - f * f * cmd(0)) / (f * f + h * h),
                                   (-f * h * cmd(0) - f * f * cmd(1)) / (f * f + h * h));
    std::printf("friction compensation %s: slew error pitch %.3e yaw %.3e rad/s (theory of the uncompensated "
                "coupling %.3e %.3e)\n",
                compensate ? "on " : "off", err(0), err(1), coupling(0), coupling(1));
    if (compensate) {
      // Bound: the nutation left after 6 time constants, averaged over 75 periods: < 1e-4 of the command.
      EXPECT_LT(err.cwiseAbs().maxCoeff(), 1e-4 * cmd.norm());
    } else {
      EXPECT_NEAR(err(0), coupling(0), 0.02 * std::abs(coupling(0)) + 1e-4 * cmd.norm());
      EXPECT_NEAR(err(1), coupling(1), 0.02 * std::abs(coupling(1)) + 1e-4 * cmd.norm());
      EXPECT_GT(err.cwiseAbs().maxCoeff(), 1e-3);  // 1.6e-3 rad/s of cross rate: visible
    }
    EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
    EXPECT_EQ(sil.tm().counters[6], 0u) << "no residual fault on a healthy gyro";
  }
}

TEST(ComponentClosedLoop, GivenCommandBeyondLimitsThenClampedPerAxisAndTorqueSaturatedByScaling) {
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.max_pitch_rate_rad_s = 0.2;
  c.max_yaw_rate_rad_s = 0.5;
  c.max_torque = 0.02;  // 0.27 rad/s at H = 0.0754
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c));
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(-0.9, 0.9);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_EQ(sil.tm().rate_cmd_rad_s, Vector2<double>(-0.2, 0.5));
  EXPECT_NE(sil.tm().flags & kSlewRateLimited, 0u);
  EXPECT_NE(sil.tm().flags & kTorquerSaturated, 0u);
  // The torque shaper (one tick of spacing at this rotor) reaches the law's torque on the
  // third tick of the same command.
  ASSERT_EQ(sil.step(), Status::kOk);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_NEAR(sil.tm().torque_cmd.cwiseAbs().maxCoeff(), 0.02, 1e-15);
  // Direction kept: torque proportional to the unsaturated law's (f w1 + H w2, f w2 - H w1).
  const double h = angular_momentum(400.0, 3e-5), f = 4e-4;
  const Vector2<double> full(f * -0.2 + h * 0.5, f * 0.5 - h * -0.2);
  // (Three ticks on, the gimbal has moved by 1e-9 rad: a per-axis clip would be off by 1e-4.)
  EXPECT_NEAR(sil.tm().torque_cmd(0) * full(1) - sil.tm().torque_cmd(1) * full(0), 0.0, 1e-12);
}

// A torque limit so small that max_torque / |torque| is subnormal (found by
// fuzz_component_tick: scaling by that ratio overshot the limit by 5e-15 relative) cannot
// precess the spin axis at all: the configuration contract refuses it, naming the rule.
TEST(ComponentClosedLoop, GivenATinyTorqueLimitThenConfigureRefusesIt) {
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.max_torque = 1.8816602877266144e-306;
  const ConfigCheck r = check(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  ASSERT_NE(r.field, nullptr);
  EXPECT_STREQ(r.field, "max_torque");
  EXPECT_EQ(r.value, c.max_torque);
  Sil<double> sil;
  EXPECT_FALSE(sil.start(c));
}

TEST(ComponentClosedLoop, GivenSlewTowardStopThenHeldAtTheProtectionCone) {
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.8, 0.0);
  bool protected_seen = false;
  for (int k = 0; k < 2000 && !protected_seen; ++k) {
    (void)sil.step();
    protected_seen = (sil.tm().flags & kGimbalStopProtect) != 0u;
  }
  ASSERT_TRUE(protected_seen);
  EXPECT_LT(sil.tm().rate_cmd_rad_s(0), 0.8) << "the outward command is cut";
  sil.run(400);
  // It settles at the protection cone (0.5 - 0.05 rad) instead of running into the stop.
  EXPECT_NEAR(sil.gyro.cone_rad(), 0.45, 3e-3);
  EXPECT_LT(std::abs(sil.tm().rate_cmd_rad_s(0)), 0.03) << "the outward rate dies away as e^(-k t), k = 20 1/s";
  EXPECT_FALSE(sil.gyro.at_gimbal_stop());
  // Slewing back out is allowed.
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(-0.3, 0.0);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_EQ(sil.tm().rate_cmd_rad_s(0), -0.3);
}

TEST(ComponentRefusals, GivenUnusableGuidanceFieldsThenTheTickRunsAsIfTheLastUsableCommandWereSent) {
  // Run A is sent a NaN slew command and an unknown request in the middle; run B is sent the
  // last usable command instead. Apart from the flags and counters of what A ignored,
  // everything is bit-identical: an ignored field leaves no other trace.
  Sil<double> a, b;
  ASSERT_TRUE(a.start());
  ASSERT_TRUE(b.start());
  ASSERT_TRUE(a.uncage());
  ASSERT_TRUE(b.uncage());
  a.guidance.slew_rate_cmd_rad_s = b.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1, 0.05);
  a.run(50);
  b.run(50);
  a.guidance.slew_rate_cmd_rad_s(1) = std::nan("");
  EXPECT_EQ(a.step(), Status::kInputIgnored);
  EXPECT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(a.tm().flags & ~b.tm().flags, static_cast<std::uint32_t>(kCommandRejected));
  a.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1, 0.05);
  EXPECT_EQ(a.step(static_cast<ModeRequest>(7)), Status::kInputIgnored);
  EXPECT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(a.tm().counters[11], 2u);
  a.run(300);
  b.run(300);
  GyroTelemetry<double> ta = a.tm(), tb = b.tm();
  ta.counters[11] = tb.counters[11] = 0;
  EXPECT_TRUE(testing::identical(ta, tb));
}

TEST(ComponentRefusals, GivenInvalidNavigationThenFlaggedAndResidualTestSuspended) {
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  ASSERT_TRUE(sil.uncage());
  sil.guidance.nav_valid = true;
  ++sil.tick;
  ASSERT_EQ(sil.gyro.advance(sil.tick, sil.R_earth_to_body, Vector2<double>::Zero()), Status::kOk);
  GuidanceInput<double> g = sil.guidance;
  g.R_earth_to_body(0, 0) = 2.0;  // not a rotation
  ASSERT_EQ(sil.component.step(sil.tick, g), Status::kInputIgnored);
  EXPECT_NE(sil.tm().flags & kNavInvalid, 0u);
  EXPECT_TRUE(testing::telemetry_finite(sil.tm()));
}

TEST(ComponentTelemetry, GivenTickLongerThanHalfANutationPeriodThenNutationUnresolvedFlagged) {
  // 600 Hz nutation (H/J): a 1 kHz tick samples it less than twice a period.
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  c.tick_s = s.tick_s = 1e-3;
  c.cage_gain_1_s = 10;
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c, s));
  sil.run(10);
  EXPECT_NE(sil.tm().flags & kNutationUnresolved, 0u);
  Sil<double> fine;
  ASSERT_TRUE(fine.start());
  fine.run(10);
  EXPECT_EQ(fine.tm().flags & kNutationUnresolved, 0u);
}

TEST(ComponentDeterminism, GivenTwoIdenticalRunsThenTelemetryIsBitIdentical) {
  auto run = [](auto tag) {
    using T = decltype(tag);
    Sil<T> sil;
    SimulatedGyroConfig<T> s = SeekerGyro<T>::stub();
    s.pickoff.noise_rad = T(1e-5);
    s.pickoff.lsb_rad = T(1e-5);
    sil.body_rate = Vector2<T>(T(0.2), T(0.1));
    EXPECT_TRUE(sil.start(SeekerGyro<T>::component(), s));
    EXPECT_TRUE(sil.uncage());
    sil.guidance.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.1));
    sil.run(1000);
    return sil.tm();
  };
  const GyroTelemetry<double> d1 = run(0.0), d2 = run(0.0);
  EXPECT_TRUE(testing::identical(d1, d2));
  const GyroTelemetry<float> f1 = run(0.0f), f2 = run(0.0f);
  EXPECT_TRUE(testing::identical(f1, f2));
  EXPECT_EQ(f1.mode, GyroMode::kFree);
  EXPECT_NEAR(static_cast<double>(f1.precession_rate_rad_s(0)), d1.precession_rate_rad_s(0), 1e-3);
}

}  // namespace
}  // namespace gyro
