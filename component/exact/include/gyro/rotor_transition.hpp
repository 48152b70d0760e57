// The exact discretisation of the rotor over one step with constant torque: the matrix
// exponential of eqs 1a/1b plus theta' = w1, psi' = w2, in closed form for every regime
// (exp, phi1 and phi2 of A dt written on N and K = N + alpha I; a fixed-length series for
// |z| <= 1, eigenvalue by eigenvalue when overdamped, the closed form otherwise). Nothing
// divides by beta or H. The derivation and why each choice: docs/exact-step.md.
#pragma once

#include <array>
#include <cmath>

#include "gyro/inline_step.hpp"
#include "gyro/rotor_parameters.hpp"

namespace gyro {

// theta, psi in the inertial small-angle frame (ISAF) and their rates.
template <typename T>
struct RotorState {
  Vector2<T> angle_rad{Vector2<T>::Zero()};   // (theta, psi)
  Vector2<T> rate_rad_s{Vector2<T>::Zero()};  // (w1, w2) = (theta', psi')
};

// The step's transition, applied as four 2x2 products per tick.
template <typename T>
struct RotorTransition {
  Matrix2<T> rate_from_rate{Matrix2<T>::Identity()};     // E0
  Matrix2<T> angle_from_rate{Matrix2<T>::Zero()};        // E1
  Matrix2<T> rate_from_torque{Matrix2<T>::Zero()};       // E1 J^-1
  Matrix2<T> angle_from_torque{Matrix2<T>::Zero()};      // E2 J^-1
  T dt_s{};
};

namespace detail {

// Coefficients of g(At) = M_k I + D_k (N t) for g = exp (k = 0), phi1 and phi2: M0 and the D_k
// are all the transition needs.
template <typename T>
struct PhiCoefficients {
  T m0, d0, d1, d2;
};

template <typename T>
constexpr std::array<T, 24> inverse_factorials() noexcept {
  std::array<T, 24> r{};
  double fact = 1.0;  // k! is exact in double up to 22!
  for (int k = 0; k < 24; ++k) {
    if (k > 0) fact *= static_cast<double>(k);
    r[static_cast<std::size_t>(k)] = static_cast<T>(1.0 / fact);
  }
  return r;
}

// |z| <= 1: (At)^k = v_k I + u_k (Nt), with v, u following the eigenvalues' recurrence
// x_{k+1} = -2a x_k - w2t2 x_{k-1}. Bounded by k |z|^(k-1): no cancellation to fear.
template <typename T>
[[nodiscard]] PhiCoefficients<T> phi_series(T a, T w2t2) noexcept {
  constexpr std::array<T, 24> inv_fact = inverse_factorials<T>();
  constexpr int kTerms = ScalarTraits<T>::kSeriesTerms;
  T v_prev = T(1), v = -a;  // v_0, v_1
  T u_prev = T(0), u = T(1);
  PhiCoefficients<T> c{inv_fact[0], T(0), T(0), T(0)};
  for (int k = 1; k <= kTerms; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    c.m0 += inv_fact[i] * v;
    c.d0 += inv_fact[i] * u;
    c.d1 += inv_fact[i + 1] * u;
    c.d2 += inv_fact[i + 2] * u;
    const T v_next = T(-2) * a * v - w2t2 * v_prev;
    const T u_next = T(-2) * a * u - w2t2 * u_prev;
    v_prev = v;
    v = v_next;
    u_prev = u;
    u = u_next;
  }
  return c;
}

// phi1(x) = (e^x - 1)/x and phi2(x) = (e^x - 1 - x)/x^2 for real x <= 0.
template <typename T>
void phi_real(T x, T& e, T& phi1, T& phi2) noexcept {
  e = std::exp(x);
  if (x >= T(-1)) {  // series: the closed forms cancel near 0
    constexpr std::array<T, 24> inv_fact = inverse_factorials<T>();
    constexpr int kTerms = ScalarTraits<T>::kSeriesTerms;
    T s1 = T(0), s2 = T(0);
    for (int k = kTerms; k >= 0; --k) {  // Horner
      s1 = s1 * x + inv_fact[static_cast<std::size_t>(k) + 1u];
      s2 = s2 * x + inv_fact[static_cast<std::size_t>(k) + 2u];
    }
    phi1 = s1;
    phi2 = s2;
  } else {
    phi1 = std::expm1(x) / x;
    phi2 = (phi1 - T(1)) / x;
  }
}

// sin(x)/x; exact to rounding for every x (sin is computed to relative accuracy).
template <typename T>
[[nodiscard]] T sinc(T x) noexcept {
  return (x == T(0)) ? T(1) : std::sin(x) / x;
}
template <typename T>
[[nodiscard]] T sinhc(T x) noexcept {
  return (x == T(0)) ? T(1) : std::sinh(x) / x;
}

// |At| > 1 and the eigenvalues not stiffly separated: phi_{k+1}(At) = (At)^-1 (phi_k(At) - I/k!)
// with (At)^-1 = -(Kt)/w2t2 and (Kt)^2 = 2a Kt - w2t2 I, which gives
// D_{k+1} = (1/k! - (M_k - a D_k) - 2a D_k) / w2t2 with M_1 - a D_1 = D_0.
template <typename T>
void phi_by_inverse(T a, T w2t2, PhiCoefficients<T>& c) noexcept {
  c.d1 = ((T(1) - c.m0) - a * c.d0) / w2t2;
  c.d2 = ((T(1) - c.d0) - T(2) * a * c.d1) / w2t2;
}

template <typename T>
[[nodiscard]] PhiCoefficients<T> phi_coefficients(T a, T b, T w2t2) noexcept {
  PhiCoefficients<T> c{};
  if (b >= T(0)) {  // under- or critically damped: |z| = omega0 t
    if (w2t2 <= T(1)) return phi_series(a, w2t2);
    const T sb = std::sqrt(b);
    const T ea = std::exp(-a);
    c.m0 = ea * std::cos(sb);
    c.d0 = ea * sinc(sb);
    phi_by_inverse(a, w2t2, c);
    return c;
  }
  const T g = std::sqrt(-b);  // overdamped: eigenvalues -a + g (slow) and -a - g (fast)
  if (a + g <= T(1)) return phi_series(a, w2t2);
  if (T(4) * g >= a) {
    // Well separated real eigenvalues: divided differences without cancellation.
    const T mu_slow = -w2t2 / (a + g);  // -a + g without cancellation
    const T mu_fast = -(a + g);
    T e_s, p1_s, p2_s, e_f, p1_f, p2_f;
    phi_real(mu_slow, e_s, p1_s, p2_s);
    phi_real(mu_fast, e_f, p1_f, p2_f);
    const T inv_2g = T(1) / (T(2) * g);
    c.m0 = (e_s + e_f) / T(2);
    c.d0 = (e_s - e_f) * inv_2g;
    c.d1 = (p1_s - p1_f) * inv_2g;
    c.d2 = (p2_s - p2_f) * inv_2g;
    return c;
  }
  // Near critical from above (g < a/4, a > 0.8): e^-a cosh g and e^-a sinh(g)/g without
  // overflow, then the closed form.
  const T e_s = std::exp(g - a), e_f = std::exp(-g - a);
  c.m0 = (e_s + e_f) / T(2);
  c.d0 = (g <= T(1)) ? std::exp(-a) * sinhc(g) : (e_s - e_f) / (T(2) * g);
  phi_by_inverse(a, w2t2, c);
  return c;
}

}  // namespace detail

namespace detail {
template <typename T>
[[nodiscard]] Status make_transition_from_terms(const RotorParameters<T>& prm, const RateMatrixTerms<T>& m, T dt_s,
                                                RotorTransition<T>& out) noexcept;
}  // namespace detail

// Builds the exact transition of `prm` over `dt_s`. Rejects invalid parameters, dt <= 0
// and any result that would not be finite; `out` is untouched unless Status::kOk.
template <typename T>
[[nodiscard]] Status make_transition(const RotorParameters<T>& prm, T dt_s,
                                     RotorTransition<T>& out) noexcept {
  const Status st = validate(prm);
  if (st != Status::kOk) return st;
  return detail::make_transition_from_terms(prm, detail::rate_matrix_terms(prm), dt_s, out);
}

namespace detail {

// make_transition() with `prm` validated and its rate-matrix terms `m` at hand (a caller that
// also needs them for the nutation map computes them once).
template <typename T>
[[nodiscard]] Status make_transition_from_terms(const RotorParameters<T>& prm, const RateMatrixTerms<T>& m, T dt_s,
                                                RotorTransition<T>& out) noexcept {
  if (!std::isfinite(dt_s)) return Status::kNonFiniteInput;
  if (!(dt_s > T(0))) return Status::kNonPositiveStep;
  const T t = dt_s;
  const T a = m.alpha * t;
  const T b = m.beta_sq * t * t;
  const T w2t2 = m.omega0_sq * t * t;
  if (!all_finite(a, b, w2t2)) return Status::kNumericalOverflow;
  const detail::PhiCoefficients<T> c = detail::phi_coefficients(a, b, w2t2);

  Matrix2<T> nt;  // N t
  nt << m.d * t, -m.p * t, m.q * t, -m.d * t;
  Matrix2<T> kt;  // K t = (N + alpha I) t, its diagonal straight from the inputs
  kt << prm.friction * m.inv_j2 * t, -m.p * t, m.q * t, prm.friction * m.inv_j1 * t;
  RotorTransition<T> r;
  r.dt_s = t;
  r.rate_from_rate = c.d0 * nt;
  r.rate_from_rate.diagonal().array() += c.m0;
  Matrix2<T> e1 = (c.d1 * t) * kt;
  e1.diagonal().array() += c.d0 * t;
  Matrix2<T> e2 = (c.d2 * t * t) * kt;
  e2.diagonal().array() += c.d1 * t * t;
  r.angle_from_rate = e1;
  r.rate_from_torque.col(0) = e1.col(0) * m.inv_j1;
  r.rate_from_torque.col(1) = e1.col(1) * m.inv_j2;
  r.angle_from_torque.col(0) = e2.col(0) * m.inv_j1;
  r.angle_from_torque.col(1) = e2.col(1) * m.inv_j2;
  if (!all_finite(r.rate_from_rate, r.angle_from_rate, r.rate_from_torque, r.angle_from_torque)) {
    return Status::kNumericalOverflow;
  }
  out = r;
  return Status::kOk;
}

}  // namespace detail

namespace detail {

// advance()'s cold path: which refusal.
template <typename T>
[[nodiscard]] Status advance_refusal(const Vector2<T>& torque, const RotorState<T>& state) noexcept {
  return all_finite(torque, state.angle_rad, state.rate_rad_s) ? Status::kNumericalOverflow : Status::kNonFiniteInput;
}

}  // namespace detail

// Advances `state` by the transition's step under constant `torque`: four 2x2 products and
// one finiteness test (about 40 instructions on x86-64). Non-finite input, or outputs too
// large to represent (within a factor 4 of the largest finite value), leave `state` as it was.
template <typename T>
[[nodiscard]] GYRO_INLINE_STEP Status advance(const RotorTransition<T>& tr, const Vector2<T>& torque, RotorState<T>& state) noexcept {
  // Column by column (Eigen's matrices are column-major): in double, pairs of products in one
  // register each; written out, without calls the compiler may not inline.
  const T w0 = state.rate_rad_s(0), w1 = state.rate_rad_s(1), t0 = torque(0), t1 = torque(1);
  const Vector2<T> angle = state.angle_rad + tr.angle_from_rate.col(0) * w0 + tr.angle_from_rate.col(1) * w1 +
                           tr.angle_from_torque.col(0) * t0 + tr.angle_from_torque.col(1) * t1;
  const Vector2<T> rate = tr.rate_from_rate.col(0) * w0 + tr.rate_from_rate.col(1) * w1 +
                          tr.rate_from_torque.col(0) * t0 + tr.rate_from_torque.col(1) * t1;
  // One test covers inputs and outputs: every input enters every output of its row with a
  // coefficient, a non-finite input times any coefficient (0 included) is non-finite, and so
  // is any sum that includes one.
  const Vector2<T> sum = angle + rate;
  if (!std::isfinite(sum(0) + sum(1))) return detail::advance_refusal(torque, state);
  state.angle_rad = angle;
  state.rate_rad_s = rate;
  return Status::kOk;
}

// One call for a step whose parameters change every time (a spinning-down rotor).
template <typename T>
[[nodiscard]] Status propagate(const RotorParameters<T>& prm, T dt_s, const Vector2<T>& torque,
                               RotorState<T>& state) noexcept {
  RotorTransition<T> tr;
  const Status st = make_transition(prm, dt_s, tr);
  if (st != Status::kOk) return st;
  return advance(tr, torque, state);
}

}  // namespace gyro
