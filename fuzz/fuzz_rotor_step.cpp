// Fuzz target: the exact rotor dynamics (rotor_transition.hpp, rotor_parameters.hpp,
// nutation.hpp) on arbitrary parameters, state, torques and step, in double and in float.
//
// Input: byte 0 (bit 0: float values decoded from their own bytes, else the double values
// narrowed; bits 1-3: steps - 1), then J1, J2, f, H, dt, theta, psi, w1, w2 and one torque
// (T1, T2) per step, each a Bytes::value (NaN, infinities, denormals, extremes, raw bits).
//
// Invariants:
//   - make_transition: a refusal leaves the output bit-identical; an acceptance gives finite
//     coefficients and the step it was asked for; a refusal of the parameters is validate()'s;
//     the same inputs give the same bits;
//   - advance: a refusal leaves the state bit-identical, an acceptance gives a finite state;
//   - make_transition + advance equals propagate bit for bit (status and state), step after step;
//   - nutation_amplitude, steady_precession_rate, torque_for_precession_rate, compute_modes:
//     a refusal leaves the output untouched, an acceptance gives finite (and for the amplitude
//     non-negative) values;
//   - step_rotation of any finite (theta, psi) is a unit quaternion (the step's attitude).
#include <array>
#include <cstdint>

#include "fuzz_support.hpp"
#include "gyro/attitude.hpp"
#include "gyro/nutation.hpp"
#include "gyro/rotor_transition.hpp"

namespace {

using gyro::fuzz::Bytes;
using gyro::fuzz::finite_coeffs;
using gyro::fuzz::same_bits;
using gyro::fuzz::same_scalar_bits;

constexpr int kMaxSteps = 8;

template <typename T>
struct Case {
  T j1{}, j2{}, f{}, h{}, dt{};
  T theta{}, psi{}, w1{}, w2{};
  std::array<T, 2 * kMaxSteps> torque{};
  int steps{1};
};

template <typename T>
Case<T> decode(Bytes& in, int steps) {
  Case<T> c;
  c.steps = steps;
  c.j1 = in.value<T>(T(1));
  c.j2 = in.value<T>(T(1));
  c.f = in.value<T>(T(1));
  c.h = in.value<T>(T(10));
  c.dt = in.value<T>(T(1e-2));
  c.theta = in.value<T>(T(1e-2));
  c.psi = in.value<T>(T(1e-2));
  c.w1 = in.value<T>(T(1));
  c.w2 = in.value<T>(T(1));
  for (int i = 0; i < 2 * steps; ++i) c.torque[static_cast<std::size_t>(i)] = in.value<T>(T(1));
  return c;
}

// double -> float with IEEE overflow to infinity spelled out (no reliance on the cast).
float narrow(double v) {
  if (v > static_cast<double>(std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
  if (v < -static_cast<double>(std::numeric_limits<float>::max())) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

Case<float> narrow(const Case<double>& d) {
  Case<float> c;
  c.steps = d.steps;
  c.j1 = narrow(d.j1);
  c.j2 = narrow(d.j2);
  c.f = narrow(d.f);
  c.h = narrow(d.h);
  c.dt = narrow(d.dt);
  c.theta = narrow(d.theta);
  c.psi = narrow(d.psi);
  c.w1 = narrow(d.w1);
  c.w2 = narrow(d.w2);
  for (std::size_t i = 0; i < c.torque.size(); ++i) c.torque[i] = narrow(d.torque[i]);
  return c;
}

template <typename T>
bool same_transition(const gyro::RotorTransition<T>& a, const gyro::RotorTransition<T>& b) {
  return same_bits(a.rate_from_rate, b.rate_from_rate) && same_bits(a.angle_from_rate, b.angle_from_rate) &&
         same_bits(a.rate_from_torque, b.rate_from_torque) &&
         same_bits(a.angle_from_torque, b.angle_from_torque) && same_scalar_bits(a.dt_s, b.dt_s);
}
template <typename T>
bool finite_transition(const gyro::RotorTransition<T>& t) {
  return finite_coeffs(t.rate_from_rate) && finite_coeffs(t.angle_from_rate) && finite_coeffs(t.rate_from_torque) &&
         finite_coeffs(t.angle_from_torque) && std::isfinite(t.dt_s);
}
template <typename T>
bool same_state(const gyro::RotorState<T>& a, const gyro::RotorState<T>& b) {
  return same_bits(a.angle_rad, b.angle_rad) && same_bits(a.rate_rad_s, b.rate_rad_s);
}

// A recognisable output that a refused call must leave alone.
template <typename T>
gyro::RotorTransition<T> sentinel_transition() {
  gyro::RotorTransition<T> t;
  t.rate_from_rate << T(11), T(12), T(13), T(14);
  t.angle_from_rate << T(21), T(22), T(23), T(24);
  t.rate_from_torque << T(31), T(32), T(33), T(34);
  t.angle_from_torque << T(41), T(42), T(43), T(44);
  t.dt_s = T(-5);
  return t;
}

template <typename T>
void check_auxiliaries(const gyro::RotorParameters<T>& prm, const gyro::Vector2<T>& rate,
                       const gyro::Vector2<T>& torque) {
  const gyro::Vector2<T> sentinel(T(-123), T(456));

  gyro::Vector2<T> amp = sentinel;
  const gyro::Status sa = gyro::nutation_amplitude(prm, rate, torque, amp);
  if (sa == gyro::Status::kOk) {
    GYRO_FUZZ_CHECK(finite_coeffs(amp) && amp.minCoeff() >= T(0));
  } else {
    GYRO_FUZZ_CHECK(same_bits(amp, sentinel));
  }

  gyro::Vector2<T> w = sentinel;
  const gyro::Status sw = gyro::steady_precession_rate(prm, torque, w);
  GYRO_FUZZ_CHECK(sw == gyro::Status::kOk ? finite_coeffs(w) : same_bits(w, sentinel));

  gyro::Vector2<T> tq = sentinel;
  const gyro::Status st = gyro::torque_for_precession_rate(prm, rate, tq);
  GYRO_FUZZ_CHECK(st == gyro::Status::kOk ? finite_coeffs(tq) : same_bits(tq, sentinel));

  gyro::RotorModes<T> m;
  m.alpha_1_s = T(-7);
  const gyro::Status sm = gyro::compute_modes(prm, m);
  if (sm == gyro::Status::kOk) {
    GYRO_FUZZ_CHECK(std::isfinite(m.alpha_1_s) && std::isfinite(m.beta_squared_1_s2) && std::isfinite(m.beta_rad_s) &&
                    std::isfinite(m.natural_rate_rad_s) && std::isfinite(m.slow_decay_rate_1_s) &&
                    std::isfinite(m.fast_decay_rate_1_s) && std::isfinite(m.nutation_hz));
    GYRO_FUZZ_CHECK(m.alpha_1_s >= T(0) && m.beta_rad_s >= T(0) && m.natural_rate_rad_s >= T(0));
  } else {
    GYRO_FUZZ_CHECK(same_scalar_bits(m.alpha_1_s, T(-7)));
  }
}

template <typename T>
void check_step_rotation(const gyro::Vector2<T>& angle) {
  const gyro::Quaternion<T> q = gyro::step_rotation(angle);
  if (finite_coeffs(angle)) {
    GYRO_FUZZ_CHECK(finite_coeffs(q.coeffs()));
    GYRO_FUZZ_CHECK(std::abs(q.norm() - T(1)) <= T(16) * std::numeric_limits<T>::epsilon());
  }
}

template <typename T>
void run(const Case<T>& c) {
  const gyro::RotorParameters<T> prm{c.j1, c.j2, c.f, c.h};
  const gyro::Status valid = gyro::validate(prm);

  const gyro::RotorTransition<T> sentinel = sentinel_transition<T>();
  gyro::RotorTransition<T> tr = sentinel;
  const gyro::Status made = gyro::make_transition(prm, c.dt, tr);
  if (made == gyro::Status::kOk) {
    GYRO_FUZZ_CHECK(valid == gyro::Status::kOk);
    GYRO_FUZZ_CHECK(std::isfinite(c.dt) && c.dt > T(0));
    GYRO_FUZZ_CHECK(finite_transition(tr));
    GYRO_FUZZ_CHECK(same_scalar_bits(tr.dt_s, c.dt));
    gyro::RotorTransition<T> again = sentinel;
    GYRO_FUZZ_CHECK(gyro::make_transition(prm, c.dt, again) == gyro::Status::kOk);
    GYRO_FUZZ_CHECK(same_transition(tr, again));
  } else {
    GYRO_FUZZ_CHECK(same_transition(tr, sentinel));
    if (valid != gyro::Status::kOk) GYRO_FUZZ_CHECK(made == valid);
  }

  gyro::RotorState<T> by_advance;
  by_advance.angle_rad << c.theta, c.psi;
  by_advance.rate_rad_s << c.w1, c.w2;
  gyro::RotorState<T> by_propagate = by_advance;
  check_auxiliaries(prm, by_advance.rate_rad_s, gyro::Vector2<T>(c.torque[0], c.torque[1]));
  check_step_rotation(by_advance.angle_rad);
  check_step_rotation(by_advance.rate_rad_s);

  for (int k = 0; k < c.steps; ++k) {
    const std::size_t i = static_cast<std::size_t>(2 * k);
    const gyro::Vector2<T> torque(c.torque[i], c.torque[i + 1]);

    gyro::Status advanced = made;
    if (made == gyro::Status::kOk) {
      const gyro::RotorState<T> before = by_advance;
      advanced = gyro::advance(tr, torque, by_advance);
      if (advanced == gyro::Status::kOk) {
        GYRO_FUZZ_CHECK(finite_coeffs(by_advance.angle_rad) && finite_coeffs(by_advance.rate_rad_s));
      } else {
        GYRO_FUZZ_CHECK(same_state(by_advance, before));
      }
    }

    const gyro::RotorState<T> before = by_propagate;
    const gyro::Status propagated = gyro::propagate(prm, c.dt, torque, by_propagate);
    GYRO_FUZZ_CHECK(propagated == advanced);
    GYRO_FUZZ_CHECK(same_state(by_propagate, by_advance));
    if (propagated != gyro::Status::kOk) GYRO_FUZZ_CHECK(same_state(by_propagate, before));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  const std::uint8_t head = in.u8();
  const int steps = 1 + ((head >> 1) & 7);
  const Case<double> d = decode<double>(in, steps);
  run(d);
  if (head & 1u) {
    run(decode<float>(in, steps));
  } else {
    run(narrow(d));
  }
  return 0;
}
