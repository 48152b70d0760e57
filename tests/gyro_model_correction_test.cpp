// GyroModel's corrections (correct_attitude, correct_gimbal_angles and the correction taken at
// the next step, the estimator's feedback): each refusal leaves the state bit-identical; a
// correction moves each gimbal angle by its own part, clears the gimbal-limit flag once back
// inside the cone, is replaced by a new uncaging, and taken at the next step it ends where the
// correction and then the step leave the gyro.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"
#include "support/requirements.hpp"
#include "support/same_bits.hpp"

namespace gyro {
namespace gyro_model_correction_test {

// correct_attitude refuses what it cannot use and then changes nothing.
TEST(GyroModelCorrection, ABadInputIsRefusedAndChangesNothing) {
  GYRO_VERIFIES("MODEL-6");
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(ReportSample<double>::config()).ok());
  const Matrix3<double> r = Matrix3<double>::Identity();
  EXPECT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), r), Status::kNotConfigured) << "caged";
  ASSERT_EQ(g.uncage(r, Vector2<double>(0.1, -0.2), Vector2<double>(0.02, -0.01)), Status::kOk);
  const Quaternion<double> q0 = g.attitude_gyro_to_earth();
  const double pitch0 = g.gimbal_pitch_rad(), yaw0 = g.gimbal_yaw_rad();
  const std::uint32_t flags0 = g.flags();
  Matrix3<double> sheared = r;
  sheared(0, 1) = 0.1;
  EXPECT_EQ(g.correct_attitude(Vector2<double>(std::nan(""), 0.0), r), Status::kNonFiniteInput);
  EXPECT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), sheared), Status::kInvalidRotation);
  EXPECT_TRUE(testing::same_bits(g.attitude_gyro_to_earth().coeffs(), q0.coeffs()));
  EXPECT_TRUE(testing::same_bits(g.gimbal_pitch_rad(), pitch0));
  EXPECT_TRUE(testing::same_bits(g.gimbal_yaw_rad(), yaw0));
  EXPECT_EQ(g.flags(), flags0);
  // Accepted: pitching the gyro up by 1 mrad raises its gimbal pitch angle by as much.
  ASSERT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), r), Status::kOk);
  EXPECT_NEAR(g.gimbal_pitch_rad() - pitch0, 1e-3, 2e-5);
  EXPECT_NEAR(g.gimbal_yaw_rad() - yaw0, 0.0, 2e-5);
}

// The same refusals with the attitude given as a checked rotation (the component's form), and
// a gimbal-angle correction that is not finite.
TEST(GyroModelCorrection, ACheckedRotationOrGimbalFormRefusesAlike) {
  GYRO_VERIFIES("MODEL-6");
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(ReportSample<double>::config()).ok());
  const CheckedRotation<double> identity;
  EXPECT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), identity), Status::kNotConfigured) << "caged";
  ASSERT_EQ(g.uncage(identity.matrix(), Vector2<double>(0.1, -0.2), Vector2<double>(0.02, -0.01)), Status::kOk);
  const Quaternion<double> q0 = g.attitude_gyro_to_earth();
  EXPECT_EQ(g.correct_attitude(Vector2<double>(0.0, std::nan("")), identity), Status::kNonFiniteInput);
  EXPECT_EQ(g.correct_gimbal_angles(Vector2<double>(std::nan(""), 0.0), identity.matrix()), Status::kNonFiniteInput);
  EXPECT_TRUE(testing::same_bits(g.attitude_gyro_to_earth().coeffs(), q0.coeffs()));
  const double pitch0 = g.gimbal_pitch_rad();
  ASSERT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), identity), Status::kOk);
  EXPECT_NEAR(g.gimbal_pitch_rad() - pitch0, 1e-3, 2e-5);
}

TEST(GyroModelCorrection, BackInsideTheConeClearsTheLimitFlag) {
  GYRO_VERIFIES("MODEL-4", "MODEL-6");
  const GyroModelConfig<double> c = ReportSample<double>::config();  // cone 0.436 rad
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  const Matrix3<double> r = Matrix3<double>::Identity();
  ASSERT_EQ(g.uncage(r, Vector2<double>::Zero(), Vector2<double>(0.5, 0.0)), Status::kOk);
  ASSERT_TRUE(g.gimbal_limit_exceeded());
  ASSERT_EQ(g.correct_attitude(Vector2<double>(-0.2, 0.0), r), Status::kOk);
  EXPECT_FALSE(g.gimbal_limit_exceeded()) << "cone " << g.gimbal_cone_rad();
  EXPECT_EQ(g.flags() & kFlagGimbalLimit, 0u);
  ASSERT_EQ(g.correct_attitude(Vector2<double>(0.0, 0.5), r), Status::kOk);
  EXPECT_TRUE(g.gimbal_limit_exceeded()) << "cone " << g.gimbal_cone_rad();
}

// A correction of the gimbal angles moves them by itself: the yaw part turns the spin axis
// about the outer axis (body z), by yaw cos(pitch) on the gyro's own axes. Off the pitch
// zero, a yaw not so resolved would move the yaw angle by yaw / cos(pitch) (4.7 % more at
// 0.3 rad). First order in the correction: 1e-5 rad leaves terms of 1e-10.
TEST(GyroModelCorrection, EachGimbalAngleMovesByItsOwnPart) {
  GYRO_VERIFIES("MODEL-6", "EST-3");
  const GyroModelConfig<double> c = ReportSample<double>::config();
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  const Matrix3<double> body = (Eigen::AngleAxisd(0.4, Vector3<double>::UnitZ()) *
                                Eigen::AngleAxisd(-0.2, Vector3<double>::UnitY()))
                                   .toRotationMatrix();
  for (const double pitch : {0.0, 0.3, -0.35}) {
    SCOPED_TRACE(pitch);
    ASSERT_EQ(g.uncage_on_gimbal(body, Vector3<double>::Zero(), Vector2<double>(pitch, 0.1)), Status::kOk);
    ASSERT_NEAR(g.gimbal_pitch_rad(), pitch, 1e-15);
    ASSERT_NEAR(g.gimbal_yaw_rad(), 0.1, 1e-15);
    const Vector2<double> d(-0.7e-5, 1e-5);
    ASSERT_EQ(g.correct_gimbal_angles(d, body), Status::kOk);
    EXPECT_NEAR(g.gimbal_pitch_rad(), pitch + d(0), 1e-9);
    EXPECT_NEAR(g.gimbal_yaw_rad(), 0.1 + d(1), 1e-9);
  }
}

// A correction followed by a new uncaging: the angles read are those of the new uncaging, as
// if the correction had never been made (it turned an attitude that uncaging replaced, against
// the body of its own time).
TEST(GyroModelCorrection, ANewUncagingReplacesIt) {
  GYRO_VERIFIES("MODEL-6");
  const GyroModelConfig<double> c = ReportSample<double>::config();
  const Matrix3<double> first = Eigen::AngleAxisd(0.3, Vector3<double>(1, -2, 0.5).normalized()).toRotationMatrix();
  const Matrix3<double> second = Eigen::AngleAxisd(-0.8, Vector3<double>(0.2, 1, -1).normalized()).toRotationMatrix();
  GyroModel<double> corrected, fresh;
  ASSERT_TRUE(corrected.configure(c).ok() && fresh.configure(c).ok());
  ASSERT_EQ(corrected.uncage(first, Vector2<double>::Zero(), Vector2<double>(0.1, -0.2)), Status::kOk);
  ASSERT_EQ(corrected.correct_attitude(Vector2<double>(0.05, 0.02), first), Status::kOk);
  ASSERT_EQ(corrected.uncage(second, Vector2<double>::Zero(), Vector2<double>(-0.1, 0.15)), Status::kOk);
  ASSERT_EQ(fresh.uncage(second, Vector2<double>::Zero(), Vector2<double>(-0.1, 0.15)), Status::kOk);
  EXPECT_EQ(corrected.gimbal_pitch_rad(), fresh.gimbal_pitch_rad());
  EXPECT_EQ(corrected.gimbal_yaw_rad(), fresh.gimbal_yaw_rad());
  ASSERT_EQ(corrected.uncage_on_gimbal(first, Vector3<double>::Zero(), Vector2<double>(0.2, 0.1)), Status::kOk);
  ASSERT_EQ(corrected.correct_attitude(Vector2<double>(0.05, 0.02), first), Status::kOk);
  ASSERT_EQ(corrected.uncage_on_gimbal(second, Vector3<double>::Zero(), Vector2<double>(0.3, -0.2)), Status::kOk);
  EXPECT_NEAR(corrected.gimbal_pitch_rad(), 0.3, 1e-12);
  EXPECT_NEAR(corrected.gimbal_yaw_rad(), -0.2, 1e-12);
}

// A correction taken at the next step is the same turn as one taken now followed by the
// step: R(c) R(a) = R(c + a + (c x a) / 2 + third order). The reference is the product of the
// two exact rotations; the roll term (c x a) / 2 is what makes them agree: without it the
// attitudes differ by |c| |a| / 2 (1e-5 rad here), with it by less than the third-order
// bound |a| |c| (|a| + |c|) / 12 = 2e-8 rad.
TEST(GyroModelCorrection, AtTheNextStepComesBeforeTheStep) {
  GYRO_VERIFIES("MODEL-6", "EST-3");
  const GyroModelConfig<double> c = ReportSample<double>::config();
  const Matrix3<double> body = Eigen::AngleAxisd(0.3, Vector3<double>(1, -2, 0.5).normalized()).toRotationMatrix();
  const auto uncaged = [&](GyroModel<double>& g) {
    return g.configure(c).ok() && g.uncage(body, Vector2<double>(1.0, -0.5), Vector2<double>(0.1, -0.2)) == Status::kOk;
  };
  GyroModel<double> now, next, probe;
  ASSERT_TRUE(uncaged(now) && uncaged(next) && uncaged(probe));
  EXPECT_EQ(GyroModel<double>().correct_gimbal_angles_at_next_step(Vector2<double>(1e-3, 0.0)),
            Status::kNotConfigured);
  EXPECT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(std::nan(""), 0.0)), Status::kNonFiniteInput);
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "a refused call changes nothing";

  const Vector2<double> d(-0.7e-3, 0.5e-3);
  ASSERT_EQ(now.correct_gimbal_angles(d, body), Status::kOk);
  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(0.5 * d)), Status::kOk);
  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(0.5 * d)), Status::kOk);  // the two add
  const Vector2<double> corr = next.pending_correction_rad();
  EXPECT_EQ(next.attitude_gyro_to_earth().coeffs(), probe.attitude_gyro_to_earth().coeffs()) << "not turned yet";

  GyroStepInput<double> in;
  in.dt_s = 0.02;
  in.spin_hz = ReportSample<double>::kSpinHz;
  in.R_earth_to_body = body;
  const Vector2<double> torque(1500.0, -800.0);  // a precession near 1 rad/s against H = 1885
  const Quaternion<double> start = next.attitude_gyro_to_earth();
  ASSERT_EQ(now.step_torque(in, torque), Status::kOk);
  ASSERT_EQ(next.step_torque(in, torque), Status::kOk);
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "taken by the step";
  const Vector2<double> a = next.isaf_angle_rad();
  ASSERT_GT(a.norm(), 1e-2) << "a step long enough for the roll term to matter";
  const double third_order = a.norm() * corr.norm() * (a.norm() + corr.norm()) / 12;
  EXPECT_LT(now.attitude_gyro_to_earth().angularDistance(next.attitude_gyro_to_earth()), third_order + 1e-14);
  const Quaternion<double> without_roll = start * step_rotation(Vector2<double>(a + corr));
  EXPECT_GT(now.attitude_gyro_to_earth().angularDistance(without_roll), 0.3 * a.norm() * corr.norm())
      << "the roll term is needed";
  EXPECT_NEAR(now.gimbal_pitch_rad(), next.gimbal_pitch_rad(), third_order);
  EXPECT_NEAR(now.gimbal_yaw_rad(), next.gimbal_yaw_rad(), third_order);

  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(d), Status::kOk);
  ASSERT_TRUE(uncaged(next));
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "uncaging drops a pending correction";
}

}  // namespace gyro_model_correction_test
}  // namespace gyro
