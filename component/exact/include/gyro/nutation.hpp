// Nutation amplitude: the size of the angular wobble that rides on the steady precession.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "gyro/rotor_parameters.hpp"

namespace gyro {

// Per-axis amplitude (rad) of the nutation that the rates `rate_rad_s` excite under a
// constant `torque`: an upper bound, for all t >= 0, of the angle's transient. The smaller of
// the report's eq 15 amplitude (underdamped) and a bound that holds in every regime, so it
// stays finite through critical damping and into overdamping; 0 when f = H = 0. Derivation:
// docs/exact-step.md. What it needs from the parameters is computed once per rotor (per H):
// per step two 2x2 products and a few scalar operations.
template <typename T>
struct NutationMap {
  Matrix2<T> steady_from_torque{Matrix2<T>::Zero()};  // w_ss = P T (eq 11: k5, k6)
  Matrix2<T> transient_from_rate{Matrix2<T>::Zero()};  // y = A^-1 u, u = w - w_ss
  Matrix2<T> rotated_from_rate{Matrix2<T>::Zero()};    // N y
  T inv_beta{};        // 1/beta when underdamped, else 0
  T envelope{};        // S, the bound of |exp(-alpha t) sin(beta t)/beta| (or sinh)
  bool has_steady{false};     // f^2 + H^2 > 0
  bool has_transient{false};  // omega0^2 > 0
  bool saturated{false};      // the transient is too large to represent
};

namespace detail {
template <typename T>
[[nodiscard]] NutationMap<T> nutation_map_from_terms(const RotorParameters<T>& prm, const RateMatrixTerms<T>& m) noexcept;
}  // namespace detail

template <typename T>
[[nodiscard]] Status make_nutation_map(const RotorParameters<T>& prm, NutationMap<T>& out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  out = detail::nutation_map_from_terms(prm, detail::rate_matrix_terms(prm));
  return Status::kOk;
}

namespace detail {

// make_nutation_map() with `prm` validated and its rate-matrix terms `m` at hand.
template <typename T>
[[nodiscard]] NutationMap<T> nutation_map_from_terms(const RotorParameters<T>& prm, const RateMatrixTerms<T>& m) noexcept {
  NutationMap<T> map;
  const T f = prm.friction, h = prm.angular_momentum;
  const T den = f * f + h * h;
  if (den > T(0) && m.omega0_sq > T(0)) {
    map.has_steady = true;
    map.has_transient = true;
    map.steady_from_torque << f / den, -h / den, h / den, f / den;
    Matrix2<T> n;
    n << m.d, -m.p, m.q, -m.d;
    // A^-1 = -(N + alpha I) / omega0^2, since (N - alpha I)(N + alpha I) = -omega0^2 I.
    Matrix2<T> a_inv = n;
    a_inv.diagonal().array() += m.alpha;
    a_inv /= -m.omega0_sq;
    map.transient_from_rate = a_inv;
    map.rotated_from_rate.noalias() = n * a_inv;
    constexpr T kE = T(2.71828182845904523536L);
    if (m.beta_sq > T(0)) {
      const T beta = std::sqrt(m.beta_sq);
      map.inv_beta = T(1) / beta;
      map.envelope = T(1) / std::max(beta, kE * m.alpha);
    } else {
      const T gamma = std::sqrt(-m.beta_sq);
      map.envelope = (m.alpha + gamma) / (kE * m.omega0_sq);  // 1/(e (alpha - gamma))
    }
  } else if (den > T(0)) {
    map.has_steady = true;  // omega0^2 underflowed to 0: no transient, as for f = H = 0
    map.steady_from_torque << f / den, -h / den, h / den, f / den;
  }
  if (!all_finite(map.steady_from_torque, map.transient_from_rate, map.rotated_from_rate, map.envelope)) {
    // A rotor with almost no spin and no friction: the transient is too large to represent.
    map.has_transient = false;
    map.transient_from_rate.setZero();
    map.rotated_from_rate.setZero();
    map.envelope = std::numeric_limits<T>::max();
    map.saturated = true;
  }
  return map;
}

}  // namespace detail

// Per-axis amplitude (rad) of the nutation that `rate_rad_s` excites under a constant
// `torque`, from a map made for the rotor. Inputs are assumed finite (callers check them);
// an amplitude too large for T is reported as the largest finite T.
template <typename T>
[[nodiscard]] Vector2<T> nutation_amplitude(const NutationMap<T>& map, const Vector2<T>& rate_rad_s,
                                            const Vector2<T>& torque) noexcept {
  if (!map.has_transient) {
    // f = H = 0: no transient to nutate; or one too large to represent.
    return map.saturated ? Vector2<T>::Constant(std::numeric_limits<T>::max()) : Vector2<T>::Zero();
  }
  const Vector2<T> u = rate_rad_s - times(map.steady_from_torque, torque);
  const Vector2<T> y = times(map.transient_from_rate, u);
  const Vector2<T> ny = times(map.rotated_from_rate, u);
  Vector2<T> amp;
  for (int i = 0; i < 2; ++i) {
    const T by_sum = std::abs(y(i)) + map.envelope * std::abs(ny(i));
    T a = by_sum;
    if (map.inv_beta > T(0)) {
      const T r = ny(i) * map.inv_beta;
      const T by_rotation = std::sqrt(y(i) * y(i) + r * r);  // may be inf as beta -> 0
      a = (by_rotation < by_sum) ? by_rotation : by_sum;
    }
    amp(i) = all_finite(a) ? a : std::numeric_limits<T>::max();
  }
  return amp;
}

// The same for one call: validates, builds the map and applies it. An amplitude too large for
// T is refused here (kNumericalOverflow, output untouched); GyroModel, which must finish its
// step, uses the map form and reads it as the largest finite T (the small-angle flag rises).
template <typename T>
[[nodiscard]] Status nutation_amplitude(const RotorParameters<T>& prm, const Vector2<T>& rate_rad_s,
                                        const Vector2<T>& torque,
                                        Vector2<T>& amplitude_rad_out) noexcept {
  NutationMap<T> map;
  const Status st = make_nutation_map(prm, map);  // validates prm
  if (st != Status::kOk) return st;
  if (!all_finite(rate_rad_s, torque)) return Status::kNonFiniteInput;
  const Vector2<T> amp = nutation_amplitude(map, rate_rad_s, torque);
  if (amp.maxCoeff() == std::numeric_limits<T>::max()) return Status::kNumericalOverflow;
  amplitude_rad_out = amp;
  return Status::kOk;
}

}  // namespace gyro
