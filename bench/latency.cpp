// Per-tick time over a million consecutive ticks: median, tail and worst case.
//
//   gyro_bench_latency [TICKS]   (CSV on stdout)
//
// Each tick is timed on its own with std::chrono::steady_clock; the figures include the
// clock's own cost, printed on the first row (the median of back-to-back readings). On a
// shared host the worst case is set by the operating system (preemption, interrupts), not
// by the code: the code's own cost is the same every tick (see the instruction counts).
//
// The component's full tick (dynamics + attitude + gimbal angles, gyro/gyro_model.hpp) is
// timed here too when that header exists: see GYRO_BENCH_COMPONENT_TICK below.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench_problem.hpp"
#include "model_workload.hpp"

namespace gyro::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Stats {
  double median_ns, p99_ns, p9999_ns, max_ns;
};

Stats summarise(std::vector<double>& ns) {
  std::sort(ns.begin(), ns.end());
  auto at = [&](double q) {
    return ns[static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1))];
  };
  return {at(0.5), at(0.99), at(0.9999), ns.back()};
}

template <typename Tick>
Stats time_ticks(long ticks, Tick&& tick) {
  std::vector<double> ns(static_cast<std::size_t>(ticks));
  for (long i = 0; i < ticks; ++i) {
    const Clock::time_point t0 = Clock::now();
    tick();
    const Clock::time_point t1 = Clock::now();
    ns[static_cast<std::size_t>(i)] = std::chrono::duration<double, std::nano>(t1 - t0).count();
  }
  return summarise(ns);
}

void print(const char* kind, const Stats& s) {
  std::printf("%s,%.1f,%.1f,%.1f,%.1f\n", kind, s.median_ns, s.p99_ns, s.p9999_ns, s.max_ns);
}

int run(long ticks) {
  const Case c = find_case("report");
  std::printf("kind,median_ns,p99_ns,p99.99_ns,max_ns\n");
  print("clock_overhead", time_ticks(ticks, [] { asm volatile("" ::: "memory"); }));

  RotorTransition<double> tr;
  if (make_transition(c.prm, 1e-3, tr) != Status::kOk) fail("make_transition");
  RotorState<double> s;
  int bad = 0;
  print("advance_double", time_ticks(ticks, [&] {
          bad |= static_cast<int>(advance(tr, c.torque, s));
          asm volatile("" ::: "memory");
        }));

  const RotorParameters<float> pf{static_cast<float>(c.prm.pitch_inertia),
                                  static_cast<float>(c.prm.yaw_inertia),
                                  static_cast<float>(c.prm.friction),
                                  static_cast<float>(c.prm.angular_momentum)};
  const Vector2<float> tf(static_cast<float>(c.torque(0)), static_cast<float>(c.torque(1)));
  RotorTransition<float> trf;
  if (make_transition(pf, 1e-3f, trf) != Status::kOk) fail("make_transition");
  RotorState<float> sf;
  print("advance_float", time_ticks(ticks, [&] {
          bad |= static_cast<int>(advance(trf, tf, sf));
          asm volatile("" ::: "memory");
        }));

  RotorState<double> sp;
  print("propagate_double_1khz", time_ticks(ticks, [&] {
          bad |= static_cast<int>(propagate(c.prm, 1e-3, c.torque, sp));
          asm volatile("" ::: "memory");
        }));

  // GYRO_BENCH_COMPONENT_TICK: the component's full tick (GyroModel<T>::step_torque from
  // gyro/gyro_model.hpp), float and double, when that header exists.
#if GYRO_BENCH_HAVE_MODEL
  ModelWorkload<double> md;
  print("model_double", time_ticks(ticks, [&] {
          bad |= static_cast<int>(md.step());
          asm volatile("" ::: "memory");
        }));
  ModelWorkload<float> mf;
  print("model_float", time_ticks(ticks, [&] {
          bad |= static_cast<int>(mf.step());
          asm volatile("" ::: "memory");
        }));
#endif

  if (bad != 0) fail("a tick returned an error status");
  return 0;
}

}  // namespace
}  // namespace gyro::bench

int main(int argc, char** argv) {
  const long ticks = (argc > 1) ? std::atol(argv[1]) : 1000000L;
  if (ticks < 2) return 2;
  return gyro::bench::run(ticks);
}
