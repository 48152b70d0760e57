// The example seeker gyro's flight-side configuration: the component's constants and
// GyroComponentConfig, with component/ headers only, so that a flight image can start from it
// without the SIL stub (gyro::examples). SeekerExample (gyro/seeker_example.hpp) adds the
// stub's and the gimbal plant's configurations of the same gyro.
//   J1 = J2 = 2e-5 kg m^2, J0 = 3e-5 kg m^2, spin 400 Hz (H = 0.0754 N m s),
//   f = 4e-4 N m s (alpha = f/J = 20 1/s: nutation decays in 50 ms), 600 Hz nutation,
//   2 kHz tick (more than two ticks per nutation period).
#pragma once

#include "gyro/component_types.hpp"

namespace gyro {

template <typename T>
struct SeekerComponentExample {
  static constexpr T kTick = T(5e-4);
  static constexpr T kJ = T(2e-5);
  static constexpr T kJ0 = T(3e-5);
  static constexpr T kFriction = T(4e-4);
  static constexpr T kSpinHz = T(400);

  static GyroComponentConfig<T> component() noexcept {
    GyroComponentConfig<T> c;
    c.tick_s = kTick;
    c.pitch_inertia = kJ;
    c.yaw_inertia = kJ;
    c.spin_inertia = kJ0;
    c.friction = kFriction;
    c.nominal_spin_hz = kSpinHz;
    c.min_spin_hz = T(300);
    c.max_pitch_rate_rad_s = T(1);
    c.max_yaw_rate_rad_s = T(1);
    c.max_torque = T(0.1);  // 1.3 rad/s of precession
    c.cage_gain_1_s = T(20);
    c.gimbal_cone_limit_rad = T(0.5);
    c.gimbal_stop_margin_rad = T(0.05);
    c.pickoff_range_rad = T(0.6);
    c.max_pickoff_step_rad = T(5e-3);
    c.estimator_gain = T(0.005);
    c.residual_limit_rad = T(2e-3);
    c.residual_persistence_ticks = 20;
    c.invalid_persistence_ticks = 10;
    c.spin_low_persistence_ticks = 50;
    c.torquer_fail_persistence_ticks = 5;
    c.uncage_settle_ticks = 400;
    return c;
  }
};

}  // namespace gyro
