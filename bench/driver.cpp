// One contender, one simulated second (or a run of ticks), for counting instructions with
// callgrind. Only the functions named gyro_bench_measured_* are counted:
//
//   valgrind --tool=callgrind --toggle-collect='gyro_bench_measured_*'
//            gyro_bench_driver second CASE CONTENDER STEPS [TOL|RUN_STEPS]
//   valgrind --tool=callgrind --toggle-collect='gyro_bench_measured_*'
//            gyro_bench_driver ticks KIND COUNT
//
// `second`: STEPS are the steps (ticks) per simulated second; dopri5 takes its tolerance
// as the fifth argument; euler and ab2 take RUN_STEPS, the number of their steps actually run
// (step size 1/STEPS), so that a method needing 1e8 steps is counted on fewer and scaled.
// Setup (the case, the right-hand side's coefficients) is outside the count; for the
// precomputed exact contender the one make_transition is inside it.
//
// `ticks`: COUNT exact steps at the report's gyro, dt = 1 ms, KIND one of
// advance_double, advance_float, advance_unchecked_double, advance_lean_double,
// advance_lean_float, propagate_double,
// propagate_double_100hz, make_transition_double, make_transition_double_100hz,
// model_double, model_float (the component's full tick, GyroModel<T>::step_torque).
//
// `gimbal`: COUNT ticks of the SIL stub's gimbal plant (gimbal_workload.hpp), KIND seeker,
// seeker_coarse (1 rad of phase per sub-step) or report, TYPE double or float:
//   valgrind --tool=callgrind --toggle-collect='gyro_bench_measured_*'
//            gyro_bench_driver gimbal KIND TYPE COUNT
//
// `model_sample`: the per-tick spread of the component's full tick. Run as
//   valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no
//            gyro_bench_driver model_sample double|float COUNT EVERY
// it runs COUNT ticks and counts every EVERY-th tick on its own (one callgrind dump each).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bench_problem.hpp"
#include "bench_tick.hpp"
#include "gimbal_workload.hpp"
#include "model_workload.hpp"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define GYRO_BENCH_HAVE_CALLGRIND 1
#endif

using gyro::RotorState;
using gyro::RotorTransition;
using gyro::Status;
using gyro::bench::Case;
using gyro::bench::LinearRhs;
using gyro::bench::NoObserver;
using gyro::bench::Vec4;

// The measured functions: external linkage and noinline, so callgrind sees each call.
extern "C" {

__attribute__((noinline)) int gyro_bench_measured_exact_propagate(const Case* c, long ticks,
                                                                  RotorState<double>* s) {
  return gyro::bench::exact_propagate(*c, ticks, *s, NoObserver{}) ? 0 : 1;
}

__attribute__((noinline)) int gyro_bench_measured_exact_precomputed(const Case* c, long ticks,
                                                                    RotorState<double>* s) {
  return gyro::bench::exact_precomputed(*c, ticks, *s, NoObserver{}) ? 0 : 1;
}

__attribute__((noinline)) void gyro_bench_measured_rk4(const LinearRhs* r, long steps, long run,
                                                       Vec4* x) {
  *x = gyro::bench::rk4(*r, steps, run, NoObserver{});
}

__attribute__((noinline)) void gyro_bench_measured_euler(const LinearRhs* r, long steps, long run,
                                                         Vec4* x) {
  *x = gyro::bench::euler(*r, steps, run, NoObserver{});
}

__attribute__((noinline)) void gyro_bench_measured_ab2(const LinearRhs* r, long steps, long run,
                                                       Vec4* x) {
  *x = gyro::bench::ab2(*r, steps, run, NoObserver{});
}

__attribute__((noinline)) long gyro_bench_measured_dopri5(const LinearRhs* r, double tol,
                                                          gyro::bench::OdeState* x) {
  return static_cast<long>(gyro::bench::dopri5(*r, tol, *x, nullptr, NoObserver{}));
}

__attribute__((noinline)) int gyro_bench_measured_gimbal_double(gyro::bench::GimbalWorkload<double>* w, long ticks) {
  int bad = 0;
  for (long i = 0; i < ticks; ++i) bad |= static_cast<int>(w->step());
  return bad;
}

__attribute__((noinline)) int gyro_bench_measured_gimbal_float(gyro::bench::GimbalWorkload<float>* w, long ticks) {
  int bad = 0;
  for (long i = 0; i < ticks; ++i) bad |= static_cast<int>(w->step());
  return bad;
}

}  // extern "C"

namespace {

long to_long(const char* s) {
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  if (end == s || *end != '\0' || v <= 0) gyro::bench::fail("bad count");
  return v;
}

int second(int argc, char** argv) {
  if (argc < 5) gyro::bench::fail("usage: second CASE CONTENDER STEPS [TOL|RUN_STEPS]");
  const Case c = gyro::bench::find_case(argv[2]);
  const std::string who = argv[3];
  const long steps = to_long(argv[4]);
  const LinearRhs r = gyro::bench::make_rhs(c);
  double out = 0.0;
  int rc = 0;
  if (who.rfind("exact_", 0) == 0) {
    RotorState<double> s;
    if (who.rfind("exact_propagate", 0) == 0) {
      rc = gyro_bench_measured_exact_propagate(&c, steps, &s);
    } else {
      rc = gyro_bench_measured_exact_precomputed(&c, steps, &s);
    }
    out = s.angle_rad(0);
  } else if (who == "dopri5") {
    if (argc < 6) gyro::bench::fail("dopri5 needs a tolerance");
    gyro::bench::OdeState x{};
    (void)gyro_bench_measured_dopri5(&r, std::atof(argv[5]), &x);
    out = x[0];
  } else {
    const long run = (argc > 5) ? to_long(argv[5]) : steps;
    Vec4 x = Vec4::Zero();
    if (who == "rk4") {
      gyro_bench_measured_rk4(&r, steps, run, &x);
    } else if (who == "euler") {
      gyro_bench_measured_euler(&r, steps, run, &x);
    } else if (who == "ab2") {
      gyro_bench_measured_ab2(&r, steps, run, &x);
    } else {
      gyro::bench::fail("unknown contender");
    }
    out = x(0);
  }
  std::printf("%s %s theta(end) = %.17g\n", c.id.c_str(), who.c_str(), out);
  return rc;
}

int ticks(int argc, char** argv) {
  if (argc < 4) gyro::bench::fail("usage: ticks KIND COUNT");
  const std::string kind = argv[2];
  const long count = to_long(argv[3]);
  const Case c = gyro::bench::find_case("report");
  const double result = gyro::bench::run_ticks(kind, c, count);
  std::printf("ticks %s x %ld: %.17g\n", kind.c_str(), count, result);
  return 0;
}

int gimbal(int argc, char** argv) {
  if (argc < 5) gyro::bench::fail("usage: gimbal KIND double|float COUNT");
  const gyro::bench::GimbalWorkloadSpec spec = gyro::bench::gimbal_workload_spec(argv[2]);
  const std::string type = argv[3];
  const long count = to_long(argv[4]);
  int bad = 0;
  if (type == "float") {
    gyro::bench::GimbalWorkload<float> w(spec);
    bad = gyro_bench_measured_gimbal_float(&w, count);
    std::printf("gimbal %s float x %ld: substeps %d tick %.9g s contact %d pitch %.9g\n", argv[2], count, w.substeps(),
                static_cast<double>(w.tick_s()), static_cast<int>(w.contact()), static_cast<double>(w.output()));
  } else {
    gyro::bench::GimbalWorkload<double> w(spec);
    bad = gyro_bench_measured_gimbal_double(&w, count);
    std::printf("gimbal %s double x %ld: substeps %d tick %.9g s contact %d pitch %.17g\n", argv[2], count, w.substeps(),
                w.tick_s(), static_cast<int>(w.contact()), w.output());
  }
  return bad;
}

#if GYRO_BENCH_HAVE_MODEL && GYRO_BENCH_HAVE_CALLGRIND
template <typename T>
int model_sample_run(long count, long every) {
  gyro::bench::ModelWorkload<T> w;
  int bad = 0;
  for (long i = 0; i < count; ++i) {
    if (i % every == 0) {
      CALLGRIND_START_INSTRUMENTATION;
      CALLGRIND_ZERO_STATS;
      CALLGRIND_TOGGLE_COLLECT;
      bad |= static_cast<int>(w.step());
      CALLGRIND_TOGGLE_COLLECT;
      CALLGRIND_DUMP_STATS;
      CALLGRIND_STOP_INSTRUMENTATION;
    } else {
      bad |= static_cast<int>(w.step());
    }
  }
  std::printf("model_sample x %ld: %.17g\n", count, static_cast<double>(w.output()));
  return bad;
}

int model_sample(int argc, char** argv) {
  if (argc < 5) gyro::bench::fail("usage: model_sample double|float COUNT EVERY");
  const std::string type = argv[2];
  const long count = to_long(argv[3]), every = to_long(argv[4]);
  return (type == "float") ? model_sample_run<float>(count, every)
                           : model_sample_run<double>(count, every);
}
#else
int model_sample(int, char**) { gyro::bench::fail("model_sample needs gyro_model.hpp and callgrind.h"); }
#endif

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "model_sample") == 0) return model_sample(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "second") == 0) return second(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "ticks") == 0) return ticks(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "gimbal") == 0) return gimbal(argc, argv);
  std::fprintf(stderr,
               "usage: %s second CASE CONTENDER STEPS [TOL|RUN_STEPS]\n"
               "       %s ticks KIND COUNT\n"
               "       %s gimbal KIND double|float COUNT\n",
               argv[0], argv[0], argv[0]);
  return 2;
}
