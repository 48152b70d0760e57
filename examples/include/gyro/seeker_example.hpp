// A small SI seeker gyro, configured for the component and for the SIL stub alike: the
// example the tests, the fuzzers and the SIL firmware images start from. The component's
// part is gyro/seeker_component_example.hpp (flight-side, no SIL code); this header adds the
// stub's and the gimbal plant's configurations of the same gyro.
#pragma once

#include "gyro/seeker_component_example.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {

template <typename T>
struct SeekerExample : SeekerComponentExample<T> {
  using Base = SeekerComponentExample<T>;
  using Base::kFriction;
  using Base::kJ;
  using Base::kJ0;
  using Base::kSpinHz;
  using Base::kTick;

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
    c.torquer_axes = TorquerAxes::kGimbal;
    c.max_body_rate_rad_s = T(40);          // roll up to 6 Hz
    c.max_torque = T(1);                    // 10x the component's torque limit
    c.max_specific_force = T(1e4);          // 1000 g
    c.max_substep_phase_rad = T(0.5);
    return c;
  }
};

}  // namespace gyro
