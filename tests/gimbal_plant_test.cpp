// The gimbal plant's contract and its parts: configuration refusals naming the field, the
// lifecycle, refused steps leaving the state bit-identical, determinism, the stop, gimbal
// lock, the spin motor and spin-down, the mass unbalance, the conventions, and float.
// Invariants and the independent checks are in gimbal_invariants_test.cpp,
// gimbal_report_limit_test.cpp and gimbal_lagrange_check.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gyro/attitude.hpp"
#include "gyro/report_sample.hpp"
#include "support/gimbal_support.hpp"

namespace gyro {
namespace {

using namespace gimbal_test;
using V2 = Vector2<double>;
using V3 = Vector3<double>;
using Config = GimbalPlantConfig<double>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Everything a caller can observe, for bit-for-bit comparisons.
struct Observed {
  GimbalJointState<double> s;
  GimbalWork<double> w;
  double motor = 0.0, energy = 0.0;
  bool contact = false, saturated = false;
};
Observed observe(const GimbalPlant<double>& p) {
  return {p.joint_state(), p.work(), p.motor_torque(), p.kinetic_energy(), p.in_contact(), p.motor_saturated()};
}
bool bit_equal(const Observed& a, const Observed& b) {
  const double va[] = {a.s.pitch_rad, a.s.yaw_rad, a.s.pitch_rate_rad_s, a.s.yaw_rate_rad_s, a.s.spin_rate_rad_s,
                       a.s.twist_rad, a.w.torquer, a.w.friction, a.w.spin, a.w.unbalance, a.motor, a.energy};
  const double vb[] = {b.s.pitch_rad, b.s.yaw_rad, b.s.pitch_rate_rad_s, b.s.yaw_rate_rad_s, b.s.spin_rate_rad_s,
                       b.s.twist_rad, b.w.torquer, b.w.friction, b.w.spin, b.w.unbalance, b.motor, b.energy};
  return std::memcmp(va, vb, sizeof va) == 0 && a.contact == b.contact && a.saturated == b.saturated;
}

// ---- configuration ----------------------------------------------------------------------------

TEST(GimbalPlantConfig, GivenTheSeekerDeviceThenAcceptedAndItsEffectiveInertiasAreTheExamples) {
  const Config c = seeker_gimbal_config<double>();
  EXPECT_TRUE(check(c).ok());
  using S = SeekerExample<double>;
  // Pitch: Iy + A. Yaw at zero angles: Oz + Iz + A (Oz + Ix s^2 + (Iz + A) c^2).
  EXPECT_NEAR(c.inner_gimbal_inertia(1) + c.rotor_transverse_inertia, S::kJ, 1e-20);
  EXPECT_NEAR(c.outer_gimbal_inertia(2) + c.inner_gimbal_inertia(2) + c.rotor_transverse_inertia, S::kJ, 1e-20);
  EXPECT_EQ(c.inner_friction, S::kFriction);
  EXPECT_EQ(c.outer_friction, S::kFriction);
  EXPECT_EQ(c.spin_inertia, S::kJ0);
  EXPECT_TRUE(check(seeker_gimbal_config<float>()).ok());
}

struct BadField {
  const char* field;
  Status status;
  std::function<void(Config&)> spoil;
};

TEST(GimbalPlantConfig, GivenEachBadFieldThenRefusedNamingIt) {
  const std::vector<BadField> cases = {
      {"spin_inertia", Status::kNonPositiveInertia, [](Config& c) { c.spin_inertia = 0.0; }},
      {"spin_inertia", Status::kNonFiniteInput, [](Config& c) { c.spin_inertia = kNaN; }},
      {"rotor_transverse_inertia", Status::kNonPositiveInertia, [](Config& c) { c.rotor_transverse_inertia = -1.0; }},
      {"rotor_transverse_inertia", Status::kOutOfRange, [](Config& c) { c.rotor_transverse_inertia = 1.4e-5; }},
      {"inner_gimbal_inertia", Status::kNonPositiveInertia, [](Config& c) { c.inner_gimbal_inertia(0) = -1e-6; }},
      {"inner_gimbal_inertia", Status::kOutOfRange, [](Config& c) { c.inner_gimbal_inertia(1) = 5e-6; }},
      {"outer_gimbal_inertia", Status::kNonFiniteInput, [](Config& c) { c.outer_gimbal_inertia(2) = kInf; }},
      {"outer_gimbal_inertia", Status::kOutOfRange, [](Config& c) { c.outer_gimbal_inertia(0) = 5e-6; }},
      {"inner_friction", Status::kNegativeFriction, [](Config& c) { c.inner_friction = -1e-9; }},
      {"outer_friction", Status::kNonFiniteInput, [](Config& c) { c.outer_friction = kNaN; }},
      {"inner_coulomb_torque", Status::kNegativeFriction, [](Config& c) { c.inner_coulomb_torque = -1.0; }},
      {"outer_coulomb_torque", Status::kNegativeFriction, [](Config& c) { c.outer_coulomb_torque = -1.0; }},
      {"coulomb_rate_scale_rad_s", Status::kOutOfRange, [](Config& c) { c.coulomb_rate_scale_rad_s = 0.0; }},
      {"max_spin_hz", Status::kOutOfRange, [](Config& c) { c.max_spin_hz = 0.0; }},
      {"motor_torque_limit", Status::kOutOfRange, [](Config& c) { c.motor_torque_limit = 0.0; }},
      {"motor_torque_limit", Status::kNonFiniteInput, [](Config& c) { c.motor_torque_limit = kNaN; }},
      {"spin_servo_bandwidth_rad_s", Status::kOutOfRange, [](Config& c) { c.spin_servo_bandwidth_rad_s = -1.0; }},
      {"spin_down_time_s", Status::kOutOfRange, [](Config& c) { c.spin_down_time_s = -1.0; }},
      {"mass_unbalance", Status::kNonFiniteInput, [](Config& c) { c.mass_unbalance = kInf; }},
      {"stop_cone_rad", Status::kOutOfRange, [](Config& c) { c.stop_cone_rad = 0.0; }},
      {"stop_cone_rad", Status::kOutOfRange, [](Config& c) { c.stop_cone_rad = 85.0 * kDeg; }},  // gimbal lock
      {"stop_cone_rad", Status::kOutOfRange, [](Config& c) { c.stop_cone_rad = 0.9e-3; }},  // below a milliradian
      {"rotor_transverse_inertia", Status::kOutOfRange, [](Config& c) { c.rotor_transverse_inertia = 3.1e1; }},
      {"inner_gimbal_inertia", Status::kOutOfRange, [](Config& c) { c.inner_gimbal_inertia = V3(20.0, 40.0, 31.0); }},
      {"outer_gimbal_inertia", Status::kOutOfRange, [](Config& c) { c.outer_gimbal_inertia = V3(62.0, 31.0, 31.0); }},
      {"stop_restitution", Status::kOutOfRange, [](Config& c) { c.stop_restitution = 1.5; }},
      {"stop_restitution", Status::kOutOfRange, [](Config& c) { c.stop_restitution = -0.1; }},
      {"spin_drive", Status::kOutOfRange, [](Config& c) { c.spin_drive = static_cast<SpinDrive>(7); }},
      {"torquer_axes", Status::kOutOfRange, [](Config& c) { c.torquer_axes = static_cast<TorquerAxes>(7); }},
      {"max_body_rate_rad_s", Status::kOutOfRange, [](Config& c) { c.max_body_rate_rad_s = 0.0; }},
      {"max_torque", Status::kOutOfRange, [](Config& c) { c.max_torque = -1.0; }},
      {"max_specific_force", Status::kNonFiniteInput, [](Config& c) { c.max_specific_force = kInf; }},
      {"max_substep_phase_rad", Status::kOutOfRange, [](Config& c) { c.max_substep_phase_rad = 0.0; }},
      {"max_substep_phase_rad", Status::kOutOfRange, [](Config& c) { c.max_substep_phase_rad = 3.0; }},
  };
  for (const BadField& b : cases) {
    Config c = seeker_gimbal_config<double>();
    b.spoil(c);
    const ConfigCheck r = check(c);
    EXPECT_EQ(r.status, b.status) << b.field;
    EXPECT_STREQ(r.field ? r.field : "(none)", b.field);
    GimbalPlant<double> p;
    EXPECT_EQ(p.configure(c, kTick).status, b.status) << b.field;
    EXPECT_EQ(p.step(V2::Zero(), {}, {}), Status::kNotConfigured);
  }
  // A free rotor needs no motor.
  Config free_rotor = seeker_gimbal_config<double>();
  free_rotor.spin_drive = SpinDrive::kFree;
  free_rotor.motor_torque_limit = 0.0;
  EXPECT_TRUE(check(free_rotor).ok());
}

TEST(GimbalPlantConfig, GivenABadTickThenRefusedNamingIt) {
  GimbalPlant<double> p;
  EXPECT_EQ(p.configure(seeker_gimbal_config<double>(), 0.0).status, Status::kNonPositiveStep);
  EXPECT_STREQ(p.configure(seeker_gimbal_config<double>(), -1e-3).field, "tick_s");
  EXPECT_EQ(p.configure(seeker_gimbal_config<double>(), kNaN).status, Status::kNonFiniteInput);
  // So long that the sub-steps would exceed kMaxGimbalSubsteps: refused, not slow.
  EXPECT_EQ(p.configure(seeker_gimbal_config<double>(), 10.0).status, Status::kOutOfRange);
  EXPECT_EQ(p.start(large_nutation<double>(), {}), Status::kNotConfigured);
}

TEST(GimbalPlantConfig, GivenTheExamplesThenTheSubStepRuleGivesTheDocumentedCounts) {
  // Seeker: nutation H/sqrt(J1 J2) = 3830 rad/s (spin 400 Hz plus 40 rad/s of roll), body
  // rate 40, friction f/D = 25.6 at the stop, servo 5: 3900 1/s x 5e-4 s / 0.5 rad -> 4.
  EXPECT_EQ(gimbal_substeps(seeker_gimbal_config<double>(), 5e-4), 4);
  EXPECT_NEAR(gimbal_fastest_rate(seeker_gimbal_config<double>()), 3900.5, 0.1);
  Config c = seeker_gimbal_config<double>();
  c.max_substep_phase_rad = 0.25;
  EXPECT_EQ(gimbal_substeps(c, 5e-4), 8);
  c.inner_coulomb_torque = 3e-4;  // regularised: 3e-4 / 0.01 / 2e-5 = 1.5e3 1/s more
  EXPECT_EQ(gimbal_substeps(c, 5e-4), 11);
  EXPECT_EQ(gimbal_substeps(c, 1e3), 0);  // beyond kMaxGimbalSubsteps
}

// ---- lifecycle and refusals -------------------------------------------------------------------

TEST(GimbalPlantLifecycle, GivenBadStartsThenRefusedAndNotStarted) {
  GimbalPlant<double> p;
  ASSERT_TRUE(p.configure(seeker_gimbal_config<double>(), kTick).ok());
  GimbalStart<double> s = large_nutation<double>();
  EXPECT_EQ(p.step(V2::Zero(), {}, {}), Status::kNotConfigured);
  EXPECT_EQ(p.set_spin_drive(SpinDrive::kFree, 0.0), Status::kNotConfigured);
  GimbalStart<double> bad = s;
  bad.gimbal_rate_rad_s(0) = kNaN;
  EXPECT_EQ(p.start(bad, {}), Status::kNonFiniteInput);
  bad = s;
  bad.spin_hz = 401.0;  // above max_spin_hz
  EXPECT_EQ(p.start(bad, {}), Status::kOutOfRange);
  bad.spin_hz = -1.0;
  EXPECT_EQ(p.start(bad, {}), Status::kOutOfRange);
  bad = s;
  bad.gimbal_angle_rad = V2(0.5, 0.3);  // cone 0.58 rad, beyond the 0.55 stop
  EXPECT_EQ(p.start(bad, {}), Status::kOutOfRange);
  BodyState<double> body;
  body.rate_rad_s = V3(41.0, 0.0, 0.0);
  EXPECT_EQ(p.start(s, body), Status::kOutOfRange);
  EXPECT_FALSE(p.started());
  EXPECT_EQ(p.start(s, {}), Status::kOk);
  EXPECT_TRUE(p.started());
  EXPECT_EQ(p.gimbal_angle_rad(), s.gimbal_angle_rad);
  EXPECT_EQ(p.gimbal_rate_rad_s(), s.gimbal_rate_rad_s);
  EXPECT_DOUBLE_EQ(p.spin_rate_rad_s(), 2.0 * kPiD * 400.0);
}

TEST(GimbalPlantLifecycle, GivenEachBadStepInputThenItsStatusAndTheStateBitIdentical) {
  GimbalPlant<double> p = started(seeker_gimbal_config<double>(), large_nutation<double>());
  ASSERT_EQ(p.step(V2(1e-3, 2e-3), {}, {}), Status::kOk);
  const Observed before = observe(p);
  BodyState<double> ok_body;
  auto with_rate = [](double v) {
    BodyState<double> b;
    b.rate_rad_s = V3(0.0, v, 0.0);
    return b;
  };
  auto with_force = [](double v) {
    BodyState<double> b;
    b.specific_force = V3(v, 0.0, 0.0);
    return b;
  };
  struct Bad {
    const char* what;
    V2 torque;
    BodyState<double> b0, b1;
    Status status;
  };
  const Bad bad[] = {
      {"NaN torque", V2(kNaN, 0.0), ok_body, ok_body, Status::kNonFiniteInput},
      {"infinite torque", V2(0.0, -kInf), ok_body, ok_body, Status::kNonFiniteInput},
      {"NaN rate at start", V2::Zero(), with_rate(kNaN), ok_body, Status::kNonFiniteInput},
      {"NaN force at end", V2::Zero(), ok_body, with_force(kNaN), Status::kNonFiniteInput},
      {"torque beyond max_torque", V2(0.0, 1.01), ok_body, ok_body, Status::kOutOfRange},
      {"body rate beyond the envelope", V2::Zero(), ok_body, with_rate(40.5), Status::kOutOfRange},
      {"specific force beyond the envelope", V2::Zero(), with_force(-1.1e4), ok_body, Status::kOutOfRange},
  };
  for (const Bad& b : bad) {
    EXPECT_EQ(p.step(b.torque, b.b0, b.b1), b.status) << b.what;
    EXPECT_TRUE(bit_equal(observe(p), before)) << b.what;
  }
  EXPECT_EQ(p.set_spin_drive(SpinDrive::kMotor, kNaN), Status::kNonFiniteInput);
  EXPECT_EQ(p.set_spin_drive(SpinDrive::kMotor, 500.0), Status::kOutOfRange);
  EXPECT_EQ(p.set_spin_drive(static_cast<SpinDrive>(9), 400.0), Status::kOutOfRange);
  EXPECT_TRUE(bit_equal(observe(p), before));
}

TEST(GimbalPlantLifecycle, GivenAStateThatOverflowsThenNumericalOverflowAndTheStateBitIdentical) {
  // A massless-gimbal device with the stop at its limit, gimbal rates no real device reaches:
  // whatever the sub-steps make of it, the plant refuses rather than keep a NaN.
  Config c = seeker_gimbal_config<double>();
  c.inner_gimbal_inertia.setZero();
  c.outer_gimbal_inertia.setZero();
  c.stop_cone_rad = kMaxGimbalStopCone<double>;
  GimbalStart<double> s;
  s.gimbal_rate_rad_s = V2(1e200, -1e200);
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s);
  const Observed before = observe(p);
  EXPECT_EQ(p.step(V2::Zero(), {}, {}), Status::kNumericalOverflow);
  EXPECT_TRUE(bit_equal(observe(p), before));
}

TEST(GimbalPlantDeterminism, GivenTwoRunsWithEverythingOnThenBitIdentical) {
  Config c = seeker_gimbal_config<double>();
  c.inner_coulomb_torque = 2e-4;
  c.outer_coulomb_torque = 2e-4;
  c.mass_unbalance = 1e-4;
  auto run_once = [&c] {
    GimbalPlant<double> p = started(c, large_nutation<double>());
    std::vector<Observed> out;
    BodyState<double> b0, b1;
    for (int k = 0; k < 400; ++k) {
      b1.rate_rad_s = V3(10.0 * std::sin(0.01 * k), 0.5, -0.3);
      b1.specific_force = V3(30.0, -5.0, -9.8);
      EXPECT_EQ(p.step(V2(0.05, -0.05), b0, b1), Status::kOk);
      b0 = b1;
      out.push_back(observe(p));
    }
    return out;
  };
  const std::vector<Observed> a = run_once(), b = run_once();
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_TRUE(bit_equal(a[k], b[k])) << "tick " << k;
}

// ---- the stop and gimbal lock -----------------------------------------------------------------

TEST(GimbalStop, GivenATorqueDrivingIntoTheStopThenContactReportedAndTheConeNeverBeyondIt) {
  const Config c = seeker_gimbal_config<double>();
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s);
  int contacts = 0;
  double worst_cone = 0.0;
  // 0.05 N m about the inner axis precesses yaw at 0.66 rad/s: the 0.55 rad stop in 0.8 s.
  run(p, kTicksPerSecond, V2(0.05, 0.0), BodyState<double>{}, [&](int, const GimbalPlant<double>& g) {
    contacts += static_cast<int>(g.in_contact());
    worst_cone = std::max(worst_cone, g.cone_rad());
    EXPECT_TRUE(std::isfinite(g.kinetic_energy()));
  });
  EXPECT_GT(contacts, 10);
  EXPECT_LE(worst_cone, c.stop_cone_rad + 1e-12);
  EXPECT_NEAR(p.cone_rad(), c.stop_cone_rad, 1e-3);  // held against it
}

// A non-spinning gyro (no gyroscopic stiffness) thrown at the stop: elastic, the gimbal energy
// comes back; dead, it is lost; in either case the outward rate is gone after the contact.
TEST(GimbalStop, GivenAThrownGimbalThenRestitutionDecidesTheEnergyKept) {
  for (const double e : {1.0, 0.0}) {
    Config c = ideal_seeker<double>();
    c.stop_cone_rad = 0.55;
    c.stop_restitution = e;
    GimbalStart<double> s;
    s.gimbal_angle_rad = V2(0.1, 0.2);
    s.gimbal_rate_rad_s = V2(2.0, 3.0);  // outward
    s.spin_hz = 0.0;
    GimbalPlant<double> p = started(c, s);
    const double e0 = p.kinetic_energy();
    int first_contact = -1;
    run(p, 400, V2::Zero().eval(), BodyState<double>{}, [&](int k, const GimbalPlant<double>& g) {
      if (g.in_contact() && first_contact < 0) first_contact = k;
      EXPECT_LE(g.cone_rad(), c.stop_cone_rad + 1e-12);
    });
    ASSERT_GE(first_contact, 0) << "restitution " << e;
    if (e == 1.0) {
      EXPECT_NEAR(p.kinetic_energy() / e0, 1.0, 2e-2) << "elastic";  // the projection's share only
    } else {
      EXPECT_LT(p.kinetic_energy(), 0.7 * e0) << "dead stop";
    }
  }
}

TEST(GimbalStop, GivenMasslessGimbalsAtTheLargestStopWithFullTorqueThenNeverNaN) {
  Config c = seeker_gimbal_config<double>();
  c.inner_gimbal_inertia.setZero();
  c.outer_gimbal_inertia.setZero();
  c.stop_cone_rad = kMaxGimbalStopCone<double>;
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s);
  BodyState<double> body;
  body.rate_rad_s = V3(25.0, 20.0, -20.0);  // within the 40 rad/s envelope
  int contacts = 0;
  for (int k = 0; k < kTicksPerSecond; ++k) {
    const Status st = p.step(V2(1.0, -1.0) * ((k / 300) % 2 == 0 ? 1.0 : -1.0), body, body);
    ASSERT_EQ(st, Status::kOk) << k;
    contacts += static_cast<int>(p.in_contact());
    ASSERT_TRUE(std::isfinite(p.kinetic_energy()) && std::isfinite(p.gimbal_angle_rad().sum()) &&
                std::isfinite(p.gimbal_rate_rad_s().sum()) && std::isfinite(p.spin_rate_rad_s()))
        << k;
    ASSERT_LE(std::abs(p.gimbal_angle_rad()(0)), c.stop_cone_rad + 1e-12);
  }
  EXPECT_GT(contacts, 0);
}

// ---- spin ---------------------------------------------------------------------------------------

TEST(GimbalSpin, GivenAFreeRotorAtRestThenItRunsDownExponentially) {
  Config c = ideal_seeker<double>();
  c.spin_down_time_s = 60.0;
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s);
  run(p, kTicksPerSecond, V2::Zero().eval(), BodyState<double>{}, [](int, const GimbalPlant<double>&) {});
  EXPECT_NEAR(p.spin_rate_rad_s() / (2.0 * kPiD * 400.0), std::exp(-1.0 / 60.0), 1e-13);
  EXPECT_LT(p.work().spin, 0.0);
}

TEST(GimbalSpin, GivenABodyRollKickBeyondTheMotorThenItSaturatesAndTheServoRecovers) {
  const Config c = seeker_gimbal_config<double>();
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s);
  BodyState<double> still, rolling;
  rolling.rate_rad_s = V3(30.0, 0.0, 0.0);
  const double inertial0 = p.spin_inertial_rad_s();
  // 30 rad/s of roll in one tick: holding the relative spin would take J0 * 6e4 = 1.8 N m.
  ASSERT_EQ(p.step(V2::Zero(), still, rolling), Status::kOk);
  EXPECT_TRUE(p.motor_saturated());
  EXPECT_NEAR(p.motor_torque(), c.motor_torque_limit, 1e-15);
  // The rotor's inertial spin moves by the motor's and the drag's impulse only (the relative
  // spin, and with it the drag, falls linearly over the tick: its mean is the midpoint's)...
  const double mean_spin = (p.spin_rate_rad_s() + 2.0 * kPiD * 400.0) / 2.0;
  const double drag = c.spin_inertia / c.spin_down_time_s * mean_spin;
  EXPECT_NEAR((p.spin_inertial_rad_s() - inertial0) * c.spin_inertia, (c.motor_torque_limit - drag) * kTick, 1e-13);
  // ...so the spin relative to the rolling gimbal drops by nearly the roll.
  EXPECT_NEAR(p.spin_rate_rad_s() - 2.0 * kPiD * 400.0, -30.0, 0.2);
  // At 0.01 N m the motor restores 30 rad/s in 0.1 s, then the 5 rad/s servo settles.
  run(p, 2 * kTicksPerSecond, V2::Zero().eval(), rolling, [](int, const GimbalPlant<double>&) {});
  EXPECT_FALSE(p.motor_saturated());
  EXPECT_NEAR(p.spin_rate_rad_s(), 2.0 * kPiD * 400.0, 1e-2);
  EXPECT_NEAR(p.motor_torque(), c.spin_inertia / c.spin_down_time_s * p.spin_rate_rad_s(), 1e-5);  // drag only
}

TEST(GimbalSpin, GivenTheMotorSwitchedOffThenTheRotorRunsDownAndOnAgainItRecovers) {
  GimbalPlant<double> p = started(seeker_gimbal_config<double>(), [] {
    GimbalStart<double> s;
    s.spin_hz = 400.0;
    return s;
  }());
  ASSERT_EQ(p.set_spin_drive(SpinDrive::kFree, 0.0), Status::kOk);
  run(p, kTicksPerSecond, V2::Zero().eval(), BodyState<double>{}, [](int, const GimbalPlant<double>&) {});
  EXPECT_NEAR(p.spin_rate_rad_s() / (2.0 * kPiD * 400.0), std::exp(-1.0 / 60.0), 1e-12);
  EXPECT_EQ(p.motor_torque(), 0.0);
  ASSERT_EQ(p.set_spin_drive(SpinDrive::kMotor, 400.0), Status::kOk);
  run(p, 3 * kTicksPerSecond, V2::Zero().eval(), BodyState<double>{}, [](int, const GimbalPlant<double>&) {});
  EXPECT_NEAR(p.spin_rate_rad_s(), 2.0 * kPiD * 400.0, 1e-3);
}

// ---- mass unbalance -----------------------------------------------------------------------------

TEST(GimbalUnbalance, GivenANoseHeavyRotorUnderGravityThenItDriftsInYawAtTheGSensitiveRate) {
  Config c = seeker_gimbal_config<double>();
  c.mass_unbalance = 1e-4;  // kg m, along +spin axis
  BodyState<double> body;
  body.specific_force = V3(0.0, 0.0, -9.80665);  // level, at rest: the accelerometer reads up
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  GimbalPlant<double> p = started(c, s, body);
  // 1 s: the nutation the start excites has decayed by e^-20 (alpha = 20 1/s).
  run(p, kTicksPerSecond, V2::Zero().eval(), body, [](int, const GimbalPlant<double>&) {});
  // Gravity on the nose-heavy rotor: a nose-down torque -m d g about the pitch axis, which
  // precesses the spin axis to the left at m d g / H (the report's g-sensitive drift; with f,
  // its k5/k6 form).
  const double h = c.spin_inertia * p.spin_inertial_rad_s(), f = c.inner_friction, t1 = -c.mass_unbalance * 9.80665;
  const double den = h * h + f * f;
  EXPECT_NEAR(p.gimbal_rate_rad_s()(1), h * t1 / den, 1e-6 * std::abs(t1 / h));
  EXPECT_NEAR(p.gimbal_rate_rad_s()(0), f * t1 / den, 1e-6 * std::abs(t1 / h));
  EXPECT_LT(p.gimbal_rate_rad_s()(1), 0.0);

  // Along the spin axis (axial acceleration) the unbalance has no moment.
  BodyState<double> axial;
  axial.specific_force = V3(500.0, 0.0, 0.0);
  GimbalPlant<double> q = started(c, s, axial);
  run(q, kTicksPerSecond / 2, V2::Zero().eval(), axial, [](int, const GimbalPlant<double>&) {});
  EXPECT_EQ(q.gimbal_rate_rad_s(), V2::Zero());
}

// ---- conventions ------------------------------------------------------------------------------

TEST(GimbalConventions, GivenAnyJointAnglesThenTheyAreTheProjectsGimbalAnglesOfTheSpinAxis) {
  for (const V2& a : {V2(0.3, -0.2), V2(-0.4, 0.1), V2(0.05, 0.5), V2(-0.5, -0.1)}) {
    GimbalStart<double> s;
    s.gimbal_angle_rad = a;
    s.spin_hz = 400.0;
    Config c = seeker_gimbal_config<double>();
    c.stop_cone_rad = 1.0;
    const GimbalPlant<double> p = started(c, s);
    // docs/conventions.md: pitch = atan2(-gp_z, hypot(gp_x, gp_y)), yaw = atan2(gp_y, gp_x).
    const GimbalAngles<double> g = gimbal_angles(Matrix3<double>::Identity().eval(), p.spin_axis_body());
    EXPECT_NEAR(g.pitch_rad, a(0), 1e-15);
    EXPECT_NEAR(g.yaw_rad, a(1), 1e-15);
    EXPECT_NEAR(std::acos(g.cosine_of_cone), p.cone_rad(), 1e-12);
    // At rest with no gimbal motion the rotor's momentum is H along the spin axis.
    const V3 h = p.rotor_angular_momentum_body();
    EXPECT_LT((h - c.spin_inertia * 2.0 * kPiD * 400.0 * p.spin_axis_body()).norm(), 1e-15);
    EXPECT_LT((p.angular_momentum_body() - h).norm(), 1e-15);
  }
}

// ---- the lean right-hand side ---------------------------------------------------------------------

TEST(GimbalSinCosNear, GivenIncrementsUpToItsReachThenTheLibrarysValuesToTwoUlp) {
  int fallbacks = 0;
  for (const double a0 : {0.0, 0.3, -0.7, 1.2, 1.5707963267948966}) {
    const SinCosNear<double> near = SinCosNear<double>::at(a0);
    for (double d = -0.05; d <= 0.05; d += 1.0 / 1024.0) {
      double s = 0.0, c = 0.0;
      near.of(a0 + d, s, c);
      EXPECT_NEAR(s, std::sin(a0 + d), 4.5e-16) << a0 << " + " << d;
      EXPECT_NEAR(c, std::cos(a0 + d), 4.5e-16) << a0 << " + " << d;
      if (std::abs(d) > SinCosNear<double>::kNear) {  // beyond its reach: the library's own
        EXPECT_EQ(s, std::sin(a0 + d));
        ++fallbacks;
      }
    }
  }
  EXPECT_GT(fallbacks, 0);
}

TEST(GimbalWorkBookkeeping, GivenItOffThenTheSameMotionAndNoWork) {
  Config c = seeker_gimbal_config<double>();
  c.mass_unbalance = 1e-5;
  BodyState<double> body;
  body.rate_rad_s = V3(5.0, 0.2, -0.1);
  body.specific_force = V3(0.0, 3.0, -9.8);
  GimbalPlant<double> with = started(c, large_nutation<double>(), body);
  GimbalPlant<double> without = with;
  without.set_work_bookkeeping(false);
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(with.step(V2(2e-3, -1e-3), body, body), Status::kOk);
    ASSERT_EQ(without.step(V2(2e-3, -1e-3), body, body), Status::kOk);
  }
  EXPECT_EQ(with.gimbal_angle_rad(), without.gimbal_angle_rad());  // the powers never feed back
  EXPECT_EQ(with.spin_rate_rad_s(), without.spin_rate_rad_s());
  EXPECT_NE(with.work().torquer, 0.0);
  EXPECT_NE(with.work().unbalance, 0.0);
  EXPECT_EQ(without.work().torquer, 0.0);
  EXPECT_EQ(without.motor_torque(), 0.0);
}

// ---- the sub-step choice ------------------------------------------------------------------------

TEST(GimbalSubstepControl, GivenAFailedTryThenMoreAsTheEighthOrderAsksUpToTheBound) {
  // Error 2^8 times the tolerance at 2 sub-steps: 4 meet it, 5 meet half of it (the safety).
  EXPECT_EQ(substeps_after_failure(2, 256.0, 1.0, 9), 5);
  EXPECT_EQ(substeps_after_failure(2, 1.0000001, 1.0, 9), 3);    // at least one more
  EXPECT_EQ(substeps_after_failure(2, 1e12, 1.0, 9), 9);         // never beyond the bound
  EXPECT_EQ(substeps_after_failure(2, kNaN, 1.0, 9), 9);         // a non-finite estimate: the bound
  EXPECT_EQ(substeps_after_failure(2, kInf, 1.0, 9), 9);
}

TEST(GimbalSubstepControl, GivenAPassedTryThenFewerOnlyWhenHalfTheToleranceIsMet) {
  EXPECT_EQ(substeps_after_success(4, 0.0, 1.0), 1);            // nothing to resolve
  EXPECT_EQ(substeps_after_success(4, 0.5 / 256.0, 1.0), 2);    // 2 meet half the tolerance
  EXPECT_EQ(substeps_after_success(4, 0.9, 1.0), 4);            // never more than the try
  EXPECT_EQ(substeps_after_success(1, 1e-30, 1.0), 1);
}

TEST(GimbalSubstepControl, GivenATargetThenTicksTakeFewerSubStepsThanTheBoundAndRepeat) {
  Config c = seeker_gimbal_config<double>();
  c.error_target_rad = 5e-6;
  BodyState<double> body;
  body.rate_rad_s = V3(5.0, 0.2, -0.1);
  GimbalPlant<double> a = started(c, GimbalStart<double>{V2::Zero(), V2(0.05, 0.05), 400.0}, body, 1e-3);
  GimbalPlant<double> b = a;
  int fewer = 0;
  for (int k = 0; k < 300; ++k) {
    const V2 torque = (k / 50) % 2 == 0 ? V2(2e-3, -1e-3) : V2(-2e-3, 1e-3);
    ASSERT_EQ(a.step(torque, body, body), Status::kOk);
    ASSERT_EQ(b.step(torque, body, body), Status::kOk);
    EXPECT_GE(a.last_substeps(), 1);
    EXPECT_LE(a.last_substeps(), a.substeps());
    fewer += static_cast<int>(a.last_substeps() < a.substeps());
  }
  EXPECT_GT(fewer, 250);
  EXPECT_TRUE(bit_equal(observe(a), observe(b)));  // the choice is deterministic
}

// ---- float ----------------------------------------------------------------------------------------

TEST(GimbalFloat, GivenTheSeekerInFloatThenItTracksTheDoubleRunOverOneSecond) {
  auto make = [](auto scalar) {
    using T = decltype(scalar);
    GimbalPlantConfig<T> c = seeker_gimbal_config<T>();
    c.inner_coulomb_torque = T(1e-4);
    c.outer_coulomb_torque = T(1e-4);
    c.mass_unbalance = T(1e-5);
    GimbalStart<T> s;
    s.gimbal_angle_rad = Vector2<T>(T(0.2), T(-0.1));
    s.gimbal_rate_rad_s = Vector2<T>(T(0.5), T(0.3));
    s.spin_hz = T(400);
    return started(c, s);
  };
  GimbalPlant<float> pf = make(0.0f);
  GimbalPlant<double> pd = make(0.0);
  double worst = 0.0;
  for (int k = 0; k < kTicksPerSecond; ++k) {
    const double sign = (k / 500) % 2 == 0 ? 1.0 : -1.0;
    BodyState<double> bd;
    bd.rate_rad_s = V3(5.0, 0.2 * sign, -0.1);
    bd.specific_force = V3(20.0, 0.0, -9.8);
    BodyState<float> bf;
    bf.rate_rad_s = bd.rate_rad_s.cast<float>();
    bf.specific_force = bd.specific_force.cast<float>();
    const V2 torque(0.01 * sign, -0.005);
    ASSERT_EQ(pd.step(torque, bd, bd), Status::kOk);
    ASSERT_EQ(pf.step(torque.cast<float>(), bf, bf), Status::kOk);
    worst = std::max(worst, (pf.gimbal_angle_rad().cast<double>() - pd.gimbal_angle_rad()).cwiseAbs().maxCoeff());
  }
  std::printf("figure: float against double over 1 s: worst gimbal-angle difference %.2e rad\n", worst);
  EXPECT_LT(worst, 1e-4);
  EXPECT_NEAR(static_cast<double>(pf.spin_rate_rad_s()), pd.spin_rate_rad_s(), 1e-3 * pd.spin_rate_rad_s());
}

}  // namespace
}  // namespace gyro
