// The software-in-the-loop closed loop, one tick at a time: the body's motion drives the
// simulated gyro, the flight component runs against it through the port, and its torquer
// command goes back to the stub, held until the next write. The one loop gyro_sil, the
// tools, the tests and the firmware images run.
//
// Tick k >= 1, in this order:
//   stub.advance(k, body at k)   the plant over [k-1, k] with the torque written at k-1;
//                                the pickoffs sampled at k
//   guidance input at k          the command with the body's attitude and rates at k
//   component.step(k, input)     reads the pickoffs, writes the torque for [k, k+1]
// Tick 0 is the power-up conversion: start() powers the stub up with the body at tick 0 and
// activates the component; tick(0, ...) then steps the component without advancing the stub.
//
// The component is any type with activate() -> Status and step(tick, GuidanceInput<T>) -> R:
// GyroComponent<T> on the stub (or on a port wrapper that spoils the wire), the flight
// computer of a processor in the loop (R = std::optional<Status>, nullopt for a tick it
// skipped), or a wrapper a test or a benchmark puts around either.
//
// No heap, no exceptions, no RTTI; float or double.
#pragma once

#include <cstdint>
#include <utility>

#include "gyro/attitude.hpp"
#include "gyro/component_types.hpp"
#include "gyro/simulated_gyro.hpp"
#include "gyro/status.hpp"

namespace gyro {

// How the stub is told the body's motion.
enum class StubBodyFeed : std::uint8_t {
  kFull,      // the whole BodySample: attitude, rates (p, q, r), specific force
  kAttitude,  // what the report's driver gives: the attitude, the pitch and yaw rates at
              // power-up and the (lateral y, normal z) specific force each tick; the stub
              // takes each tick's rate from the two attitudes
};

// What guidance sends at a tick besides the body's motion.
template <typename T>
struct GuidanceCommand {
  ModeRequest request{ModeRequest::kNone};
  Vector2<T> slew_rate_cmd_rad_s{Vector2<T>::Zero()};
  bool nav_valid{true};
};

// The component's input at a tick: the command, with the body's attitude and rates.
template <typename T>
[[nodiscard]] GuidanceInput<T> guidance_input(const GuidanceCommand<T>& command, const BodySample<T>& body) noexcept {
  GuidanceInput<T> in;
  in.request = command.request;
  in.slew_rate_cmd_rad_s = command.slew_rate_cmd_rad_s;
  in.nav_valid = command.nav_valid;
  in.R_earth_to_body = body.R_earth_to_body;
  in.body_rate_rad_s = body.rate_rad_s;
  return in;
}

// What start() or tick() returned: the stub's status first; the component ran only when it is
// kOk (otherwise `component` holds its default).
template <typename ComponentResult>
struct SilStatus {
  Status stub{Status::kOk};
  ComponentResult component{};
};

template <typename T, typename Component>
class SilLoop {
 public:
  using StepResult = decltype(std::declval<Component&>().step(std::uint64_t{}, std::declval<const GuidanceInput<T>&>()));

  SilLoop(SimulatedGyro<T>& stub, Component& component, StubBodyFeed feed = StubBodyFeed::kFull) noexcept
      : stub_(stub), component_(component), feed_(feed) {}

  // Tick 0: the stub powers up with the body (both configured before), then the component is
  // activated.
  [[nodiscard]] SilStatus<Status> start(const BodySample<T>& body) noexcept(noexcept(std::declval<Component&>().activate())) {
    SilStatus<Status> s;
    s.stub = feed_ == StubBodyFeed::kAttitude
                 ? stub_.start(body.R_earth_to_body, Vector2<T>(body.rate_rad_s(1), body.rate_rad_s(2)))
                 : stub_.start(body);
    if (s.stub != Status::kOk) return s;
    s.component = component_.activate();
    return s;
  }

  // Tick k: the stub advances to the body at k (not at k = 0), the component steps with the
  // command.
  [[nodiscard]] SilStatus<StepResult> tick(std::uint64_t k, const BodySample<T>& body,
                                           const GuidanceCommand<T>& command) noexcept(kStepNoexcept) {
    SilStatus<StepResult> s;
    if (k > 0) {
      s.stub = feed_ == StubBodyFeed::kAttitude
                   ? stub_.advance(k, body.R_earth_to_body, Vector2<T>(body.specific_force(1), body.specific_force(2)))
                   : stub_.advance(k, body);
      if (s.stub != Status::kOk) return s;
    }
    input_ = guidance_input(command, body);
    s.component = component_.step(k, input_);
    return s;
  }

  [[nodiscard]] const GuidanceInput<T>& input() const noexcept { return input_; }  // the last tick's
  [[nodiscard]] SimulatedGyro<T>& stub() noexcept { return stub_; }
  [[nodiscard]] const SimulatedGyro<T>& stub() const noexcept { return stub_; }
  [[nodiscard]] Component& component() noexcept { return component_; }
  [[nodiscard]] const Component& component() const noexcept { return component_; }

 private:
  static constexpr bool kStepNoexcept =
      noexcept(std::declval<Component&>().step(std::uint64_t{}, std::declval<const GuidanceInput<T>&>()));

  SimulatedGyro<T>& stub_;
  Component& component_;
  StubBodyFeed feed_;
  GuidanceInput<T> input_{};
};

// One tick's passive rotation of a body turning at constant pitch and yaw rates (q, r), as
// the report's driver GYMAIN turns it: pitch by q dt about body y, then yaw by r dt about z.
template <typename T>
[[nodiscard]] Matrix3<T> pitch_then_yaw_turn(const Vector2<T>& pitch_yaw_rate_rad_s, T tick_s) noexcept {
  return frame_rotation_z(pitch_yaw_rate_rad_s(1) * tick_s) * frame_rotation_y(pitch_yaw_rate_rad_s(0) * tick_s);
}

// Such a body at an attitude: rates (0, q, r), no specific force.
template <typename T>
[[nodiscard]] BodySample<T> turning_body(const Matrix3<T>& R_earth_to_body, const Vector2<T>& pitch_yaw_rate_rad_s) noexcept {
  BodySample<T> b;
  b.R_earth_to_body = R_earth_to_body;
  b.rate_rad_s = Vector3<T>(T(0), pitch_yaw_rate_rad_s(0), pitch_yaw_rate_rad_s(1));
  return b;
}

}  // namespace gyro
