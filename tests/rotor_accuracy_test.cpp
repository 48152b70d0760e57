// Accuracy of the exact rotor discretisation (make_transition + advance, propagate) against an
// independent reference: the matrix exponential of the 6x6 augmented system
//
//   d/dt (theta, psi, w1, w2, T1, T2) = [[0, I, 0], [0, A, J^-1], [0, 0, 0]] (...)
//
// by scaling and squaring with a long Taylor series in quadruple precision. The reference
// never uses the closed form (no eigenvalues, no regime branches), only + - * /.
//
// Error measure, per output state x_i:
//   err_i = |x_i - x_ref_i| / max(|x_ref_i|, scale_i),
//   scale_i = the largest term the exact solution adds up: max(|x0_i|, |Phi_ij x0_j|, |Gamma_ij T_j|).
// Bounds: 1e-12 in double, 1e-5 in float (float inputs, reference at the same float inputs),
// except where the problem itself is ill-conditioned. The floor of a case is the largest change
// of the exact answer (same measure) when one input (J1, J2, f, H or dt) moves by one ulp of the
// scalar type; when 16 x floor exceeds the bound, the bound is 16 x floor. Every case must
// also be within 16 x max(floor, u) (u: unit roundoff), which implies the bounds above.
//
// The floor passes 1/16 of the bound for beta*dt >= 1e4 rad in double (about 200 rad in
// float): one ulp of dt moves the nutation phase by beta*dt*u. It can do so well below that,
// from beta*dt ~ 1e2 in double and ~ 10 in float: the measure compares each output with its
// largest term, and a term caught near a zero of its oscillation is small while its
// sensitivity to the phase is not (with J2 = 100 J1 the rate coupling sqrt(J2/J1) alone is
// 10). A sweep of 1000 undamped cases with 1e3 <= beta*dt < 1e4 found 15% with an error above
// 1e-12, every one within 2.2x its floor: no double computation of the phase does better, so
// the floor is computed for every case, not only for beta*dt >= 1e4.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "gyro/rotor_transition.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// ----------------------------------------------------------------------------------------------
// Quadruple precision. GCC provides __float128 on x86-64 (and ppc64le with -mfloat128); its
// arithmetic comes from libgcc, so nothing beyond + - * / is needed from libquadmath. Elsewhere
// (aarch64, riscv64: long double is IEEE quad; 32-bit ppc: IBM double-double; armhf: long double
// is plain double) the reference falls back to long double. On armhf that leaves the reference
// no more precise than the code under test; the bounds are deliberately not loosened for it.
#if defined(__SIZEOF_FLOAT128__)
__extension__ typedef __float128 Quad;
constexpr int kQuadMantissaBits = 113;
#else
using Quad = long double;
constexpr int kQuadMantissaBits = std::numeric_limits<long double>::digits;
#endif

Quad quad_epsilon() {
  Quad e = 1;
  for (int i = 1; i < kQuadMantissaBits; ++i) e /= 2;
  return e;
}
Quad qabs(Quad x) { return x < 0 ? -x : x; }
double to_double(Quad x) { return static_cast<double>(x); }
Quad qsqrt(Quad v) {  // Newton from the double root: quadratic convergence, two steps suffice
  if (!(v > 0)) return 0;
  Quad x = static_cast<Quad>(std::sqrt(to_double(v)));
  for (int i = 0; i < 3; ++i) x = (x + v / x) / 2;
  return x;
}

struct Mat6 {
  Quad a[6][6];
};

Mat6 identity6() {
  Mat6 r{};
  for (int i = 0; i < 6; ++i) r.a[i][i] = 1;
  return r;
}

Mat6 mul(const Mat6& x, const Mat6& y) {
  Mat6 r{};
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 6; ++k) {
      const Quad xik = x.a[i][k];
      if (xik == 0) continue;
      for (int j = 0; j < 6; ++j) r.a[i][j] += xik * y.a[k][j];
    }
  }
  return r;
}

// exp(m): scale by 2^-s until the 1-norm is <= 1/2, Taylor series of 30 terms (the first
// dropped term is below 0.5^31/31! = 6e-44), then square s times.
Mat6 expm(const Mat6& m) {
  Quad norm = 0;
  for (int j = 0; j < 6; ++j) {
    Quad col = 0;
    for (int i = 0; i < 6; ++i) col += qabs(m.a[i][j]);
    norm = std::max(norm, col);
  }
  int squarings = 0;
  Quad factor = 1;
  while (norm * factor > Quad(0.5)) {
    factor /= 2;
    ++squarings;
  }
  Mat6 x{};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) x.a[i][j] = m.a[i][j] * factor;
  }
  constexpr int kTerms = 30;
  Mat6 r = identity6();  // Horner: I + x/1 (I + x/2 (I + ... (I + x/K)))
  for (int k = kTerms; k >= 1; --k) {
    r = mul(x, r);
    for (int i = 0; i < 6; ++i) {
      for (int j = 0; j < 6; ++j) r.a[i][j] /= k;
    }
    for (int i = 0; i < 6; ++i) r.a[i][i] += 1;
  }
  for (int s = 0; s < squarings; ++s) r = mul(r, r);
  return r;
}

struct QuadParams {
  Quad j1, j2, f, h, dt;
};

// x(dt) = Phi x0 + Gamma T for x = (theta, psi, w1, w2).
struct Reference {
  Quad phi[4][4];
  Quad gamma[4][2];
};

Reference reference(const QuadParams& p) {
  Mat6 m{};
  m.a[0][2] = p.dt;
  m.a[1][3] = p.dt;
  m.a[2][2] = -p.f / p.j1 * p.dt;
  m.a[2][3] = -p.h / p.j1 * p.dt;
  m.a[3][2] = p.h / p.j2 * p.dt;
  m.a[3][3] = -p.f / p.j2 * p.dt;
  m.a[2][4] = p.dt / p.j1;
  m.a[3][5] = p.dt / p.j2;
  const Mat6 e = expm(m);
  Reference r{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) r.phi[i][j] = e.a[i][j];
    for (int j = 0; j < 2; ++j) r.gamma[i][j] = e.a[i][4 + j];
  }
  return r;
}

// beta^2 = (f^2 + H^2)/(J1 J2) - alpha^2 = H^2/(J1 J2) - (f^2/4)(1/J1 - 1/J2)^2, in quad.
Quad exact_beta_sq(const QuadParams& p) {
  const Quad dk = (1 / p.j1 - 1 / p.j2) / 2;
  return p.h * p.h / (p.j1 * p.j2) - p.f * p.f * dk * dk;
}
Quad exact_omega0_sq(const QuadParams& p) { return (p.f * p.f + p.h * p.h) / (p.j1 * p.j2); }

// The reference answer and the scale of each output, for given initial state and torque.
struct Expected {
  std::array<Quad, 4> x;
  std::array<Quad, 4> scale;
};

Expected expected(const Reference& r, const std::array<Quad, 4>& x0, const std::array<Quad, 2>& tq) {
  Expected e{};
  for (int i = 0; i < 4; ++i) {
    Quad sum = 0;
    Quad scale = qabs(x0[static_cast<std::size_t>(i)]);  // the state's own initial value
    for (int j = 0; j < 4; ++j) {
      const Quad term = r.phi[i][j] * x0[static_cast<std::size_t>(j)];
      sum += term;
      scale = std::max(scale, qabs(term));
    }
    for (int j = 0; j < 2; ++j) {
      const Quad term = r.gamma[i][j] * tq[static_cast<std::size_t>(j)];
      sum += term;
      scale = std::max(scale, qabs(term));
    }
    e.x[static_cast<std::size_t>(i)] = sum;
    e.scale[static_cast<std::size_t>(i)] = scale;
  }
  return e;
}

double relative_error(const Expected& e, const std::array<Quad, 4>& x) {
  double worst = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const Quad den = std::max(qabs(e.x[i]), e.scale[i]);
    const Quad diff = qabs(x[i] - e.x[i]);
    const double err = (den > 0) ? to_double(diff / den) : to_double(diff);
    worst = std::max(worst, err);
  }
  return worst;
}

// ----------------------------------------------------------------------------------------------
// Test cases: parameters in double; the float run rounds every input to float.

struct Case {
  std::string regime;
  double j1, j2, f, h, dt;
  std::array<double, 4> x0;     // theta, psi, w1, w2
  std::array<double, 2> torque;
  bool tune_friction;           // re-choose f in the scalar type: beta^2/omega0^2 nearest target
  double target_rel_beta_sq;
};

// Deterministic everywhere: only the raw 64-bit stream of mt19937_64 is used.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : g_(seed) {}
  double uniform01() { return static_cast<double>(g_() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform01()); }
  double sign() { return (g_() & 1U) ? 1.0 : -1.0; }
  double signed_log_uniform(double lo, double hi) { return sign() * log_uniform(lo, hi); }
  double inertia_ratio(double lo, double hi) {  // in [lo, hi] or its inverse, hitting the ends
    const double u = uniform01();
    double r = (u < 0.1) ? hi : log_uniform(lo, hi);
    return (g_() & 1U) ? r : 1.0 / r;
  }

 private:
  std::mt19937_64 g_;
};

void random_state(Rng& rng, Case& c) {
  c.x0 = {rng.signed_log_uniform(1e-4, 1e-1), rng.signed_log_uniform(1e-4, 1e-1),
          rng.signed_log_uniform(1e-3, 1e1), rng.signed_log_uniform(1e-3, 1e1)};
  c.torque = {rng.signed_log_uniform(1e-3, 1e1), rng.signed_log_uniform(1e-3, 1e1)};
}

// Friction for beta^2 = target * omega0^2 (0: critical), H = 1.
double friction_for(double j1, double j2, double target) {
  const double k = (1.0 / j1 - 1.0 / j2) * (1.0 / j1 - 1.0 / j2) / 4.0;
  return std::sqrt((1.0 - target) / (j1 * j2 * k + target));
}

// Sets dt and scales (f, H) together (which keeps the damping regime) so that
// rate*dt = z, with z log-uniform in [1e-7, 1e5], rate in [1e-3, 1e6] rad/s, dt in [1e-9, 100] s.
void set_step(Rng& rng, double unit_rate, Case& c) {
  const double z = rng.log_uniform(1e-7, 1e5);
  const double rate = rng.log_uniform(std::max(1e-3, z / 100.0), std::min(1e6, z / 1e-9));
  const double scale = rate / unit_rate;
  c.f *= scale;
  c.h *= scale;
  c.dt = z / rate;
}

double fastest_rate(double j1, double j2, double f, double h) {
  const double alpha = f / 2.0 * (1.0 / j1 + 1.0 / j2);
  const double omega0_sq = (f * f + h * h) / (j1 * j2);
  const double beta_sq = omega0_sq - alpha * alpha;
  return beta_sq >= 0.0 ? std::sqrt(omega0_sq) : alpha + std::sqrt(-beta_sq);
}

std::vector<Case> make_cases() {
  std::vector<Case> cases;
  Rng rng(0x67797230'5eed0001ULL);
  const double kReportH = 2.0 * 3.14159265358979323846 * 100.0 * 3.0;

  // The report's gyro: dt log-spaced from 1e-9 to 100 s (beta*dt from 9e-7 to 9e4 rad).
  for (int i = 0; i < 40; ++i) {
    Case c{"underdamped/report", 2.25, 2.0, 5.0, kReportH, std::pow(10.0, -9.0 + 11.0 * i / 39.0),
           {}, {}, false, 0.0};
    random_state(rng, c);
    cases.push_back(c);
  }
  // Random underdamped: f below critical, inertia ratios up to 100 (and J1 = J2).
  for (int i = 0; i < 70; ++i) {
    Case c{"underdamped/random", rng.log_uniform(1e-2, 10.0), 0, 0, 1.0, 0, {}, {}, false, 0.0};
    c.j2 = (i % 10 == 0) ? c.j1 : c.j1 * rng.inertia_ratio(1.0, 100.0);
    const double u = rng.log_uniform(1e-4, 0.999);
    c.f = (c.j1 == c.j2) ? u * 100.0 / c.j1 : u * friction_for(c.j1, c.j2, 0.0);
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // Critically damped, beta^2 = 0 exactly: H = 0 and J1 = J2.
  for (int i = 0; i < 20; ++i) {
    Case c{"critical/exact", rng.log_uniform(1e-2, 10.0), 0, 1.0, 0.0, 0, {}, {}, false, 0.0};
    c.j2 = c.j1;
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // J1 != J2, f nearest critical in the scalar type, and beta^2 = +-1e-10 omega0^2.
  const std::array<std::pair<const char*, double>, 3> near{
      {{"critical/nearest", 0.0}, {"critical/+1e-10", 1e-10}, {"critical/-1e-10", -1e-10}}};
  for (const auto& [name, target] : near) {
    const int n = (target == 0.0) ? 30 : 15;
    for (int i = 0; i < n; ++i) {
      Case c{name, rng.log_uniform(1e-2, 10.0), 0, 0, 1.0, 0, {}, {}, true, target};
      c.j2 = c.j1 * rng.inertia_ratio(1.05, 100.0);
      c.f = friction_for(c.j1, c.j2, target);
      set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
      random_state(rng, c);
      cases.push_back(c);
    }
  }
  // Between those and the regimes either side: f = (1 +- 1e-8 .. 1e-1) x critical.
  for (int i = 0; i < 30; ++i) {
    const bool over = i % 2 == 0;
    Case c{over ? "critical/above" : "critical/below", rng.log_uniform(1e-2, 10.0), 0, 0, 1.0, 0, {}, {}, false,
           0.0};
    c.j2 = c.j1 * rng.inertia_ratio(1.05, 100.0);
    c.f = friction_for(c.j1, c.j2, 0.0) * (1.0 + (over ? 1.0 : -1.0) * rng.log_uniform(1e-8, 1e-1));
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // Overdamped: mild (f up to 3x critical) and stiff (f 10 to 1e4 x critical).
  for (int i = 0; i < 60; ++i) {
    const bool stiff = i >= 30;
    Case c{stiff ? "overdamped/stiff" : "overdamped/mild", rng.log_uniform(1e-2, 10.0), 0, 0, 1.0, 0,
           {}, {}, false, 0.0};
    c.j2 = c.j1 * rng.inertia_ratio(stiff ? 10.0 : 1.5, 100.0);
    c.f = friction_for(c.j1, c.j2, 0.0) * (stiff ? rng.log_uniform(10.0, 1e4) : rng.log_uniform(1.01, 3.0));
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // No spin (H = 0, J1 != J2): two real decay rates f/J1 and f/J2.
  for (int i = 0; i < 25; ++i) {
    Case c{"no spin H=0", rng.log_uniform(1e-2, 10.0), 0, 1.0, 0.0, 0, {}, {}, false, 0.0};
    c.j2 = c.j1 * rng.inertia_ratio(1.05, 100.0);
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // No friction (f = 0): undamped nutation at beta = H/sqrt(J1 J2).
  for (int i = 0; i < 25; ++i) {
    Case c{"no friction f=0", rng.log_uniform(1e-2, 10.0), 0, 0.0, 1.0, 0, {}, {}, false, 0.0};
    c.j2 = (i % 5 == 0) ? c.j1 : c.j1 * rng.inertia_ratio(1.0, 100.0);
    set_step(rng, fastest_rate(c.j1, c.j2, c.f, c.h), c);
    random_state(rng, c);
    cases.push_back(c);
  }
  // f = H = 0: free gimbals, the torque accelerates them.
  for (int i = 0; i < 15; ++i) {
    Case c{"free f=H=0", rng.log_uniform(1e-2, 10.0), 0, 0.0, 0.0, rng.log_uniform(1e-9, 100.0), {}, {},
           false, 0.0};
    c.j2 = c.j1 * rng.inertia_ratio(1.0, 100.0);
    random_state(rng, c);
    cases.push_back(c);
  }
  // A heavy and a light gimbal (J ratio 100), at or above critical friction, many time
  // constants per step, driven by the torque: the light axis's response is 100x smaller than
  // the heavy one's, so any mixing of the two in the diagonal of E1/E2 shows.
  for (int i = 0; i < 30; ++i) {
    Case c{"inertia ratio 100", rng.log_uniform(1e-2, 10.0), 0, 0, (i % 3 == 0) ? 0.0 : 1.0, 0, {}, {},
           false, 0.0};
    c.j2 = c.j1 * ((i % 2 == 0) ? 100.0 : 0.01);
    c.f = (c.h == 0.0) ? 1.0 : friction_for(c.j1, c.j2, 0.0) * rng.log_uniform(1.0, 100.0);
    const double z = rng.log_uniform(10.0, 1e5);
    c.dt = z / fastest_rate(c.j1, c.j2, c.f, c.h);
    random_state(rng, c);
    c.x0[2] *= 1e-3;
    c.x0[3] *= 1e-3;
    cases.push_back(c);
  }
  return cases;
}

const std::vector<Case>& all_cases() {
  static const std::vector<Case> cases = make_cases();
  return cases;
}

// ----------------------------------------------------------------------------------------------
// Running one case in a scalar type.

template <typename T>
struct Precision;
template <>
struct Precision<double> {
  static constexpr double kTolerance = 1e-12;
  static constexpr const char* kName = "double";
};
template <>
struct Precision<float> {
  static constexpr double kTolerance = 1e-5;
  static constexpr const char* kName = "float";
};

template <typename T>
struct TypedCase {
  RotorParameters<T> prm;
  T dt;
  Vector2<T> angle0, rate0, torque;
};

template <typename T>
QuadParams to_quad(const RotorParameters<T>& p, T dt) {
  return {static_cast<Quad>(p.pitch_inertia), static_cast<Quad>(p.yaw_inertia), static_cast<Quad>(p.friction),
          static_cast<Quad>(p.angular_momentum), static_cast<Quad>(dt)};
}

// f in T whose exact beta^2/omega0^2 is nearest the target (J1, J2, H fixed).
template <typename T>
T tuned_friction(const RotorParameters<T>& p, double target) {
  const Quad j1 = static_cast<Quad>(p.pitch_inertia), j2 = static_cast<Quad>(p.yaw_inertia);
  const Quad h = static_cast<Quad>(p.angular_momentum);
  const Quad dk = (1 / j1 - 1 / j2) / 2;
  const Quad tq = static_cast<Quad>(target);
  const Quad f_exact = qsqrt(h * h * (1 - tq) / (j1 * j2 * dk * dk + tq));
  auto deviation = [&](T f) {
    const QuadParams q{j1, j2, static_cast<Quad>(f), h, 1};
    return qabs(exact_beta_sq(q) / exact_omega0_sq(q) - tq);
  };
  T best = static_cast<T>(f_exact);
  Quad best_dev = deviation(best);
  for (const T dir : {-std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity()}) {
    T f = static_cast<T>(f_exact);
    for (int i = 0; i < 16; ++i) {
      f = std::nextafter(f, dir);
      const Quad dev = deviation(f);
      if (dev < best_dev) {
        best_dev = dev;
        best = f;
      }
    }
  }
  return best;
}

template <typename T>
TypedCase<T> typed(const Case& c) {
  TypedCase<T> t{};
  t.prm = {static_cast<T>(c.j1), static_cast<T>(c.j2), static_cast<T>(c.f), static_cast<T>(c.h)};
  if (c.tune_friction) t.prm.friction = tuned_friction(t.prm, c.target_rel_beta_sq);
  t.dt = static_cast<T>(c.dt);
  t.angle0 = Vector2<T>(static_cast<T>(c.x0[0]), static_cast<T>(c.x0[1]));
  t.rate0 = Vector2<T>(static_cast<T>(c.x0[2]), static_cast<T>(c.x0[3]));
  t.torque = Vector2<T>(static_cast<T>(c.torque[0]), static_cast<T>(c.torque[1]));
  return t;
}

template <typename T>
Expected expected_for(const TypedCase<T>& t, const QuadParams& q) {
  const std::array<Quad, 4> x0{static_cast<Quad>(t.angle0(0)), static_cast<Quad>(t.angle0(1)),
                               static_cast<Quad>(t.rate0(0)), static_cast<Quad>(t.rate0(1))};
  const std::array<Quad, 2> tq{static_cast<Quad>(t.torque(0)), static_cast<Quad>(t.torque(1))};
  return expected(reference(q), x0, tq);
}

// The floor: the largest change of the exact answer under a one-ulp change (in T) of one input.
template <typename T>
double conditioning_floor(const TypedCase<T>& t, const Expected& base) {
  double floor = 0.0;
  for (int which = 0; which < 5; ++which) {
    RotorParameters<T> p = t.prm;
    T dt = t.dt;
    const T inf = std::numeric_limits<T>::infinity();
    switch (which) {
      case 0: p.pitch_inertia = std::nextafter(p.pitch_inertia, inf); break;
      case 1: p.yaw_inertia = std::nextafter(p.yaw_inertia, inf); break;
      case 2: p.friction = std::nextafter(p.friction, inf); break;
      case 3: p.angular_momentum = std::nextafter(p.angular_momentum, inf); break;
      default: dt = std::nextafter(dt, inf); break;
    }
    TypedCase<T> moved = t;
    moved.prm = p;
    moved.dt = dt;
    floor = std::max(floor, relative_error(base, expected_for(moved, to_quad(p, dt)).x));
  }
  return floor;
}

struct RegimeStats {
  int cases = 0;
  double max_beta_dt = 0.0;
  double worst = 0.0;          // worst err over the cases held to the fixed bound
  int relaxed = 0;             // cases whose floor puts the bound above the fixed one
  double worst_relaxed = 0.0;  // worst err over those
  double worst_ratio = 0.0;    // worst err / max(floor, u) over all cases
};

template <typename T>
void run_accuracy() {
  using P = Precision<T>;
  const double u = static_cast<double>(std::numeric_limits<T>::epsilon()) / 2;  // unit roundoff
  std::map<std::string, RegimeStats> stats;
  int failures = 0;
  for (const Case& c : all_cases()) {
    const TypedCase<T> t = typed<T>(c);
    const QuadParams q = to_quad(t.prm, t.dt);
    const Expected e = expected_for(t, q);

    RotorTransition<T> tr;
    ASSERT_EQ(make_transition(t.prm, t.dt, tr), Status::kOk) << c.regime << " dt=" << c.dt;
    RotorState<T> s;
    s.angle_rad = t.angle0;
    s.rate_rad_s = t.rate0;
    ASSERT_EQ(advance(tr, t.torque, s), Status::kOk) << c.regime << " dt=" << c.dt;
    const std::array<Quad, 4> x{static_cast<Quad>(s.angle_rad(0)), static_cast<Quad>(s.angle_rad(1)),
                                static_cast<Quad>(s.rate_rad_s(0)), static_cast<Quad>(s.rate_rad_s(1))};
    const double err = relative_error(e, x);
    const double floor = conditioning_floor(t, e);
    const bool relaxed = 16.0 * floor > P::kTolerance;
    const double bound = relaxed ? 16.0 * floor : P::kTolerance;
    // Within 16x of what the inputs' own rounding allows, or of one rounding of the output.
    // Stricter than the fixed bound where the case is well conditioned; it caught the
    // inertia-ratio cancellation (err up to 100x floor) that the fixed float bound let through.
    const double near_best = 16.0 * std::max(floor, u);

    const Quad beta_sq = exact_beta_sq(q);
    const double beta_dt = beta_sq > 0 ? to_double(qsqrt(beta_sq) * q.dt) : 0.0;
    RegimeStats& st = stats[c.regime];
    ++st.cases;
    st.max_beta_dt = std::max(st.max_beta_dt, beta_dt);
    st.worst_ratio = std::max(st.worst_ratio, err / std::max(floor, u));
    if (relaxed) {
      ++st.relaxed;
      st.worst_relaxed = std::max(st.worst_relaxed, err);
    } else {
      st.worst = std::max(st.worst, err);
    }
    if (!(err <= bound) || !(err <= near_best)) {
      ++failures;
      ADD_FAILURE() << P::kName << " " << c.regime << ": err " << err << ", bound " << bound << ", 16 max(floor, u) "
                    << near_best << " (floor " << floor << ", beta*dt " << beta_dt << ")\n  J1=" << t.prm.pitch_inertia
                    << " J2=" << t.prm.yaw_inertia << " f=" << t.prm.friction << " H=" << t.prm.angular_momentum
                    << " dt=" << t.dt << " beta^2/omega0^2=" << to_double(beta_sq / exact_omega0_sq(q));
    }
  }
  std::printf("Worst error per regime, %s: bound %.0e, or 16 x floor where that is larger\n", P::kName,
              P::kTolerance);
  std::printf("  %-20s %5s %10s %11s | %7s %11s | %s\n", "regime", "cases", "max b*dt", "worst err", "relaxed",
              "worst err", "err/max(floor,u)");
  for (const auto& [name, st] : stats) {
    std::printf("  %-20s %5d %10.3g %11.3e | %7d %11.3e | %.3g\n", name.c_str(), st.cases, st.max_beta_dt, st.worst,
                st.relaxed, st.worst_relaxed, st.worst_ratio);
    char value[128];
    std::snprintf(value, sizeof value, "worst %.3e; %d cases at 16x floor, worst %.3e; err/max(floor,u) %.3g",
                  st.worst, st.relaxed, st.worst_relaxed, st.worst_ratio);
    ::testing::Test::RecordProperty(std::string(P::kName) + " " + name, value);
  }
  EXPECT_EQ(failures, 0);
}

// Targets with no type wider than double (armhf: long double is double, no __float128) have
// no reference for double: the double comparisons run on the host and the wider targets.
bool no_reference_wider_than_double() { return kQuadMantissaBits <= std::numeric_limits<double>::digits; }

TEST(RotorAccuracy, GivenCasesInEveryRegimeThenDoubleWithin1e12OfQuadReference) {
  GYRO_VERIFIES("EXACT-1");
  if (no_reference_wider_than_double()) GTEST_SKIP() << "no floating type wider than double on this target";
  ASSERT_GE(all_cases().size(), 300U);
  run_accuracy<double>();
}

TEST(RotorAccuracy, GivenCasesInEveryRegimeThenFloatWithin1e5OfQuadReference) {
  GYRO_VERIFIES("EXACT-1", "RULE-8");
  run_accuracy<float>();
}

// ----------------------------------------------------------------------------------------------
// The reference itself, against answers known without it.

TEST(RotorAccuracyReference, GivenNoSpinNoFrictionThenReferenceIsThePolynomial) {
  GYRO_VERIFIES("EXACT-1");
  const QuadParams q{Quad(0.75), Quad(3.5), 0, 0, Quad(12.5)};
  const Reference r = reference(q);
  // theta = theta0 + w0 dt + T/J dt^2/2, w = w0 + T/J dt
  const Quad tol = 64 * quad_epsilon();
  EXPECT_LE(to_double(qabs(r.phi[0][2] - q.dt)), to_double(tol * q.dt));
  EXPECT_LE(to_double(qabs(r.gamma[0][0] - q.dt * q.dt / 2 / q.j1)), to_double(tol * q.dt * q.dt / q.j1));
  EXPECT_LE(to_double(qabs(r.gamma[1][1] - q.dt * q.dt / 2 / q.j2)), to_double(tol * q.dt * q.dt / q.j2));
  EXPECT_LE(to_double(qabs(r.gamma[2][0] - q.dt / q.j1)), to_double(tol * q.dt / q.j1));
  EXPECT_EQ(to_double(r.phi[2][3]), 0.0);
  EXPECT_EQ(to_double(r.gamma[0][1]), 0.0);
}

TEST(RotorAccuracyReference, GivenEqualInertiasNoFrictionThenReferenceRotatesTheRates) {
  GYRO_VERIFIES("EXACT-1");
  if (no_reference_wider_than_double()) GTEST_SKIP() << "no floating type wider than double on this target";
  // J1 = J2 = J, f = 0: w(t) = R(H t / J) w0. beta*dt = 1e5 rad, long double sin/cos (x86:
  // 64-bit mantissa) of an exactly representable argument.
  const long double angle = 1e5L;
  const QuadParams q{2, 2, 0, Quad(4), Quad(angle) / 2};
  const Reference r = reference(q);
  const long double c = std::cos(angle), s = std::sin(angle);
  const double tol = 1e3 * static_cast<double>(std::numeric_limits<long double>::epsilon());
  EXPECT_NEAR(to_double(r.phi[2][2]), static_cast<double>(c), tol);
  EXPECT_NEAR(to_double(r.phi[2][3]), static_cast<double>(-s), tol);
  EXPECT_NEAR(to_double(r.phi[3][2]), static_cast<double>(s), tol);
  // Angle from rate: int_0^t R(beta s) ds = [[sin, cos - 1], [1 - cos, sin]] / beta, beta = 2.
  EXPECT_NEAR(to_double(r.phi[0][2]), static_cast<double>(s / 2), tol);
  EXPECT_NEAR(to_double(r.phi[0][3]), static_cast<double>((c - 1) / 2), tol);
}

TEST(RotorAccuracyReference, GivenStiffAndOscillatoryCasesThenReferenceIsASemigroup) {
  GYRO_VERIFIES("EXACT-1");
  for (const QuadParams& q : {QuadParams{Quad(0.01), Quad(1), Quad(300), Quad(0.5), Quad(7)},
                              QuadParams{Quad(2.25), Quad(2), Quad(5), Quad(1884.9555921538758), Quad(50)}}) {
    const Reference half = reference(q);
    QuadParams q2 = q;
    q2.dt = 2 * q.dt;
    const Reference full = reference(q2);
    // Phi(2dt) = Phi(dt)^2 on the 4x4 block.
    double worst = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        Quad sq = 0;
        for (int k = 0; k < 4; ++k) sq += half.phi[i][k] * half.phi[k][j];
        worst = std::max(worst, to_double(qabs(sq - full.phi[i][j]) / std::max(Quad(1), qabs(full.phi[i][j]))));
      }
    }
    EXPECT_LE(worst, to_double(Quad(1e6) * quad_epsilon()));
  }
}

// ----------------------------------------------------------------------------------------------
// Properties of the implementation.

template <typename T>
void expect_paths_agree_bit_for_bit() {
  for (const Case& c : all_cases()) {
    const TypedCase<T> t = typed<T>(c);
    RotorTransition<T> tr;
    ASSERT_EQ(make_transition(t.prm, t.dt, tr), Status::kOk);
    RotorState<T> a;
    a.angle_rad = t.angle0;
    a.rate_rad_s = t.rate0;
    RotorState<T> b = a;
    ASSERT_EQ(advance(tr, t.torque, a), Status::kOk);
    ASSERT_EQ(propagate(t.prm, t.dt, t.torque, b), Status::kOk);
    EXPECT_EQ(std::memcmp(a.angle_rad.data(), b.angle_rad.data(), sizeof(T) * 2), 0) << c.regime;
    EXPECT_EQ(std::memcmp(a.rate_rad_s.data(), b.rate_rad_s.data(), sizeof(T) * 2), 0) << c.regime;
  }
}

TEST(RotorAccuracy, GivenAnyCaseWhenPrecomputedOrOneCallThenResultsAgreeBitForBit) {
  GYRO_VERIFIES("EXACT-2");
  expect_paths_agree_bit_for_bit<double>();
  expect_paths_agree_bit_for_bit<float>();
}

struct SemigroupCase {
  const char* name;
  RotorParameters<double> prm;
  double dt;  // a power of two, so that n*dt is exact
  int n;
};

TEST(RotorAccuracy, GivenNStepsOfDtThenEqualsOneStepOfNDt) {
  GYRO_VERIFIES("EXACT-2");
  const double h_report = 2.0 * 3.14159265358979323846 * 100.0 * 3.0;
  RotorParameters<double> near_critical{1.0, 4.0, 0.0, 2.0};
  near_critical.friction = tuned_friction(near_critical, 0.0);
  const SemigroupCase cases[] = {
      {"report underdamped", {2.25, 2.0, 5.0, h_report}, 0x1p-10, 256},
      {"critical exact", {2.0, 2.0, 3.0, 0.0}, 0x1p-6, 128},
      {"critical nearest", near_critical, 0x1p-5, 200},
      {"overdamped stiff", {1.0, 50.0, 400.0, 3.0}, 0x1p-8, 512},
      {"no spin", {0.5, 5.0, 2.0, 0.0}, 0x1p-4, 100},
      {"no friction", {1.0, 2.0, 0.0, 10.0}, 0x1p-7, 100},
      {"free", {1.0, 3.0, 0.0, 0.0}, 0x1p-3, 10},
  };
  const Vector2<double> torque(0.7, -1.3);
  for (const SemigroupCase& c : cases) {
    RotorState<double> many;
    many.angle_rad = Vector2<double>(0.01, -0.02);
    many.rate_rad_s = Vector2<double>(0.5, 0.3);
    RotorState<double> one = many;
    RotorTransition<double> step;
    ASSERT_EQ(make_transition(c.prm, c.dt, step), Status::kOk);
    for (int i = 0; i < c.n; ++i) ASSERT_EQ(advance(step, torque, many), Status::kOk);
    const double total = c.dt * c.n;
    ASSERT_EQ(propagate(c.prm, total, torque, one), Status::kOk);
    // Both against the scale of the long step's exact solution.
    TypedCase<double> t{c.prm, total, Vector2<double>(0.01, -0.02), Vector2<double>(0.5, 0.3), torque};
    const Expected e = expected_for(t, to_quad(c.prm, total));
    const std::array<Quad, 4> x_many{Quad(many.angle_rad(0)), Quad(many.angle_rad(1)), Quad(many.rate_rad_s(0)),
                                     Quad(many.rate_rad_s(1))};
    const std::array<Quad, 4> x_one{Quad(one.angle_rad(0)), Quad(one.angle_rad(1)), Quad(one.rate_rad_s(0)),
                                    Quad(one.rate_rad_s(1))};
    Expected e_one = e;
    e_one.x = x_one;
    EXPECT_LE(relative_error(e_one, x_many), 1e-12) << c.name;
    EXPECT_LE(relative_error(e, x_one), 1e-12) << c.name;
  }
}

template <typename T>
void expect_steady_state(const RotorParameters<T>& prm, T tolerance) {
  const Vector2<T> torque(T(0.7), T(-1.3));
  Vector2<T> w_ss = Vector2<T>::Zero();
  ASSERT_EQ(steady_precession_rate(prm, torque, w_ss), Status::kOk);
  RotorModes<T> modes;
  ASSERT_EQ(compute_modes(prm, modes), Status::kOk);
  // 200 time constants of the slowest mode: the transient is below any rounding.
  const T dt = T(200) / modes.slow_decay_rate_1_s;
  RotorState<T> s;
  s.angle_rad = Vector2<T>(T(0.01), T(-0.02));
  s.rate_rad_s = Vector2<T>(T(5), T(-3));
  ASSERT_EQ(propagate(prm, dt, torque, s), Status::kOk);
  EXPECT_LE((s.rate_rad_s - w_ss).norm(), tolerance * w_ss.norm())
      << "J1=" << prm.pitch_inertia << " J2=" << prm.yaw_inertia << " f=" << prm.friction
      << " H=" << prm.angular_momentum;
}

TEST(RotorAccuracy, GivenALongStepThenRatesEqualSteadyPrecession) {
  GYRO_VERIFIES("EXACT-3");
  const double h_report = 2.0 * 3.14159265358979323846 * 100.0 * 3.0;
  const RotorParameters<double> rotors[] = {
      {2.25, 2.0, 5.0, h_report},  // underdamped (the report's gyro)
      {2.0, 2.0, 3.0, 0.0},        // critical
      {1.0, 50.0, 400.0, 3.0},     // overdamped, stiff
      {1.0, 2.0, 3.0, 0.5},        // overdamped, mild
      {0.5, 5.0, 2.0, 0.0},        // no spin
  };
  for (const RotorParameters<double>& p : rotors) {
    expect_steady_state(p, 1e-12);
    expect_steady_state(RotorParameters<float>{static_cast<float>(p.pitch_inertia), static_cast<float>(p.yaw_inertia),
                                               static_cast<float>(p.friction), static_cast<float>(p.angular_momentum)},
                        1e-5f);
  }
}

// Nutation period from the zero crossings of w1 - w1_ss, sampled finely with the exact step.
double measured_nutation_period(const RotorParameters<double>& prm, double sample_dt, int samples) {
  const Vector2<double> torque(0.4, 0.9);
  Vector2<double> w_ss = Vector2<double>::Zero();
  EXPECT_EQ(steady_precession_rate(prm, torque, w_ss), Status::kOk);
  RotorTransition<double> tr;
  EXPECT_EQ(make_transition(prm, sample_dt, tr), Status::kOk);
  RotorState<double> s;
  s.rate_rad_s = w_ss + Vector2<double>(0.3, -0.2);
  double prev = s.rate_rad_s(0) - w_ss(0);
  double first = -1.0, last = -1.0;
  int crossings = 0;
  for (int i = 1; i <= samples; ++i) {
    EXPECT_EQ(advance(tr, torque, s), Status::kOk);
    const double g = s.rate_rad_s(0) - w_ss(0);
    if ((prev < 0.0) != (g < 0.0)) {
      // Linear interpolation: its bias is the same at every crossing and cancels in differences.
      const double t = sample_dt * (i - 1 + prev / (prev - g));
      if (crossings == 0) first = t;
      last = t;
      ++crossings;
    }
    prev = g;
  }
  EXPECT_GE(crossings, 20);
  return 2.0 * (last - first) / (crossings - 1);  // zero crossings are half a period apart
}

TEST(RotorAccuracy, GivenLightDampingThenRatesOscillateWithPeriodTwoPiOverBeta) {
  GYRO_VERIFIES("EXACT-3");
  const double pi = 3.14159265358979323846;
  const RotorParameters<double> rotors[] = {
      {2.25, 2.0, 5.0, 2.0 * pi * 100.0 * 3.0},  // the report's gyro, 141 Hz
      {1.0, 4.0, 0.2, 10.0},                     // J2 = 4 J1
  };
  for (const RotorParameters<double>& p : rotors) {
    // The report's INITG: beta = sqrt((f^2 + H^2)/(J1 J2) - alpha^2).
    const double f = p.friction, h = p.angular_momentum, j1 = p.pitch_inertia, j2 = p.yaw_inertia;
    const double alpha = f / 2.0 * (1.0 / j1 + 1.0 / j2);
    const double beta = std::sqrt((f * f + h * h) / (j1 * j2) - alpha * alpha);
    const double period = 2.0 * pi / beta;
    const double measured = measured_nutation_period(p, period / 400.0, 400 * 30);
    EXPECT_NEAR(measured / period, 1.0, 1e-7) << "beta=" << beta;
  }
}

}  // namespace
}  // namespace gyro
