// Equations of motion of the two-axis gimbal with a prescribed body motion (Kane's form, each
// body in its own frame; derivation in docs/gimbal-plant.md, checked against Lagrange's
// equations derived symbolically by tests/gimbal_lagrange_check.py).
//
// Speeds u = (theta', psi', phi'). Each body's angular velocity is sum_j u_bj u_j + (terms
// without u'), its angular acceleration sum_j u_bj u_j' + a_b0, and
//   M u' = Q - sum_b u_bj . (J_b a_b0 + W_b x J_b W_b)
// with the partial angular velocities u_bj (in inner axes: theta -> y, psi -> (-sin th, 0,
// cos th), phi -> x for the rotor). M is sparse:
//   [ Iy + A        0                                 0      ]
//   [ 0      Oz + (Ix + J0) s^2 + (Iz + A) c^2     -J0 s    ]   s, c = sin, cos theta
//   [ 0             -J0 s                             J0     ]
// so theta'' is one division and (psi'', phi'') a 2x2 with determinant J0 D,
// D = Oz + Ix s^2 + (Iz + A) c^2 > 0 below gimbal lock (the stop keeps |theta| <= 80 deg).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyro/gimbal_kinematics.hpp"
#include "gyro/gimbal_plant_config.hpp"

namespace gyro {

// What the equations need from a configuration, folded once (and what they would otherwise
// recompute at every evaluation).
template <typename T>
struct GimbalParameters {
  GimbalInertias<T> inertia{};
  Vector2<T> friction{Vector2<T>::Zero()};  // viscous (pitch/inner, yaw/outer)
  Vector2<T> coulomb{Vector2<T>::Zero()};   // dry friction magnitudes
  T inv_coulomb_scale{};                    // 1 / coulomb_rate_scale_rad_s
  SpinDrive spin_drive{SpinDrive::kMotor};
  T motor_torque_limit{};
  T servo_bandwidth{};
  T spin_drag{};                            // J0 / spin_down_time_s, or 0
  T mass_unbalance{};
  TorquerAxes torquer_axes{TorquerAxes::kGimbal};
  T pitch_inertia{};                        // Iy + A: the pitch row of M
  T inner_z_inertia{};                      // Iz + A: in D
  Vector3<T> inner_gyroscopic{Vector3<T>::Zero()};  // (Iz - Iy, Ix - Iz, Iy - Ix): W x J W
  T rotor_gyroscopic{};                     // J0 - A: the rotor's W x J W (axisymmetric)
};

template <typename T>
[[nodiscard]] GimbalParameters<T> make_gimbal_parameters(const GimbalPlantConfig<T>& c) noexcept {
  GimbalParameters<T> p;
  p.inertia.outer = c.outer_gimbal_inertia;
  p.inertia.inner = c.inner_gimbal_inertia;
  p.inertia.rotor = Vector3<T>(c.spin_inertia, c.rotor_transverse_inertia, c.rotor_transverse_inertia);
  p.friction = Vector2<T>(c.inner_friction, c.outer_friction);
  p.coulomb = Vector2<T>(c.inner_coulomb_torque, c.outer_coulomb_torque);
  p.inv_coulomb_scale = T(1) / c.coulomb_rate_scale_rad_s;
  p.spin_drive = c.spin_drive;
  p.motor_torque_limit = c.motor_torque_limit;
  p.servo_bandwidth = c.spin_servo_bandwidth_rad_s;
  p.spin_drag = c.spin_down_time_s > T(0) ? c.spin_inertia / c.spin_down_time_s : T(0);
  p.mass_unbalance = c.mass_unbalance;
  p.torquer_axes = c.torquer_axes;
  p.pitch_inertia = c.inner_gimbal_inertia(1) + c.rotor_transverse_inertia;
  p.inner_z_inertia = c.inner_gimbal_inertia(2) + c.rotor_transverse_inertia;
  const Vector3<T>& i = c.inner_gimbal_inertia;
  p.inner_gyroscopic = Vector3<T>(i(2) - i(1), i(0) - i(2), i(1) - i(0));
  p.rotor_gyroscopic = c.spin_inertia - c.rotor_transverse_inertia;
  return p;
}

// The body's motion at one instant, body axes.
template <typename T>
struct BodyInstant {
  Vector3<T> rate_rad_s{Vector3<T>::Zero()};       // w = (p, q, r)
  Vector3<T> rate_dot_rad_s2{Vector3<T>::Zero()};  // dw/dt (the same in body and inertial axes)
  Vector3<T> specific_force{Vector3<T>::Zero()};   // what an accelerometer at the centre reads
};

// What drives the joints over a step.
template <typename T>
struct GimbalDrive {
  Vector2<T> torque{Vector2<T>::Zero()};  // (T1 pitch/inner axis, T2 yaw/outer axis)
  T spin_command_rad_s{};                 // kMotor: the relative spin the motor holds
};

template <typename T>
struct GimbalAccelerations {
  T pitch_acc{}, yaw_acc{}, spin_acc{};  // theta'', psi'', phi''
  T twist_rate{};                        // chi'
  T motor_torque{};                      // on the rotor about the spin axis
  bool motor_saturated{false};
  // Power of each generalised force, sum_j Q_j u_j: with the body at rest their sum is the
  // rate of change of the kinetic energy.
  T torquer_power{}, friction_power{}, spin_power{}, unbalance_power{};
};

namespace gimbal_detail {

// tanh(x) from one expm1 (the library's tanh calls it and more): within rounding of it, and
// exactly +-1 where tanh rounds to it (|x| > 20 in double, 10 in float).
template <typename T>
[[nodiscard]] T smooth_sign(T x) noexcept {
  const T a = std::abs(x);
  if (a > T(sizeof(T) == 4 ? 10 : 20)) return std::copysign(T(1), x);  // NaN goes on to expm1
  const T e = std::expm1(T(2) * a);
  return std::copysign(e / (e + T(2)), x);
}

// Viscous plus regularised dry friction; the tanh is skipped for a bearing configured without
// dry friction (a configuration constant: every tick still costs the same).
template <typename T>
[[nodiscard]] T bearing_friction(T rate, T viscous, T coulomb, T inv_scale) noexcept {
  const T viscous_part = -viscous * rate;
  return coulomb > T(0) ? viscous_part - coulomb * smooth_sign(rate * inv_scale) : viscous_part;
}

// Generalised forces (theta, psi) of a torque on the inner gimbal (its reaction on the body,
// whose motion is prescribed, does no work in the equations): its y component, and its
// component along the yaw axis.
template <typename T>
[[nodiscard]] Vector2<T> on_joints(const GimbalFrames<T>& f, const Vector3<T>& torque_inner) noexcept {
  return Vector2<T>(torque_inner(1), f.yaw_axis_in_inner().dot(torque_inner));
}

}  // namespace gimbal_detail

// Whether an evaluation also gives the powers of the generalised forces (the energy
// bookkeeping): the integration needs only the accelerations.
enum class GimbalPowers : std::uint8_t { kSkip = 0, kCompute };

// theta'', psi'', phi'' (and the motor torque, the twist rate and, when asked, the powers) at
// one instant, with the frames at the state's angles given. An effect the configuration leaves
// out (unbalance, dry friction, the gyro's torque axes) costs nothing.
template <typename T>
[[nodiscard]] GimbalAccelerations<T> gimbal_accelerations(const GimbalParameters<T>& prm, const GimbalJointState<T>& s,
                                                          const GimbalFrames<T>& f, const GimbalDrive<T>& drive,
                                                          const BodyInstant<T>& body, GimbalPowers powers) noexcept {
  using gimbal_detail::bearing_friction;
  using gimbal_detail::on_joints;
  const GimbalInertias<T>& j = prm.inertia;
  const T th_d = s.pitch_rate_rad_s, ps_d = s.yaw_rate_rad_s, ph_d = s.spin_rate_rad_s;
  const GimbalBodyRates<T> w = gimbal_body_rates(f, s, body.rate_rad_s);

  // a_b0: each body's angular acceleration with the joint accelerations set to zero. The body
  // rate in outer axes and W_O in inner axes differ from W_O and W_I only in the components
  // the joint rates add to (z and y), which these terms do not use.
  Vector3<T> a_outer = f.body_to_outer(body.rate_dot_rad_s2);
  a_outer(0) += ps_d * w.outer(1);  // psi' (w x z)
  a_outer(1) -= ps_d * w.outer(0);
  Vector3<T> a_inner = f.outer_to_inner(a_outer);
  a_inner(0) -= th_d * w.inner(2);  // theta' (W_O x y)
  a_inner(2) += th_d * w.inner(0);
  // a_R0 = a_I0 + phi' (W_I x x); its x component is a_I0's.
  const T a_rotor_y = a_inner(1) + ph_d * w.inner(2);
  const T a_rotor_z = a_inner(2) - ph_d * w.inner(1);

  // J_b a_b0 + W_b x J_b W_b for the outer gimbal (z needed) and inner gimbal plus rotor, the
  // cross products written out for diagonal inertias (the rotor's axisymmetric).
  const T outer_z = j.outer(2) * a_outer(2) + (j.outer(1) - j.outer(0)) * w.outer(0) * w.outer(1);
  const Vector3<T>& wi = w.inner;
  const Vector3<T>& gi = prm.inner_gyroscopic;
  const T rotor_wx = w.rotor(0);
  const T assembly_x = j.inner(0) * a_inner(0) + gi(0) * wi(1) * wi(2) + j.rotor(0) * a_inner(0);
  const T assembly_y = j.inner(1) * a_inner(1) + gi(1) * wi(2) * wi(0) + j.rotor(1) * a_rotor_y +
                       prm.rotor_gyroscopic * rotor_wx * wi(2);
  const T assembly_z = j.inner(2) * a_inner(2) + gi(2) * wi(0) * wi(1) + j.rotor(1) * a_rotor_z -
                       prm.rotor_gyroscopic * rotor_wx * wi(1);

  // Generalised forces on (theta, psi).
  Vector2<T> q_torquer, q_friction;
  if (prm.torquer_axes == TorquerAxes::kGimbal) {
    q_torquer = drive.torque;
    q_friction = Vector2<T>(bearing_friction(th_d, prm.friction(0), prm.coulomb(0), prm.inv_coulomb_scale),
                            bearing_friction(ps_d, prm.friction(1), prm.coulomb(1), prm.inv_coulomb_scale));
  } else {
    // The gyro's non-rolling pitch and yaw axes: the inner gimbal's y, z turned by chi about x.
    const T sc = std::sin(s.twist_rad), cc = std::cos(s.twist_rad);
    const Vector3<T> y_gyro(T(0), cc, sc), z_gyro(T(0), -sc, cc);
    const T w1 = w.inner.dot(y_gyro), w2 = w.inner.dot(z_gyro);
    q_torquer = on_joints(f, Vector3<T>(drive.torque(0) * y_gyro + drive.torque(1) * z_gyro));
    const T fr1 = bearing_friction(w1, prm.friction(0), prm.coulomb(0), prm.inv_coulomb_scale);
    const T fr2 = bearing_friction(w2, prm.friction(1), prm.coulomb(1), prm.inv_coulomb_scale);
    q_friction = on_joints(f, Vector3<T>(fr1 * y_gyro + fr2 * z_gyro));
  }
  // Unbalance: -m d x_I x f on the rotor = m d (0, f_z, -f_y) in inner axes: on the joints
  // (m d f_z, -cos(theta) m d f_y).
  Vector2<T> q_unbalance = Vector2<T>::Zero();
  if (prm.mass_unbalance != T(0)) {
    const Vector3<T> f_inner = f.outer_to_inner(f.body_to_outer(body.specific_force));
    q_unbalance = Vector2<T>(prm.mass_unbalance * f_inner(2), -f.cp * prm.mass_unbalance * f_inner(1));
  }
  const T drag = -prm.spin_drag * ph_d;

  const T b_pitch = q_torquer(0) + q_friction(0) + q_unbalance(0) - assembly_y;
  const T b_yaw = q_torquer(1) + q_friction(1) + q_unbalance(1) - outer_z + f.sp * assembly_x - f.cp * assembly_z;
  const T b_spin = drag - j.rotor(0) * a_inner(0);  // (W_R x J_R W_R) . x = 0 (axisymmetric)

  GimbalAccelerations<T> out;
  out.pitch_acc = b_pitch / prm.pitch_inertia;
  const T s2 = f.sp * f.sp, c2 = f.cp * f.cp;
  const T d = j.outer(2) + j.inner(0) * s2 + prm.inner_z_inertia * c2;  // det / J0
  bool free_spin = prm.spin_drive == SpinDrive::kFree;
  if (!free_spin) {
    const T spin_acc = prm.servo_bandwidth * (drive.spin_command_rad_s - ph_d);
    const T yaw_acc = (b_yaw + j.rotor(0) * f.sp * spin_acc) / (d + j.rotor(0) * s2);
    const T needed = j.rotor(0) * (spin_acc - f.sp * yaw_acc) - b_spin;
    if (std::abs(needed) <= prm.motor_torque_limit) {
      out.yaw_acc = yaw_acc;
      out.spin_acc = spin_acc;
      out.motor_torque = needed;
    } else {
      out.motor_torque = std::copysign(prm.motor_torque_limit, needed);
      out.motor_saturated = true;
      free_spin = true;
    }
  }
  if (free_spin) {
    const T b = b_spin + out.motor_torque;
    out.yaw_acc = (b_yaw + f.sp * b) / d;
    out.spin_acc = b / j.rotor(0) + f.sp * out.yaw_acc;
  }
  out.twist_rate = -w.inner(0);
  if (powers == GimbalPowers::kCompute) {
    const Vector2<T> rates(th_d, ps_d);
    out.torquer_power = q_torquer.dot(rates);
    out.friction_power = q_friction.dot(rates);
    out.spin_power = (out.motor_torque + drag) * ph_d;
    out.unbalance_power = q_unbalance.dot(rates);
  }
  return out;
}

// The same with the frames computed from the state's angles, and the powers.
template <typename T>
[[nodiscard]] GimbalAccelerations<T> gimbal_accelerations(const GimbalParameters<T>& prm, const GimbalJointState<T>& s,
                                                          const GimbalDrive<T>& drive,
                                                          const BodyInstant<T>& body) noexcept {
  return gimbal_accelerations(prm, s, gimbal_frames(s.pitch_rad, s.yaw_rad), drive, body, GimbalPowers::kCompute);
}

}  // namespace gyro
