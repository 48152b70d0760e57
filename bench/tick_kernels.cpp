// The exact step per tick: inlined in a loop (as a caller's tick would have it) with a
// compiler barrier each tick, so the coefficients, torque and state are loaded from memory
// and stored back every tick as in a real component, and nothing is hoisted out of the loop.
#include "bench_tick.hpp"

#include "model_workload.hpp"

#include <cmath>
#include <cstdio>

namespace {

inline void barrier() { asm volatile("" ::: "memory"); }

template <typename T>
gyro::RotorTransition<T> transition_of(const gyro::bench::Case& c, double dt) {
  gyro::RotorParameters<T> p{static_cast<T>(c.prm.pitch_inertia), static_cast<T>(c.prm.yaw_inertia),
                             static_cast<T>(c.prm.friction),
                             static_cast<T>(c.prm.angular_momentum)};
  gyro::RotorTransition<T> tr;
  if (gyro::make_transition(p, static_cast<T>(dt), tr) != gyro::Status::kOk) {
    gyro::bench::fail("make_transition (ticks)");
  }
  return tr;
}

template <typename T>
gyro::Vector2<T> torque_of(const gyro::bench::Case& c) {
  return gyro::Vector2<T>(static_cast<T>(c.torque(0)), static_cast<T>(c.torque(1)));
}

// What the step could cost: the same four products with one finiteness test on the outputs
// (a non-finite input always yields a non-finite output, so bad input is still refused and
// the state left as it was). Double: Eigen's vectorised products; float: written out,
// because Eigen does not inline its 2x2 float products at -O2.
inline int advance_lean(const gyro::RotorTransition<double>& tr, const gyro::Vector2<double>& torque,
                        gyro::RotorState<double>& s) {
  gyro::Vector2<double> angle = s.angle_rad;
  angle.noalias() += tr.angle_from_rate * s.rate_rad_s;
  angle.noalias() += tr.angle_from_torque * torque;
  gyro::Vector2<double> rate = gyro::Vector2<double>::Zero();
  rate.noalias() = tr.rate_from_rate * s.rate_rad_s;
  rate.noalias() += tr.rate_from_torque * torque;
  const gyro::Vector2<double> sum = angle + rate;
  if (!std::isfinite(sum(0) + sum(1))) return 1;
  s.angle_rad = angle;
  s.rate_rad_s = rate;
  return 0;
}

inline int advance_lean(const gyro::RotorTransition<float>& tr, const gyro::Vector2<float>& torque,
                        gyro::RotorState<float>& s) {
  const float w1 = s.rate_rad_s(0), w2 = s.rate_rad_s(1), t1 = torque(0), t2 = torque(1);
  const float a1 = s.angle_rad(0) + tr.angle_from_rate(0, 0) * w1 + tr.angle_from_rate(0, 1) * w2 +
                   tr.angle_from_torque(0, 0) * t1 + tr.angle_from_torque(0, 1) * t2;
  const float a2 = s.angle_rad(1) + tr.angle_from_rate(1, 0) * w1 + tr.angle_from_rate(1, 1) * w2 +
                   tr.angle_from_torque(1, 0) * t1 + tr.angle_from_torque(1, 1) * t2;
  const float r1 = tr.rate_from_rate(0, 0) * w1 + tr.rate_from_rate(0, 1) * w2 +
                   tr.rate_from_torque(0, 0) * t1 + tr.rate_from_torque(0, 1) * t2;
  const float r2 = tr.rate_from_rate(1, 0) * w1 + tr.rate_from_rate(1, 1) * w2 +
                   tr.rate_from_torque(1, 0) * t1 + tr.rate_from_torque(1, 1) * t2;
  if (!std::isfinite((a1 + a2) + (r1 + r2))) return 1;
  s.angle_rad << a1, a2;
  s.rate_rad_s << r1, r2;
  return 0;
}

}  // namespace

extern "C" {

int gyro_bench_one_advance_double(const gyro::RotorTransition<double>* tr,
                                  const gyro::Vector2<double>* torque,
                                  gyro::RotorState<double>* s) {
  return static_cast<int>(gyro::advance(*tr, *torque, *s));
}

int gyro_bench_one_advance_float(const gyro::RotorTransition<float>* tr,
                                 const gyro::Vector2<float>* torque, gyro::RotorState<float>* s) {
  return static_cast<int>(gyro::advance(*tr, *torque, *s));
}

void gyro_bench_one_advance_unchecked_double(const gyro::RotorTransition<double>* tr,
                                             const gyro::Vector2<double>* torque,
                                             gyro::RotorState<double>* s) {
  gyro::Vector2<double> angle = s->angle_rad;
  angle.noalias() += tr->angle_from_rate * s->rate_rad_s;
  angle.noalias() += tr->angle_from_torque * *torque;
  gyro::Vector2<double> rate = gyro::Vector2<double>::Zero();
  rate.noalias() = tr->rate_from_rate * s->rate_rad_s;
  rate.noalias() += tr->rate_from_torque * *torque;
  s->angle_rad = angle;
  s->rate_rad_s = rate;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_advance_double(
    const gyro::RotorTransition<double>* tr, const gyro::Vector2<double>* torque,
    gyro::RotorState<double>* s, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::advance(*tr, *torque, *s));
  }
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_advance_float(
    const gyro::RotorTransition<float>* tr, const gyro::Vector2<float>* torque,
    gyro::RotorState<float>* s, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::advance(*tr, *torque, *s));
  }
  return bad;
}

__attribute__((noinline)) void gyro_bench_measured_ticks_advance_unchecked_double(
    const gyro::RotorTransition<double>* tr, const gyro::Vector2<double>* torque,
    gyro::RotorState<double>* s, long count) {
  for (long i = 0; i < count; ++i) {
    barrier();
    gyro::Vector2<double> angle = s->angle_rad;
    angle.noalias() += tr->angle_from_rate * s->rate_rad_s;
    angle.noalias() += tr->angle_from_torque * *torque;
    gyro::Vector2<double> rate = gyro::Vector2<double>::Zero();
    rate.noalias() = tr->rate_from_rate * s->rate_rad_s;
    rate.noalias() += tr->rate_from_torque * *torque;
    s->angle_rad = angle;
    s->rate_rad_s = rate;
  }
}

__attribute__((noinline)) int gyro_bench_measured_ticks_advance_lean_double(
    const gyro::RotorTransition<double>* tr, const gyro::Vector2<double>* torque,
    gyro::RotorState<double>* s, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= advance_lean(*tr, *torque, *s);
  }
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_advance_lean_float(
    const gyro::RotorTransition<float>* tr, const gyro::Vector2<float>* torque,
    gyro::RotorState<float>* s, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= advance_lean(*tr, *torque, *s);
  }
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_propagate_double(
    const gyro::RotorParameters<double>* p, double dt, const gyro::Vector2<double>* torque,
    gyro::RotorState<double>* s, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::propagate(*p, dt, *torque, *s));
  }
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_make_transition_double(
    const gyro::RotorParameters<double>* p, double dt, gyro::RotorTransition<double>* tr,
    long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    barrier();
    bad |= static_cast<int>(gyro::make_transition(*p, dt, *tr));
  }
  return bad;
}

#if GYRO_BENCH_HAVE_MODEL
__attribute__((noinline)) int gyro_bench_measured_ticks_model_double(
    gyro::bench::ModelWorkload<double>* w, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) bad |= static_cast<int>(w->step());
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_ticks_model_float(
    gyro::bench::ModelWorkload<float>* w, long count) {
  int bad = 0;
  for (long i = 0; i < count; ++i) bad |= static_cast<int>(w->step());
  return bad;
}
#endif

}  // extern "C"

namespace gyro::bench {

double run_ticks(const std::string& kind, const Case& c, long count) {
  const bool slow = kind.size() > 6 && kind.compare(kind.size() - 6, 6, "_100hz") == 0;
  const double dt = slow ? 0.01 : 0.001;
  int bad = 0;
  double out = 0.0;
  if (kind == "advance_lean_double") {
    const RotorTransition<double> tr = transition_of<double>(c, dt);
    const Vector2<double> torque = torque_of<double>(c);
    RotorState<double> s;
    bad = gyro_bench_measured_ticks_advance_lean_double(&tr, &torque, &s, count);
    out = s.angle_rad(0);
  } else if (kind == "advance_lean_float") {
    const RotorTransition<float> tr = transition_of<float>(c, dt);
    const Vector2<float> torque = torque_of<float>(c);
    RotorState<float> s;
    bad = gyro_bench_measured_ticks_advance_lean_float(&tr, &torque, &s, count);
    out = static_cast<double>(s.angle_rad(0));
  } else if (kind == "advance_double" || kind == "advance_unchecked_double") {
    const RotorTransition<double> tr = transition_of<double>(c, dt);
    const Vector2<double> torque = torque_of<double>(c);
    RotorState<double> s;
    if (kind == "advance_double") {
      bad = gyro_bench_measured_ticks_advance_double(&tr, &torque, &s, count);
    } else {
      gyro_bench_measured_ticks_advance_unchecked_double(&tr, &torque, &s, count);
    }
    out = s.angle_rad(0);
  } else if (kind == "advance_float") {
    const RotorTransition<float> tr = transition_of<float>(c, dt);
    const Vector2<float> torque = torque_of<float>(c);
    RotorState<float> s;
    bad = gyro_bench_measured_ticks_advance_float(&tr, &torque, &s, count);
    out = static_cast<double>(s.angle_rad(0));
  } else if (kind.rfind("propagate_double", 0) == 0) {
    RotorState<double> s;
    bad = gyro_bench_measured_ticks_propagate_double(&c.prm, dt, &c.torque, &s, count);
    out = s.angle_rad(0);
  } else if (kind.rfind("make_transition_double", 0) == 0) {
    RotorTransition<double> tr;
    bad = gyro_bench_measured_ticks_make_transition_double(&c.prm, dt, &tr, count);
    out = tr.rate_from_rate(0, 0);
#if GYRO_BENCH_HAVE_MODEL
  } else if (kind == "model_double") {
    ModelWorkload<double> w;
    bad = gyro_bench_measured_ticks_model_double(&w, count);
    out = w.output();
  } else if (kind == "model_float") {
    ModelWorkload<float> w;
    bad = gyro_bench_measured_ticks_model_float(&w, count);
    out = static_cast<double>(w.output());
#endif
  } else {
    fail("unknown tick kind");
  }
  if (bad != 0) fail("a tick returned an error status");
  return out;
}

}  // namespace gyro::bench
