// The linear rotor model of the report (eqs 1a, 1b) and its characteristic quantities.
//
//   J1 w1' + f w1 + H w2 = T1        theta' = w1   (pitch)
//   J2 w2' + f w2 - H w1 = T2        psi'   = w2   (yaw)
//
// Any consistent unit system works (the report uses slug*ft^2; SI works the same).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "gyro/scalar_traits.hpp"
#include "gyro/status.hpp"

namespace gyro {

template <typename T>
using Vector2 = Eigen::Matrix<T, 2, 1>;
template <typename T>
using Matrix2 = Eigen::Matrix<T, 2, 2>;

// m v and m^T v for 2x2 matrices, column by column (Eigen's order): in float, Eigen's
// Matrix2f * Vector2f is an out-of-line call at -O2 (about 40 instructions); these inline.
template <typename T>
[[nodiscard]] Vector2<T> times(const Matrix2<T>& m, const Vector2<T>& v) noexcept {
  return Vector2<T>(m(0, 0) * v(0) + m(0, 1) * v(1), m(1, 0) * v(0) + m(1, 1) * v(1));
}
template <typename T>
[[nodiscard]] Vector2<T> transpose_times(const Matrix2<T>& m, const Vector2<T>& v) noexcept {
  return Vector2<T>(m(0, 0) * v(0) + m(1, 0) * v(1), m(0, 1) * v(0) + m(1, 1) * v(1));
}

template <typename T>
inline constexpr T kPi = T(3.14159265358979323846264338327950288L);

template <typename T>
struct RotorParameters {
  T pitch_inertia{};     // J1, about the pitch gimbal axis
  T yaw_inertia{};       // J2, about the yaw gimbal axis
  T friction{};          // f, viscous gimbal friction (torque per rad/s)
  T angular_momentum{};  // H = 2*pi*spin_hz*J0, the rotor's spin angular momentum
};

// H = 2*pi*spin_hz*J0 (report, symbols list).
template <typename T>
[[nodiscard]] constexpr T angular_momentum(T spin_hz, T spin_inertia) noexcept {
  return T(2) * kPi<T> * spin_hz * spin_inertia;
}

// Finiteness tests without a branch per value: x * 0 is +-0 for every finite x and NaN for an
// infinity or a NaN (no -ffast-math anywhere, so the compiler may not fold it), and a sum of
// such products is 0 only if every one is. The per-tick checks cost a few instructions.
template <typename T>
[[nodiscard]] constexpr bool all_finite(const T& a) noexcept {
  return a * T(0) == T(0);
}
template <typename T, int R, int C>
[[nodiscard]] bool all_finite(const Eigen::Matrix<T, R, C>& m) noexcept {
  return (m * T(0)).sum() == T(0);  // x * 0 is 0 when finite, else NaN; Eigen unrolls the sum
}
template <typename A, typename B, typename... Rest>
[[nodiscard]] bool all_finite(const A& a, const B& b, const Rest&... rest) noexcept {
  // & not &&: no branch per argument (on unsigned: clang's -Wbitwise-instead-of-logical).
  return (static_cast<unsigned>(all_finite(a)) & static_cast<unsigned>(all_finite(b, rest...))) != 0U;
}

template <typename T>
[[nodiscard]] Status validate(const RotorParameters<T>& p) noexcept {
  static_assert(kIsSupportedScalar<T>, "gyro supports float and double");
  if (!all_finite(p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum)) {
    return Status::kNonFiniteInput;
  }
  if (!(p.pitch_inertia > T(0)) || !(p.yaw_inertia > T(0))) return Status::kNonPositiveInertia;
  if (p.friction < T(0)) return Status::kNegativeFriction;
  if (p.angular_momentum < T(0)) return Status::kNegativeAngularMomentum;
  return Status::kOk;
}

enum class DampingRegime : std::uint8_t {
  kUnderdamped,  // beta^2 > 0: the rotor nutates at beta rad/s, decaying at alpha
  kCritical,     // beta^2 = 0 exactly
  kOverdamped,   // beta^2 < 0: two real decay rates alpha -+ gamma, no nutation
  kFree,         // f = H = 0: no restoring or damping term at all
};

// The eigenvalues of the rate equations are -alpha +- i*beta (report eq 11).
template <typename T>
struct RotorModes {
  T alpha_1_s{};             // alpha = (f/2)(1/J1 + 1/J2)
  T beta_squared_1_s2{};     // beta^2 = (f^2 + H^2)/(J1 J2) - alpha^2, of either sign
  T beta_rad_s{};            // sqrt(beta^2) when underdamped, else 0
  T natural_rate_rad_s{};    // omega0 = sqrt((f^2 + H^2)/(J1 J2)) = |eigenvalue|
  T slow_decay_rate_1_s{};   // alpha - gamma when overdamped, alpha otherwise
  T fast_decay_rate_1_s{};   // alpha + gamma when overdamped, alpha otherwise
  T nutation_hz{};           // beta / (2 pi), 0 when not underdamped
  DampingRegime regime{DampingRegime::kFree};
};

namespace detail {

// The rate matrix is A = N - alpha*I with N = [[d, -p], [q, -d]] and N^2 = -beta^2 I.
// All terms come straight from the inputs, so beta^2 near zero is computed without the
// cancellation of the report's (f^2 + H^2)/(J1 J2) - alpha^2.
template <typename T>
struct RateMatrixTerms {
  T inv_j1, inv_j2;
  T alpha;    // (f/2)(1/J1 + 1/J2)
  T d;        // (f/2)(1/J2 - 1/J1)
  T p, q;     // H/J1, H/J2
  T omega0_sq;  // (f^2 + H^2)/(J1 J2)
  T beta_sq;    // (H/sqrt(J1 J2))^2 - d^2, as a product of sum and difference
};

template <typename T>
[[nodiscard]] RateMatrixTerms<T> rate_matrix_terms(const RotorParameters<T>& prm) noexcept {
  RateMatrixTerms<T> m{};
  m.inv_j1 = T(1) / prm.pitch_inertia;
  m.inv_j2 = T(1) / prm.yaw_inertia;
  const T half_f = prm.friction / T(2);
  m.alpha = half_f * (m.inv_j1 + m.inv_j2);
  m.d = half_f * ((prm.pitch_inertia - prm.yaw_inertia) * (m.inv_j1 * m.inv_j2));
  m.p = prm.angular_momentum * m.inv_j1;
  m.q = prm.angular_momentum * m.inv_j2;
  const T f = prm.friction, h = prm.angular_momentum;
  m.omega0_sq = (f * f + h * h) * (m.inv_j1 * m.inv_j2);
  const T s = h * std::sqrt(m.inv_j1 * m.inv_j2);
  const T ad = std::abs(m.d);
  m.beta_sq = (s - ad) * (s + ad);
  return m;
}

}  // namespace detail

template <typename T>
[[nodiscard]] Status compute_modes(const RotorParameters<T>& prm, RotorModes<T>& out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  const detail::RateMatrixTerms<T> m = detail::rate_matrix_terms(prm);
  if (!all_finite(m.omega0_sq, m.beta_sq, m.alpha)) return Status::kNumericalOverflow;
  RotorModes<T> r{};
  r.alpha_1_s = m.alpha;
  r.beta_squared_1_s2 = m.beta_sq;
  r.natural_rate_rad_s = std::sqrt(m.omega0_sq);
  r.slow_decay_rate_1_s = m.alpha;
  r.fast_decay_rate_1_s = m.alpha;
  if (m.omega0_sq == T(0)) {
    r.regime = DampingRegime::kFree;
  } else if (m.beta_sq > T(0)) {
    r.regime = DampingRegime::kUnderdamped;
    r.beta_rad_s = std::sqrt(m.beta_sq);
    r.nutation_hz = r.beta_rad_s / (T(2) * kPi<T>);
  } else if (m.beta_sq == T(0)) {
    r.regime = DampingRegime::kCritical;
  } else {
    r.regime = DampingRegime::kOverdamped;
    const T gamma = std::sqrt(-m.beta_sq);
    // alpha - gamma = omega0^2 / (alpha + gamma): no cancellation for a stiff rotor.
    r.slow_decay_rate_1_s = m.omega0_sq / (m.alpha + gamma);
    r.fast_decay_rate_1_s = m.alpha + gamma;
  }
  out = r;
  return Status::kOk;
}

// Steady precession under constant torque (report eq 11, k5 and k6):
//   w1 = (f T1 - H T2)/(f^2 + H^2),  w2 = (H T1 + f T2)/(f^2 + H^2).
// Friction couples the axes: a pitch torque also drives a pitch rate when f > 0.
template <typename T>
[[nodiscard]] Status steady_precession_rate(const RotorParameters<T>& prm,
                                            const Vector2<T>& torque,
                                            Vector2<T>& rate_out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  if (!all_finite(torque)) return Status::kNonFiniteInput;
  const T f = prm.friction, h = prm.angular_momentum;
  const T den = f * f + h * h;
  if (den == T(0)) return Status::kNoSteadyState;
  const Vector2<T> r((f * torque(0) - h * torque(1)) / den, (h * torque(0) + f * torque(1)) / den);
  if (!all_finite(r)) return Status::kNumericalOverflow;
  rate_out = r;
  return Status::kOk;
}

// The exact inverse: the torque whose steady precession is `rate` (from eqs 1a, 1b at
// w' = 0): T1 = f w1 + H w2, T2 = f w2 - H w1. Compensates friction cross-coupling.
template <typename T>
[[nodiscard]] Status torque_for_precession_rate(const RotorParameters<T>& prm,
                                                const Vector2<T>& rate,
                                                Vector2<T>& torque_out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  if (!all_finite(rate)) return Status::kNonFiniteInput;
  const T f = prm.friction, h = prm.angular_momentum;
  const Vector2<T> t(f * rate(0) + h * rate(1), f * rate(1) - h * rate(0));
  if (!all_finite(t)) return Status::kNumericalOverflow;
  torque_out = t;
  return Status::kOk;
}

}  // namespace gyro
