// The component keeps flying whatever its inputs (docs/component.md, "Corrupt input"): each
// class of corrupt input alone (the tick count, the guidance commands, the navigation, the
// pickoff readings, the spin readback), then random streams of corrupt and good input
// interleaved, against the SIL stub (behind a corrupting wire or a faulty harness) and a
// scripted port, in float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/corrupting_port.hpp"
#include "support/faulty_harness.hpp"
#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_fail_operational_test {

using testing::Bench;
using testing::CorruptingPort;
using testing::counter_of;
using testing::FaultyRig;
using testing::SeekerGyro;
using testing::Sil;
using testing::telemetry_finite;
using testing::WireFault;

constexpr std::uint32_t kIgnoredInput = kCommandRejected | kTickInvalid;

// The component behind a corrupting wire to the SIL stub; the body turns slowly. `tick` is
// the true tick (the stub's); each call may hand the component another count.
// The component as the loop calls it, handed the test's tick count and input instead of the
// loop's, or not called at all (a tick lost).
template <typename T>
struct TamperedComponent {
  GyroComponent<T>& component;
  std::uint64_t count{0};
  GuidanceInput<T> input{};
  bool skip{false};

  [[nodiscard]] Status activate() noexcept { return component.activate(); }
  [[nodiscard]] Status step(std::uint64_t /*tick*/, const GuidanceInput<T>& /*in*/) noexcept {
    return skip ? Status::kOk : component.step(count, input);
  }
};

template <typename T>
struct Rig {
  SimulatedGyro<T> gyro;
  CorruptingPort<T> wire{gyro};
  GyroComponent<T> component{wire};
  TamperedComponent<T> tampered{component};
  SilLoop<T, TamperedComponent<T>> loop{gyro, tampered, StubBodyFeed::kAttitude};
  GuidanceInput<T> guidance;
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector3<T> body_rate{T(0), T(0.05), T(-0.04)};
  std::uint64_t tick{0};
  bool ever_at_stop{false};

  bool start() {
    guidance.nav_valid = true;
    if (!gyro.configure(SeekerGyro<T>::stub()).ok() || !component.configure(SeekerGyro<T>::component()).ok()) {
      return false;
    }
    const SilStatus<Status> started = loop.start(turning_body(R_earth_to_body, pitch_yaw()));
    return started.stub == Status::kOk && started.component == Status::kOk;
  }

  // The world moves one tick; the component is called with `g` (its tick count, request,
  // commands and navigation as given: the test corrupts them).
  Status step_with(std::uint64_t count, GuidanceInput<T> g) { return world_tick(count, g, false); }
  // The world moves one tick; the component is not called.
  Status lose_tick() { return world_tick(0, good_guidance(), true); }
  // A good tick: the true count and navigation.
  Status step(ModeRequest request = ModeRequest::kNone) {
    GuidanceInput<T> g = good_guidance();
    g.request = request;
    return step_with(tick + 1, g);
  }
  [[nodiscard]] GuidanceInput<T> good_guidance() const {
    GuidanceInput<T> g = guidance;
    g.nav_valid = true;
    g.R_earth_to_body = next_attitude();
    g.body_rate_rad_s = body_rate;
    return g;
  }
  [[nodiscard]] Vector2<T> pitch_yaw() const { return Vector2<T>(body_rate(1), body_rate(2)); }
  [[nodiscard]] Matrix3<T> next_attitude() const {
    return pitch_then_yaw_turn(pitch_yaw(), SeekerGyro<T>::kTick) * R_earth_to_body;
  }
  Status world_tick(std::uint64_t count, const GuidanceInput<T>& g, bool skip) {
    R_earth_to_body = next_attitude();
    ++tick;
    tampered.count = count;
    tampered.input = g;
    tampered.skip = skip;
    const SilStatus<Status> ran = loop.tick(tick, turning_body(R_earth_to_body, pitch_yaw()), GuidanceCommand<T>{});
    EXPECT_EQ(ran.stub, Status::kOk);
    ever_at_stop = ever_at_stop || gyro.at_gimbal_stop();
    return ran.stub != Status::kOk ? ran.stub : ran.component;
  }
  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) EXPECT_EQ(step(), Status::kOk) << k;
  }
  bool uncage() {
    run(100);
    (void)step(ModeRequest::kUncage);
    run(static_cast<int>(SeekerGyro<T>::component().uncage_settle_ticks));
    return component.mode() == GyroMode::kFree;
  }
  [[nodiscard]] const GyroTelemetry<T>& tm() const { return component.telemetry(); }
  [[nodiscard]] std::uint32_t count(ComponentFlag f) const {
    for (int i = 0; i < kComponentFlagCount; ++i) {
      if (f == (1u << static_cast<unsigned>(i))) return tm().counters[static_cast<std::size_t>(i)];
    }
    return 0;
  }
};

const GyroComponentConfig<double> kSeekerConfig = SeekerGyro<double>::component();

// ---- the tick count --------------------------------------------------------------------------

TEST(ComponentTicks, ACountFarAheadCostsTwoFlaggedTicks) {
  GYRO_VERIFIES("TICK-3");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.2, -0.1);
  rig.run(100);
  EXPECT_EQ(rig.step_with(rig.tick + 1'000'000'000ULL, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
  // The next correct count is behind the corrupted one: flagged once more, resynchronised.
  EXPECT_EQ(rig.step_with(rig.tick + 1, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
  for (int k = 0; k < 200; ++k) {
    ASSERT_EQ(rig.step(), Status::kOk) << k;
    EXPECT_EQ(rig.tm().flags & kIgnoredInput, 0u);
  }
  EXPECT_EQ(rig.count(kTickInvalid), 2u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.2, -0.1)) << "still slewing as commanded";
  EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), kSeekerConfig.residual_limit_rad / 10);
  // A cage request is honoured at once.
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
}

TEST(ComponentTicks, RepeatsAndStepsBackAreOneTickEach) {
  GYRO_VERIFIES("TICK-3");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.3, 0.3);
  for (int k = 0; k < 300; ++k) {
    // Every third call repeats the last count, every fifth goes back by ten.
    const std::uint64_t count = (k % 3 == 0) ? rig.tick : (k % 5 == 0) ? rig.tick - 10 : rig.tick + 1;
    (void)rig.step_with(count, rig.good_guidance());
    // The component is never refused and never predicts a tick that did not pass: the
    // residual stays at the clean run's level.
    EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), kSeekerConfig.residual_limit_rad / 10) << k;
  }
  EXPECT_NE(rig.tm().counters[15], 0u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault) << "counts this bad for this long latch a fault";
  EXPECT_NE(rig.tm().counters[17], 0u) << "and say it was the input";
  // Good counts again: the cage request of the second good tick is honoured.
  (void)rig.step();
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
}

TEST(ComponentTicks, AGapIsBridgedAndTheResidualStaysSmall) {
  GYRO_VERIFIES("TICK-2");
  // Two rigs, one ticked every tick, one missing ticks: after a gap of g ticks the component
  // predicts over g ticks, so its residual stays at the level of the rig that missed nothing.
  for (const std::uint64_t gap : {2ULL, 5ULL, 8ULL}) {
    SCOPED_TRACE(gap);
    Rig<double> rig;
    ASSERT_TRUE(rig.start());
    ASSERT_TRUE(rig.uncage());
    rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.5, -0.4);
    rig.run(50);
    for (std::uint64_t k = 1; k < gap; ++k) ASSERT_EQ(rig.lose_tick(), Status::kOk);  // the world moves
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kTickSkipped, 0u);
    EXPECT_EQ(rig.tm().flags & kTickInvalid, 0u);
    EXPECT_LT(rig.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "predicted over the whole gap";
  }
  // One tick more than max_tick_gap is not believed: one tick, flagged invalid.
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  rig.run(10);
  EXPECT_EQ(rig.step_with(rig.tick + 1 + kSeekerConfig.max_tick_gap, rig.good_guidance()), Status::kInputIgnored);
  EXPECT_NE(rig.tm().flags & kTickInvalid, 0u);
}

// Lost ticks are no bad input: each bridged gap, the longest included, is flagged and counted
// once, the tick runs with status kOk, and the tick after it is an ordinary one.
TEST(ComponentTicks, ABridgedGapIsCountedNotIgnored) {
  GYRO_VERIFIES("TICK-2");
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  ASSERT_EQ(b.step_at(b.tick + 3), Status::kOk) << "lost ticks are no bad input";
  EXPECT_TRUE(b.raised(kTickSkipped));
  EXPECT_FALSE(b.raised(kTickInvalid));
  EXPECT_EQ(b.tm().counters[counter_of(kTickSkipped)], 1u);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_FALSE(b.raised(kTickSkipped)) << "the tick after a bridged gap is an ordinary one";
  ASSERT_EQ(b.step_at(b.tick + kSeekerConfig.max_tick_gap), Status::kOk) << "the longest gap bridged";
  EXPECT_TRUE(b.raised(kTickSkipped));
  EXPECT_EQ(b.tm().counters[counter_of(kTickSkipped)], 2u);
  EXPECT_EQ(b.tm().counters[counter_of(kTickInvalid)], 0u);
}

// The tick tracker's elapsed ticks reach the pickoff gate: a slew of 1 rad/s moves the gimbal
// 5e-4 rad a tick, so over a gap of four ticks the reading moves beyond one tick's bound of
// 1.75e-3 rad and within four ticks'.
TEST(ComponentTicks, AReadingAfterAGapGetsTheGapsJumpBound) {
  GYRO_VERIFIES("TICK-2", "PICK-3");
  GyroComponentConfig<double> c = kSeekerConfig;
  c.max_pickoff_step_rad = 1.75e-3;  // the contract's least: 2 (a tick at 1 rad/s + a full-torque nutation)
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c));
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(1.0, 0.0);
  sil.run(40);
  ASSERT_EQ(sil.tm().flags & (kPickoffJump | kPickoffInvalid | kPickoffStale), 0u);
  const Vector2<double> before = sil.tm().gimbal_measured_rad;
  ASSERT_EQ(sil.lose_ticks(3), Status::kOk);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_NE(sil.tm().flags & kTickSkipped, 0u);
  const double moved = (sil.tm().gimbal_measured_rad - before).cwiseAbs().maxCoeff();
  EXPECT_EQ(sil.tm().flags & kPickoffJump, 0u) << "a move of " << moved << " rad over 4 ticks";
  EXPECT_GT(moved, c.max_pickoff_step_rad) << "the reading after the gap was accepted";
  EXPECT_LT(moved, 4 * c.max_pickoff_step_rad);
}

// ---- guidance commands ------------------------------------------------------------------------

TEST(ComponentGuidance, ANonFiniteSlewHoldsTheLastOne) {
  GYRO_VERIFIES("INPUT-1");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.1, 0.05);
  rig.run(20);
  GuidanceInput<double> bad = rig.good_guidance();
  bad.slew_rate_cmd_rad_s(1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(rig.step_with(rig.tick + 1, bad), Status::kInputIgnored);
  EXPECT_EQ(rig.tm().flags & kIgnoredInput, static_cast<std::uint32_t>(kCommandRejected));
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.1, 0.05)) << "the last usable command, held";
  EXPECT_TRUE(telemetry_finite(rig.tm()));
  bad.request = static_cast<ModeRequest>(7);
  bad.slew_rate_cmd_rad_s = Vector2<double>(0.2, 0.0);
  EXPECT_EQ(rig.step_with(rig.tick + 1, bad), Status::kInputIgnored) << "an unknown request is dropped";
  EXPECT_EQ(rig.tm().rate_cmd_rad_s, Vector2<double>(0.2, 0.0)) << "the rest of the input is used";
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
  EXPECT_EQ(rig.tm().counters[11], 2u);
}

// Run A is sent a NaN slew command and an unknown request in the middle; run B is sent the
// last usable command instead. Apart from the flags and counters of what A ignored,
// everything is bit-identical.
TEST(ComponentGuidance, AnIgnoredFieldLeavesNoOtherTrace) {
  GYRO_VERIFIES("INPUT-1", "LIFE-5");
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

// ---- navigation -------------------------------------------------------------------------------

TEST(ComponentNavigation, AnOutageIsFlownNotRefused) {
  GYRO_VERIFIES("INPUT-3");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  // A long outage, the body turning on: the caller says invalid and sends NaN rates.
  for (int k = 0; k < 4000; ++k) {
    GuidanceInput<double> g = rig.good_guidance();
    g.nav_valid = false;
    g.body_rate_rad_s.setConstant(std::numeric_limits<double>::quiet_NaN());
    g.R_earth_to_body.setConstant(std::numeric_limits<double>::quiet_NaN());
    ASSERT_EQ(rig.step_with(rig.tick + 1, g), Status::kOk) << "nothing the caller marked invalid is an error";
    ASSERT_NE(rig.tm().flags & kNavInvalid, 0u);
    ASSERT_TRUE(telemetry_finite(rig.tm()));
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree) << "an outage is no gyro fault";
  EXPECT_FALSE(rig.ever_at_stop);
  // Caged during the outage: the gimbal loop alone closes the angles.
  for (int k = 0; k < 400; ++k) {
    GuidanceInput<double> g = rig.good_guidance();
    g.nav_valid = false;
    g.request = k == 0 ? ModeRequest::kCage : ModeRequest::kNone;
    ASSERT_EQ(rig.step_with(rig.tick + 1, g), Status::kOk);
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_LT(rig.tm().gimbal_measured_rad.cwiseAbs().maxCoeff(), 0.01);
  EXPECT_FALSE(rig.ever_at_stop);
}

TEST(ComponentNavigation, UnusableNavigationIsIgnored) {
  GYRO_VERIFIES("INPUT-4");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  const auto expect_ignored = [&](const GuidanceInput<double>& g, const char* what) {
    EXPECT_EQ(rig.step_with(rig.tick + 1, g), Status::kInputIgnored) << what;
    EXPECT_EQ(rig.tm().flags & (kNavInvalid | kCommandRejected), kNavInvalid | kCommandRejected) << what;
    EXPECT_TRUE(telemetry_finite(rig.tm())) << what;
  };
  GuidanceInput<double> g = rig.good_guidance();
  g.body_rate_rad_s(0) = std::numeric_limits<double>::infinity();
  expect_ignored(g, "non-finite rate");
  g = rig.good_guidance();
  g.body_rate_rad_s(2) = 1e160;
  expect_ignored(g, "a rate beyond max_body_rate_rad_s");
  g = rig.good_guidance();
  g.R_earth_to_body(0, 0) = 2.0;
  expect_ignored(g, "not a rotation");
  rig.run(10);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
}

// Navigation that stops vouching for the body (marked invalid) leaves its rates unknown: the
// torque law's bearing term, friction times the body's rate on the gimbal axes, drops out
// instead of holding the last believed rate. Caged at a zero reading the command is then
// exactly that of a body at rest once the shaper has let the earlier commands out.
TEST(ComponentNavigation, TorqueLawTakesTheBodyRateAsUnknown) {
  GYRO_VERIFIES("INPUT-3", "EST-7");
  Bench turning;
  Bench still;
  ASSERT_TRUE(turning.ok && still.ok);
  turning.guidance.body_rate_rad_s = Vector3<double>(0.0, 0.5, -0.3);  // (roll, pitch, yaw)
  turning.run(10);
  still.run(10);
  EXPECT_GT(turning.tm().torque_cmd.cwiseAbs().maxCoeff(), 1e-3) << "caged, the loop follows the turning body";
  turning.guidance.nav_valid = false;
  still.guidance.nav_valid = false;
  for (int k = 0; k < 40; ++k) {
    (void)turning.step();
    (void)still.step();
  }
  EXPECT_TRUE(turning.raised(kNavInvalid));
  EXPECT_TRUE(turning.tm().torque_cmd == still.tm().torque_cmd)
      << turning.tm().torque_cmd.transpose() << " against " << still.tm().torque_cmd.transpose();
  EXPECT_TRUE(turning.port.torque_written == Vector2<double>::Zero()) << turning.port.torque_written.transpose();
}

// ---- the pickoffs -------------------------------------------------------------------------------

TEST(ComponentPickoffs, NineteenInvalidInTwentyLatchAFault) {
  GYRO_VERIFIES("PICK-6");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  int k = 0;
  for (; k < 400 && rig.component.mode() != GyroMode::kFault; ++k) {
    rig.wire.fault = (k % 20 == 19) ? WireFault::kNone : WireFault::kNotValid;
    (void)rig.step();
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_LE(k, static_cast<int>(kSeekerConfig.invalid_persistence_ticks) + 2);
}

TEST(ComponentPickoffs, ABiasJumpLatchesAndCagingRecovers) {
  GYRO_VERIFIES("PICK-3", "PICK-6", "MODE-5");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.wire.fault = WireFault::kJump;  // from now on every reading is 0.1 rad off
  int k = 0;
  for (; k < 100 && rig.component.mode() != GyroMode::kFault; ++k) (void)rig.step();
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_EQ(k, static_cast<int>(kSeekerConfig.invalid_persistence_ticks)) << "each reading rejected as a jump";
  // In safe mode the shifted readings are the reference: caging is possible.
  (void)rig.step();
  ASSERT_EQ(rig.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  rig.run(50);
  EXPECT_EQ(rig.tm().flags & kPickoffJump, 0u);
}

TEST(ComponentPickoffs, TheFirstReadingAfterStaleOnesIsTaken) {
  GYRO_VERIFIES("PICK-2");
  Rig<double> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  rig.guidance.slew_rate_cmd_rad_s = Vector2<double>(1.0, 0.0);  // 5e-4 rad per tick
  rig.run(20);
  // Stale for 8 ticks (below the fault's persistence): the gimbal moves 4e-3 rad, and the jump
  // bound grows with the blind ticks.
  rig.wire.fault = WireFault::kStale;
  for (int k = 0; k < 8; ++k) (void)rig.step();
  rig.wire.fault = WireFault::kNone;
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.tm().flags & (kPickoffJump | kPickoffStale | kPickoffInvalid), 0u);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
}

// A reading beyond the pickoffs' physical range (valid bit set, sequence advancing) is not
// believed: flagged invalid, not accepted, and a fault once it persists.
TEST(ComponentPickoffs, OutOfRangeIsInvalidThenAFault) {
  GYRO_VERIFIES("PICK-1", "PICK-6");
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 20; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<double> accepted = rig.tm().gimbal_measured_rad;
  rig.harness.angle_override = true;
  rig.harness.angle_rad = Vector2<double>(0.0, -(kSeekerConfig.pickoff_range_rad + 0.01));
  for (std::uint32_t n = 1; n < kSeekerConfig.invalid_persistence_ticks; ++n) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kPickoffInvalid, 0U) << n;
    EXPECT_EQ(rig.tm().gimbal_measured_rad, accepted) << "the last accepted reading stands";
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_EQ(rig.tm().counters[3], kSeekerConfig.invalid_persistence_ticks);  // kPickoffInvalid
}

// ---- the spin readback --------------------------------------------------------------------------

// A stopped rotor is a reading, not a failed readback: flown, low, and nothing turns NaN.
TEST(ComponentSpin, AStoppedRotorIsFlownAndLow) {
  GYRO_VERIFIES("SPIN-1", "SPIN-2");
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = 0.0;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().spin_hz, 0.0) << "a stopped rotor is a reading, not a failed readback";
  EXPECT_TRUE(b.raised(kSpinLow));
  EXPECT_TRUE(telemetry_finite(b.tm()));
}

TEST(ComponentSpin, AFailedReadOrHugeSpinFliesTheNominal) {
  GYRO_VERIFIES("SPIN-1", "PORT-1");
  {
    Bench b;
    ASSERT_TRUE(b.ok);
    b.port.read_status = PortStatus::kTimeout;
    b.port.fill_on_failure = true;  // the driver wrote a spin it did not read
    b.port.reading.spin_hz = 350.0;
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_TRUE(b.raised(kPickoffInvalid));
    EXPECT_EQ(b.tm().spin_hz, kSeekerConfig.nominal_spin_hz);
  }
  {
    // J0 = 1: the largest double as a spin has a momentum of 2 pi times it, beyond any double.
    GyroComponentConfig<double> c = kSeekerConfig;  // the seeker scaled to J0 = 1 (as the contract has it)
    c.spin_inertia = 1.0;
    c.pitch_inertia = 1.0;
    c.yaw_inertia = 1.0;
    c.friction = 20.0;
    c.max_torque = 2000.0;
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.spin_hz = std::numeric_limits<double>::max();
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_EQ(b.tm().spin_hz, c.nominal_spin_hz);
    EXPECT_TRUE(telemetry_finite(b.tm()));
  }
}

TEST(ComponentSpin, ANonFiniteOrNegativeSpinFliesTheNominal) {
  GYRO_VERIFIES("SPIN-1");
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.0}) {
    FaultyRig<double> rig;
    ASSERT_TRUE(rig.start());
    rig.harness.spin_override = true;
    rig.harness.spin_hz = bad;
    for (int k = 0; k < 5; ++k) ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_EQ(rig.tm().spin_hz, kSeekerConfig.nominal_spin_hz) << bad;
    EXPECT_TRUE(telemetry_finite(rig.tm())) << bad;
  }
}

// ---- random streams of corrupt and good input -----------------------------------------------

// Spoils one thing of a tick, of a random class: the tick count, a command, the navigation or
// the wire. Applied once or several times to the same tick, the classes mix.
template <typename T>
void corrupt(Rig<T>& rig, std::mt19937_64& rng, std::uint64_t& count, GuidanceInput<T>& g) {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const auto index = [&rng](int n) { return static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(n)); };
  switch (rng() % 10) {
    case 0: count = rng(); break;
    case 1: count = rig.tick - (rng() % 50); break;
    case 2: g.slew_rate_cmd_rad_s(index(2)) = nan; break;
    case 3: g.request = static_cast<ModeRequest>(3 + rng() % 200); break;
    case 4:
      g.nav_valid = false;
      g.body_rate_rad_s.setConstant(nan);
      break;
    case 5: g.body_rate_rad_s(index(3)) = std::numeric_limits<T>::infinity(); break;
    case 6: g.R_earth_to_body(index(3), index(3)) += T(0.5); break;
    default: rig.wire.fault = static_cast<WireFault>(1 + rng() % (testing::kWireFaultCount - 1)); break;
  }
}

template <typename T>
void run_random_streams(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Rig<T> rig;
  ASSERT_TRUE(rig.start());
  ASSERT_TRUE(rig.uncage());
  const T max_torque = SeekerGyro<T>::component().max_torque;
  int worst_back_in_control = 0;
  int worst_cage = 0;
  for (int burst = 0; burst < 12; ++burst) {
    // Good flying, a modest slew (the body turns slowly: only corrupt input could reach the stop).
    const T slew = T(0.2) * (static_cast<T>(rng() % 200) / T(100) - T(1));
    rig.guidance.slew_rate_cmd_rad_s = Vector2<T>(slew, -slew / T(2));
    for (int k = 0; k < 100; ++k) (void)rig.step();
    // A stretch of corrupt input: each tick corrupt with probability 1/2 (alone or mixed).
    const int length = 5 + static_cast<int>(rng() % 150);
    for (int k = 0; k < length; ++k) {
      std::uint64_t count = rig.tick + 1;
      GuidanceInput<T> g = rig.good_guidance();
      rig.wire.fault = WireFault::kNone;
      if (rng() % 2 == 0) {
        const int classes = 1 + static_cast<int>(rng() % 3);
        for (int c = 0; c < classes; ++c) corrupt(rig, rng, count, g);
      }
      if (rng() % 40 == 0) g.request = ModeRequest::kCage;
      (void)rig.step_with(count, g);
      const GyroTelemetry<T>& t = rig.tm();
      ASSERT_TRUE(telemetry_finite(t)) << "burst " << burst << " tick " << k;
      ASSERT_LE(t.torque_cmd.cwiseAbs().maxCoeff(), max_torque);
      ASSERT_FALSE(rig.ever_at_stop) << "burst " << burst << " tick " << k;
    }
    rig.wire.fault = WireFault::kNone;
    // Good input resumes, with a cage request every tick: how many ticks until a clean tick
    // (status kOk, nothing ignored), and until the cage request is honoured?
    int clean = 0, caged = 0;
    for (int k = 1; k <= 100 && (clean == 0 || caged == 0); ++k) {
      const Status st = rig.step(ModeRequest::kCage);
      if (clean == 0 && st == Status::kOk) clean = k;
      if (caged == 0 && rig.component.mode() == GyroMode::kCaged) caged = k;
    }
    worst_back_in_control = std::max(worst_back_in_control, clean);
    worst_cage = std::max(worst_cage, caged);
    ASSERT_EQ(rig.component.mode(), GyroMode::kCaged) << "burst " << burst;
    ASSERT_GT(clean, 0) << "burst " << burst;
    // And back to free flight.
    rig.run(100);
    (void)rig.step(ModeRequest::kUncage);
    rig.run(static_cast<int>(SeekerGyro<T>::component().uncage_settle_ticks));
    ASSERT_EQ(rig.component.mode(), GyroMode::kFree) << "burst " << burst;
  }
  std::printf("seed %llu: clean tick within %d ticks of good input, cage within %d\n",
              static_cast<unsigned long long>(seed), worst_back_in_control, worst_cage);
  EXPECT_LE(worst_back_in_control, 2) << "the first good tick may still follow an untrusted count";
  EXPECT_LE(worst_cage, 2) << "the first good tick may still see the last bad tick's failed write";
  EXPECT_FALSE(rig.ever_at_stop);
}

TEST(ComponentFailOperationalProperty, RecoversInDouble) {
  GYRO_VERIFIES("INPUT-6", "LIFE-5", "TLM-4");
  for (std::uint64_t seed = 1; seed <= 10; ++seed) run_random_streams<double>(seed);
}
TEST(ComponentFailOperationalProperty, RecoversInFloat) {
  GYRO_VERIFIES("INPUT-6", "LIFE-5", "TLM-4", "RULE-8");
  for (std::uint64_t seed = 101; seed <= 110; ++seed) run_random_streams<float>(seed);
}

}  // namespace component_fail_operational_test
}  // namespace gyro
