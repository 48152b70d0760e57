// Active stop protection: a bound on the gimbal's outward motion, whatever moves it.
//
// A free gyro holds its inertial direction, so the body's own turn carries the gimbal toward
// its stop; withholding the outward part of a command is not enough. With c the cone angle
// (spin axis against body x) and c_p the protection cone, the gimbal's outward rate c' (the
// spin axis's rate relative to the body, along the outward direction) is held to
//   c' <= k (sin c_p - sin c) / cos c,
// i.e. d(sin c)/dt <= k (sin c_p - sin c): far inside the bound is slack, it slows the gimbal
// as it nears c_p and drives it back from beyond, without a step at any cone. The rate the
// torquers are asked for is moved along the outward direction only, so the command's part
// across it is flown as asked (docs/component.md, "Stop protection").
// No heap, no exceptions, no RTTI; C++17.
#pragma once

#include <algorithm>

#include "gyro/gimbal_geometry.hpp"

namespace gyro {

// Below this sin^2 of the cone the spin axis is on body x (1 urad): no direction is outward.
template <typename T>
inline constexpr T kCentredSinSq = T(1e-12);

template <typename T>
struct StopBound {
  T sin_protect{T(1)};  // sin c_p
  T gain_1_s{};         // k
};

// How far the gimbal's outward rate exceeds the bound when the spin axis precesses at `rate`
// (inertial, on y_I, z_I) on a body turning at `body` (on y_I, z_I): rad/s along the outward
// direction, <= 0 within it; 0 at the centre, where no direction is outward.
template <typename T>
struct OutwardExcess {
  T rate_rad_s{};                          // the excess (> 0: beyond the bound)
  T allowed_rad_s{};                       // the bound on the outward rate against the body
  Vector2<T> outward{Vector2<T>::Zero()};  // unit outward direction on (y_I, z_I)
};

template <typename T>
[[nodiscard]] OutwardExcess<T> outward_excess(const GimbalFrame<T>& f, const Vector2<T>& rate,
                                              const Vector2<T>& body, const StopBound<T>& bound) noexcept {
  // (sin th cos ps, sin ps): the outward direction times sin c, the spin axis's distance from
  // body x (y_I = (-sin ps, cos ps, 0)); cos c is the spin axis's body x component.
  const Vector2<T> m(f.sin_pitch * f.y_inner_body(1), -f.y_inner_body(0));
  const T sin_sq = m.squaredNorm();
  OutwardExcess<T> e;
  if (!(sin_sq > kCentredSinSq<T>)) return e;
  const T sin_c = std::sqrt(sin_sq);
  const T cos_c = std::max(f.spin_axis_body(0), kMinCosPitch<T>);
  e.outward = m / sin_c;
  e.allowed_rad_s = bound.gain_1_s * (bound.sin_protect - sin_c) / cos_c;
  e.rate_rad_s = e.outward.dot(rate - body) - e.allowed_rad_s;
  return e;
}

template <typename T>
struct ProtectedRate {
  Vector2<T> rate_rad_s{Vector2<T>::Zero()};  // the rate to fly (inertial, on y_I, z_I)
  Vector2<T> outward{Vector2<T>::Zero()};     // unit outward direction (zero if not acting)
  T outward_rate_rad_s{};                     // its inertial rate along `outward`, when acting
  bool acting{false};                         // the bound moved the rate
};

// The rate wanted, moved along the outward direction just enough to keep the bound.
template <typename T>
[[nodiscard]] ProtectedRate<T> protect_stop(const GimbalFrame<T>& f, const Vector2<T>& wanted,
                                            const Vector2<T>& body, const StopBound<T>& bound) noexcept {
  ProtectedRate<T> p;
  p.rate_rad_s = wanted;
  const OutwardExcess<T> e = outward_excess(f, wanted, body, bound);
  if (e.rate_rad_s > T(0)) {
    p.rate_rad_s = wanted - e.rate_rad_s * e.outward;
    p.outward = e.outward;
    p.outward_rate_rad_s = e.outward.dot(body) + e.allowed_rad_s;  // not from rate_rad_s: no cancellation
    p.acting = true;
  }
  return p;
}

}  // namespace gyro
