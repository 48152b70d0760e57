// The case the component's tick is measured on, the same on x86-64 (bench/component_tick.cpp,
// callgrind) and on the Cortex-M targets (firmware/tick_cost/, QEMU -icount): the seeker
// example closed around the SIL stub's gimbal plant by the SIL loop, caged, uncaged at tick
// 50, then slewing while the body turns in pitch and yaw and rolls at 2 rad/s.
//   steady     the spin readback is constant: the estimator's transition stays cached;
//   spin_down  the readback changes every tick (the plant's rotor free-running down): the
//              transition is rebuilt every tick.
// The meter sees every GyroComponent::step call: meter.measure(tick, call) runs call() (the
// step) and returns its Status. C++17, no heap: the firmware image builds it too.
#pragma once

#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro_bench {

enum class TickCase : std::uint8_t { kSteady, kSpinDown };

// Ticks before the free-flight ticks: caged, uncaged (tick 50) and settled.
constexpr std::uint64_t kTickCaseSettleTicks = 600;

// The component with the meter around its step.
template <typename T, typename Meter>
class MeteredComponent {
 public:
  MeteredComponent(gyro::GyroComponent<T>& component, Meter& meter) noexcept : component_(component), meter_(meter) {}
  [[nodiscard]] gyro::Status activate() noexcept { return component_.activate(); }
  [[nodiscard]] gyro::Status step(std::uint64_t tick, const gyro::GuidanceInput<T>& in) noexcept {
    return meter_.measure(tick, [&]() noexcept { return component_.step(tick, in); });
  }

 private:
  gyro::GyroComponent<T>& component_;
  Meter& meter_;
};

// What a run of the case ended with.
struct TickCaseResult {
  int error{0};             // 0; 2: the stub refused a call; 3: the component's configure or activate
  std::uint64_t not_ok{0};  // step calls that returned other than kOk
  gyro::GyroMode mode{gyro::GyroMode::kIdle};
};

// Runs tick 0 and ticks 1 .. ticks with `stub` and `component` (not yet configured: the case
// configures both).
template <typename T, typename Meter>
TickCaseResult run_tick_case(TickCase which, std::uint64_t ticks, gyro::SimulatedGyro<T>& stub,
                             gyro::GyroComponent<T>& component, Meter& meter) noexcept {
  using namespace gyro;
  TickCaseResult result;
  SimulatedGyroConfig<T> s = SeekerExample<T>::stub();
  if (which == TickCase::kSpinDown) {
    s.gimbal.spin_drive = SpinDrive::kFree;
    s.gimbal.spin_down_time_s = T(20);
  }
  MeteredComponent<T, Meter> metered(component, meter);
  SilLoop<T, MeteredComponent<T, Meter>> loop(stub, metered, StubBodyFeed::kAttitude);
  const Vector2<T> pitch_yaw_rate(T(0.2), T(-0.1));
  // The stub's body turns in pitch and yaw; the component is also told of a 2 rad/s roll.
  BodySample<T> body = turning_body(Matrix3<T>(Matrix3<T>::Identity()), pitch_yaw_rate);
  body.rate_rad_s(0) = T(2);
  if (!stub.configure(s).ok()) return {2, 0, component.mode()};
  if (!component.configure(SeekerExample<T>::component()).ok()) return {3, 0, component.mode()};
  const SilStatus<Status> started = loop.start(body);
  if (started.stub != Status::kOk) return {2, 0, component.mode()};
  if (started.component != Status::kOk) return {3, 0, component.mode()};
  const Matrix3<T> turn = pitch_then_yaw_turn(pitch_yaw_rate, SeekerExample<T>::kTick);
  GuidanceCommand<T> command;
  command.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.2));
  for (std::uint64_t k = 1; k <= ticks; ++k) {
    body.R_earth_to_body = turn * body.R_earth_to_body;
    command.request = (k == 50) ? ModeRequest::kUncage : ModeRequest::kNone;
    const SilStatus<Status> ran = loop.tick(k, body, command);
    if (ran.stub != Status::kOk) return {2, result.not_ok, component.mode()};
    if (ran.component != Status::kOk) ++result.not_ok;
  }
  result.mode = component.mode();
  return result;
}

}  // namespace gyro_bench
