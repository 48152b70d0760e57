// The gimbal plant in the limit where the device becomes the report's gyro: no gimbal
// inertia, torques and friction about the gyro's own non-rolling axes (TorquerAxes::kGyro) on
// its inertial rates, a free rotor. There the plant and GyroModel (the report's exact linear
// step, component/report/include/gyro/gyro_model.hpp) solve the same motion, the model with the
// torque held in each step's frame and the step's rotation composed per step: their gimbal
// angles must agree to the model's step discretisation, second order in the step.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gyro/gyro_model.hpp"
#include "support/gimbal_support.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

using namespace gimbal_test;
using V2 = Vector2<double>;
using V3 = Vector3<double>;
using M3 = Matrix3<double>;

constexpr double kJ0 = 3e-5, kA = 2e-5, kFriction = 4e-4, kSpinHz = 400.0;

GimbalPlantConfig<double> report_limit_plant() {
  GimbalPlantConfig<double> c = seeker_gimbal_config<double>();
  c.spin_inertia = kJ0;
  c.rotor_transverse_inertia = kA;
  c.inner_gimbal_inertia.setZero();
  c.outer_gimbal_inertia.setZero();
  c.inner_friction = kFriction;
  c.outer_friction = kFriction;
  c.spin_drive = SpinDrive::kFree;
  c.spin_down_time_s = 0.0;
  c.spin_servo_bandwidth_rad_s = 0.0;
  c.torquer_axes = TorquerAxes::kGyro;
  c.stop_cone_rad = 1.2;
  c.max_substep_phase_rad = 0.25;  // its own error far below the model's (docs/gimbal-plant.md)
  return c;
}

GyroModelConfig<double> report_model() {
  GyroModelConfig<double> c;
  c.pitch_inertia = kA;
  c.yaw_inertia = kA;
  c.spin_inertia = kJ0;
  c.friction = kFriction;
  c.gimbal_cone_limit_rad = 1.2;
  c.max_pitch_rate_rad_s = 10.0;
  c.max_yaw_rate_rad_s = 10.0;
  return c;
}

// Worst gimbal-angle difference over 1 s between plant and model at step dt, the body turning
// at the constant body rate w (body axes), the gyro starting along body x with inertial rates
// (w1, w2) = (0.5, -0.3) rad/s about its pitch and yaw axes, torques (0.01, 0.005) N m held.
double worst_difference(double dt, const V3& w) {
  const V2 gyro_rate(0.5, -0.3), torque(0.01, 0.005);
  const int steps = static_cast<int>(std::lround(1.0 / dt));

  GyroModel<double> model;
  EXPECT_TRUE(model.configure(report_model()).ok());
  EXPECT_EQ(model.uncage(M3::Identity(), gyro_rate), Status::kOk);
  GyroStepInput<double> in;
  in.dt_s = dt;
  in.spin_hz = kSpinHz;

  // At zero gimbal angles the inner gimbal's inertial rate is w + (0, theta', psi'), and the
  // rotor's inertial spin is phi' + p.
  GimbalStart<double> s;
  s.gimbal_rate_rad_s = gyro_rate - V2(w(1), w(2));
  s.spin_hz = kSpinHz - w(0) / (2.0 * kPiD);
  BodyState<double> body;
  body.rate_rad_s = w;
  GimbalPlant<double> plant = started(report_limit_plant(), s, body, dt);

  double worst = 0.0;
  for (int k = 1; k <= steps; ++k) {
    // The body's attitude: a constant body rate is a rotation about a fixed axis.
    const double t = k * dt;
    const M3 body_to_earth = (w.norm() > 0.0) ? Eigen::AngleAxisd(w.norm() * t, w.normalized()).toRotationMatrix()
                                              : M3::Identity().eval();
    in.R_earth_to_body = body_to_earth.transpose();
    EXPECT_EQ(model.step_torque(in, torque), Status::kOk);
    EXPECT_EQ(plant.step(torque, body, body), Status::kOk);
    const V2 d = plant.gimbal_angle_rad() - V2(model.gimbal_pitch_rad(), model.gimbal_yaw_rad());
    worst = std::max(worst, d.cwiseAbs().maxCoeff());
  }
  return worst;
}

struct LimitCase {
  const char* name;
  V3 body_rate;
};

class GimbalReportLimit : public ::testing::TestWithParam<LimitCase> {};

TEST_P(GimbalReportLimit, GivenTheReportsDeviceWhenTheStepIsHalvedThenTheDifferenceFromGyroModelFallsFourfold) {
  GYRO_VERIFIES("STUB-1");
  const LimitCase lc = GetParam();
  const double dts[] = {2.5e-4, 1.25e-4, 6.25e-5};
  double e[3] = {};
  for (int i = 0; i < 3; ++i) e[i] = worst_difference(dts[i], lc.body_rate);
  for (int i = 0; i < 3; ++i) {
    std::printf("figure: report limit, %s, dt %.2e s: worst gimbal-angle difference %.3e rad%s", lc.name, dts[i], e[i],
                i > 0 ? "" : "\n");
    if (i > 0) std::printf(" (order %.2f)\n", std::log2(e[i - 1] / e[i]));
  }
  for (int i = 1; i < 3; ++i) {
    const double order = std::log2(e[i - 1] / e[i]);
    EXPECT_GT(order, 1.8) << "dt " << dts[i];
    EXPECT_LT(order, 2.2) << "dt " << dts[i];
  }
  EXPECT_LT(e[2], 1e-8);  // and the two are close: the same physics
}

INSTANTIATE_TEST_SUITE_P(Seeker, GimbalReportLimit,
                         ::testing::Values(LimitCase{"body at rest", V3::Zero()},
                                           LimitCase{"body rolling and turning", V3(5.0, 0.1, -0.1)}),
                         [](const ::testing::TestParamInfo<LimitCase>& i) { return std::to_string(i.index); });

}  // namespace
}  // namespace gyro
