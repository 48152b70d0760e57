// Per-tick kernels of the exact propagator, compiled in their own translation unit
// (tick_kernels.cpp) so the out-of-line step can be read in the disassembly.
#pragma once

#include <string>

#include "bench_problem.hpp"

extern "C" {

// One exact step with precomputed coefficients, out of line (read with objdump).
int gyro_bench_one_advance_double(const gyro::RotorTransition<double>* tr,
                                  const gyro::Vector2<double>* torque,
                                  gyro::RotorState<double>* s);
int gyro_bench_one_advance_float(const gyro::RotorTransition<float>* tr,
                                 const gyro::Vector2<float>* torque, gyro::RotorState<float>* s);
// The same four 2x2 products without advance()'s finiteness checks, for comparison.
void gyro_bench_one_advance_unchecked_double(const gyro::RotorTransition<double>* tr,
                                             const gyro::Vector2<double>* torque,
                                             gyro::RotorState<double>* s);
}

namespace gyro::bench {

// Runs `count` ticks of `kind` at the case's gyro (dt = 1 ms, or 10 ms for the *_100hz kinds)
// inside a function named gyro_bench_measured_ticks_*; returns a value of the final state.
// Kinds: advance_double, advance_float, advance_unchecked_double, advance_lean_double,
// advance_lean_float, propagate_double,
// propagate_double_100hz, make_transition_double, make_transition_double_100hz, and, when
// gyro/gyro_model.hpp exists, model_double and model_float (GyroModel<T>::step_torque).
double run_ticks(const std::string& kind, const Case& c, long count);

}  // namespace gyro::bench
