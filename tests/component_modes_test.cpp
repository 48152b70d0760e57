// GyroComponent's lifecycle and modes (docs/component.md, "Lifecycle" and "Modes"), against the
// SIL stub and a scripted port: configure, activate, the transitions of the mode table, the
// requests refused, and what leaving safe mode restarts.
#include <gtest/gtest.h>

#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/corrupting_port.hpp"
#include "support/requirements.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_modes_test {

using testing::Bench;
using testing::CorruptingPort;
using testing::SeekerGyro;
using testing::Sil;
using testing::WireFault;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// ---- lifecycle ------------------------------------------------------------------------------

TEST(ComponentLifecycle, ActivatesOnceAfterConfigureOnly) {
  GYRO_VERIFIES("LIFE-2", "LIFE-3");
  Sil<double> sil;
  ASSERT_TRUE(sil.gyro.configure(SeekerGyro<double>::stub()).ok());
  ASSERT_EQ(sil.gyro.start(sil.R_earth_to_body, sil.body_rate), Status::kOk);
  EXPECT_EQ(sil.component.activate(), Status::kNotConfigured);
  EXPECT_EQ(sil.component.step(1, sil.guidance), Status::kNotConfigured);
  ASSERT_TRUE(sil.component.configure(kSeeker).ok());
  EXPECT_EQ(sil.component.mode(), GyroMode::kIdle);
  ASSERT_EQ(sil.component.activate(), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(sil.component.activate(), Status::kWrongMode);
  const ConfigCheck again = sil.component.configure(kSeeker);
  EXPECT_EQ(again.status, Status::kWrongMode);
}

// A step before activation reads and writes nothing: refused, flagged kNotActive and counted.
TEST(ComponentLifecycle, StepBeforeActivationIsRefusedAndCounted) {
  GYRO_VERIFIES("LIFE-4");
  SimulatedGyro<double> gyro;
  CorruptingPort<double> wire{gyro};
  GyroComponent<double> c{wire};
  GuidanceInput<double> g;
  EXPECT_EQ(c.step(1, g), Status::kNotConfigured);
  ASSERT_TRUE(c.configure(kSeeker).ok());
  EXPECT_EQ(c.step(2, g), Status::kNotConfigured);
  EXPECT_EQ(c.telemetry().flags, static_cast<std::uint32_t>(kNotActive));
  EXPECT_EQ(c.telemetry().counters[16], 2u) << "both refusals are counted";
  EXPECT_EQ(c.mode(), GyroMode::kIdle);
  EXPECT_EQ(wire.writes, 0);
}

// ---- caged, uncaging, free --------------------------------------------------------------------

TEST(ComponentModes, CagedGimbalsFollowTheTurningBody) {
  GYRO_VERIFIES("TORQ-1");
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

TEST(ComponentModes, UncagingFreesTheGyroAfterTheSettleTicks) {
  GYRO_VERIFIES("MODE-2");
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  sil.run(100);
  ASSERT_EQ(sil.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  EXPECT_EQ(sil.tm().torque_cmd, Vector2<double>::Zero());
  sil.run(static_cast<int>(kSeeker.uncage_settle_ticks) - 1);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  sil.run(1);
  EXPECT_EQ(sil.component.mode(), GyroMode::kFree);
  ASSERT_EQ(sil.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
}

// A cage request while uncaging cages in the same tick; the abandoned uncaging's settle count
// does not carry on into free mode.
TEST(ComponentModes, ACageRequestEndsUncagingAtOnce) {
  GYRO_VERIFIES("MODE-3");
  Sil<double> sil;
  sil.body_rate = Vector2<double>(0.4, -0.3);
  ASSERT_TRUE(sil.start());
  sil.run(200);
  ASSERT_EQ(sil.step(ModeRequest::kUncage), Status::kOk);
  ASSERT_EQ(sil.component.mode(), GyroMode::kUncaging);
  sil.run(10);
  EXPECT_EQ(sil.tm().torque_cmd, Vector2<double>::Zero()) << "torquers off while uncaging";
  ASSERT_EQ(sil.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(sil.tm().mode, GyroMode::kCaged);
  // Caged in the same tick: the caging law drives the torquers to follow the turning body.
  EXPECT_GT(sil.tm().torque_cmd.cwiseAbs().maxCoeff(), 0.0);
  sil.run(static_cast<int>(kSeeker.uncage_settle_ticks) + 10);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
}

// Uncaging settles for uncage_settle_ticks before the gyro is free, counted from each uncage
// request: neither an uncaging abandoned half way nor a completed one shortens the next.
TEST(ComponentModes, EachUncagingSettlesForTheFullCount) {
  GYRO_VERIFIES("MODE-2");
  GyroComponentConfig<double> c = kSeeker;
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
TEST(ComponentModes, TheUncageTickReportsTheRestartedEstimator) {
  GYRO_VERIFIES("EST-1", "TLM-1");
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

// ---- requests refused -------------------------------------------------------------------------

// The uncaging starts the estimator at the body's attitude and the gimbal angles: without
// usable navigation or an accepted reading there is nothing to start it at.
TEST(ComponentModes, NoUncagingWithoutNavigationOrAReading) {
  GYRO_VERIFIES("MODE-1");
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  b.guidance.nav_valid = false;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kCaged) << "no navigation: no attitude to uncage at";
  b.guidance.nav_valid = true;
  b.port.reading.valid = false;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kCaged) << "no reading: no gimbal angles to uncage at";
  b.port.reading.valid = true;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kUncaging);
}

// A request lasts one tick: one refused is flagged and counted in its tick; one for what is
// already in effect is not refused.
TEST(ComponentModes, OnlyARefusedRequestIsFlagged) {
  GYRO_VERIFIES("MODE-6");
  Sil<double> sil;
  ASSERT_TRUE(sil.start());
  sil.run(100);
  sil.nav_valid = false;
  (void)sil.step(ModeRequest::kUncage);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  EXPECT_NE(sil.tm().flags & kRequestRefused, 0u);
  EXPECT_EQ(sil.tm().counters[20], 1u);
  (void)sil.step();
  EXPECT_EQ(sil.tm().flags & kRequestRefused, 0u) << "a request lasts one tick";
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  sil.nav_valid = true;
  (void)sil.step(ModeRequest::kUncage);
  EXPECT_EQ(sil.component.mode(), GyroMode::kUncaging);
  EXPECT_EQ(sil.tm().flags & kRequestRefused, 0u);
  (void)sil.step(ModeRequest::kUncage);
  EXPECT_EQ(sil.tm().flags & kRequestRefused, 0u) << "already in effect: not refused";
  (void)sil.step(ModeRequest::kCage);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  (void)sil.step(ModeRequest::kCage);
  EXPECT_EQ(sil.tm().flags & kRequestRefused, 0u) << "already caged: not refused";
}

// ---- leaving safe mode --------------------------------------------------------------------------

// The estimator, which followed its own prediction while the readings were off, restarts at
// the first good reading: no residual, the prediction the measurement.
TEST(ComponentModes, LeavingSafeModeRestartsTheEstimator) {
  GYRO_VERIFIES("MODE-5");
  SimulatedGyro<double> gyro;
  CorruptingPort<double> wire{gyro};
  GyroComponent<double> component{wire};
  const Matrix3<double> body = Matrix3<double>::Identity();  // at rest
  ASSERT_TRUE(gyro.configure(SeekerGyro<double>::stub()).ok());
  ASSERT_EQ(gyro.start(body, Vector2<double>::Zero()), Status::kOk);
  ASSERT_TRUE(component.configure(kSeeker).ok());
  ASSERT_EQ(component.activate(), Status::kOk);
  GuidanceInput<double> g;
  g.nav_valid = true;
  std::uint64_t tick = 0;
  const auto step = [&](ModeRequest request) {
    ++tick;
    EXPECT_EQ(gyro.advance(tick, body, Vector2<double>::Zero()), Status::kOk);
    g.request = request;
    return component.step(tick, g);
  };
  for (int k = 0; k < 100; ++k) (void)step(ModeRequest::kNone);
  wire.fault = WireFault::kJump;  // every reading 0.1 rad off from now on
  for (int k = 0; k < 15; ++k) (void)step(ModeRequest::kNone);
  ASSERT_EQ(component.mode(), GyroMode::kFault);
  ASSERT_GT(component.telemetry().residual_rad.cwiseAbs().maxCoeff(), 0.05) << "the estimator kept to the gyro";
  ASSERT_EQ(step(ModeRequest::kCage), Status::kOk);
  ASSERT_EQ(component.mode(), GyroMode::kCaged);
  ASSERT_EQ(step(ModeRequest::kNone), Status::kOk);
  const GyroTelemetry<double>& t = component.telemetry();
  EXPECT_EQ(t.residual_rad, Vector2<double>::Zero());
  EXPECT_NEAR(t.gimbal_predicted_rad(0), t.gimbal_measured_rad(0), 1e-12);
  EXPECT_NEAR(t.gimbal_predicted_rad(1), t.gimbal_measured_rad(1), 1e-12);
  for (int k = 0; k < 50; ++k) ASSERT_EQ(step(ModeRequest::kNone), Status::kOk);
  EXPECT_EQ(component.mode(), GyroMode::kCaged) << "no residual fault from the old prediction";
  EXPECT_EQ(t.flags & kResidualFault, 0u);
}

// The residual monitor is fed only on measured ticks, and in safe mode a measured tick resets
// it. Safe mode entered for another fault and spent without navigation (so without a measured
// tick) keeps whatever fill the monitor had: leaving it must start the monitor afresh, or a
// residual just short of its persistence before the fault trips it at the first residual after.
TEST(ComponentModes, LeavingSafeModeResetsTheResidualMonitor) {
  GYRO_VERIFIES("FAULT-2");
  Bench b;
  ASSERT_TRUE(b.ok);
  const std::uint32_t n = kSeeker.residual_persistence_ticks;
  const double limit = kSeeker.residual_limit_rad;
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
  b.run(static_cast<int>(kSeeker.invalid_persistence_ticks));
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

}  // namespace component_modes_test
}  // namespace gyro
