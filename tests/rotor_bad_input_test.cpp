// Bad input to the rotor dynamics: every rejection returns its documented Status (status.hpp)
// and leaves the caller's output object bit-identical; huge-but-finite inputs report
// kNumericalOverflow instead of producing NaN or infinity. Also the nutation amplitude:
// the report's formula (eqs 13-15), continuity across critical damping, and that it bounds
// the angle transient of a fine simulation in every damping regime, and the nutation map's
// saturated and underflowing rotors.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "gyro/nutation.hpp"
#include "gyro/rotor_transition.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// The bytes of an object, to prove a rejected call did not write to it (NaN payloads and
// signed zeros included, which == would not see).
template <typename Obj>
class Bytes {
 public:
  explicit Bytes(const Obj& o) noexcept { std::memcpy(bytes_.data(), static_cast<const void*>(&o), sizeof(Obj)); }
  [[nodiscard]] bool same_as(const Obj& o) const noexcept {
    return std::memcmp(bytes_.data(), static_cast<const void*>(&o), sizeof(Obj)) == 0;
  }

 private:
  std::array<unsigned char, sizeof(Obj)> bytes_{};
};

template <typename T>
RotorParameters<T> report_rotor() {  // the report's gyro: J1 = 2.25, J2 = 2, f = 5, 100 Hz x J0 = 3
  return {T(2.25), T(2), T(5), angular_momentum(T(100), T(3))};
}

// Distinctive contents for every output object, so that any write shows.
template <typename T>
RotorTransition<T> sentinel_transition() {
  RotorTransition<T> tr;
  tr.rate_from_rate << T(1.25), T(-2.5), T(3.75), T(-4.5);
  tr.angle_from_rate << T(5.5), T(-6.25), T(7.125), T(-8.75);
  tr.rate_from_torque << T(9.5), T(-10.25), T(11.75), T(-12.5);
  tr.angle_from_torque << T(13.25), T(-14.5), T(15.75), T(-16.125);
  tr.dt_s = T(0.0625);
  return tr;
}
template <typename T>
RotorState<T> sentinel_state() {
  RotorState<T> s;
  s.angle_rad = Vector2<T>(T(0.125), T(-0.375));
  s.rate_rad_s = Vector2<T>(T(1.5), T(-2.75));
  return s;
}
template <typename T>
Vector2<T> sentinel_vector() {
  return Vector2<T>(T(7.5), T(-8.25));
}
template <typename T>
RotorModes<T> sentinel_modes() {
  RotorModes<T> m;
  m.alpha_1_s = T(1.5);
  m.beta_squared_1_s2 = T(-2.5);
  m.beta_rad_s = T(3.5);
  m.natural_rate_rad_s = T(4.5);
  m.slow_decay_rate_1_s = T(5.5);
  m.fast_decay_rate_1_s = T(6.5);
  m.nutation_hz = T(7.5);
  m.regime = DampingRegime::kCritical;
  return m;
}

template <typename T>
class BadInput : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(BadInput, Scalars);

template <typename T>
constexpr T kNaN = std::numeric_limits<T>::quiet_NaN();
template <typename T>
constexpr T kInf = std::numeric_limits<T>::infinity();

// Calls every function that takes rotor parameters and expects `expected` from each, with
// its output left exactly as it was.
template <typename T>
void expect_every_call_rejects(const RotorParameters<T>& prm, Status expected, const char* what) {
  SCOPED_TRACE(what);
  const Vector2<T> torque(T(0.5), T(-0.25));
  {
    RotorModes<T> out = sentinel_modes<T>();
    const Bytes<RotorModes<T>> before(out);
    EXPECT_EQ(compute_modes(prm, out), expected) << "compute_modes";
    EXPECT_TRUE(before.same_as(out)) << "compute_modes wrote its output";
  }
  {
    RotorTransition<T> out = sentinel_transition<T>();
    const Bytes<RotorTransition<T>> before(out);
    EXPECT_EQ(make_transition(prm, T(0.01), out), expected) << "make_transition";
    EXPECT_TRUE(before.same_as(out)) << "make_transition wrote its output";
  }
  {
    RotorState<T> state = sentinel_state<T>();
    const Bytes<RotorState<T>> before(state);
    EXPECT_EQ(propagate(prm, T(0.01), torque, state), expected) << "propagate";
    EXPECT_TRUE(before.same_as(state)) << "propagate wrote the state";
  }
  {
    Vector2<T> out = sentinel_vector<T>();
    const Bytes<Vector2<T>> before(out);
    EXPECT_EQ(steady_precession_rate(prm, torque, out), expected) << "steady_precession_rate";
    EXPECT_TRUE(before.same_as(out)) << "steady_precession_rate wrote its output";
  }
  {
    Vector2<T> out = sentinel_vector<T>();
    const Bytes<Vector2<T>> before(out);
    EXPECT_EQ(torque_for_precession_rate(prm, Vector2<T>(T(0.1), T(0.2)), out), expected)
        << "torque_for_precession_rate";
    EXPECT_TRUE(before.same_as(out)) << "torque_for_precession_rate wrote its output";
  }
  {
    Vector2<T> out = sentinel_vector<T>();
    const Bytes<Vector2<T>> before(out);
    EXPECT_EQ(nutation_amplitude(prm, Vector2<T>(T(0.1), T(0.2)), torque, out), expected) << "nutation_amplitude";
    EXPECT_TRUE(before.same_as(out)) << "nutation_amplitude wrote its output";
  }
}

// Parameter field i of RotorParameters: 0 J1, 1 J2, 2 f, 3 H.
template <typename T>
RotorParameters<T> with_field(int i, T value) {
  RotorParameters<T> p = report_rotor<T>();
  switch (i) {
    case 0: p.pitch_inertia = value; break;
    case 1: p.yaw_inertia = value; break;
    case 2: p.friction = value; break;
    default: p.angular_momentum = value; break;
  }
  return p;
}
constexpr const char* kFieldNames[] = {"J1", "J2", "f", "H"};

TYPED_TEST(BadInput, GivenNaNOrInfinityInAnyParameterWhenAnyCallThenNonFiniteInputAndOutputUntouched) {
  GYRO_VERIFIES("EXACT-5", "RULE-9");
  using T = TypeParam;
  for (int i = 0; i < 4; ++i) {
    for (const T v : {kNaN<T>, -kNaN<T>, kInf<T>, -kInf<T>}) {
      SCOPED_TRACE(std::string(kFieldNames[i]) + " = " + std::to_string(static_cast<double>(v)));
      expect_every_call_rejects(with_field(i, v), Status::kNonFiniteInput, "non-finite parameter");
    }
  }
}

TYPED_TEST(BadInput, GivenZeroOrNegativeInertiaWhenAnyCallThenNonPositiveInertia) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  for (int i = 0; i < 2; ++i) {
    for (const T v : {T(0), -T(0), -std::numeric_limits<T>::denorm_min(), T(-1), std::numeric_limits<T>::lowest()}) {
      SCOPED_TRACE(std::string(kFieldNames[i]) + " = " + std::to_string(static_cast<double>(v)));
      expect_every_call_rejects(with_field(i, v), Status::kNonPositiveInertia, "inertia <= 0");
    }
  }
}

TYPED_TEST(BadInput, GivenNegativeFrictionWhenAnyCallThenNegativeFriction) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  for (const T v : {-std::numeric_limits<T>::denorm_min(), T(-5), std::numeric_limits<T>::lowest()}) {
    expect_every_call_rejects(with_field(2, v), Status::kNegativeFriction, "f < 0");
  }
}

TYPED_TEST(BadInput, GivenNegativeAngularMomentumWhenAnyCallThenNegativeAngularMomentum) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  for (const T v : {-std::numeric_limits<T>::denorm_min(), T(-1884.9), std::numeric_limits<T>::lowest()}) {
    expect_every_call_rejects(with_field(3, v), Status::kNegativeAngularMomentum, "H < 0");
  }
}

TYPED_TEST(BadInput, GivenNegativeZeroFrictionAndSpinWhenAnyCallThenAcceptedAsZero) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  // -0.0 is not < 0: the free rotor (f = H = 0) it describes is valid for the transition.
  const RotorParameters<T> p{T(1), T(2), -T(0), -T(0)};
  RotorTransition<T> tr;
  EXPECT_EQ(make_transition(p, T(0.5), tr), Status::kOk);
  RotorModes<T> m;
  ASSERT_EQ(compute_modes(p, m), Status::kOk);
  EXPECT_EQ(m.regime, DampingRegime::kFree);
}

TYPED_TEST(BadInput, GivenZeroNegativeOrNonFiniteStepWhenMakeTransitionOrPropagateThenRejectedAndUntouched) {
  GYRO_VERIFIES("EXACT-5", "RULE-9");
  using T = TypeParam;
  const RotorParameters<T> p = report_rotor<T>();
  const Vector2<T> torque(T(0.5), T(-0.25));
  struct StepCase {
    T dt;
    Status expected;
  };
  const StepCase cases[] = {
      {T(0), Status::kNonPositiveStep},
      {-T(0), Status::kNonPositiveStep},
      {-std::numeric_limits<T>::denorm_min(), Status::kNonPositiveStep},
      {T(-0.01), Status::kNonPositiveStep},
      {std::numeric_limits<T>::lowest(), Status::kNonPositiveStep},
      {kNaN<T>, Status::kNonFiniteInput},
      {-kNaN<T>, Status::kNonFiniteInput},
      {kInf<T>, Status::kNonFiniteInput},
      {-kInf<T>, Status::kNonFiniteInput},
  };
  for (const StepCase& c : cases) {
    SCOPED_TRACE("dt = " + std::to_string(static_cast<double>(c.dt)));
    RotorTransition<T> tr = sentinel_transition<T>();
    const Bytes<RotorTransition<T>> tr_before(tr);
    EXPECT_EQ(make_transition(p, c.dt, tr), c.expected);
    EXPECT_TRUE(tr_before.same_as(tr));
    RotorState<T> state = sentinel_state<T>();
    const Bytes<RotorState<T>> state_before(state);
    EXPECT_EQ(propagate(p, c.dt, torque, state), c.expected);
    EXPECT_TRUE(state_before.same_as(state));
  }
}

TYPED_TEST(BadInput, GivenNonFiniteTorqueWhenAdvancingOrSteadyRateOrAmplitudeThenNonFiniteInputAndUntouched) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  const RotorParameters<T> p = report_rotor<T>();
  RotorTransition<T> tr;
  ASSERT_EQ(make_transition(p, T(0.01), tr), Status::kOk);
  for (int axis = 0; axis < 2; ++axis) {
    for (const T v : {kNaN<T>, kInf<T>, -kInf<T>}) {
      SCOPED_TRACE("torque(" + std::to_string(axis) + ") = " + std::to_string(static_cast<double>(v)));
      Vector2<T> torque(T(0.5), T(-0.25));
      torque(axis) = v;
      RotorState<T> state = sentinel_state<T>();
      const Bytes<RotorState<T>> before(state);
      EXPECT_EQ(advance(tr, torque, state), Status::kNonFiniteInput);
      EXPECT_TRUE(before.same_as(state));
      EXPECT_EQ(propagate(p, T(0.01), torque, state), Status::kNonFiniteInput);
      EXPECT_TRUE(before.same_as(state));
      Vector2<T> out = sentinel_vector<T>();
      const Bytes<Vector2<T>> out_before(out);
      EXPECT_EQ(steady_precession_rate(p, torque, out), Status::kNonFiniteInput);
      EXPECT_TRUE(out_before.same_as(out));
      EXPECT_EQ(nutation_amplitude(p, Vector2<T>(T(0.1), T(0.2)), torque, out), Status::kNonFiniteInput);
      EXPECT_TRUE(out_before.same_as(out));
      // The same value as a rate.
      EXPECT_EQ(nutation_amplitude(p, torque, Vector2<T>(T(0.1), T(0.2)), out), Status::kNonFiniteInput);
      EXPECT_TRUE(out_before.same_as(out));
      EXPECT_EQ(torque_for_precession_rate(p, torque, out), Status::kNonFiniteInput);
      EXPECT_TRUE(out_before.same_as(out));
    }
  }
}

TYPED_TEST(BadInput, GivenNonFiniteStateWhenAdvancingOrPropagatingThenNonFiniteInputAndStateBitIdentical) {
  GYRO_VERIFIES("EXACT-5", "RULE-9");
  using T = TypeParam;
  const RotorParameters<T> p = report_rotor<T>();
  RotorTransition<T> tr;
  ASSERT_EQ(make_transition(p, T(0.01), tr), Status::kOk);
  const Vector2<T> torque(T(0.5), T(-0.25));
  for (int component = 0; component < 4; ++component) {
    for (const T v : {kNaN<T>, -kNaN<T>, kInf<T>, -kInf<T>}) {
      SCOPED_TRACE("state[" + std::to_string(component) + "] = " + std::to_string(static_cast<double>(v)));
      RotorState<T> state = sentinel_state<T>();
      (component < 2 ? state.angle_rad : state.rate_rad_s)(component % 2) = v;
      const Bytes<RotorState<T>> before(state);
      EXPECT_EQ(advance(tr, torque, state), Status::kNonFiniteInput);
      EXPECT_TRUE(before.same_as(state));
      EXPECT_EQ(propagate(p, T(0.01), torque, state), Status::kNonFiniteInput);
      EXPECT_TRUE(before.same_as(state));
    }
  }
}

TYPED_TEST(BadInput, GivenNoSpinAndNoFrictionWhenSteadyRateThenNoSteadyStateButTransitionAndAmplitudeFine) {
  GYRO_VERIFIES("EXACT-5", "EXACT-4");
  using T = TypeParam;
  const RotorParameters<T> p{T(1), T(3), T(0), T(0)};
  Vector2<T> out = sentinel_vector<T>();
  const Bytes<Vector2<T>> before(out);
  EXPECT_EQ(steady_precession_rate(p, Vector2<T>(T(1), T(0)), out), Status::kNoSteadyState);
  EXPECT_TRUE(before.same_as(out));
  // Nothing to nutate without spin or friction: amplitude 0, not a rejection.
  EXPECT_EQ(nutation_amplitude(p, Vector2<T>(T(1), T(2)), Vector2<T>(T(1), T(0)), out), Status::kOk);
  EXPECT_EQ(out, Vector2<T>::Zero());
  RotorTransition<T> tr;
  EXPECT_EQ(make_transition(p, T(2), tr), Status::kOk);
}

// ----------------------------------------------------------------------------------------------
// Huge but finite: the result does not fit the type. kNumericalOverflow, output untouched.

TYPED_TEST(BadInput, GivenHugeButFiniteInputsWhenResultOverflowsThenNumericalOverflowNotNaN) {
  GYRO_VERIFIES("EXACT-5");
  using T = TypeParam;
  const T big = std::numeric_limits<T>::max() / T(4);
  const T huge_h = std::sqrt(std::numeric_limits<T>::max()) * T(16);  // H^2 overflows
  const T tiny_j = T(1) / std::sqrt(std::numeric_limits<T>::max());   // 1/(J1 J2) overflows
  {
    SCOPED_TRACE("spin so fast that beta^2 dt^2 overflows");
    const RotorParameters<T> p{T(1), T(1), T(0), huge_h};
    RotorTransition<T> tr = sentinel_transition<T>();
    const Bytes<RotorTransition<T>> before(tr);
    EXPECT_EQ(make_transition(p, T(1), tr), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(tr));
    RotorModes<T> m = sentinel_modes<T>();
    const Bytes<RotorModes<T>> m_before(m);
    EXPECT_EQ(compute_modes(p, m), Status::kNumericalOverflow);
    EXPECT_TRUE(m_before.same_as(m));
  }
  {
    SCOPED_TRACE("inertias so small that omega0^2 overflows");
    const RotorParameters<T> p{tiny_j, tiny_j, T(1), T(1)};
    RotorModes<T> m = sentinel_modes<T>();
    const Bytes<RotorModes<T>> m_before(m);
    EXPECT_EQ(compute_modes(p, m), Status::kNumericalOverflow);
    EXPECT_TRUE(m_before.same_as(m));
    RotorState<T> state = sentinel_state<T>();
    const Bytes<RotorState<T>> before(state);
    EXPECT_EQ(propagate(p, T(1), Vector2<T>(T(1), T(1)), state), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(state));
  }
  {
    SCOPED_TRACE("a nutation amplitude |A^-1 (w - w_ss)| beyond the type: huge inertia and rate");
    const T heavy = std::sqrt(std::numeric_limits<T>::max()) / T(16);
    const RotorParameters<T> p{heavy, heavy, T(1), T(1)};
    Vector2<T> amp = sentinel_vector<T>();
    const Bytes<Vector2<T>> amp_before(amp);
    EXPECT_EQ(nutation_amplitude(p, Vector2<T>(big, -big), Vector2<T>(T(1), T(1)), amp), Status::kNumericalOverflow);
    EXPECT_TRUE(amp_before.same_as(amp));
  }
  {
    SCOPED_TRACE("a free rotor whose angle outgrows the type: dt^2/2 T/J");
    const RotorParameters<T> p{T(1), T(1), T(0), T(0)};
    RotorTransition<T> tr = sentinel_transition<T>();
    const Bytes<RotorTransition<T>> before(tr);
    EXPECT_EQ(make_transition(p, std::sqrt(std::numeric_limits<T>::max()) * T(2), tr), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(tr));
  }
  {
    SCOPED_TRACE("a finite transition applied to a torque that overflows the state");
    const RotorParameters<T> p{T(1e-3), T(1e-3), T(0), T(0)};
    RotorTransition<T> tr;
    ASSERT_EQ(make_transition(p, T(10), tr), Status::kOk);
    for (const Vector2<T>& torque : {Vector2<T>(big, T(0)), Vector2<T>(T(0), -big)}) {
      RotorState<T> state = sentinel_state<T>();
      const Bytes<RotorState<T>> before(state);
      EXPECT_EQ(advance(tr, torque, state), Status::kNumericalOverflow);
      EXPECT_TRUE(before.same_as(state));
      EXPECT_EQ(propagate(p, T(10), torque, state), Status::kNumericalOverflow);
      EXPECT_TRUE(before.same_as(state));
    }
    RotorState<T> state = sentinel_state<T>();  // and a state whose rate overflows the angle
    state.rate_rad_s = Vector2<T>(big, big);
    const Bytes<RotorState<T>> before(state);
    EXPECT_EQ(advance(tr, Vector2<T>(T(1), T(1)), state), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(state));
  }
  {
    SCOPED_TRACE("steady precession T/H beyond the type");
    const RotorParameters<T> p{T(1), T(1), T(0), T(1) / huge_h};
    Vector2<T> out = sentinel_vector<T>();
    const Bytes<Vector2<T>> before(out);
    EXPECT_EQ(steady_precession_rate(p, Vector2<T>(big, T(0)), out), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(out));
    // Friction and torque so large that f T and f^2 + H^2 both overflow (inf/inf = NaN inside).
    const RotorParameters<T> q{T(1), T(1), big, T(1)};
    EXPECT_EQ(steady_precession_rate(q, Vector2<T>(big, T(0)), out), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(out));
  }
  {
    SCOPED_TRACE("torque for a precession rate beyond the type");
    const RotorParameters<T> p{T(1), T(1), big, big};
    Vector2<T> out = sentinel_vector<T>();
    const Bytes<Vector2<T>> before(out);
    EXPECT_EQ(torque_for_precession_rate(p, Vector2<T>(big, big), out), Status::kNumericalOverflow);
    EXPECT_TRUE(before.same_as(out));
  }
}

// ----------------------------------------------------------------------------------------------
// Nutation amplitude.

template <typename T>
class NutationAmplitudeOf : public ::testing::Test {};
TYPED_TEST_SUITE(NutationAmplitudeOf, Scalars);

// The report's eqs 11, 13-15 in long double: amplitude of theta and psi's nutation.
template <typename T>
Vector2<double> report_amplitude(const RotorParameters<T>& prm, const Vector2<T>& w, const Vector2<T>& torque) {
  using L = long double;
  const L j1 = static_cast<L>(prm.pitch_inertia), j2 = static_cast<L>(prm.yaw_inertia);
  const L f = static_cast<L>(prm.friction), h = static_cast<L>(prm.angular_momentum);
  const L t1 = static_cast<L>(torque(0)), t2 = static_cast<L>(torque(1));
  const L k5 = (f * t1 - h * t2) / (f * f + h * h);
  const L k6 = (h * t1 + f * t2) / (f * f + h * h);
  const L alpha = f / 2 * (1 / j1 + 1 / j2);
  const L beta = std::sqrt((f * f + h * h) / (j1 * j2) - alpha * alpha);
  const L k2 = static_cast<L>(w(0)) - k5;
  const L k4 = static_cast<L>(w(1)) - k6;
  const L k1 = ((alpha * j1 - f) * k2 - h * k4) / (beta * j1);
  const L k3 = ((alpha * j1 - f) * k1 + beta * j1 * k2) / h;
  const L den = alpha * alpha + beta * beta;
  return {static_cast<double>(std::sqrt((k1 * k1 + k2 * k2) / den)),
          static_cast<double>(std::sqrt((k3 * k3 + k4 * k4) / den))};
}

TYPED_TEST(NutationAmplitudeOf, GivenReportGyroWhenNutationAmplitudeThenEqualsReportEq15) {
  GYRO_VERIFIES("EXACT-4");
  using T = TypeParam;
  const double tol = std::is_same_v<T, float> ? 1e-5 : 1e-12;
  const RotorParameters<T> p = report_rotor<T>();
  const Vector2<T> rates[] = {{T(0.1), T(-0.05)}, {T(0), T(0)}, {T(-3), T(2)}, {T(1e-3), T(0.5)}};
  const Vector2<T> torques[] = {{T(0), T(0)}, {T(1), T(2)}, {T(-50), T(7)}};
  for (const Vector2<T>& w : rates) {
    for (const Vector2<T>& tq : torques) {
      Vector2<T> amp = Vector2<T>::Zero();
      ASSERT_EQ(nutation_amplitude(p, w, tq, amp), Status::kOk);
      const Vector2<double> expected = report_amplitude(p, w, tq);
      for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR(static_cast<double>(amp(i)), expected(i), tol * std::max(expected(i), 1e-30))
            << "axis " << i << " w=(" << w.transpose() << ") T=(" << tq.transpose() << ")";
      }
    }
  }
}

TYPED_TEST(NutationAmplitudeOf, GivenFrictionThroughCriticalWhenNutationAmplitudeThenFiniteAndContinuous) {
  GYRO_VERIFIES("EXACT-4");
  using T = TypeParam;
  // J2 = 4 J1, H = 1: critical friction f_c = 2 H sqrt(J1 J2)/|J2 - J1| = 4/3.
  const T f_c = T(4) / T(3);
  const Vector2<T> w(T(0.3), T(-0.2));
  const Vector2<T> torque(T(0.1), T(0.05));
  auto amplitude = [&](T f) {
    Vector2<T> amp = Vector2<T>::Zero();
    EXPECT_EQ(nutation_amplitude(RotorParameters<T>{T(1), T(4), f, T(1)}, w, torque, amp), Status::kOk);
    EXPECT_TRUE(all_finite(amp)) << "f = " << f;
    return amp;
  };
  const Vector2<T> at_critical = amplitude(f_c);
  const T eps = std::numeric_limits<T>::epsilon();
  for (T delta = T(1e-1); delta > T(4) * eps; delta /= T(10)) {
    const Vector2<T> below = amplitude(f_c * (T(1) - delta));
    const Vector2<T> above = amplitude(f_c * (T(1) + delta));
    // The overdamped side moves like sqrt(delta) (gamma = sqrt(-beta^2)); the underdamped side
    // smoothly. 4 sqrt(delta) + rounding bounds both.
    const T allowed = T(4) * std::sqrt(delta) + T(64) * std::sqrt(eps);
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(std::abs(below(i) - at_critical(i)), allowed * at_critical(i)) << "delta " << delta;
      EXPECT_LE(std::abs(above(i) - at_critical(i)), allowed * at_critical(i)) << "delta " << delta;
    }
  }
  // Exactly critical (beta^2 == 0 with no rounding): H = 0, J1 = J2, so N = 0: the transient
  // is a pure decay of A^-1 (w - w_ss), whose size the amplitude is.
  Vector2<T> amp = Vector2<T>::Zero();
  const RotorParameters<T> exact{T(2), T(2), T(3), T(0)};
  RotorModes<T> modes;
  ASSERT_EQ(compute_modes(exact, modes), Status::kOk);
  ASSERT_EQ(modes.regime, DampingRegime::kCritical);
  ASSERT_EQ(nutation_amplitude(exact, w, torque, amp), Status::kOk);
  Vector2<T> w_ss = Vector2<T>::Zero();
  ASSERT_EQ(steady_precession_rate(exact, torque, w_ss), Status::kOk);
  // 16 eps: armhf's unfused NEON float arithmetic lands 9 eps away on a value of 0.18.
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(amp(i), std::abs(w(i) - w_ss(i)) * T(2) / T(3), T(16) * eps);
}

// The angle's transient from a fine simulation with the exact step: angle(t) minus the
// precession line angle0 + w_ss t + B it settles on, B = -A^-1 (w0 - w_ss) (from the matrix A
// itself). Returns the largest |transient| per axis.
Vector2<double> simulated_transient(const RotorParameters<double>& p, const Vector2<double>& w0,
                                    const Vector2<double>& torque, double sample_dt, int samples) {
  Vector2<double> w_ss = Vector2<double>::Zero();
  EXPECT_EQ(steady_precession_rate(p, torque, w_ss), Status::kOk);
  Matrix2<double> a_mat;
  a_mat << -p.friction / p.pitch_inertia, -p.angular_momentum / p.pitch_inertia, p.angular_momentum / p.yaw_inertia,
      -p.friction / p.yaw_inertia;
  const Vector2<double> b = -a_mat.inverse() * (w0 - w_ss);
  RotorTransition<double> tr;
  EXPECT_EQ(make_transition(p, sample_dt, tr), Status::kOk);
  RotorState<double> s;
  s.rate_rad_s = w0;
  Vector2<double> worst = b.cwiseAbs();  // t = 0
  for (int i = 1; i <= samples; ++i) {
    EXPECT_EQ(advance(tr, torque, s), Status::kOk);
    const Vector2<double> transient = s.angle_rad - w_ss * (sample_dt * i) - b;
    worst = worst.cwiseMax(transient.cwiseAbs());
  }
  return worst;
}

TEST(NutationAmplitude, GivenEveryDampingRegimeWhenSimulatedFinelyThenAmplitudeBoundsTheAngleTransient) {
  GYRO_VERIFIES("EXACT-4");
  const double pi = 3.14159265358979323846;
  struct Rotor {
    const char* name;
    RotorParameters<double> prm;
  };
  RotorParameters<double> near_critical{1.0, 4.0, 4.0 / 3.0, 1.0};
  RotorParameters<double> critical_exact{2.0, 2.0, 3.0, 0.0};
  const Rotor rotors[] = {
      {"underdamped, the report's gyro", {2.25, 2.0, 5.0, 2.0 * pi * 100.0 * 3.0}},
      {"underdamped, beta < e alpha", {1.0, 4.0, 1.2, 1.0}},
      {"critical, J1 != J2", near_critical},
      {"critical, H = 0 and J1 = J2", critical_exact},
      {"overdamped, mild", {1.0, 4.0, 1.6, 1.0}},
      {"overdamped, stiff", {1.0, 50.0, 60.0, 3.0}},
      {"overdamped, no spin", {0.5, 5.0, 2.0, 0.0}},
  };
  std::mt19937_64 rng(0x6e757461ULL);
  auto uniform = [&rng](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1p-53; };
  for (const Rotor& r : rotors) {
    SCOPED_TRACE(r.name);
    const RotorParameters<double>& p = r.prm;
    RotorModes<double> modes;
    ASSERT_EQ(compute_modes(p, modes), Status::kOk);
    // 64 samples per nutation period and per fastest time constant, until the slowest mode
    // has decayed by e^-30.
    double sample_dt = 1.0 / (64.0 * modes.fast_decay_rate_1_s);
    if (modes.beta_rad_s > 0.0) sample_dt = std::min(sample_dt, 2.0 * pi / modes.beta_rad_s / 64.0);
    const int samples = static_cast<int>(30.0 / modes.slow_decay_rate_1_s / sample_dt);
    ASSERT_LT(samples, 400000);

    // Random initial rates and torques, plus the initial rate that puts the transient's
    // decay and its N-term in the ratio where a Euclidean (hypot) envelope falls short near
    // critical damping: y = 0.15 and (N y)/alpha = 1 on each axis in turn.
    std::vector<std::pair<Vector2<double>, Vector2<double>>> inputs;  // (w0, torque)
    for (int k = 0; k < 12; ++k) {
      inputs.emplace_back(Vector2<double>(uniform(-1, 1), uniform(-1, 1)), Vector2<double>(uniform(-1, 1), uniform(-1, 1)));
    }
    const double j1 = p.pitch_inertia, j2 = p.yaw_inertia, f = p.friction, h = p.angular_momentum;
    const double alpha = modes.alpha_1_s, d = f / 2.0 * (1.0 / j2 - 1.0 / j1), pp = h / j1, q = h / j2;
    Matrix2<double> a_mat;
    a_mat << -f / j1, -h / j1, h / j2, -f / j2;
    for (int axis = 0; axis < 2; ++axis) {
      if (h == 0.0) break;  // N is diagonal (or zero): no cross-axis term to arrange
      Vector2<double> y = Vector2<double>::Zero();
      // Row `axis` of N y = alpha with y(axis) = 0.15: solve for the other component.
      if (axis == 0) y = Vector2<double>(0.15, (d * 0.15 - alpha) / pp);
      else y = Vector2<double>((alpha + d * 0.15) / q, 0.15);
      const Vector2<double> torque(0.2, -0.1);
      Vector2<double> w_ss = Vector2<double>::Zero();
      ASSERT_EQ(steady_precession_rate(p, torque, w_ss), Status::kOk);
      inputs.emplace_back(w_ss + a_mat * (y * 1e-3), torque);
    }
    for (const auto& [w0, torque] : inputs) {
      Vector2<double> amp = Vector2<double>::Zero();
      ASSERT_EQ(nutation_amplitude(p, w0, torque, amp), Status::kOk);
      const Vector2<double> actual = simulated_transient(p, w0, torque, sample_dt, samples);
      for (int i = 0; i < 2; ++i) {
        EXPECT_LE(actual(i), amp(i) * (1.0 + 1e-9) + 1e-15)
            << "axis " << i << ": simulated max " << actual(i) << " > amplitude " << amp(i) << " (ratio "
            << actual(i) / amp(i) << ") w0=(" << w0.transpose() << ") T=(" << torque.transpose() << ")";
      }
      if (r.name[0] == 'u' && r.prm.angular_momentum > 1000.0) {
        // Lightly damped: the report's envelope is tight (the first peak, within a period).
        for (int i = 0; i < 2; ++i) EXPECT_GE(actual(i), 0.98 * amp(i)) << "axis " << i;
      }
    }
  }
}

// ---- the nutation map and the steady precession's inverse ------------------------------------

// A rotor whose transient map cannot be represented in T (J2/J1 of 1e300 with next to no spin
// and no friction: A^-1 overflows): the map says so, the amplitude is the largest finite T
// (GyroModel then raises its small-angle flag), and the one-call form refuses it untouched.
template <typename T>
void expect_saturated_map(const RotorParameters<T>& prm) {
  NutationMap<T> map;
  ASSERT_EQ(make_nutation_map(prm, map), Status::kOk);
  EXPECT_TRUE(map.saturated);
  EXPECT_FALSE(map.has_transient);
  EXPECT_TRUE(map.has_steady);
  EXPECT_EQ(map.envelope, std::numeric_limits<T>::max());
  EXPECT_TRUE(all_finite(map.steady_from_torque, map.transient_from_rate, map.rotated_from_rate));
  const Vector2<T> rate(T(1e-3), T(-2e-3));
  const Vector2<T> torque(T(0), T(0));
  const Vector2<T> amp = nutation_amplitude(map, rate, torque);
  EXPECT_EQ(amp, Vector2<T>::Constant(std::numeric_limits<T>::max()));
  Vector2<T> out(T(7), T(7));
  EXPECT_EQ(nutation_amplitude(prm, rate, torque, out), Status::kNumericalOverflow);
  EXPECT_EQ(out, Vector2<T>(T(7), T(7))) << "a refused call leaves its output as it was";
}

TEST(NutationMap, ATransientBeyondDoubleSaturates) {
  GYRO_VERIFIES("EXACT-4", "EXACT-5");
  expect_saturated_map(RotorParameters<double>{1e-150, 1e150, 0.0, 1e-161});
}

TEST(NutationMap, ATransientBeyondFloatSaturates) {
  GYRO_VERIFIES("EXACT-4", "EXACT-5", "RULE-8");
  expect_saturated_map(RotorParameters<float>{1e-20f, 1e20f, 0.0f, 1e-22f});
}

// Friction with no spin on gimbals so heavy that omega0^2 = f^2/(J1 J2) underflows to 0 while
// f^2 does not: a steady precession exists (w = T/f), a transient does not (as for f = H = 0).
TEST(NutationMap, AnUnderflowingOmega0LeavesSteadyOnly) {
  GYRO_VERIFIES("EXACT-4");
  const RotorParameters<double> prm{1e200, 1e200, 1e-150, 0.0};
  NutationMap<double> map;
  ASSERT_EQ(make_nutation_map(prm, map), Status::kOk);
  EXPECT_TRUE(map.has_steady);
  EXPECT_FALSE(map.has_transient);
  EXPECT_FALSE(map.saturated);
  EXPECT_EQ(map.steady_from_torque(0, 0), 1e150);  // f / (f^2 + H^2) = 1/f
  EXPECT_EQ(map.steady_from_torque(1, 0), 0.0);
  Vector2<double> out(7.0, 7.0);
  ASSERT_EQ(nutation_amplitude(prm, Vector2<double>(0.5, -0.25), Vector2<double>(1e-160, 0.0), out),
            Status::kOk);
  EXPECT_EQ(out, Vector2<double>::Zero());
}

TEST(NutationMap, BadParametersAreRefusedUntouched) {
  GYRO_VERIFIES("EXACT-5");
  NutationMap<double> map;
  map.envelope = 42.0;
  EXPECT_EQ(make_nutation_map(RotorParameters<double>{2.25, 2.0, -1.0, 100.0}, map), Status::kNegativeFriction);
  EXPECT_EQ(make_nutation_map(RotorParameters<double>{0.0, 2.0, 5.0, 100.0}, map), Status::kNonPositiveInertia);
  EXPECT_EQ(map.envelope, 42.0);
  EXPECT_FALSE(map.has_steady);
}

TEST(TorqueForPrecessionRate, RefusesBadInputUntouched) {
  GYRO_VERIFIES("EXACT-5");
  const RotorParameters<double> rotor{2.25, 2.0, 5.0, angular_momentum(100.0, 3.0)};
  const Vector2<double> untouched(7.0, -7.0);
  Vector2<double> out = untouched;
  RotorParameters<double> no_inertia = rotor;
  no_inertia.yaw_inertia = 0.0;
  EXPECT_EQ(torque_for_precession_rate(no_inertia, Vector2<double>(0.1, 0.2), out), Status::kNonPositiveInertia);
  EXPECT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.1, std::nan("")), out), Status::kNonFiniteInput);
  // H w2 beyond the largest double: not representable, refused rather than returned as inf.
  EXPECT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.0, 1e306), out), Status::kNumericalOverflow);
  EXPECT_EQ(out, untouched);
  // And the accepted case is the exact inverse of the steady precession.
  ASSERT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.1, 0.2), out), Status::kOk);
  Vector2<double> back;
  ASSERT_EQ(steady_precession_rate(rotor, out, back), Status::kOk);
  EXPECT_NEAR(back(0), 0.1, 1e-15);
  EXPECT_NEAR(back(1), 0.2, 1e-15);
}

}  // namespace
}  // namespace gyro
