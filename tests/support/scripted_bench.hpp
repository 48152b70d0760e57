// A bench for tests of the component's edges: the component on a port whose readings the
// test writes, the body at rest with usable navigation.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gyro/gyro_component.hpp"
#include "support/sil_fixture.hpp"

namespace gyro::testing {

// Counter index of a flag bit in telemetry.counters.
constexpr std::size_t counter_of(ComponentFlag f) {
  std::size_t i = 0;
  while ((1u << i) != static_cast<std::uint32_t>(f)) ++i;
  return i;
}

// A port whose readings the test writes: each read returns `reading` with the sequence
// advanced (unless `hold_sequence`), or `read_status`. `fill_on_failure` makes a failed read
// still write the reading (a driver breaking the port's contract). Torques are recorded.
class ScriptedPort final : public GyroPort<double> {
 public:
  ScriptedPort() noexcept {
    reading.valid = true;
    reading.spin_hz = 400.0;
    reading.spin_valid = true;
  }
  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<double>& out) noexcept override {
    if (!hold_sequence) ++reading.sequence;
    if (read_status != PortStatus::kOk && !fill_on_failure) return read_status;
    out = reading;
    return read_status;
  }
  [[nodiscard]] PortStatus write_torquer(const Vector2<double>& torque) noexcept override {
    torque_written = torque;
    return PortStatus::kOk;
  }

  PickoffReading<double> reading{};  // at (0, 0), valid, 400 Hz
  PortStatus read_status{PortStatus::kOk};
  bool hold_sequence{false};
  bool fill_on_failure{false};
  Vector2<double> torque_written{Vector2<double>::Zero()};
};

// The component on a scripted port, the body at rest with usable navigation. The first
// reading goes out with sequence 1 (set `port.reading.sequence` to start elsewhere).
struct Bench {
  ScriptedPort port;
  GyroComponent<double> component{port};
  GuidanceInput<double> guidance;
  std::uint64_t tick{0};

  explicit Bench(const GyroComponentConfig<double>& c = SeekerGyro<double>::component()) {
    guidance.nav_valid = true;
    ok = component.configure(c).ok() && component.activate() == Status::kOk;
  }
  Status step(ModeRequest request = ModeRequest::kNone) { return step_at(tick + 1, request); }
  Status step_at(std::uint64_t count, ModeRequest request = ModeRequest::kNone) {
    tick = count;
    guidance.request = request;
    return component.step(count, guidance);
  }
  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) (void)step();
  }
  [[nodiscard]] const GyroTelemetry<double>& tm() const { return component.telemetry(); }
  [[nodiscard]] bool raised(ComponentFlag f) const { return (tm().flags & f) != 0u; }
  bool ok{false};
};

}  // namespace gyro::testing
