// Kinematics of the two-axis gimbal: the frames, the angular velocities of its three bodies,
// and the mechanical quantities the plant reports (kinetic energy, momenta).
//
// Frames (docs/conventions.md, docs/gimbal-plant.md):
//   body B   x forward, y right, z down; angular velocity w = (p, q, r) in B
//   outer O  C_BO = Rz(psi): the yaw joint turns O about body z by psi (active)
//   inner I  C_OI = Ry(theta): the pitch joint turns I about O's y by theta (active);
//            the spin axis is I's x, in B (cos th cos ps, cos th sin ps, -sin th)
//   rotor    turns about I's x by phi relative to I (axisymmetric: phi itself never enters)
// Angular velocities, each body in its own frame (no other frame is needed):
//   outer  W_O = C_OB w + psi' z
//   inner  W_I = C_IO W_O + theta' y
//   rotor  W_R = W_I + phi' x
// Inertias are diagonal there: outer (Ox, Oy, Oz) in O, inner (Ix, Iy, Iz) in I, rotor
// (J0, A, A) in I.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "gyro/attitude.hpp"  // Vector3, Matrix3

namespace gyro {

// The generalised coordinates and speeds, and the twist of the gyro's non-rolling axes.
template <typename T>
struct GimbalJointState {
  T pitch_rad{};         // theta, the inner (pitch) joint angle = the gimbal pitch angle
  T yaw_rad{};           // psi, the outer (yaw) joint angle = the gimbal yaw angle
  T pitch_rate_rad_s{};  // theta'
  T yaw_rate_rad_s{};    // psi'
  T spin_rate_rad_s{};   // phi', the rotor's spin relative to the inner gimbal
  T twist_rad{};         // chi: the gyro's non-rolling axes turned about the spin axis from
                         // the inner gimbal's (chi' = -(W_I . x); zero at start())
};

// Sines and cosines of the joint angles, and the frame changes built from them.
template <typename T>
struct GimbalFrames {
  T sp{}, cp{T(1)};  // sin, cos of theta (pitch)
  T sy{}, cy{T(1)};  // sin, cos of psi (yaw)

  [[nodiscard]] Vector3<T> body_to_outer(const Vector3<T>& v) const noexcept {
    return Vector3<T>(cy * v(0) + sy * v(1), cy * v(1) - sy * v(0), v(2));
  }
  [[nodiscard]] Vector3<T> outer_to_body(const Vector3<T>& v) const noexcept {
    return Vector3<T>(cy * v(0) - sy * v(1), sy * v(0) + cy * v(1), v(2));
  }
  [[nodiscard]] Vector3<T> outer_to_inner(const Vector3<T>& v) const noexcept {
    return Vector3<T>(cp * v(0) - sp * v(2), v(1), sp * v(0) + cp * v(2));
  }
  [[nodiscard]] Vector3<T> inner_to_outer(const Vector3<T>& v) const noexcept {
    return Vector3<T>(cp * v(0) + sp * v(2), v(1), cp * v(2) - sp * v(0));
  }
  // The yaw (outer, body z) axis in inner-gimbal axes: the partial angular velocity of psi.
  [[nodiscard]] Vector3<T> yaw_axis_in_inner() const noexcept { return Vector3<T>(-sp, T(0), cp); }
};

template <typename T>
[[nodiscard]] GimbalFrames<T> gimbal_frames(T pitch_rad, T yaw_rad) noexcept {
  GimbalFrames<T> f;
  f.sp = std::sin(pitch_rad);
  f.cp = std::cos(pitch_rad);
  f.sy = std::sin(yaw_rad);
  f.cy = std::cos(yaw_rad);
  return f;
}

// Sine and cosine of angles near one whose sine and cosine are known: the angle-sum formula
// with the increment's Taylor series, within rounding of std::sin and std::cos for increments
// up to kNear (the first term left out is below 3e-22), the library beyond. A Runge-Kutta
// step's stages stay that close to its start: the equations then need two library calls a
// step instead of two a stage. Basic arithmetic only: the same on every machine.
template <typename T>
struct SinCosNear {
  static constexpr T kNear = T(0.03125);
  T angle{}, s{}, c{T(1)};

  [[nodiscard]] static SinCosNear at(T a) noexcept { return SinCosNear{a, std::sin(a), std::cos(a)}; }
  // (sin a, cos a) into sa, ca.
  void of(T a, T& sa, T& ca) const noexcept {
    const T d = a - angle;
    if (!(std::abs(d) <= kNear)) {
      sa = std::sin(a);
      ca = std::cos(a);
      return;
    }
    const T d2 = d * d;
    const T cd = T(1) + d2 * (T(-1.0 / 2) + d2 * (T(1.0 / 24) + d2 * (T(-1.0 / 720) + d2 * T(1.0 / 40320))));
    const T sd = d * (T(1) + d2 * (T(-1.0 / 6) + d2 * (T(1.0 / 120) + d2 * (T(-1.0 / 5040) + d2 * T(1.0 / 362880)))));
    sa = s * cd + c * sd;
    ca = c * cd - s * sd;
  }
};

// The frames at (pitch, yaw) from references near them.
template <typename T>
[[nodiscard]] GimbalFrames<T> gimbal_frames(const SinCosNear<T>& pitch, const SinCosNear<T>& yaw, T pitch_rad,
                                            T yaw_rad) noexcept {
  GimbalFrames<T> f;
  pitch.of(pitch_rad, f.sp, f.cp);
  yaw.of(yaw_rad, f.sy, f.cy);
  return f;
}

// Inertial angular velocities of the three bodies, each in its own frame.
template <typename T>
struct GimbalBodyRates {
  Vector3<T> outer{Vector3<T>::Zero()};  // W_O, outer-gimbal axes
  Vector3<T> inner{Vector3<T>::Zero()};  // W_I, inner-gimbal axes
  Vector3<T> rotor{Vector3<T>::Zero()};  // W_R, inner-gimbal axes
};

template <typename T>
[[nodiscard]] GimbalBodyRates<T> gimbal_body_rates(const GimbalFrames<T>& f, const GimbalJointState<T>& s,
                                                   const Vector3<T>& body_rate_rad_s) noexcept {
  GimbalBodyRates<T> w;
  w.outer = f.body_to_outer(body_rate_rad_s);
  w.outer(2) += s.yaw_rate_rad_s;
  w.inner = f.outer_to_inner(w.outer);
  w.inner(1) += s.pitch_rate_rad_s;
  w.rotor = w.inner;
  w.rotor(0) += s.spin_rate_rad_s;
  return w;
}

// The bodies' inertias in their own frames (diagonals).
template <typename T>
struct GimbalInertias {
  Vector3<T> outer{Vector3<T>::Zero()};  // (Ox, Oy, Oz)
  Vector3<T> inner{Vector3<T>::Zero()};  // (Ix, Iy, Iz)
  Vector3<T> rotor{Vector3<T>::Zero()};  // (J0, A, A)
};

// Angular momentum of inner gimbal plus rotor about the centre, inner-gimbal axes.
template <typename T>
[[nodiscard]] Vector3<T> inner_assembly_momentum(const GimbalInertias<T>& j, const GimbalBodyRates<T>& w) noexcept {
  return j.inner.cwiseProduct(w.inner) + j.rotor.cwiseProduct(w.rotor);
}

template <typename T>
[[nodiscard]] T gimbal_kinetic_energy(const GimbalInertias<T>& j, const GimbalBodyRates<T>& w) noexcept {
  return (w.outer.dot(j.outer.cwiseProduct(w.outer)) + w.inner.dot(j.inner.cwiseProduct(w.inner)) +
          w.rotor.dot(j.rotor.cwiseProduct(w.rotor))) /
         T(2);
}

// Generalised momenta dT/d(theta', psi', phi'): sum over the bodies of the partial angular
// velocity of each speed dotted with the body's angular momentum.
template <typename T>
[[nodiscard]] Vector3<T> gimbal_generalised_momentum(const GimbalInertias<T>& j, const GimbalFrames<T>& f,
                                                     const GimbalBodyRates<T>& w) noexcept {
  const Vector3<T> h = inner_assembly_momentum(j, w);
  return Vector3<T>(h(1), j.outer(2) * w.outer(2) + f.yaw_axis_in_inner().dot(h), j.rotor(0) * w.rotor(0));
}

// Total angular momentum of the three bodies about the centre, body axes.
template <typename T>
[[nodiscard]] Vector3<T> gimbal_angular_momentum(const GimbalInertias<T>& j, const GimbalFrames<T>& f,
                                                 const GimbalBodyRates<T>& w) noexcept {
  const Vector3<T> outer = j.outer.cwiseProduct(w.outer) + f.inner_to_outer(inner_assembly_momentum(j, w));
  return f.outer_to_body(outer);
}

// The spin axis (inner x) in body axes.
template <typename T>
[[nodiscard]] Vector3<T> spin_axis_in_body(const GimbalFrames<T>& f) noexcept {
  return Vector3<T>(f.cp * f.cy, f.cp * f.sy, -f.sp);
}

}  // namespace gyro
