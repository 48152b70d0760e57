// Instructions per tick of GyroComponent::step alone, under callgrind, on the case of
// bench/component_tick_case.hpp (the seeker example slewing on a turning body). Only the
// component's step is collected (callgrind client requests around it), from the first
// free-flight tick on; the stub and the loop are not.
//
//   valgrind --tool=callgrind --collect-atstart=no gyro_bench_component_tick <double|float>
//       <steady|spin_down> <ticks>
// prints the ticks; instructions per tick: the difference of two run lengths (scripts/bench.sh).
#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "component_tick_case.hpp"

namespace {

// Callgrind's collection on around each step from tick `from` on.
struct CallgrindMeter {
  std::uint64_t from;
  template <typename Call>
  gyro::Status measure(std::uint64_t tick, Call&& call) noexcept {
    const bool counted = tick >= from;
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    const gyro::Status st = call();
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    return st;
  }
};

template <typename T>
int run(gyro_bench::TickCase which, std::uint64_t ticks) {
  gyro::SimulatedGyro<T> stub;
  gyro::GyroComponent<T> component(stub);
  CallgrindMeter meter{gyro_bench::kTickCaseSettleTicks + 1};
  const gyro_bench::TickCaseResult r =
      gyro_bench::run_tick_case(which, ticks + gyro_bench::kTickCaseSettleTicks, stub, component, meter);
  if (r.error != 0) return r.error;
  std::printf("%llu ticks counted, mode %s, %llu calls not kOk\n", static_cast<unsigned long long>(ticks),
              gyro::enum_name_or(r.mode, "unknown"), static_cast<unsigned long long>(r.not_ok));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s <double|float> <steady|spin_down> <ticks>\n", argv[0]);
    return 1;
  }
  const gyro_bench::TickCase which =
      std::strcmp(argv[2], "spin_down") == 0 ? gyro_bench::TickCase::kSpinDown : gyro_bench::TickCase::kSteady;
  const auto ticks = static_cast<std::uint64_t>(std::strtoull(argv[3], nullptr, 10));
  return std::strcmp(argv[1], "float") == 0 ? run<float>(which, ticks) : run<double>(which, ticks);
}
