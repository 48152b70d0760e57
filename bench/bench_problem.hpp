// The benchmark workload: one simulated second of the rotor (eqs 1a/1b plus theta' = w1,
// psi' = w2) from rest, under the constant torque whose steady precession is a commanded
// slew, for each gyro of the study, and the integrators that compete to simulate it.
//
// Every contender integrates the same linear system from the same initial state; only the
// method differs. The exact propagator is gyro's own (rotor_transition.hpp); the numerical
// contenders are what a simulation author would otherwise pick: classic RK4, Boost.Odeint's
// controlled Dormand-Prince 5(4), forward Euler and Adams-Bashforth 2.
#pragma once

#include <Eigen/Core>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gyro/report_sample.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/rotor_transition.hpp"

namespace gyro::bench {

using Vec2 = Vector2<double>;
using Vec4 = Eigen::Matrix<double, 4, 1>;  // (theta, psi, w1, w2)

// The report's sample run commands THTDCM = -0.19 rad/s (pitch) and PSIDCM = 0.013 rad/s (yaw).
inline const Vec2 kSlewRadS = ReportSample<double>::slew_command();
inline constexpr double kSimulatedSeconds = 1.0;
inline constexpr double kAccuracyTargetRad = 1e-6;

struct Case {
  std::string id;
  std::string label;
  RotorParameters<double> prm{};
  double spin_hz{};
  double spin_inertia{};
  double nutation_hz{};
  double alpha_1_s{};
  Vec2 torque{Vec2::Zero()};  // constant torque whose steady precession is kSlewRadS
  bool in_sweep{};            // a point of the seeker's spin-rate sweep
};

[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "gyro bench: %s\n", what);
  std::exit(2);
}

inline Case make_case(std::string id, std::string label, double j1, double j2, double friction,
                      double spin_hz, double spin_inertia, bool in_sweep) {
  Case c;
  c.id = std::move(id);
  c.label = std::move(label);
  c.prm = RotorParameters<double>{j1, j2, friction, angular_momentum(spin_hz, spin_inertia)};
  c.spin_hz = spin_hz;
  c.spin_inertia = spin_inertia;
  c.in_sweep = in_sweep;
  RotorModes<double> modes;
  if (compute_modes(c.prm, modes) != Status::kOk) fail("invalid rotor parameters");
  c.nutation_hz = modes.nutation_hz;
  c.alpha_1_s = modes.alpha_1_s;
  if (torque_for_precession_rate(c.prm, kSlewRadS, c.torque) != Status::kOk) fail("torque");
  return c;
}

// The seeker gyro: J1 = J2 = 2e-5 kg m^2, spin inertia 3e-5 kg m^2, friction for a nutation
// time constant 1/alpha = 50 ms (alpha = f/J when J1 = J2). With J1 = J2 the nutation rate is
// H/J exactly, so a nutation frequency fixes the spin rate: spin = nutation * J / J0.
inline constexpr double kSeekerJ = 2e-5;
inline constexpr double kSeekerJ0 = 3e-5;
inline constexpr double kSeekerFriction = kSeekerJ / 0.050;

inline Case seeker_case(std::string id, std::string label, double spin_hz, bool in_sweep) {
  return make_case(std::move(id), std::move(label), kSeekerJ, kSeekerJ, kSeekerFriction, spin_hz,
                   kSeekerJ0, in_sweep);
}

inline const std::vector<double>& sweep_nutation_hz() {
  static const std::vector<double> v{50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0};
  return v;
}

inline std::vector<Case> all_cases() {
  std::vector<Case> cases;
  // The report's sample gyro, from gyro/report_sample.hpp (slug ft^2).
  const GyroModelConfig<double> report = ReportSample<double>::config();
  cases.push_back(make_case("report", "report sample (slug ft^2)", report.pitch_inertia, report.yaw_inertia,
                            report.friction, ReportSample<double>::kSpinHz, report.spin_inertia, false));
  cases.push_back(seeker_case("seeker", "seeker, 400 Hz spin (SI)", 400.0, true));
  for (double nut : sweep_nutation_hz()) {
    char id[32];
    std::snprintf(id, sizeof id, "sweep_%05.0f", nut);
    char label[64];
    std::snprintf(label, sizeof label, "seeker, %.0f Hz nutation", nut);
    cases.push_back(seeker_case(id, label, nut * kSeekerJ / kSeekerJ0, true));
  }
  return cases;
}

inline Case find_case(const std::string& id) {
  for (const Case& c : all_cases()) {
    if (c.id == id) return c;
  }
  fail("unknown case id");
}

// ---------------------------------------------------------------------------------------
// The exact solution.

// The state at time t from rest, in one exact step: the reference for every contender.
inline RotorState<double> exact_at(const Case& c, double t) {
  RotorState<double> s;
  if (t == 0.0) return s;
  RotorTransition<double> tr;
  if (make_transition(c.prm, t, tr) != Status::kOk) fail("make_transition (reference)");
  if (advance(tr, c.torque, s) != Status::kOk) fail("advance (reference)");
  return s;
}

inline double angle_error(double theta, double psi, const RotorState<double>& ref) {
  return std::max(std::abs(theta - ref.angle_rad(0)), std::abs(psi - ref.angle_rad(1)));
}

// Exact propagator at the guidance tick, coefficients recomputed every tick (propagate).
template <typename Obs>
bool exact_propagate(const Case& c, long ticks, RotorState<double>& s, Obs&& obs) {
  const double dt = kSimulatedSeconds / static_cast<double>(ticks);
  bool ok = true;
  for (long i = 1; i <= ticks; ++i) {
    ok = (propagate(c.prm, dt, c.torque, s) == Status::kOk) && ok;
    obs(i, s);
  }
  return ok;
}

// Exact propagator at the guidance tick, coefficients computed once (make_transition) and
// applied every tick (advance).
template <typename Obs>
bool exact_precomputed(const Case& c, long ticks, RotorState<double>& s, Obs&& obs) {
  const double dt = kSimulatedSeconds / static_cast<double>(ticks);
  RotorTransition<double> tr;
  bool ok = make_transition(c.prm, dt, tr) == Status::kOk;
  for (long i = 1; i <= ticks; ++i) {
    ok = (advance(tr, c.torque, s) == Status::kOk) && ok;
    obs(i, s);
  }
  return ok;
}

// ---------------------------------------------------------------------------------------
// The numerical contenders. The right-hand side is written out with its coefficients
// folded once, the cheapest form a user could write.

struct LinearRhs {
  double k1{}, k2{};  // T1/J1, T2/J2
  double f1{}, h1{};  // f/J1, H/J1
  double f2{}, h2{};  // f/J2, H/J2
};

inline LinearRhs make_rhs(const Case& c) {
  LinearRhs r;
  r.k1 = c.torque(0) / c.prm.pitch_inertia;
  r.k2 = c.torque(1) / c.prm.yaw_inertia;
  r.f1 = c.prm.friction / c.prm.pitch_inertia;
  r.h1 = c.prm.angular_momentum / c.prm.pitch_inertia;
  r.f2 = c.prm.friction / c.prm.yaw_inertia;
  r.h2 = c.prm.angular_momentum / c.prm.yaw_inertia;
  return r;
}

// J1 w1' + f w1 + H w2 = T1,  J2 w2' + f w2 - H w1 = T2,  theta' = w1,  psi' = w2.
inline Vec4 rhs(const LinearRhs& r, const Vec4& x) {
  Vec4 d = Vec4::Zero();
  d << x(2), x(3), r.k1 - r.f1 * x(2) - r.h1 * x(3), r.k2 + r.h2 * x(2) - r.f2 * x(3);
  return d;
}

// Each fixed-step method takes `steps_per_second` steps of h = 1/steps_per_second and
// runs the first `run_steps` of them (all of them unless measuring a scaled-down run).

template <typename Obs>
Vec4 rk4(const LinearRhs& r, long steps_per_second, long run_steps, Obs&& obs) {
  const double h = kSimulatedSeconds / static_cast<double>(steps_per_second);
  const double h2 = 0.5 * h, h6 = h / 6.0;
  Vec4 x = Vec4::Zero();
  for (long i = 1; i <= run_steps; ++i) {
    const Vec4 k1 = rhs(r, x);
    const Vec4 k2 = rhs(r, x + h2 * k1);
    const Vec4 k3 = rhs(r, x + h2 * k2);
    const Vec4 k4 = rhs(r, x + h * k3);
    x += h6 * (k1 + 2.0 * (k2 + k3) + k4);
    obs(i, x);
  }
  return x;
}

template <typename Obs>
Vec4 euler(const LinearRhs& r, long steps_per_second, long run_steps, Obs&& obs) {
  const double h = kSimulatedSeconds / static_cast<double>(steps_per_second);
  Vec4 x = Vec4::Zero();
  for (long i = 1; i <= run_steps; ++i) {
    x += h * rhs(r, x);
    obs(i, x);
  }
  return x;
}

// Adams-Bashforth 2, started with one Heun (RK2) step.
template <typename Obs>
Vec4 ab2(const LinearRhs& r, long steps_per_second, long run_steps, Obs&& obs) {
  const double h = kSimulatedSeconds / static_cast<double>(steps_per_second);
  const double h32 = 1.5 * h, h12 = 0.5 * h;
  Vec4 x = Vec4::Zero();
  if (run_steps < 1) return x;
  Vec4 f_prev = rhs(r, x);
  x += h12 * (f_prev + rhs(r, x + h * f_prev));
  obs(1L, x);
  for (long i = 2; i <= run_steps; ++i) {
    const Vec4 f = rhs(r, x);
    x += h32 * f - h12 * f_prev;
    f_prev = f;
    obs(i, x);
  }
  return x;
}

// Boost.Odeint: controlled runge_kutta_dopri5 (abs = rel tolerance), integrate_adaptive over
// the whole second in one call, so the step size carries over (the cheapest use of it).
using OdeState = std::array<double, 4>;
inline constexpr double kDopriFirstStep = 1e-4;

struct OdeSystem {
  LinearRhs r;
  long* evaluations;  // counts right-hand-side calls when not null
  void operator()(const OdeState& x, OdeState& d, double /*t*/) const {
    if (evaluations != nullptr) ++*evaluations;
    d[0] = x[2];
    d[1] = x[3];
    d[2] = r.k1 - r.f1 * x[2] - r.h1 * x[3];
    d[3] = r.k2 + r.h2 * x[2] - r.f2 * x[3];
  }
};

// Returns the number of accepted steps.
template <typename Obs>
std::size_t dopri5(const LinearRhs& r, double tol, OdeState& x, long* evaluations, Obs&& obs) {
  namespace odeint = boost::numeric::odeint;
  x = OdeState{0.0, 0.0, 0.0, 0.0};
  auto stepper = odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<OdeState>());
  return odeint::integrate_adaptive(stepper, OdeSystem{r, evaluations}, x, 0.0,
                                    kSimulatedSeconds, kDopriFirstStep, obs);
}

struct NoObserver {
  template <typename... A>
  void operator()(const A&...) const noexcept {}
};

}  // namespace gyro::bench
