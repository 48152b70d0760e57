// The estimator (gyro/estimator.hpp), without a port: its start at the measured gimbal angles, the
// prediction over the elapsed ticks with the torque held, the residual and its feedback, a refused
// step, and the frame the torque law resolves on.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gyro/estimator.hpp"
#include "gyro/seeker_component_example.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace estimator_test {

const GyroComponentConfig<double> kSeeker = SeekerComponentExample<double>::component();
const double kSpin = kSeeker.nominal_spin_hz;
const Navigation<double> kStill{};  // identity attitude, body at rest

Estimator<double> configured() {
  Estimator<double> e;
  EXPECT_TRUE(e.configure(kSeeker).ok());
  return e;
}

Estimator<double> started_at(const Vector2<double>& g) {
  Estimator<double> e = configured();
  EXPECT_TRUE(e.start(kStill, g));
  return e;
}

TEST(Estimator, ItStartsAtTheMeasuredAnglesWhenMeasurable) {
  GYRO_VERIFIES("EST-1");
  Estimator<double> e = configured();
  const Vector2<double> g(0.1, -0.05);
  const Prediction blind = e.predict(1, kSpin, kStill, false, g);
  EXPECT_FALSE(e.ready());
  EXPECT_FALSE(blind.compared);
  const Prediction first = e.predict(1, kSpin, kStill, true, g);
  EXPECT_TRUE(e.ready());
  EXPECT_FALSE(first.compared) << "the start predicts nothing";
  EXPECT_NEAR((e.predicted_rad() - g).cwiseAbs().maxCoeff(), 0.0, 1e-15);
  EXPECT_EQ(e.residual_rad(), Vector2<double>::Zero());
}

TEST(Estimator, ARefusedStartChangesNothing) {
  GYRO_VERIFIES("EST-1", "RULE-9");
  Estimator<double> e = configured();
  const Navigation<double> bad(CheckedRotation<double>(),
                               Vector3<double>(0, std::numeric_limits<double>::quiet_NaN(), 0));
  EXPECT_FALSE(e.start(bad, Vector2<double>(0.1, 0.1)));
  EXPECT_FALSE(e.ready());
  EXPECT_EQ(e.predicted_rad(), Vector2<double>::Zero());
}

TEST(Estimator, AFreeGyroOnAStillBodyHoldsItsAngles) {
  GYRO_VERIFIES("EST-2");
  const Vector2<double> g(0.1, -0.05);
  Estimator<double> e = started_at(g);
  for (int k = 0; k < 200; ++k) {
    const Prediction p = e.predict(1, kSpin, kStill, true, g);
    ASSERT_TRUE(p.compared);
    ASSERT_EQ(p.flags, 0u);
  }
  EXPECT_LT((e.predicted_rad() - g).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(e.residual_rad().cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Estimator, ElapsedTicksSpanTheWholeGap) {
  GYRO_VERIFIES("EST-2", "TICK-2");
  // A torque held precesses the gyro at T/H (0.13 rad/s): 2.7e-4 rad over four ticks.
  const Vector2<double> torque(0.01, 0.0);
  Estimator<double> one_by_one = started_at(Vector2<double>::Zero());
  Estimator<double> at_once = started_at(Vector2<double>::Zero());
  Estimator<double> one_tick = started_at(Vector2<double>::Zero());
  for (Estimator<double>* e : {&one_by_one, &at_once, &one_tick}) e->hold_torque(torque);
  for (int k = 0; k < 4; ++k) (void)one_by_one.predict(1, kSpin, kStill, false, Vector2<double>::Zero());
  (void)at_once.predict(4, kSpin, kStill, false, Vector2<double>::Zero());
  (void)one_tick.predict(1, kSpin, kStill, false, Vector2<double>::Zero());
  EXPECT_GT(one_by_one.predicted_rad().norm(), 2e-4);
  EXPECT_LT((at_once.predicted_rad() - one_by_one.predicted_rad()).norm(), 1e-9);
  EXPECT_GT((one_tick.predicted_rad() - one_by_one.predicted_rad()).norm(), 1e-4);
  EXPECT_EQ(at_once.torque_held(), torque);
}

TEST(Estimator, TheResidualFeedsBackItsGainPerTick) {
  GYRO_VERIFIES("EST-3");
  // Measured 1 mrad off a gyro at rest: each tick takes the gain's share of the residual.
  Estimator<double> e = started_at(Vector2<double>::Zero());
  const Vector2<double> measured(1e-3, -5e-4);
  (void)e.predict(1, kSpin, kStill, true, measured);
  Vector2<double> before = e.residual_rad();
  EXPECT_NEAR((before - measured).norm(), 0.0, 1e-12);
  for (int k = 0; k < 10; ++k) {
    (void)e.predict(1, kSpin, kStill, true, measured);
    const Vector2<double> r = e.residual_rad();
    EXPECT_NEAR(r(0) / before(0), 1.0 - kSeeker.estimator_gain, 1e-6) << k;
    EXPECT_NEAR(r(1) / before(1), 1.0 - kSeeker.estimator_gain, 1e-6) << k;
    before = r;
  }
}

TEST(Estimator, ARefusedStepStopsItUntilTheNextReading) {
  GYRO_VERIFIES("EST-4");
  Estimator<double> e = started_at(Vector2<double>(0.05, 0.0));
  const Prediction refused =
      e.predict(1, std::numeric_limits<double>::infinity(), kStill, true, Vector2<double>(0.05, 0.0));
  EXPECT_FALSE(refused.compared);
  EXPECT_FALSE(e.ready());
  const Vector2<double> g(-0.02, 0.03);
  (void)e.predict(1, kSpin, kStill, true, g);
  EXPECT_TRUE(e.ready());
  EXPECT_NEAR((e.predicted_rad() - g).cwiseAbs().maxCoeff(), 0.0, 1e-15) << "restarted at the reading";
}

TEST(Estimator, APredictionBeyondThePickoffRangeStopsIt) {
  GYRO_VERIFIES("EST-9");
  // The navigation's attitude jumps 1 rad in pitch in one tick: the inertial gyro is then
  // predicted 1 rad off the body, beyond the pickoffs' 0.6 rad, where the gimbal cannot be.
  Estimator<double> e = started_at(Vector2<double>(0.05, 0.0));
  CheckedRotation<double> pitched;
  ASSERT_TRUE(GyroModel<double>::check_body_attitude(frame_rotation_y(1.0), pitched));
  const Navigation<double> jumped(pitched, Vector3<double>::Zero());
  const Prediction p = e.predict(1, kSpin, jumped, true, Vector2<double>(0.05, 0.0));
  EXPECT_GT(e.predicted_rad().cwiseAbs().maxCoeff(), kSeeker.pickoff_range_rad);
  EXPECT_FALSE(p.compared);
  EXPECT_NE(p.flags & kGimbalLimit, 0u);
  EXPECT_FALSE(e.ready());
  const Vector2<double> g(0.04, 0.01);
  (void)e.predict(1, kSpin, jumped, true, g);
  EXPECT_TRUE(e.ready());
  EXPECT_NEAR((e.predicted_rad() - g).cwiseAbs().maxCoeff(), 0.0, 1e-15) << "restarted at the reading";
  const Prediction next = e.predict(1, kSpin, jumped, true, g);
  EXPECT_TRUE(next.compared);
  EXPECT_LT(e.residual_rad().cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Estimator, TheFrameIsTheEstimatorsOnlyWithNavigation) {
  GYRO_VERIFIES("EST-7");
  const Vector2<double> started(0.2, -0.1), pickoffs(-0.3, 0.25);
  Estimator<double> e = configured();
  EXPECT_EQ(e.frame(true, pickoffs).spin_axis_body, gimbal_frame_at(pickoffs).spin_axis_body) << "not started";
  EXPECT_EQ(e.inner_gimbal_roll_rad_s(), 0.0);
  ASSERT_TRUE(e.start(kStill, started));
  EXPECT_LT((e.frame(true, pickoffs).spin_axis_body - gimbal_frame_at(started).spin_axis_body).norm(), 1e-15);
  EXPECT_EQ(e.frame(false, pickoffs).spin_axis_body, gimbal_frame_at(pickoffs).spin_axis_body);
}

TEST(Estimator, RestartWaitsForTheNextReading) {
  GYRO_VERIFIES("EST-4", "MODE-5");
  Estimator<double> e = started_at(Vector2<double>(0.05, 0.0));
  e.restart();
  EXPECT_FALSE(e.ready());
  (void)e.predict(1, kSpin, kStill, false, Vector2<double>::Zero());
  EXPECT_FALSE(e.ready()) << "not without a measurable tick";
}

}  // namespace estimator_test
}  // namespace gyro
