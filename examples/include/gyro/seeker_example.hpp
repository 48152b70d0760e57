// A small SI seeker gyro, configured for the component and for the SIL stub alike: the
// example the tests, the firmware images and the fuzzers start from.
//   J1 = J2 = 2e-5 kg m^2, J0 = 3e-5 kg m^2, spin 400 Hz (H = 0.0754 N m s),
//   f = 4e-4 N m s (alpha = f/J = 20 1/s: nutation decays in 50 ms), 600 Hz nutation,
//   2 kHz tick (more than two ticks per nutation period).
#pragma once

#include "gyro/component_types.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {

template <typename T>
struct SeekerExample {
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

  // The hardware as designed: the gimbal plant, no imperfections, spin readback on, a stop
  // beyond the cone. (Its `gyro` fields describe the same rotor for the report's plant.)
  static SimulatedGyroConfig<T> stub() noexcept {
    SimulatedGyroConfig<T> s;
    s.plant = PlantKind::kGimbal;
    s.gimbal = gimbal();
    s.gyro.pitch_inertia = kJ;
    s.gyro.yaw_inertia = kJ;
    s.gyro.spin_inertia = kJ0;
    s.gyro.friction = kFriction;
    s.gyro.gimbal_cone_limit_rad = T(0.5);
    s.gyro.max_pitch_rate_rad_s = T(10);
    s.gyro.max_yaw_rate_rad_s = T(10);
    s.tick_s = kTick;
    s.spin_hz = kSpinHz;
    s.has_spin_readback = true;
    s.gimbal_stop_rad = T(0.55);
    s.seed = 1;
    return s;
  }

  // The same seeker as a device for the gimbal plant (gyro/gimbal_plant.hpp): a rotor of
  // J0 = 3e-5, A = 1.6e-5 kg m^2 (J0 <= 2A) on gimbal rings of a few e-6 kg m^2, chosen so
  // that the effective inertias at zero gimbal angles are J1 = J2 = 2e-5 (pitch: Iy + A; yaw:
  // Oz + Iz + A), friction 4e-4 N m s on each bearing, the 400 Hz spin held by a motor.
  static GimbalPlantConfig<T> gimbal() noexcept {
    const T transverse = T(1.6e-5);
    const T ring = (kJ - transverse) / T(2);  // 2e-6: the inner ring's x and z, the outer's z
    GimbalPlantConfig<T> c;
    c.spin_inertia = kJ0;
    c.rotor_transverse_inertia = transverse;
    // Thin rings: the inner ring in its x-z plane (Iy = Ix + Iz), the outer in its y-z plane.
    c.inner_gimbal_inertia = Vector3<T>(ring, kJ - transverse, ring);
    c.outer_gimbal_inertia = Vector3<T>(T(2) * ring, ring, ring);
    c.inner_friction = kFriction;
    c.outer_friction = kFriction;
    c.spin_drive = SpinDrive::kMotor;
    c.max_spin_hz = kSpinHz;
    c.motor_torque_limit = T(0.01);         // 30x what 100 rad/s^2 of body roll acceleration takes
    c.spin_servo_bandwidth_rad_s = T(5);    // the spin loop recovers in about 0.2 s
    c.spin_down_time_s = T(60);             // free-running, the rotor runs down in a minute
    c.stop_cone_rad = T(0.55);              // as the SIL stub's stop (SeekerExample::stub())
    c.stop_restitution = T(0.2);
    c.torque_axes = TorqueAxes::kGimbal;
    c.max_body_rate_rad_s = T(40);          // roll up to 6 Hz
    c.max_torque = T(1);                    // 10x the component's torque limit
    c.max_specific_force = T(1e4);          // 1000 g
    c.max_substep_phase_rad = T(0.5);
    return c;
  }
};

}  // namespace gyro
