// What the gimbal plant tests share (gimbal_plant_test.cpp, gimbal_invariants_test.cpp,
// gimbal_report_limit_test.cpp): the test devices, the large-nutation start, and a runner.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "gyro/gimbal_plant.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/seeker_gimbal.hpp"

namespace gyro::gimbal_test {

template <typename T>
constexpr double D(T x) noexcept {
  return static_cast<double>(x);
}

constexpr double kPiD = 3.14159265358979323846;
constexpr double kDeg = kPiD / 180.0;
constexpr double kTick = 5e-4;  // the seeker example's tick
constexpr int kTicksPerSecond = 2000;

// The seeker's device with the stop opened to 1 rad (no contact in the invariant runs) and,
// unless a test adds them, no friction, a free rotor without drag and no unbalance.
template <typename T>
GimbalPlantConfig<T> ideal_seeker() {
  GimbalPlantConfig<T> c = seeker_gimbal_config<T>();
  c.inner_friction = T(0);
  c.outer_friction = T(0);
  c.spin_drive = SpinDrive::kFree;
  c.spin_down_time_s = T(0);
  c.spin_servo_bandwidth_rad_s = T(0);
  c.stop_cone_rad = T(1);
  return c;
}

// Large nutation: a 30 deg cone (pitch 20 deg, yaw 22.9 deg) and 5 rad/s on each gimbal.
template <typename T>
GimbalStart<T> large_nutation() {
  const double pitch = 20.0 * kDeg;
  const double yaw = std::acos(std::cos(30.0 * kDeg) / std::cos(pitch));
  GimbalStart<T> s;
  s.gimbal_angle_rad = Vector2<T>(static_cast<T>(pitch), static_cast<T>(yaw));
  s.gimbal_rate_rad_s = Vector2<T>(T(5), T(5));
  s.spin_hz = SeekerExample<T>::kSpinHz;
  return s;
}

template <typename T>
GimbalPlant<T> started(const GimbalPlantConfig<T>& c, const GimbalStart<T>& s, const BodyState<T>& body = {},
                       double tick = kTick) {
  GimbalPlant<T> p;
  const ConfigCheck cc = p.configure(c, static_cast<T>(tick));
  EXPECT_TRUE(cc.ok()) << (cc.field ? cc.field : "");
  EXPECT_EQ(p.start(s, body), Status::kOk);
  return p;
}

// Steps `ticks` times with a held torque and a constant body state, calling on_tick(k, plant)
// after each; fails the test on the first refused step.
template <typename T, typename OnTick>
void run(GimbalPlant<T>& p, int ticks, const Vector2<T>& torque, const BodyState<T>& body, OnTick&& on_tick) {
  for (int k = 0; k < ticks; ++k) {
    const Status st = p.step(torque, body, body);
    ASSERT_EQ(st, Status::kOk) << "tick " << k << ": " << to_string(st);
    on_tick(k, p);
  }
}

}  // namespace gyro::gimbal_test
