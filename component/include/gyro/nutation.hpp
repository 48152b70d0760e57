// Nutation amplitude: the size of the angular wobble that rides on the steady precession.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "gyro/rotor_parameters.hpp"

namespace gyro {

// Per-axis amplitude (rad) of the nutation that the rates `rate_rad_s` excite under a
// constant `torque`: an upper bound, for all t >= 0, of the angle's transient
// exp(A t) y with y = A^-1 (w - w_ss). With exp(A t) = c(t) I + s(t) N, the transient of
// axis i is c(t) y_i + s(t) (N y)_i, and two bounds hold:
//   underdamped  |c| <= e^-alpha t, |s| <= e^-alpha t / beta:   hypot(y_i, (N y)_i / beta),
//                the report's eq 15 amplitude sqrt((k1^2 + k2^2)/(alpha^2 + beta^2));
//   every regime |c| <= 1, |s| <= S:   |y_i| + S |(N y)_i|, with S = 1/max(beta, e*alpha)
//                (the bound of t exp(-alpha t)), or 1/(e*(alpha - gamma)) when overdamped.
// The amplitude is the smaller of the two. For beta >= e*alpha (the lightly damped gyros the
// report treats) that is the report's formula; towards critical damping, where the report's
// divides by zero, the second takes over, finite and continuous through critical damping and
// into overdamping. (Capping 1/beta inside the hypot instead is not a bound: near critical
// the transient exceeded it by up to 7.6%.) Without spin and friction (f = H = 0) there is
// no transient to nutate: the amplitude is 0.
template <typename T>
[[nodiscard]] Status nutation_amplitude(const RotorParameters<T>& prm, const Vector2<T>& rate_rad_s,
                                        const Vector2<T>& torque,
                                        Vector2<T>& amplitude_rad_out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  if (!all_finite(rate_rad_s, torque)) return Status::kNonFiniteInput;
  const detail::RateMatrixTerms<T> m = detail::rate_matrix_terms(prm);
  if (m.omega0_sq == T(0)) {
    amplitude_rad_out.setZero();
    return Status::kOk;
  }
  Vector2<T> w_ss;
  const Status ss = steady_precession_rate(prm, torque, w_ss);
  if (ss != Status::kOk) return ss;
  const Vector2<T> u0 = rate_rad_s - w_ss;
  Matrix2<T> n;
  n << m.d, -m.p, m.q, -m.d;
  // A^-1 = -(N + alpha I) / omega0^2, since (N - alpha I)(N + alpha I) = -omega0^2 I.
  const Vector2<T> y0 = -(n * u0 + m.alpha * u0) / m.omega0_sq;
  const Vector2<T> ny0 = n * y0;
  constexpr T kE = T(2.71828182845904523536L);
  Vector2<T> amp = Vector2<T>::Zero();
  if (m.beta_sq > T(0)) {
    const T beta = std::sqrt(m.beta_sq);
    const T s_max = T(1) / std::max(beta, kE * m.alpha);  // >= |exp(-alpha t) sin(beta t)/beta|
    for (int i = 0; i < 2; ++i) {
      const T by_rotation = std::hypot(y0(i), ny0(i) / beta);  // may be inf as beta -> 0
      const T by_sum = std::abs(y0(i)) + s_max * std::abs(ny0(i));
      amp(i) = (by_rotation < by_sum) ? by_rotation : by_sum;
    }
  } else {
    const T gamma = std::sqrt(-m.beta_sq);
    const T s_max = (m.alpha + gamma) / (kE * m.omega0_sq);  // 1/(e (alpha - gamma))
    for (int i = 0; i < 2; ++i) amp(i) = std::abs(y0(i)) + s_max * std::abs(ny0(i));
  }
  if (!all_finite(amp)) return Status::kNumericalOverflow;
  amplitude_rad_out = amp;
  return Status::kOk;
}

}  // namespace gyro
