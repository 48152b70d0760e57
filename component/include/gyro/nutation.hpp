// Nutation amplitude: the size of the angular wobble that rides on the steady precession.
#pragma once

#include <cmath>

#include "gyro/rotor_parameters.hpp"

namespace gyro {

// Per-axis amplitude (rad) of the nutation that the rates `rate_rad_s` excite under a
// constant `torque`: the envelope of the angle's transient, exp(A t) A^-1 (w - w_ss).
//
// Underdamped, this is the report's eq 15 amplitude sqrt((k1^2 + k2^2)/(alpha^2 + beta^2))
// as long as beta >= e*alpha (the lightly damped gyros the report treats). The envelope
// factor 1/beta is capped at the exact bound 1/(e*alpha) of t*exp(-alpha t) and, overdamped,
// at 1/(e*(alpha - gamma)), so the amplitude stays finite and continuous through critical
// damping, where the report's formula divides by zero. Without spin and friction (f = H = 0)
// there is no transient to nutate: the amplitude is 0.
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
  T envelope;  // sup over t >= 0 of |exp(-alpha t) sin(beta t)/beta| (or its bound)
  if (m.beta_sq > T(0)) {
    const T beta = std::sqrt(m.beta_sq);
    envelope = (beta >= kE * m.alpha) ? T(1) / beta : T(1) / (kE * m.alpha);
  } else {
    const T gamma = std::sqrt(-m.beta_sq);
    envelope = (m.alpha + gamma) / (kE * m.omega0_sq);  // 1/(e (alpha - gamma))
  }
  const Vector2<T> amp(std::hypot(y0(0), envelope * ny0(0)), std::hypot(y0(1), envelope * ny0(1)));
  if (!all_finite(amp)) return Status::kNumericalOverflow;
  amplitude_rad_out = amp;
  return Status::kOk;
}

}  // namespace gyro
