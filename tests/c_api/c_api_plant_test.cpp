// The C API's gimbal plant (gyro_plant_d_*): the C++ GimbalPlant, bit for bit, through a
// rolling, turning body with torques on both axes; refusals change nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "c_fields.hpp"  // c/src: write_config, to fill the C struct from the C++ example
#include "gyro/gimbal_plant.hpp"
#include "gyro/gyro.h"
#include "gyro/seeker_gimbal.hpp"

namespace gyro {
namespace {

TEST(CApiPlant, GivenTheSeekerGimbalThroughARollingTurnThenItIsTheCppPlantBitForBit) {
  const GimbalPlantConfig<double> cpp = seeker_gimbal_config<double>();
  gyro_plant_config c{};
  ASSERT_TRUE(c_api::write_config(c_api::kPlantConfig, cpp, &c));
  constexpr double kTick = 1e-3;
  gyro_plant_d* p = gyro_plant_d_create();
  gyro_refusal r{};
  ASSERT_EQ(gyro_plant_d_configure(p, &c, kTick, &r), GYRO_OK) << (r.field != nullptr ? r.field : "");
  GimbalPlant<double> plant;
  ASSERT_TRUE(plant.configure(cpp, kTick).ok());

  const double angle[2] = {0.05, -0.1}, rate[2] = {0.2, 0.0}, body0[3] = {5.0, 0.1, 0.0}, force0[3] = {0, 0, -9.8};
  BodyState<double> body;
  body.rate_rad_s = Vector3<double>(body0[0], body0[1], body0[2]);
  body.specific_force = Vector3<double>(force0[0], force0[1], force0[2]);
  ASSERT_EQ(gyro_plant_d_start(p, angle, rate, 400.0, body0, force0), GYRO_OK);
  ASSERT_EQ(plant.start({Vector2<double>(angle[0], angle[1]), Vector2<double>(rate[0], rate[1]), 400.0}, body),
            Status::kOk);
  for (int k = 1; k <= 300; ++k) {
    const double t = k * kTick;
    const double torque[2] = {1e-3 * std::sin(20 * t), -5e-4};
    const double w[3] = {5.0 + t, 0.1 * std::cos(3 * t), 0.2 * t};
    BodyState<double> end = body;
    end.rate_rad_s = Vector3<double>(w[0], w[1], w[2]);
    ASSERT_EQ(gyro_plant_d_step(p, torque, w, nullptr), GYRO_OK) << k;
    ASSERT_EQ(plant.step(Vector2<double>(torque[0], torque[1]), body, end), Status::kOk) << k;
    body = end;
  }
  double a[2], w[2], axis[3];
  gyro_plant_d_gimbal(p, a, w);
  gyro_plant_d_spin_axis_body(p, axis);
  EXPECT_EQ(a[0], plant.gimbal_angle_rad()(0));
  EXPECT_EQ(a[1], plant.gimbal_angle_rad()(1));
  EXPECT_EQ(w[1], plant.gimbal_rate_rad_s()(1));
  EXPECT_EQ(axis[2], plant.spin_axis_body()(2));
  EXPECT_EQ(gyro_plant_d_cone(p), plant.cone_rad());
  EXPECT_EQ(gyro_plant_d_spin_rate(p), plant.spin_rate_rad_s());
  EXPECT_EQ(gyro_plant_d_in_contact(p), plant.in_contact() ? 1 : 0);

  // A torque beyond the plant's envelope is refused and moves nothing.
  const double too_much[2] = {10.0, 0.0};
  EXPECT_EQ(gyro_plant_d_step(p, too_much, nullptr, nullptr), GYRO_OUT_OF_RANGE);
  double a2[2], w2[2];
  gyro_plant_d_gimbal(p, a2, w2);
  EXPECT_EQ(a2[0], a[0]);
  EXPECT_EQ(w2[1], w[1]);
  gyro_plant_d_destroy(p);
}

}  // namespace
}  // namespace gyro
