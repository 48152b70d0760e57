// The estimator inside the tick, against the SIL stub, its gimbal plant and a faulty harness:
// the prediction spans lost ticks at the nominal spin, follows the body's rate changing within
// a tick, and is skipped, never poisoned, when the scalar type cannot represent it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/faulty_harness.hpp"
#include "support/requirements.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_estimator_test {

using testing::FaultyRig;
using testing::SeekerGyro;
using testing::Sil;
using testing::telemetry_finite;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// ---- lost ticks ---------------------------------------------------------------------------------

// The estimator's transition is cached per spin and step: with the spin held at the nominal
// (no readback), a gap changes only the step, and the prediction must span all of it.
TEST(ComponentEstimator, SpansLostTicksAtTheNominalSpin) {
  GYRO_VERIFIES("EST-2", "TICK-2");
  GyroComponentConfig<double> c = kSeeker;
  c.use_spin_readback = false;
  for (const int gap : {2, 5, 8}) {
    SCOPED_TRACE(gap);
    Sil<double> sil;
    ASSERT_TRUE(sil.start(c));
    ASSERT_TRUE(sil.uncage());
    sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.5, -0.4);
    sil.run(50);
    ASSERT_EQ(sil.lose_ticks(gap - 1), Status::kOk);
    ASSERT_EQ(sil.step(), Status::kOk);
    EXPECT_NE(sil.tm().flags & kTickSkipped, 0u);
    EXPECT_LT(sil.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "predicted over the whole gap";
    ASSERT_EQ(sil.step(), Status::kOk);
    EXPECT_LT(sil.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "and one tick again after it";
  }
}

// ---- the body's rate within a tick -----------------------------------------------------------

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

// The bearings drag the rotor with the body: a torque f (body rate - gyro rate) on the gimbal
// axes, which the torque law compensates a tick late. Over a tick in which the body's pitch
// rate ramps from 0 to q, the drag's impulse is f q dt / 2. An estimator that held the end
// rate over the tick would take f q dt: the extra impulse f q dt / 2 moves the spin axis by
// f q dt / (2 H) and sets it nutating with that radius (up to f q dt / H off). One that holds
// the tick's mean rate has the impulse right and errs only by the ramp's second moment, about
// f q dt^2 / (12 J) in angle. The truth is the plant, which integrates the linear rate
// finely. At a 10 kHz tick (beta dt = 0.38 rad) the two differ by a factor of 16:
// 5.3e-6 rad against 3.3e-7 rad.
TEST(ComponentEstimator, FollowsTheBodysMeanRateOverATick) {
  GYRO_VERIFIES("EST-2");
  GyroComponentConfig<double> c = kSeeker;
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

// ---- a prediction the scalar type cannot represent ---------------------------------------------

// A spin readback so large that the exact transition over a tick overflows the scalar type
// (H^2 / (J1 J2) is not representable): the estimator cannot predict and must not poison the
// state; it restarts from the next good reading.
template <typename T>
void expect_estimator_restarts_after_unrepresentable_prediction(T huge_spin_hz) {
  FaultyRig<T> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 20; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<T> predicted_before = rig.tm().gimbal_predicted_rad;
  ASSERT_EQ(rig.step(), Status::kOk);
  ASSERT_NE(rig.tm().gimbal_predicted_rad, predicted_before) << "a turning body moves the prediction";

  rig.harness.spin_override = true;
  rig.harness.spin_hz = huge_spin_hz;
  const Vector2<T> predicted_last = rig.tm().gimbal_predicted_rad;
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.tm().spin_hz, huge_spin_hz) << "a finite, non-negative readback is used";
  EXPECT_EQ(rig.tm().gimbal_predicted_rad, predicted_last) << "no prediction this tick";
  EXPECT_NE(rig.tm().flags & kTorquerSaturated, 0U) << "H that large asks beyond the torquer";
  EXPECT_LE(rig.tm().torque_cmd.cwiseAbs().maxCoeff(), SeekerGyro<T>::component().max_torque);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
  // While the readback stays that large the estimator alternates between re-initialising from
  // the reading and failing to predict; nothing it publishes is non-finite.
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_TRUE(telemetry_finite(rig.tm())) << k;
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << k;
  }

  rig.harness.spin_override = false;
  ASSERT_EQ(rig.step(), Status::kOk);
  // Re-initialised from this tick's accepted reading: the prediction is the measurement.
  EXPECT_EQ(rig.tm().residual_rad, Vector2<T>::Zero());
  EXPECT_NEAR(static_cast<double>(rig.tm().gimbal_predicted_rad(0)),
              static_cast<double>(rig.tm().gimbal_measured_rad(0)), 1e-6);
  EXPECT_NEAR(static_cast<double>(rig.tm().gimbal_predicted_rad(1)),
              static_cast<double>(rig.tm().gimbal_measured_rad(1)), 1e-6);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(rig.tm().flags & kResidualFault, 0U);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
}

TEST(ComponentEstimator, OverflowSkipsAndRestartsInDouble) {
  GYRO_VERIFIES("EST-4");
  expect_estimator_restarts_after_unrepresentable_prediction<double>(1e200);
}

TEST(ComponentEstimator, OverflowSkipsAndRestartsInFloat) {
  GYRO_VERIFIES("EST-4", "RULE-8");
  expect_estimator_restarts_after_unrepresentable_prediction<float>(1e30f);
}

}  // namespace component_estimator_test
}  // namespace gyro
