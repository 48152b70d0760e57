// Validation of the component's configuration: refuses with the first bad field's name.
#pragma once

#include <cmath>

#include "gyro/component_types.hpp"
#include "gyro/exact_step_check.hpp"
#include "gyro/gyro_model.hpp"

namespace gyro {

// The nominal rotor has a finite exact step over a tick; a refusal names the field responsible.
template <typename T>
[[nodiscard]] ConfigCheck check_nominal_step(const GyroComponentConfig<T>& c) noexcept {
  constexpr ExactStepFields kFields{"pitch_inertia", "yaw_inertia", "spin_inertia",
                                    "friction",      "nominal_spin_hz", "tick_s"};
  return check_exact_step(c.pitch_inertia, c.yaw_inertia, c.spin_inertia, c.friction, c.nominal_spin_hz, c.tick_s,
                          kFields);
}

template <typename T>
[[nodiscard]] ConfigCheck check(const GyroComponentConfig<T>& c) noexcept {
  const FieldRefusal real = first_refusal<RealFields>(c);
  if (real.status != Status::kOk) return {real.status, real.field};
  if (!(c.min_spin_hz < c.nominal_spin_hz)) return {Status::kOutOfRange, "min_spin_hz"};
  // The caging loop is a discrete first-order loop: gain * tick <= 1 keeps it monotone.
  if (c.cage_gain_1_s * c.tick_s > T(1)) return {Status::kOutOfRange, "cage_gain_1_s"};
  if (!(c.gimbal_cone_limit_rad <= kPi<T> / T(2))) return {Status::kOutOfRange, "gimbal_cone_limit_rad"};
  if (!(c.gimbal_stop_margin_rad < c.gimbal_cone_limit_rad)) return {Status::kOutOfRange, "gimbal_stop_margin_rad"};
  if (c.estimator_gain > T(1)) return {Status::kOutOfRange, "estimator_gain"};
  const FieldRefusal count = first_refusal<CountFields>(c);
  if (count.status != Status::kOk) return {count.status, count.field};
  return check_nominal_step(c);
}

// The exact-dynamics model the component predicts with: the configured rotor, its limits,
// the torquers and bearings on the gimbal axes, no error sources (those are the hardware's,
// to be caught by the residual).
template <typename T>
[[nodiscard]] GyroModelConfig<T> estimator_config(const GyroComponentConfig<T>& c) noexcept {
  GyroModelConfig<T> m;
  m.pitch_inertia = c.pitch_inertia;
  m.yaw_inertia = c.yaw_inertia;
  m.spin_inertia = c.spin_inertia;
  m.friction = c.friction;
  m.gimbal_cone_limit_rad = c.gimbal_cone_limit_rad;
  m.max_pitch_rate_rad_s = c.max_pitch_rate_rad_s;
  m.max_yaw_rate_rad_s = c.max_yaw_rate_rad_s;
  m.small_angle_limit_rad = c.small_angle_limit_rad;
  m.torquer_axes = TorquerAxes::kGimbal;
  return m;
}

}  // namespace gyro
