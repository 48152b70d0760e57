// GyroModel with its torquers on the gimbal axes (TorquerAxes::kGimbal) against the analytic
// precession of a gimballed rotor. Without friction, a torque T_out on the outer gimbal (body
// z) reaches the rotor as T_out / cos th about z_I, so the spin axis pitches at
// th' = -T_out / (H cos th): sin th falls at the constant rate k = T_out / H,
//   sin th(t) = sin th0 - k t,
// while the lever 1 / cos th changes along the way. The pitch rate changes, and the rotor's
// transverse inertia J1 answers with a yaw rate w_z = -J1 th'' / H (no inner torque), that is
// ps' = w_z / cos th; integrated over th (dt = -cos th dth / k),
//   ps(t) = (J1 k / (2 H)) (1 / cos^2 th(t) - 1 / cos^2 th0). The model holds each step's torque at the
// frame of the step's middle; holding it at the start's (a lever one half step late) leaves an
// error that grows with the step, which this catches.
#include <gtest/gtest.h>

#include <cmath>

#include "gyro/gyro_model.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// The seeker's rotor (H = 0.0754 N m s at 300 Hz, 600 Hz nutation), frictionless, with the
// given torquers.
GyroModelConfig<double> seeker_rotor(TorquerAxes axes) {
  GyroModelConfig<double> c;
  c.pitch_inertia = 2e-5;
  c.yaw_inertia = 2e-5;
  c.spin_inertia = 4e-5;
  c.friction = 0;
  c.gimbal_cone_limit_rad = 1.5;
  c.max_pitch_rate_rad_s = 10;
  c.max_yaw_rate_rad_s = 10;
  c.torquer_axes = axes;
  return c;
}

struct PrecessionRun {
  double worst_pitch_error_rad{0};
  double worst_yaw_error_rad{0};
  double final_pitch_rad{0};
  double final_yaw_rad{0};
};

// The seeker's rotor (H = 0.0754 N m s, 600 Hz nutation), body at rest, started on the steady
// precession at th0 (so no nutation is excited), one second of T_out = 0.5 H.
PrecessionRun run_outer_torque_precession(double dt) {
  const GyroModelConfig<double> c = seeker_rotor(TorquerAxes::kGimbal);
  const double spin_hz = 300;
  const double h = 2 * kPi<double> * spin_hz * c.spin_inertia;
  const double k = 0.5;  // T_out / H, rad/s
  const double th0 = 0.5;
  GyroModel<double> g;
  EXPECT_TRUE(g.configure(c).ok());
  EXPECT_EQ(g.uncage(Matrix3<double>::Identity(), Vector2<double>(-k / std::cos(th0), 0), Vector2<double>(th0, 0)),
            Status::kOk);
  GyroStepInput<double> in;
  in.dt_s = dt;
  in.spin_hz = spin_hz;
  const Vector2<double> torquers(0, k * h);
  PrecessionRun r;
  const long steps = std::lround(1.0 / dt);
  for (long i = 1; i <= steps; ++i) {
    if (g.step_torque(in, torquers) != Status::kOk) {
      ADD_FAILURE() << "step " << i;
      break;
    }
    const double pitch = std::asin(std::sin(th0) - k * static_cast<double>(i) * dt);
    const double yaw = c.pitch_inertia * k / (2 * h) * (1 / std::pow(std::cos(pitch), 2) - 1 / std::pow(std::cos(th0), 2));
    r.worst_pitch_error_rad = std::max(r.worst_pitch_error_rad, std::abs(g.gimbal_pitch_rad() - pitch));
    r.worst_yaw_error_rad = std::max(r.worst_yaw_error_rad, std::abs(g.gimbal_yaw_rad() - yaw));
  }
  r.final_pitch_rad = g.gimbal_pitch_rad();
  r.final_yaw_rad = g.gimbal_yaw_rad();
  return r;
}

TEST(GyroModelGimbalPrecession, GivenAnOuterTorqueWhenThePitchSweepsThenSinPitchFallsAtTOverHToSecondOrder) {
  GYRO_VERIFIES("MODEL-5", "PORT-3");
  const PrecessionRun coarse = run_outer_torque_precession(2e-3);
  const PrecessionRun fine = run_outer_torque_precession(1e-3);
  // The sweep: from 0.5 rad to asin(sin 0.5 - 0.5) = -0.021 rad, the lever 1 / cos th from
  // 1.14 down to 1; the yaw the transverse inertia leaves, -2.0e-5 rad at the end.
  EXPECT_NEAR(fine.final_pitch_rad, -0.020576, 1e-6);
  EXPECT_NEAR(fine.final_yaw_rad, -1.976e-5, 2e-8);
  EXPECT_LT(fine.worst_pitch_error_rad, 1e-7);
  EXPECT_LT(fine.worst_yaw_error_rad, 2e-8);
  // At least second order in the step: halving it divides the error by four or more.
  EXPECT_GT(coarse.worst_pitch_error_rad / fine.worst_pitch_error_rad, 3.5)
      << coarse.worst_pitch_error_rad << " " << fine.worst_pitch_error_rad;
}

// The report's torquers (kGyro) need no gimbal frame to step, but the model still reads it out
// (rate_on_gimbal_rad_s, gimbal_frame_now) and resolves gimbal corrections with it: it must be
// the frame of the last step, not of the uncaging. A gyro at rest on a body that rolls about
// the spin axis: the gyro's axes do not roll, the gimbal's roll with the body, so the twist
// between them is the body's roll.
TEST(GyroModelGimbalFrame, GivenTheReportsTorquersWhenTheBodyRollsAboutTheSpinAxisThenTheFrameTwistsWithIt) {
  GYRO_VERIFIES("MODEL-5");
  const GyroModelConfig<double> c = seeker_rotor(TorquerAxes::kGyro);
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  ASSERT_EQ(g.uncage(Matrix3<double>::Identity(), Vector2<double>::Zero()), Status::kOk);
  GyroStepInput<double> in;
  in.dt_s = 1e-3;
  in.spin_hz = 300;
  for (int k = 1; k <= 10; ++k) {
    const double roll = 0.07 * k;
    in.R_earth_to_body = Eigen::AngleAxis<double>(roll, Vector3<double>::UnitX()).toRotationMatrix().transpose();
    ASSERT_EQ(g.step_torque(in, Vector2<double>::Zero()), Status::kOk);
    const Matrix2<double>& twist = g.gimbal_frame_now().gimbal_to_gyro;
    EXPECT_NEAR(twist(0, 0), std::cos(roll), 1e-12) << k;
    EXPECT_NEAR(twist(0, 1), -std::sin(roll), 1e-12) << k;
  }
}

}  // namespace
}  // namespace gyro
