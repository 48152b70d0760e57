// Paths of the tick that ordinary flights rarely take, each pinned by what it must do
// (docs/mutation.md names the mutants each test kills): the body's rate changing within a
// tick, stale readings and an invalid spin readback, a reading and its prediction on opposite
// sides of zero near a gimbal stop, leaving safe mode after ticks that could not be measured,
// uncaging again, the torque law once navigation is lost, and the torque shaper at its
// longest spacing and on leaving safe mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::Bench;
using testing::SeekerGyro;

const GyroComponentConfig<double> kSeekerDefaults = SeekerGyro<double>::component();

// The component on the SIL stub's gimbal plant, the body given as rates at each tick (the
// plant takes them linear in between) and the attitude that such a motion reaches.
struct PlantBench {
  SimulatedGyro<double> gyro;
  GyroComponent<double> component{gyro};
  GuidanceInput<double> guidance;
  BodySample<double> body;
  std::uint64_t tick{0};
  bool ok{false};

  explicit PlantBench(const GyroComponentConfig<double>& c, const SimulatedGyroConfig<double>& s) {
    guidance.nav_valid = true;
    ok = gyro.configure(s).ok() && gyro.start(body) == Status::kOk && component.configure(c).ok() &&
         component.activate() == Status::kOk;
  }
  // One tick over which the body's pitch rate goes linearly from its last value to q_end.
  Status step(double q_end, ModeRequest request = ModeRequest::kNone) {
    const double dt = component.config().tick_s;
    const double q_start = body.rate_rad_s(1);
    body.R_earth_to_body = frame_rotation_y(0.5 * (q_start + q_end) * dt) * body.R_earth_to_body;
    body.rate_rad_s(1) = q_end;
    ++tick;
    const Status st = gyro.advance(tick, body);
    if (st != Status::kOk) return st;
    guidance.request = request;
    guidance.R_earth_to_body = body.R_earth_to_body;
    guidance.body_rate_rad_s = body.rate_rad_s;
    return component.step(tick, guidance);
  }
  [[nodiscard]] const GyroTelemetry<double>& tm() const { return component.telemetry(); }
};

// ---- the body's rate within a tick -----------------------------------------------------------

// The bearings drag the rotor with the body: a torque f (body rate - gyro rate) on the gimbal
// axes, which the torque law compensates a tick late. Over a tick in which the body's pitch
// rate ramps from 0 to q, the drag's impulse is f q dt / 2. An estimator that held the end
// rate over the tick would take f q dt: the extra impulse f q dt / 2 moves the spin axis by
// f q dt / (2 H) and sets it nutating with that radius (up to f q dt / H off). One that holds
// the tick's mean rate has the impulse right and errs only by the ramp's second moment, about
// f q dt^2 / (12 J) in angle. The truth is the plant, which integrates the linear rate
// finely. At a 10 kHz tick (beta dt = 0.38 rad) the two differ by a factor of 16:
// 5.3e-6 rad against 3.3e-7 rad.
TEST(ComponentBodyRate, GivenTheBodysRateRampingWithinATickThenThePredictionFollowsTheMeanRateOverIt) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.tick_s = 1e-4;
  c.uncage_settle_ticks = 1;
  SimulatedGyroConfig<double> s = SeekerGyro<double>::stub();
  s.tick_s = c.tick_s;
  PlantBench b(c, s);
  ASSERT_TRUE(b.ok);
  for (int k = 0; k < 200; ++k) ASSERT_EQ(b.step(0.0), Status::kOk);
  ASSERT_EQ(b.step(0.0, ModeRequest::kUncage), Status::kOk);
  for (int k = 0; k < 300; ++k) ASSERT_EQ(b.step(0.0), Status::kOk);
  ASSERT_EQ(b.component.mode(), GyroMode::kFree);
  ASSERT_LT(b.tm().residual_rad.cwiseAbs().maxCoeff(), 1e-9) << "at rest the prediction is the plant";

  const double q = 20.0;  // 0 to 20 rad/s within one tick, then held
  const double h = angular_momentum(c.nominal_spin_hz, c.spin_inertia);
  const double end_rate_error = c.friction * q * c.tick_s / (2 * h);
  double worst = 0;
  for (int k = 0; k < 30; ++k) {  // a nutation period and a half
    ASSERT_EQ(b.step(q), Status::kOk);
    ASSERT_EQ(b.tm().flags & (kPickoffJump | kPickoffInvalid | kResidualFault), 0u);
    worst = std::max(worst, b.tm().residual_rad.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(b.tm().gimbal_measured_rad.cwiseAbs().maxCoeff(), 0.05) << "the body turned under the gyro";
  EXPECT_LT(worst, 0.2 * end_rate_error) << "an end-rate estimator errs by " << end_rate_error << " rad";
}

// ---- readings without information ----------------------------------------------------------

// A stale reading (the same conversion again) tells as little as an invalid one: the jump
// bound widens by one tick's step for each, so that the next fresh reading may have moved
// that much further.
TEST(ComponentPickoffs, GivenStaleReadingsThenTheJumpBoundWidensByTheTicksWithoutInformation) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(3);
  const double bound = kSeekerDefaults.max_pickoff_step_rad;
  b.port.hold_sequence = true;
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(b.step(), Status::kOk);
    ASSERT_TRUE(b.raised(kPickoffStale));
  }
  b.port.hold_sequence = false;  // four ticks since the last reading taken: four bounds
  b.port.reading.gimbal_angle_rad = Vector2<double>(0.0, -3.5 * bound);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().flags & (kPickoffJump | kPickoffStale | kPickoffInvalid), 0u);
  EXPECT_EQ(b.tm().gimbal_measured_rad(1), -3.5 * bound);
}

// A spin readback the port marks invalid is no spin, however plausible its value: the
// nominal spin is used and nothing is flagged low.
TEST(ComponentSpin, GivenAReadbackMarkedInvalidThenTheNominalSpinIsUsed) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_valid = false;
  for (const double spin : {350.0, 100.0}) {
    b.port.reading.spin_hz = spin;
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_EQ(b.tm().spin_hz, kSeekerDefaults.nominal_spin_hz) << spin;
    EXPECT_FALSE(b.raised(kSpinLow)) << spin;
  }
  b.port.reading.spin_valid = true;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().spin_hz, 100.0) << "marked valid again: used";
  EXPECT_TRUE(b.raised(kSpinLow));
}

// ---- navigation lost -----------------------------------------------------------------------

// Navigation that stops vouching for the body (marked invalid) leaves its rates unknown: the
// torque law's bearing term, friction times the body's rate on the gimbal axes, drops out
// instead of holding the last believed rate. Caged at a zero reading the command is then
// exactly that of a body at rest once the shaper has let the earlier commands out.
TEST(ComponentNavigation, GivenNavigationLostWhileTheBodyTurnsThenTheTorqueLawTakesTheBodyRateAsUnknown) {
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

// ---- leaving safe mode --------------------------------------------------------------------------

// The residual monitor is fed only on measured ticks, and in safe mode a measured tick resets
// it. Safe mode entered for another fault and spent without navigation (so without a measured
// tick) keeps whatever fill the monitor had: leaving it must start the monitor afresh, or a
// residual just short of its persistence before the fault trips it at the first residual after.
TEST(ComponentModes, GivenSafeModeWithoutAMeasuredTickWhenLeftThenTheResidualFaultTakesItsFullPersistenceAgain) {
  Bench b;
  ASSERT_TRUE(b.ok);
  const std::uint32_t n = kSeekerDefaults.residual_persistence_ticks;
  const double limit = kSeekerDefaults.residual_limit_rad;
  b.run(5);
  // A reading 4e-3 rad off the prediction (within the jump bound, twice the residual limit):
  // the residual exceeds its limit on n - 1 ticks, one short of the fault.
  b.port.reading.gimbal_angle_rad = Vector2<double>(4e-3, 0.0);
  for (std::uint32_t k = 0; k + 1 < n; ++k) {
    ASSERT_EQ(b.step(), Status::kOk);
    ASSERT_GT(b.tm().residual_rad.cwiseAbs().maxCoeff(), limit) << k;
  }
  ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
  // The readings fail: safe mode on the reading monitor.
  b.port.reading.valid = false;
  b.run(static_cast<int>(kSeekerDefaults.invalid_persistence_ticks));
  ASSERT_EQ(b.component.mode(), GyroMode::kFault);
  ASSERT_EQ(b.tm().flags & kResidualFault, 0u);
  // Readings back, navigation not: no measured tick, and out of safe mode on request.
  b.port.reading.valid = true;
  b.guidance.nav_valid = false;
  b.run(2);
  ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);
  ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
  b.guidance.nav_valid = true;
  ASSERT_EQ(b.step(), Status::kOk);  // the estimator restarts at the reading
  ASSERT_EQ(b.tm().residual_rad, Vector2<double>::Zero());
  // The reading moves 3e-3 rad: a residual beyond the limit every tick from now on.
  b.port.reading.gimbal_angle_rad = Vector2<double>(7e-3, 0.0);
  for (std::uint32_t k = 1; k < n; ++k) {
    ASSERT_EQ(b.step(), Status::kOk);
    ASSERT_GT(b.tm().residual_rad.cwiseAbs().maxCoeff(), limit) << k;
    ASSERT_EQ(b.component.mode(), GyroMode::kCaged) << "residual fault after " << k << " of " << n << " ticks";
  }
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kResidualFault));
  EXPECT_EQ(b.component.mode(), GyroMode::kFault) << "after exactly its persistence";
}

// Uncaging settles for uncage_settle_ticks before the gyro is free, counted from each uncage
// request: neither an uncaging abandoned half way nor a completed one shortens the next.
TEST(ComponentModes, GivenTheGyroCagedAgainWhenUncagedOnceMoreThenItSettlesForTheFullCountAgain) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.uncage_settle_ticks = 20;
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.run(5);
  const auto settles_in_full = [&b, &c]() {
    if (b.step(ModeRequest::kUncage) != Status::kOk || b.component.mode() != GyroMode::kUncaging) return false;
    for (std::uint32_t k = 1; k < c.uncage_settle_ticks; ++k) {
      if (b.step() != Status::kOk || b.component.mode() != GyroMode::kUncaging) return false;
    }
    return b.step() == Status::kOk && b.component.mode() == GyroMode::kFree;
  };
  ASSERT_TRUE(settles_in_full());
  ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);
  b.run(5);
  EXPECT_TRUE(settles_in_full()) << "after a completed uncaging";
  ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);
  b.run(5);
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  b.run(static_cast<int>(c.uncage_settle_ticks) / 2);
  ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);  // abandoned half way
  b.run(5);
  EXPECT_TRUE(settles_in_full()) << "after an abandoned uncaging";
}

// The uncage tick restarts the estimator at the reading: its telemetry shows the estimator it
// starts (no residual, the prediction at the reading), not the caged one's last comparison.
TEST(ComponentModes, GivenAReadingOffTheCagedPredictionWhenUncagedThenTheTickReportsTheRestartedEstimator) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  const Vector2<double> reading(1e-3, -5e-4);
  b.port.reading.gimbal_angle_rad = reading;
  ASSERT_EQ(b.step(), Status::kOk);
  ASSERT_GT(b.tm().residual_rad.cwiseAbs().maxCoeff(), 4e-4) << "caged, the prediction was off the reading";
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  ASSERT_EQ(b.component.mode(), GyroMode::kUncaging);
  EXPECT_EQ(b.tm().residual_rad, Vector2<double>::Zero());
  EXPECT_NEAR(b.tm().gimbal_predicted_rad(0), reading(0), 1e-12);
  EXPECT_NEAR(b.tm().gimbal_predicted_rad(1), reading(1), 1e-12);
}

// ---- the torque shaper's reach ----------------------------------------------------------------

// The shaper spaces its taps by the fewest ticks m with m beta dt >= pi/2, up to 15 ticks;
// beyond, it is off. For J1 = J2 = J the nutation is beta = H / J exactly (the friction
// terms cancel in beta^2 = (f^2 + H^2) / J^2 - (f / J)^2), so a spin readback picks
// beta dt = pi/29 (m = 15: on, its first tap a = 1 / (2 (1 - cos(15 pi/29))) = 0.4730) or
// pi/31 (m would be 16: off, a step of the law passes at once). The step: a gimbal reading
// that appears while caged, whose loop asks a constant rate from then on.
TEST(ComponentTorqueShaper, GivenANutationNeedingFifteenTicksBetweenTapsThenShapedAndSixteenThenOff) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.min_spin_hz = 1.0;
  const double j = c.pitch_inertia;
  for (const int steps_per_half_turn : {29, 31}) {
    SCOPED_TRACE(steps_per_half_turn);
    const double beta_dt = kPi<double> / steps_per_half_turn;
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.spin_hz = beta_dt / c.tick_s * j / (2 * kPi<double> * c.spin_inertia);
    b.run(40);
    ASSERT_EQ(b.port.torque_written, Vector2<double>::Zero());
    b.port.reading.gimbal_angle_rad = Vector2<double>(2e-3, 0.0);
    ASSERT_EQ(b.step(), Status::kOk);
    const double first = b.port.torque_written(1);
    b.run(35);  // beyond two spacings of 15
    ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
    const double steady = b.port.torque_written(1);
    ASSERT_GT(std::abs(steady), 1e-4);
    if (steps_per_half_turn == 29) {
      EXPECT_NEAR(first / steady, 1 / (2 * (1 - std::cos(15 * beta_dt))), 1e-3) << "shaped, taps 15 ticks apart";
    } else {
      EXPECT_NEAR(first / steady, 1.0, 1e-3) << "not shaped";
    }
  }
}

// A tick aliasing the nutation shapes with its folded phase while m beta dt is within a turn:
// beta dt = 3.77 (the seeker at 1 kHz) excites the nutation as 2 pi - 3.77 = 2.51 does (m = 1,
// a = 1 / (2 (1 - cos 2.51))); a whole turn a tick, or a turn and 2.51, none.
TEST(ComponentTorqueShaper, GivenATickAliasingTheNutationThenShapedByTheFoldedPhaseWithinATurn) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.min_spin_hz = 1.0;
  const double j = c.pitch_inertia;
  const double seeker = 3.77;
  for (const double beta_dt : {seeker, 2 * kPi<double>, 2 * kPi<double> + (2 * kPi<double> - seeker)}) {
    SCOPED_TRACE(beta_dt);
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.spin_hz = beta_dt / c.tick_s * j / (2 * kPi<double> * c.spin_inertia);
    b.run(40);
    b.port.reading.gimbal_angle_rad = Vector2<double>(2e-3, 0.0);
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_NE(b.tm().flags & kNutationUnresolved, 0u) << "the pickoffs alias the nutation";
    const double first = b.port.torque_written(1);
    b.run(10);
    const double steady = b.port.torque_written(1);
    ASSERT_GT(std::abs(steady), 1e-4);
    const double expected = beta_dt == seeker ? 1 / (2 * (1 - std::cos(2 * kPi<double> - seeker))) : 1.0;
    EXPECT_NEAR(first / steady, expected, 1e-3);
  }
}

// The shaper's design follows the spin readback within 0.1 %: a readback 0.05 % off the one
// the design was made for keeps it (its first tap a of the old beta), one 0.5 % off redoes it.
// Two components see the same readback when a gimbal reading appears (caged, body at rest:
// the law's torque is the same for both); one had seen beta dt = pi/15 before, the other the
// readback all along. The ratio of their first torques is a(old beta) / a(new beta) when the
// design was kept and 1 when it was redone; a(beta) = 1 / (2 (1 - cos(8 beta dt))), beta = H / J.
TEST(ComponentTorqueShaper, GivenASpinReadbackWithinATenthOfAPercentOfTheDesignsThenTheDesignIsKeptAndBeyondRedone) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.min_spin_hz = 10.0;
  const double j = c.pitch_inertia;
  const double beta_dt = kPi<double> / 15;  // taps 8 ticks apart, and still 8 at 0.5 % less
  const double spin0 = beta_dt / c.tick_s * j / (2 * kPi<double> * c.spin_inertia);
  const auto first_tap = [](double b_dt) { return 1 / (2 * (1 - std::cos(8 * b_dt))); };
  for (const double change : {-5e-4, -5e-3}) {
    SCOPED_TRACE(change);
    const double spin1 = spin0 * (1 + change);
    Bench before(c), along(c);
    ASSERT_TRUE(before.ok && along.ok);
    before.port.reading.spin_hz = spin0;
    along.port.reading.spin_hz = spin1;
    before.run(40);
    along.run(40);
    before.port.reading.spin_hz = spin1;
    before.run(3);
    along.run(3);
    ASSERT_EQ(before.port.torque_written, Vector2<double>::Zero());
    for (Bench* b : {&before, &along}) {
      b->port.reading.gimbal_angle_rad = Vector2<double>(2e-3, 0.0);
      ASSERT_EQ(b->step(), Status::kOk);
    }
    const double ratio = before.port.torque_written(1) / along.port.torque_written(1);
    ASSERT_TRUE(std::isfinite(ratio)) << along.port.torque_written.transpose();
    if (std::abs(change) < 1e-3) {
      const double kept = first_tap(beta_dt) / first_tap(beta_dt * (1 + change));
      ASSERT_GT(std::abs(kept - 1), 1e-4) << "the two designs differ";
      EXPECT_NEAR(ratio, kept, 1e-9) << "kept: the first tap of the old beta";
    } else {
      EXPECT_NEAR(ratio, 1.0, 1e-12) << "redone at the readback";
    }
  }
}

// Safe mode writes zero torque at once and empties the shaper: leaving it starts from rest.
// Here the fault latches while the cage loop is pulling (an input fault: a request no
// enumerator has, every tick, with the readings still accepted), so the shaper's taps hold
// the cage loop's torques; caged again at a zero reading with the body at rest, the law asks
// for nothing, and nothing from before the fault may be blended in.
TEST(ComponentTorqueShaper, GivenSafeModeEnteredWhileTheCageLoopPullsWhenCagedAtRestThenNoTorqueOfBeforeIsWritten) {
  GyroComponentConfig<double> c = kSeekerDefaults;
  c.min_spin_hz = 10.0;
  const double beta_dt = kPi<double> / 7.5;  // taps 4 ticks apart
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = beta_dt / c.tick_s * c.pitch_inertia / (2 * kPi<double> * c.spin_inertia);
  b.run(20);
  ASSERT_EQ(b.port.torque_written, Vector2<double>::Zero());
  b.port.reading.gimbal_angle_rad = Vector2<double>(2e-3, -1e-3);
  b.run(12);  // beyond two spacings: every tap holds the cage loop's torque
  ASSERT_GT(b.port.torque_written.cwiseAbs().minCoeff(), 1e-5);
  const auto unknown_request = static_cast<ModeRequest>(7);
  for (std::uint32_t k = 0; k < c.input_persistence_ticks && b.component.mode() != GyroMode::kFault; ++k) {
    ASSERT_EQ(b.step(unknown_request), Status::kInputIgnored);
  }
  ASSERT_EQ(b.component.mode(), GyroMode::kFault);
  EXPECT_EQ(b.port.torque_written, Vector2<double>::Zero()) << "safe mode cuts at once";
  b.port.reading.gimbal_angle_rad = Vector2<double>::Zero();
  for (int k = 0; k < 200 && b.component.mode() == GyroMode::kFault; ++k) ASSERT_EQ(b.step(ModeRequest::kCage), Status::kOk);
  ASSERT_EQ(b.component.mode(), GyroMode::kCaged);
  for (int k = 0; k < 12; ++k) {
    EXPECT_EQ(b.port.torque_written, Vector2<double>::Zero()) << k << " ticks after leaving safe mode";
    ASSERT_EQ(b.step(), Status::kOk);
  }
}

}  // namespace
}  // namespace gyro
