// Instructions per tick of GyroComponent::step alone, under callgrind: the seeker example
// closed around the SIL stub, slewing while the body turns and rolls. Only the component's
// step is collected (callgrind client requests around it); the stub and the loop are not.
//
//   valgrind --tool=callgrind --collect-atstart=no gyro_bench_component_tick <double|float>
//       <steady|spin_down> <ticks>
// prints the ticks; instructions per tick = callgrind's total / ticks.
//   steady     the spin readback is constant: the estimator's transition stays cached;
//   spin_down  the readback changes every tick: the transition is rebuilt every tick.
#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"

namespace {

// The component with callgrind's collection on around its step, from tick `from` on.
template <typename T>
struct CountedComponent {
  gyro::GyroComponent<T>& component;
  std::uint64_t from;

  [[nodiscard]] gyro::Status activate() noexcept { return component.activate(); }
  [[nodiscard]] gyro::Status step(std::uint64_t tick, const gyro::GuidanceInput<T>& in) noexcept {
    const bool counted = tick >= from;
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    const gyro::Status st = component.step(tick, in);
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    return st;
  }
};

template <typename T>
int run(bool spin_down, long ticks) {
  using namespace gyro;
  SimulatedGyroConfig<T> s = SeekerExample<T>::stub();
  if (spin_down) {  // the gimbal plant's rotor free-running down
    s.gimbal.spin_drive = SpinDrive::kFree;
    s.gimbal.spin_down_time_s = T(20);
  }
  SimulatedGyro<T> stub;
  GyroComponent<T> comp(stub);
  CountedComponent<T> counted{comp, 601};  // caged, uncaged and settled first: the free-flight tick
  SilLoop<T, CountedComponent<T>> loop(stub, counted, StubBodyFeed::kAttitude);
  const Vector2<T> pitch_yaw_rate(T(0.2), T(-0.1));
  // The stub's body turns in pitch and yaw; the component is also told of a 2 rad/s roll.
  BodySample<T> body = turning_body(Matrix3<T>(Matrix3<T>::Identity()), pitch_yaw_rate);
  body.rate_rad_s(0) = T(2);
  if (!stub.configure(s).ok()) return 2;
  if (!comp.configure(SeekerExample<T>::component()).ok()) return 3;
  const SilStatus<Status> started = loop.start(body);
  if (started.stub != Status::kOk) return 2;
  if (started.component != Status::kOk) return 3;
  const Matrix3<T> turn = pitch_then_yaw_turn(pitch_yaw_rate, SeekerExample<T>::kTick);
  GuidanceCommand<T> command;
  command.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.2));
  long failures = 0;
  for (long k = 1; k <= ticks + 600; ++k) {
    body.R_earth_to_body = turn * body.R_earth_to_body;
    command.request = (k == 50) ? ModeRequest::kUncage : ModeRequest::kNone;
    const SilStatus<Status> ran = loop.tick(static_cast<std::uint64_t>(k), body, command);
    if (ran.stub != Status::kOk) return 4;
    if (ran.component != Status::kOk) ++failures;
  }
  std::printf("%ld ticks counted, mode %s, %ld calls not kOk\n", ticks, to_string(comp.mode()), failures);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s <double|float> <steady|spin_down> <ticks>\n", argv[0]);
    return 1;
  }
  const bool spin_down = std::strcmp(argv[2], "spin_down") == 0;
  const long ticks = std::atol(argv[3]);
  return std::strcmp(argv[1], "float") == 0 ? run<float>(spin_down, ticks) : run<double>(spin_down, ticks);
}
