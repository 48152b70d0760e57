// The rare branches of the attitude pieces (gyro/attitude.hpp, gyro/gimbal_geometry.hpp),
// each against an independent reference: the exact step rotation across its series edge, in
// its closed form and where the squares of its angles overflow; the gimbal frame at gimbal
// lock, where the yaw is undefined and the outer torquer has no authority left.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "gyro/attitude.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// Eigen's angle-axis quaternion in long double, for a rotation vector (0, th, ps).
Eigen::Quaternion<long double> angle_axis_reference(double th, double ps) {
  const long double a = std::hypot(static_cast<long double>(th), static_cast<long double>(ps));
  const Eigen::Matrix<long double, 3, 1> axis(0.0L, static_cast<long double>(th) / a, static_cast<long double>(ps) / a);
  return Eigen::Quaternion<long double>(Eigen::AngleAxis<long double>(a, axis));
}

// The series is used up to a rotation of kSmallRotation = 0.05 rad (half-angle 0.025), the
// closed form beyond: both must be the rotation of their angle to a few ulps, at the edge, on
// either side of it, and far from it.
TEST(StepRotation, GivenAnglesAcrossTheSeriesEdgeAndBeyondThenItIsTheRotationOfTheirAngleToRounding) {
  GYRO_VERIFIES("MODEL-3");
  const double edge = ScalarTraits<double>::kSmallRotation;
  const double eps = std::numeric_limits<double>::epsilon();
  for (const double angle : {1e-8, 1e-3, 0.02, std::nextafter(edge, 0.0), edge, std::nextafter(edge, 1.0), 0.07, 0.15,
                             0.3, 1.0, 3.0}) {
    for (const Vector2<double>& dir : {Vector2<double>(1.0, 0.0), Vector2<double>(0.6, -0.8)}) {
      const double th = angle * dir(0), ps = angle * dir(1);
      SCOPED_TRACE(::testing::Message() << "angle " << angle << " (" << th << ", " << ps << ")");
      const Quaternion<double> q = step_rotation(Vector2<double>(th, ps));
      const Eigen::Quaternion<long double> r = angle_axis_reference(th, ps);
      // w = cos(h) to a few ulps of 1 (near h = pi/2 the rounding of h itself shows);
      // the axis part sin(h)/(2h) (th, ps) to a few ulps of itself, however small.
      const auto near = [eps](double got, long double want) {
        return std::abs(static_cast<long double>(got) - want) <= static_cast<long double>(4 * eps) * std::abs(want);
      };
      EXPECT_LE(std::abs(static_cast<long double>(q.w()) - r.w()), 4 * eps) << q.w() - static_cast<double>(r.w());
      EXPECT_EQ(q.x(), 0.0);
      EXPECT_TRUE(near(q.y(), r.y())) << q.y() - static_cast<double>(r.y());
      EXPECT_TRUE(near(q.z(), r.z())) << q.z() - static_cast<double>(r.z());
    }
  }
}

// Angles whose squares overflow (beyond 1.3e154 rad) take the half angles without squaring:
// still a unit quaternion about the axis (0, th, ps). (At such angles one ulp is many turns:
// only the axis and the norm mean anything.)
TEST(StepRotation, GivenAnglesWhoseSquaresOverflowThenAUnitQuaternionAboutTheirAxis) {
  GYRO_VERIFIES("MODEL-3");
  for (const double scale : {1e150, 1e154, 1e155, 1e200, 1e307}) {
    SCOPED_TRACE(scale);
    const double th = 0.6 * scale, ps = -0.8 * scale;
    const Quaternion<double> q = step_rotation(Vector2<double>(th, ps));
    ASSERT_TRUE(q.coeffs().allFinite()) << q.coeffs().transpose();
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_EQ(q.x(), 0.0);
    // (y, z) along (0.6, -0.8): the cross product vanishes (or both are zero at sin = 0).
    EXPECT_NEAR(q.y() * -0.8 - q.z() * 0.6, 0.0, 1e-15);
  }
}

// The spin axis along body z (pitch 90 deg, nose-up): the yaw is undefined, so the frame
// takes yaw zero; the outer torquer's cos th is held at kMinCosPitch instead of dividing by
// zero. Built from exact matrix entries, so that cos th is exactly zero.
TEST(GimbalFrameLock, GivenTheSpinAxisExactlyAlongBodyZThenTheFrameIsFiniteWithYawZeroAndCosPitchAtItsGuard) {
  GYRO_VERIFIES("MODEL-5");
  Matrix3<double> gyro_to_body;
  gyro_to_body.col(0) = Vector3<double>(0.0, 0.0, -1.0);  // x: pitch +90 deg
  gyro_to_body.col(1) = Vector3<double>(0.0, 1.0, 0.0);
  gyro_to_body.col(2) = Vector3<double>(1.0, 0.0, 0.0);
  ASSERT_TRUE(is_rotation(gyro_to_body));
  const GimbalFrame<double> f = gimbal_frame(gyro_to_body);
  EXPECT_EQ(f.cos_pitch, kMinCosPitch<double>);
  EXPECT_EQ(f.sin_pitch, 1.0);
  EXPECT_EQ(f.y_inner_body, Vector3<double>(0.0, 1.0, 0.0));
  EXPECT_EQ(f.z_inner_body, Vector3<double>(1.0, 0.0, 0.0)) << "x cross y_I";
  EXPECT_EQ(f.gimbal_to_gyro, Matrix2<double>::Identity());
  const Vector2<double> on_rotor = rotor_torque_from_torquers(f, Vector2<double>(0.01, 0.02));
  EXPECT_EQ(on_rotor, Vector2<double>(0.01, 0.02 / kMinCosPitch<double>));

  const GimbalFrame<double> at = gimbal_frame_at(Vector2<double>(kPi<double> / 2, 0.0));
  EXPECT_EQ(at.cos_pitch, kMinCosPitch<double>) << "cos(pi/2) rounds to 6e-17, below the guard";
  EXPECT_TRUE(all_finite(rotor_torque_from_torquers(at, Vector2<double>(0.01, 0.02))));
}

// Away from the lock the frame read off a gyro's axes is the frame at its gimbal angles: the
// spin axis turned by pitch about y, then yaw about z (Eigen's active rotations), no twist.
TEST(GimbalFrameLock, GivenAGyroOnItsGimbalsThenTheFrameOfItsAxesIsTheFrameAtItsAngles) {
  GYRO_VERIFIES("MODEL-5");
  for (const Vector2<double>& g : {Vector2<double>(0.3, -0.7), Vector2<double>(-1.2, 2.5), Vector2<double>(1.5, 0.1)}) {
    SCOPED_TRACE(g.transpose());
    const Matrix3<double> gyro_to_body = (Eigen::AngleAxis<double>(g(1), Vector3<double>::UnitZ()) *
                                          Eigen::AngleAxis<double>(g(0), Vector3<double>::UnitY()))
                                             .toRotationMatrix();
    const GimbalFrame<double> f = gimbal_frame(gyro_to_body);
    const GimbalFrame<double> at = gimbal_frame_at(g);
    EXPECT_NEAR(f.cos_pitch, std::cos(g(0)), 1e-15);
    EXPECT_NEAR(at.cos_pitch, std::cos(g(0)), 1e-15);
    EXPECT_NEAR(f.sin_pitch, std::sin(g(0)), 1e-15);
    EXPECT_NEAR(at.sin_pitch, std::sin(g(0)), 1e-15);
    EXPECT_LT((f.spin_axis_body - at.spin_axis_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((f.y_inner_body - at.y_inner_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((f.z_inner_body - at.z_inner_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((f.gimbal_to_gyro - Matrix2<double>::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  }
}

// A gyro twisted about its spin axis against the gimbal: the 2x2 twist is each dot product of
// the gimbal's (y_I, z_I) with the gyro's (y_g, z_g), taken here from the matrices directly,
// and the frame from an attitude and a body (without the whole product) is the frame of the
// product.
TEST(GimbalFrameTwist, GivenAGyroRolledOnItsGimbalThenTheTwistIsTheDotProductsOfTheTwoFrames) {
  GYRO_VERIFIES("MODEL-5");
  const Vector2<double> gimbal(0.4, -1.1);
  for (const double roll : {0.0, 0.3, -2.0, 3.0}) {
    SCOPED_TRACE(roll);
    const Matrix3<double> gyro_to_body = (Eigen::AngleAxis<double>(gimbal(1), Vector3<double>::UnitZ()) *
                                          Eigen::AngleAxis<double>(gimbal(0), Vector3<double>::UnitY()) *
                                          Eigen::AngleAxis<double>(roll, Vector3<double>::UnitX()))
                                             .toRotationMatrix();
    const GimbalFrame<double> f = gimbal_frame(gyro_to_body);
    const Vector3<double> y_g = gyro_to_body.col(1), z_g = gyro_to_body.col(2);
    Matrix2<double> dots;
    dots << f.y_inner_body.dot(y_g), f.z_inner_body.dot(y_g), f.y_inner_body.dot(z_g), f.z_inner_body.dot(z_g);
    EXPECT_LT((f.gimbal_to_gyro - dots).cwiseAbs().maxCoeff(), 1e-15) << f.gimbal_to_gyro << "\n" << dots;
    EXPECT_NEAR(f.gimbal_to_gyro(0, 0), std::cos(roll), 1e-15);
    EXPECT_NEAR(f.gimbal_to_gyro(0, 1), std::sin(roll), 1e-15);

    // The same gyro as an attitude on a body turned in earth axes.
    const Matrix3<double> earth_to_body = (Eigen::AngleAxis<double>(0.7, Vector3<double>(1.0, -2.0, 0.5).normalized()))
                                              .toRotationMatrix();
    const Quaternion<double> gyro_to_earth(Matrix3<double>(earth_to_body.transpose() * gyro_to_body));
    GimbalFrame<double> from_attitude;
    gimbal_frame(earth_to_body, gyro_to_earth, from_attitude);
    EXPECT_LT((from_attitude.spin_axis_body - f.spin_axis_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((from_attitude.y_inner_body - f.y_inner_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((from_attitude.z_inner_body - f.z_inner_body).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((from_attitude.gimbal_to_gyro - f.gimbal_to_gyro).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_NEAR(from_attitude.cos_pitch, f.cos_pitch, 1e-15);
    EXPECT_NEAR(from_attitude.sin_pitch, f.sin_pitch, 1e-15);
  }
}

// The torque at a frame moved by a pitch change and an inner-gimbal roll, against the torque at
// the frame built exactly at the moved angles: the error is third order (halving the move
// divides it by about 8; a sign or a missing second-order term would leave a ratio of 2 or 4).
TEST(GimbalFrameMoved, GivenAPitchChangeAndARollThenTheTorqueIsTheMovedFramesToThirdOrder) {
  GYRO_VERIFIES("MODEL-5");
  const auto frame_of = [](double pitch, double gyro_roll) {
    return gimbal_frame(Matrix3<double>((Eigen::AngleAxis<double>(0.6, Vector3<double>::UnitZ()) *
                                         Eigen::AngleAxis<double>(pitch, Vector3<double>::UnitY()) *
                                         Eigen::AngleAxis<double>(gyro_roll, Vector3<double>::UnitX()))
                                            .toRotationMatrix()));
  };
  const Vector2<double> torquer(0.03, -0.08);
  for (const double pitch : {0.0, 0.5, -1.2}) {
    for (const double gyro_roll : {0.0, 0.4, -2.5}) {
      for (const double sign : {1.0, -1.0}) {
        SCOPED_TRACE(testing::Message() << pitch << " " << gyro_roll << " " << sign);
        const GimbalFrame<double> start = frame_of(pitch, gyro_roll);
        const auto error = [&](double h) {
          // The inner gimbal rolling by roll against the gyro's axes: the gyro's roll on it falls.
          const double dth = sign * h, roll = -2.0 * h;
          const GimbalFrame<double> moved = frame_of(pitch + dth, gyro_roll - roll);
          const Vector2<double> exact = times(moved.gimbal_to_gyro, rotor_torque_from_torquers(moved, torquer));
          return (rotor_torque_on_gyro_axes_moved(start, torquer, dth, roll) - exact).norm();
        };
        const double e1 = error(1e-2), e2 = error(5e-3);
        EXPECT_LT(e1, 2e-6 * torquer.norm() / std::cos(pitch));
        EXPECT_GT(e1 / e2, 6.5) << e1 << " " << e2;
        EXPECT_LT(e1 / e2, 9.5) << e1 << " " << e2;
      }
      // A roll far beyond a step's (a step far too coarse): the torque keeps its size within
      // 1 %, instead of growing with the square of the move.
      const GimbalFrame<double> start = frame_of(pitch, gyro_roll);
      const double size = rotor_torque_from_torquers(start, torquer).norm();
      for (const double roll : {0.5, -3.0, 40.0}) {
        EXPECT_NEAR(rotor_torque_on_gyro_axes_moved(start, torquer, 0.0, roll).norm(), size, 0.01 * size) << roll;
      }
      // A pitch move as far beyond (the roll within the step's): taken as half a radian.
      for (const double dth : {-3.0, 40.0}) {
        EXPECT_EQ(rotor_torque_on_gyro_axes_moved(start, torquer, dth, 0.0),
                  rotor_torque_on_gyro_axes_moved(start, torquer, std::copysign(0.5, dth), 0.0))
            << dth;
      }
    }
  }
}

// The rotation check at its tolerance: rows 0 and 1 unit and orthogonal, row 2 their cross
// product, each within kRotationTolerance. A rotation whose entries move by half the tolerance
// passes (and is then within 3 tolerances of orthonormal, R R^T - I); one whose last row moves
// by twice the tolerance, whose first row is 2 tolerances too long, or whose last row is turned
// over (a reflection: det -1) does not.
template <typename T>
void check_rotation_tolerance() {
  const T tol = ScalarTraits<T>::kRotationTolerance;
  const Matrix3<T> r =
      Eigen::AngleAxis<T>(T(0.9), Vector3<T>(T(1), T(-2), T(0.5)).normalized()).toRotationMatrix();
  ASSERT_TRUE(is_rotation(r));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      SCOPED_TRACE(testing::Message() << "entry " << i << ", " << j);
      Matrix3<T> m = r;
      m(i, j) += tol / T(4);
      EXPECT_TRUE(is_rotation(m));
      EXPECT_LE(orthonormality_error(m), T(3) * tol);
      if (i == 2) {
        m(2, j) = r(2, j) + T(2) * tol;
        EXPECT_FALSE(is_rotation(m)) << "the last row off the cross product";
      }
    }
  }
  Matrix3<T> longer = r;
  longer.row(0) *= T(1) + T(2) * tol;
  EXPECT_FALSE(is_rotation(longer)) << "a first row 2 tolerances too long";
  Matrix3<T> reflection = r;
  reflection.row(2) *= T(-1);
  EXPECT_FALSE(is_rotation(reflection));
  EXPECT_FALSE(is_rotation(Matrix3<T>(-r))) << "det -1";
}

TEST(RotationCheck, GivenARotationMovedWithinAndBeyondTheToleranceThenAcceptedAndRefused) {
  GYRO_VERIFIES("INPUT-4");
  check_rotation_tolerance<double>();
  check_rotation_tolerance<float>();
}

}  // namespace
}  // namespace gyro
