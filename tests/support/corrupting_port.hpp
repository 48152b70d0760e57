// A port between the component and the SIL stub that corrupts what passes through it on
// request: a failed read or write, NaN or out-of-range angles, a stale sequence, a jump. The
// stub underneath stays a full implementation of the port; this only spoils the wire.
#pragma once

#include <cstdint>
#include <limits>

#include "gyro/gyro_port.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro::testing {

enum class WireFault : std::uint8_t {
  kNone,
  kReadFails,      // the port answers kTimeout
  kNotValid,       // the valid bit is clear
  kNanAngle,       // a NaN angle with the valid bit set
  kOutOfRange,     // an angle far beyond any pickoff's range
  kStale,          // the previous reading again, sequence included
  kJump,           // the angles moved by 0.1 rad
  kWriteFails,     // the torquer write answers kBusError (the stub keeps its last torque)
  kSpinGarbage,    // a NaN spin readback marked valid
};
inline constexpr int kWireFaultCount = 9;

template <typename T>
class CorruptingPort final : public GyroPort<T> {
 public:
  explicit CorruptingPort(SimulatedGyro<T>& gyro) noexcept : gyro_(gyro) {}

  WireFault fault{WireFault::kNone};

  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    if (fault == WireFault::kReadFails) return PortStatus::kTimeout;
    PickoffReading<T> r;
    const PortStatus st = gyro_.read_pickoffs(r);
    if (st != PortStatus::kOk) return st;
    switch (fault) {
      case WireFault::kNotValid: r.valid = false; break;
      case WireFault::kNanAngle: r.gimbal_angle_rad(0) = std::numeric_limits<T>::quiet_NaN(); break;
      case WireFault::kOutOfRange: r.gimbal_angle_rad(1) = T(1e6); break;
      case WireFault::kStale: r = last_; break;
      case WireFault::kJump: r.gimbal_angle_rad += Vector2<T>(T(0.1), T(-0.1)); break;
      case WireFault::kSpinGarbage: r.spin_hz = std::numeric_limits<T>::quiet_NaN(); break;
      default: break;
    }
    last_ = r;
    out = r;
    return PortStatus::kOk;
  }

  [[nodiscard]] PortStatus write_torquer(const Vector2<T>& torque) noexcept override {
    ++writes;
    if (fault == WireFault::kWriteFails) return PortStatus::kBusError;
    return gyro_.write_torquer(torque);
  }

  int writes{0};

 private:
  SimulatedGyro<T>& gyro_;
  PickoffReading<T> last_{};
};

}  // namespace gyro::testing
