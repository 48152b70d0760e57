// The gimbal stop: a rigid contact on the total cone angle between spin axis and body x,
//   g(theta, psi) = cos theta cos psi - cos stop >= 0.
// Resolved at the end of each sub-step that ends beyond it (docs/gimbal-plant.md):
//   position  the spin axis is put back on the cone at the same clock angle about body x;
//   velocity  if the gimbals still move outward (g' < 0), an impulse along M^-1 grad g (the
//             joints' own inertia, spin included) turns g' into -e g' (restitution e).
// The impulse acts on the joints only, none about the spin axis: the rotor's inertial spin is
// kept, its spin relative to the inner gimbal changes by sin(theta) times the yaw rate's.
#pragma once

#include <cmath>

#include "gyro/gimbal_kinematics.hpp"

namespace gyro {

template <typename T>
struct GimbalStop {
  T cos_stop{T(1)};
  T sin_stop{};
  T restitution{};
};

template <typename T>
[[nodiscard]] GimbalStop<T> make_gimbal_stop(T stop_cone_rad, T restitution) noexcept {
  return GimbalStop<T>{std::cos(stop_cone_rad), std::sin(stop_cone_rad), restitution};
}

// True if `s` was beyond the stop; then it is moved onto it as above.
template <typename T>
[[nodiscard]] bool resolve_gimbal_stop(const GimbalStop<T>& stop, const GimbalInertias<T>& j,
                                       GimbalJointState<T>& s) noexcept {
  const GimbalFrames<T> f = gimbal_frames(s.pitch_rad, s.yaw_rad);
  if (f.cp * f.cy >= stop.cos_stop) return false;

  // Back onto the cone at the same clock angle: spin axis (cos stop, sin stop (y, z)/|(y, z)|).
  const Vector3<T> axis = spin_axis_in_body(f);
  const T rho = std::hypot(axis(1), axis(2));
  T uy = T(1), uz = T(0);  // spin axis straight back (cone 180 deg): leave it to the right
  if (rho > T(0)) {
    uy = axis(1) / rho;
    uz = axis(2) / rho;
  }
  const T x = stop.cos_stop, y = stop.sin_stop * uy, z = stop.sin_stop * uz;
  s.pitch_rad = std::asin(-z);
  s.yaw_rad = std::atan2(y, x);
  const T cp = std::hypot(x, y), sp = -z;  // cos theta >= cos stop > 0
  const T cy = x / cp, sy = y / cp;

  // Outward rate and the impulse that reverses it.
  const T n_pitch = -sp * cy, n_yaw = -cp * sy;  // grad g
  const T g_rate = n_pitch * s.pitch_rate_rad_s + n_yaw * s.yaw_rate_rad_s;
  if (g_rate < T(0)) {
    const T m_pitch = j.inner(1) + j.rotor(1);
    const T d = j.outer(2) + j.inner(0) * sp * sp + (j.inner(2) + j.rotor(1)) * cp * cp;
    const T lambda = -(T(1) + stop.restitution) * g_rate / (n_pitch * n_pitch / m_pitch + n_yaw * n_yaw / d);
    const T d_yaw_rate = lambda * n_yaw / d;
    s.pitch_rate_rad_s += lambda * n_pitch / m_pitch;
    s.yaw_rate_rad_s += d_yaw_rate;
    s.spin_rate_rad_s += sp * d_yaw_rate;
  }
  return true;
}

}  // namespace gyro
