// The SIL gyro behind a faulty harness: a wiring fault between the flight computer and a
// healthy gyro. Readings pass through (the spin readback replaced when `spin_override` is set,
// the angles when `angle_override` is); torquer writes fail with `write_status` unless it is
// kOk, and then never reach the gyro.
#pragma once

#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/sil_fixture.hpp"

namespace gyro::testing {

template <typename T>
class FaultyHarness final : public GyroPort<T> {
 public:
  explicit FaultyHarness(SimulatedGyro<T>& gyro) noexcept : gyro_(gyro) {}

  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    const PortStatus st = gyro_.read_pickoffs(out);
    if (st == PortStatus::kOk && spin_override) {
      out.spin_hz = spin_hz;
      out.spin_valid = true;
    }
    if (st == PortStatus::kOk && angle_override) out.gimbal_angle_rad = angle_rad;
    return st;
  }
  [[nodiscard]] PortStatus write_torquer(const Vector2<T>& torque) noexcept override {
    if (write_status != PortStatus::kOk) return write_status;
    return gyro_.write_torquer(torque);
  }

  PortStatus write_status{PortStatus::kOk};
  bool spin_override{false};
  T spin_hz{};
  bool angle_override{false};  // valid bit and sequence stay the gyro's
  Vector2<T> angle_rad{Vector2<T>::Zero()};

 private:
  SimulatedGyro<T>& gyro_;
};

// The component on the faulty harness, the body turning at constant rates.
template <typename T>
struct FaultyRig {
  SimulatedGyro<T> gyro;
  FaultyHarness<T> harness{gyro};
  GyroComponent<T> component{harness};
  SilLoop<T, GyroComponent<T>> loop{gyro, component, StubBodyFeed::kAttitude};
  GuidanceCommand<T> guidance;
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector2<T> body_rate{T(0.4), T(-0.3)};
  std::uint64_t tick{0};

  bool start() {
    if (!gyro.configure(SeekerGyro<T>::stub()).ok() || !component.configure(SeekerGyro<T>::component()).ok()) {
      return false;
    }
    const SilStatus<Status> started = loop.start(turning_body(R_earth_to_body, body_rate));
    return started.stub == Status::kOk && started.component == Status::kOk;
  }
  Status step() {
    R_earth_to_body = pitch_then_yaw_turn(body_rate, SeekerGyro<T>::kTick) * R_earth_to_body;
    ++tick;
    const SilStatus<Status> ran = loop.tick(tick, turning_body(R_earth_to_body, body_rate), guidance);
    return ran.stub != Status::kOk ? ran.stub : ran.component;
  }
  [[nodiscard]] const GyroTelemetry<T>& tm() const { return component.telemetry(); }
};

}  // namespace gyro::testing
