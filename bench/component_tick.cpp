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
#include "gyro/simulated_gyro.hpp"

namespace {

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
  Matrix3<T> R = Matrix3<T>::Identity();
  const Vector3<T> body_rate(T(2), T(0.2), T(-0.1));  // roll, pitch, yaw (rad/s)
  if (!stub.configure(s).ok() || stub.start(R, Vector2<T>(body_rate(1), body_rate(2))) != Status::kOk) return 2;
  if (!comp.configure(SeekerExample<T>::component()).ok() || comp.activate() != Status::kOk) return 3;
  const T dt = SeekerExample<T>::kTick;
  const Matrix3<T> turn = frame_rotation_z(body_rate(2) * dt) * frame_rotation_y(body_rate(1) * dt);
  GuidanceInput<T> in;
  in.nav_valid = true;
  in.body_rate_rad_s = body_rate;
  long failures = 0;
  for (long k = 1; k <= ticks + 600; ++k) {
    R = turn * R;
    if (stub.advance(static_cast<std::uint64_t>(k), R, Vector2<T>::Zero()) != Status::kOk) return 4;
    in.R_earth_to_body = R;
    in.request = (k == 50) ? ModeRequest::kUncage : ModeRequest::kNone;
    in.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.2));
    const bool counted = k > 600;  // caged, uncaged and settled first: the free-flight tick
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    const Status st = comp.step(static_cast<std::uint64_t>(k), in);
    if (counted) CALLGRIND_TOGGLE_COLLECT;
    if (st != Status::kOk) ++failures;
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
