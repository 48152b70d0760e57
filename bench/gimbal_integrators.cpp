// The SIL stub's gimbal plant against Boost.Odeint's integrators on the plant's own right-hand
// side (gimbal_accelerations, the same lean equations), at equal error: 1 s of the seeker's
// device (seeker_gimbal_config) at a 2 kHz and a 1 kHz tick, the body rolling at 5 rad/s and
// turning at (0.2, -0.1) rad/s, gravity plus a lateral 3 m/s^2, the torques held over each tick
// and slewing the gimbals at 0.25 rad/s, reversed every 0.25 s (bench/gimbal_workload.hpp's
// motion). The error is the worst gimbal angle over the second against the plant's tight
// setting at 1/16 rad per sub-step (eighth order: far below every contender's).
//
//   gyro_bench_gimbal_integrators calibrate TARGET_RAD     CSV of each contender's setting
//   gyro_bench_gimbal_integrators run CASE CONTENDER SETTING
//
// Contenders: plant (GimbalPlant, setting = error_target_rad), plant_fixed (the tight setting
// at the default phase; setting unused), rk4 (setting = steps per tick), dopri5 and rkf78
// (controlled, absolute tolerance = setting, the step carried from tick to tick). `run` is what
// scripts/bench.sh counts with callgrind (gyro_bench_measured_* only).
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gyro/gimbal_dynamics.hpp"
#include "gyro/gimbal_plant.hpp"
#include "gyro/seeker_gimbal.hpp"

namespace {

using gyro::Vector2;
using gyro::Vector3;
using V2 = Vector2<double>;
using OdeState = std::array<double, 6>;  // theta, psi, theta', psi', phi', chi

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "gyro_bench_gimbal_integrators: %s\n", what);
  std::exit(2);
}

struct Motion {
  double tick_s{};
  int ticks{};
  int reverse_every{};
  V2 torque{V2::Zero()};
  gyro::BodyState<double> body{};
  gyro::GimbalStart<double> start{};
  gyro::GimbalPlantConfig<double> config{};
  [[nodiscard]] V2 torque_at(int k) const { return (k / reverse_every) % 2 == 0 ? torque : V2(-torque); }
};

Motion motion(const std::string& id) {
  Motion m;
  if (id == "seeker_2khz") {
    m.tick_s = 5e-4;
  } else if (id == "seeker_1khz") {
    m.tick_s = 1e-3;
  } else {
    fail("unknown case (seeker_2khz, seeker_1khz)");
  }
  m.config = gyro::seeker_gimbal_config<double>();
  m.ticks = static_cast<int>(std::lround(1.0 / m.tick_s));
  m.reverse_every = static_cast<int>(std::lround(0.25 / m.tick_s));
  m.start.spin_hz = m.config.max_spin_hz;
  m.body.rate_rad_s = Vector3<double>(5.0, 0.2, -0.1);
  m.body.specific_force = Vector3<double>(0.0, 3.0, -9.80665);
  const double h = m.config.spin_inertia * 2.0 * 3.141592653589793 * m.config.max_spin_hz;
  m.torque = V2(0.25 * h, -0.25 * h);
  return m;
}

using Trace = std::vector<V2>;  // the gimbal angles after each tick

// The plant, one tick at a time, as the SIL stub runs it (no work bookkeeping).
void run_plant(const Motion& m, double target, double phase, Trace* trace) {
  gyro::GimbalPlantConfig<double> c = m.config;
  c.error_target_rad = target;
  c.max_substep_phase_rad = phase;
  gyro::GimbalPlant<double> p;
  if (!p.configure(c, m.tick_s).ok()) fail("configure");
  p.set_work_bookkeeping(false);
  if (p.start(m.start, m.body) != gyro::Status::kOk) fail("start");
  for (int k = 0; k < m.ticks; ++k) {
    if (p.step(m.torque_at(k), m.body, m.body) != gyro::Status::kOk) fail("step");
    if (trace != nullptr) trace->push_back(p.gimbal_angle_rad());
  }
}

// The same equations for Odeint: frames from the library's sin and cos at every evaluation.
struct GimbalOde {
  const gyro::GimbalParameters<double>* prm;
  gyro::GimbalDrive<double> drive;
  gyro::BodyInstant<double> body;
  long* evaluations;
  void operator()(const OdeState& x, OdeState& d, double /*t*/) const {
    if (evaluations != nullptr) ++*evaluations;
    const gyro::GimbalJointState<double> s{x[0], x[1], x[2], x[3], x[4], x[5]};
    const gyro::GimbalAccelerations<double> a = gyro::gimbal_accelerations(
        *prm, s, gyro::gimbal_frames(s.pitch_rad, s.yaw_rad), drive, body, gyro::GimbalPowers::kSkip);
    d = {x[2], x[3], a.pitch_acc, a.yaw_acc, a.spin_acc, a.twist_rate};
  }
};

template <typename Advance>
void run_ode(const Motion& m, Advance&& advance, long* evaluations, Trace* trace) {
  const gyro::GimbalParameters<double> prm = gyro::make_gimbal_parameters(m.config);
  GimbalOde ode{&prm, {}, {}, evaluations};
  ode.drive.spin_command_rad_s = 2.0 * 3.141592653589793 * m.start.spin_hz;
  ode.body.rate_rad_s = m.body.rate_rad_s;
  ode.body.specific_force = m.body.specific_force;
  OdeState x{0.0, 0.0, 0.0, 0.0, ode.drive.spin_command_rad_s, 0.0};
  for (int k = 0; k < m.ticks; ++k) {
    ode.drive.torque = m.torque_at(k);
    advance(ode, x, k * m.tick_s, (k + 1) * m.tick_s);
    if (trace != nullptr) trace->push_back(V2(x[0], x[1]));
  }
}

void run_rk4(const Motion& m, int steps, long* evaluations, Trace* trace) {
  boost::numeric::odeint::runge_kutta4<OdeState> rk4;
  run_ode(
      m,
      [&](const GimbalOde& ode, OdeState& x, double t0, double t1) {
        const double h = (t1 - t0) / steps;
        for (int i = 0; i < steps; ++i) rk4.do_step(ode, x, t0 + i * h, h);
      },
      evaluations, trace);
}

// A controlled stepper over each tick, its step carried from tick to tick.
template <typename Stepper>
void run_controlled(const Motion& m, Stepper stepper, long* evaluations, Trace* trace) {
  namespace odeint = boost::numeric::odeint;
  double dt = m.tick_s;
  run_ode(
      m,
      [&](const GimbalOde& ode, OdeState& x, double t, double t1) {
        for (int guard = 0; t < t1; ++guard) {
          if (guard > 1000000) fail("no progress");
          const double left = t1 - t;
          const bool last = dt >= left;
          double step = last ? left : dt;
          if (stepper.try_step(ode, x, t, step) == odeint::success) {
            if (!last) dt = step;  // the controller's next step; a clamped last one keeps the old
          } else {
            dt = step;
          }
        }
      },
      evaluations, trace);
}

void run(const Motion& m, const std::string& who, double setting, long* evaluations, Trace* trace) {
  namespace odeint = boost::numeric::odeint;
  if (who == "plant") {
    run_plant(m, setting, m.config.max_substep_phase_rad, trace);
  } else if (who == "plant_fixed") {
    run_plant(m, 0.0, m.config.max_substep_phase_rad, trace);
  } else if (who == "rk4") {
    run_rk4(m, static_cast<int>(setting), evaluations, trace);
  } else if (who == "dopri5") {
    run_controlled(m, odeint::make_controlled(setting, 0.0, odeint::runge_kutta_dopri5<OdeState>()), evaluations,
                   trace);
  } else if (who == "rkf78") {
    run_controlled(m, odeint::make_controlled(setting, 0.0, odeint::runge_kutta_fehlberg78<OdeState>()), evaluations,
                   trace);
  } else {
    fail("unknown contender (plant, plant_fixed, rk4, dopri5, rkf78)");
  }
}

double worst_error(const Trace& a, const Trace& ref) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < ref.size(); ++i) {
    worst = std::max(worst, (a[i] - ref[i]).cwiseAbs().maxCoeff());
  }
  return a.size() == ref.size() && std::isfinite(worst) ? worst : INFINITY;
}

// Each contender's cheapest setting (on a grid: whole steps per tick, tolerances and targets a
// quarter decade apart) whose worst error is within the target.
int calibrate(double target) {
  std::printf("case,contender,setting,error_rad,evaluations\n");
  for (const char* id : {"seeker_2khz", "seeker_1khz"}) {
    const Motion m = motion(id);
    Trace ref;
    run_plant(m, 0.0, 1.0 / 16.0, &ref);
    auto report = [&](const char* who, double setting) {
      Trace t;
      long evaluations = 0;
      run(m, who, setting, &evaluations, &t);
      const double e = worst_error(t, ref);
      std::printf("%s,%s,%.6g,%.3e,%ld\n", id, who, setting, e, evaluations);
      return e;
    };
    auto grid = [&](const char* who) {
      for (int q = 12; q <= 60; ++q) {  // 1e-3 down to 1e-15
        const double setting = std::pow(10.0, -q / 4.0);
        Trace t;
        run(m, who, setting, nullptr, &t);
        if (worst_error(t, ref) <= target) return setting;
      }
      fail("no setting meets the target");
    };
    report("plant_fixed", 0.0);
    report("plant", grid("plant"));
    for (int n = 1;; ++n) {
      Trace t;
      run(m, "rk4", n, nullptr, &t);
      if (worst_error(t, ref) <= target) {
        report("rk4", n);
        break;
      }
      if (n > 4096) fail("rk4 never meets the target");
    }
    report("dopri5", grid("dopri5"));
    report("rkf78", grid("rkf78"));
  }
  return 0;
}

}  // namespace

extern "C" __attribute__((noinline)) double gyro_bench_measured_gimbal_integrator(const Motion* m, const char* who,
                                                                                  double setting) {
  Trace t;
  t.reserve(static_cast<std::size_t>(m->ticks));
  run(*m, who, setting, nullptr, &t);
  return t.back()(0);
}

int main(int argc, char** argv) {
  if (argc >= 3 && std::strcmp(argv[1], "calibrate") == 0) return calibrate(std::atof(argv[2]));
  if (argc >= 5 && std::strcmp(argv[1], "run") == 0) {
    const Motion m = motion(argv[2]);
    std::printf("%s %s %s: pitch %.17g\n", argv[2], argv[3], argv[4],
                gyro_bench_measured_gimbal_integrator(&m, argv[3], std::atof(argv[4])));
    return 0;
  }
  std::fprintf(stderr, "usage: %s calibrate TARGET_RAD | run CASE CONTENDER SETTING\n", argv[0]);
  return 2;
}
