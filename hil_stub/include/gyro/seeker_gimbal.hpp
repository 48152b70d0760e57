// The seeker example (gyro/seeker_example.hpp) as a device for the gimbal plant: a rotor of
// J0 = 3e-5, A = 1.6e-5 kg m^2 (a disc with some axial length: J0 <= 2A) on gimbal rings of a
// few e-6 kg m^2, chosen so that the effective inertias at zero gimbal angles are the
// example's J1 = J2 = 2e-5 (pitch: Iy + A; yaw: Oz + Iz + A), with its friction 4e-4 N m s on
// each bearing and its 400 Hz spin held by a motor. The component's configuration stays
// valid for it; the model error left is what the plant is for.
#pragma once

#include "gyro/gimbal_plant_config.hpp"
#include "gyro/seeker_example.hpp"

namespace gyro {

template <typename T>
[[nodiscard]] GimbalPlantConfig<T> seeker_gimbal_config() noexcept {
  using S = SeekerExample<T>;
  const T transverse = T(1.6e-5);
  const T ring = (S::kJ - transverse) / T(2);  // 2e-6: the inner ring's x and z, the outer's z
  GimbalPlantConfig<T> c;
  c.spin_inertia = S::kJ0;
  c.rotor_transverse_inertia = transverse;
  // Thin rings: the inner ring in its x-z plane (Iy = Ix + Iz), the outer in its y-z plane.
  c.inner_gimbal_inertia = Vector3<T>(ring, S::kJ - transverse, ring);
  c.outer_gimbal_inertia = Vector3<T>(T(2) * ring, ring, ring);
  c.inner_friction = S::kFriction;
  c.outer_friction = S::kFriction;
  c.spin_drive = SpinDrive::kMotor;
  c.max_spin_hz = S::kSpinHz;
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

}  // namespace gyro
