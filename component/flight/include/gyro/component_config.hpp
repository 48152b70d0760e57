// Validation of the component's configuration: refuses with the first bad field's name.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>

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
  struct Field {
    T value;
    const char* name;
    bool zero_allowed;  // value >= 0 when true, value > 0 otherwise
    Status refusal;
  };
  constexpr Status kRange = Status::kOutOfRange;
  const Field fields[] = {
      {c.tick_s, "tick_s", false, Status::kNonPositiveStep},
      {c.pitch_inertia, "pitch_inertia", false, Status::kNonPositiveInertia},
      {c.yaw_inertia, "yaw_inertia", false, Status::kNonPositiveInertia},
      {c.spin_inertia, "spin_inertia", false, Status::kNonPositiveInertia},
      {c.friction, "friction", true, Status::kNegativeFriction},
      {c.nominal_spin_hz, "nominal_spin_hz", false, kRange},
      {c.min_spin_hz, "min_spin_hz", true, kRange},
      {c.max_pitch_rate_rad_s, "max_pitch_rate_rad_s", false, kRange},
      {c.max_yaw_rate_rad_s, "max_yaw_rate_rad_s", false, kRange},
      {c.max_torque, "max_torque", false, kRange},
      {c.cage_gain_1_s, "cage_gain_1_s", true, kRange},
      {c.gimbal_cone_limit_rad, "gimbal_cone_limit_rad", false, kRange},
      {c.gimbal_stop_margin_rad, "gimbal_stop_margin_rad", true, kRange},
      {c.small_angle_limit_rad, "small_angle_limit_rad", false, kRange},
      {c.pickoff_range_rad, "pickoff_range_rad", false, kRange},
      {c.max_pickoff_step_rad, "max_pickoff_step_rad", false, kRange},
      {c.estimator_gain, "estimator_gain", true, kRange},
      {c.residual_limit_rad, "residual_limit_rad", false, kRange},
      {c.max_body_rate_rad_s, "max_body_rate_rad_s", false, kRange},
  };
  for (const Field& f : fields) {
    if (!std::isfinite(f.value)) return {Status::kNonFiniteInput, f.name};
    if (f.zero_allowed ? !(f.value >= T(0)) : !(f.value > T(0))) return {f.refusal, f.name};
  }
  if (!(c.min_spin_hz < c.nominal_spin_hz)) return {Status::kOutOfRange, "min_spin_hz"};
  // The caging loop is a discrete first-order loop: gain * tick <= 1 keeps it monotone.
  if (c.cage_gain_1_s * c.tick_s > T(1)) return {Status::kOutOfRange, "cage_gain_1_s"};
  if (!(c.gimbal_cone_limit_rad <= kPi<T> / T(2))) return {Status::kOutOfRange, "gimbal_cone_limit_rad"};
  if (!(c.gimbal_stop_margin_rad < c.gimbal_cone_limit_rad)) return {Status::kOutOfRange, "gimbal_stop_margin_rad"};
  if (c.estimator_gain > T(1)) return {Status::kOutOfRange, "estimator_gain"};
  struct Count {
    std::uint32_t value;
    const char* name;
  };
  const Count counts[] = {
      {c.residual_persistence_ticks, "residual_persistence_ticks"},
      {c.invalid_persistence_ticks, "invalid_persistence_ticks"},
      {c.spin_low_persistence_ticks, "spin_low_persistence_ticks"},
      {c.torquer_fail_persistence_ticks, "torquer_fail_persistence_ticks"},
      {c.input_persistence_ticks, "input_persistence_ticks"},
      {c.max_tick_gap, "max_tick_gap"},
  };
  const Count* const zero = std::find_if(std::begin(counts), std::end(counts),
                                         [](const Count& n) noexcept { return n.value == 0u; });
  if (zero != std::end(counts)) return {Status::kOutOfRange, zero->name};
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
