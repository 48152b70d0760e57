// The hardware abstraction between the gyro component and the gyro's electronics: torquer
// commands out, gimbal pickoff readings (and spin-rate readback) in. A real driver on the
// guidance computer implements it; so does the software-in-the-loop SimulatedGyro.
//
// Dispatch is virtual: the component is compiled once and handed any implementation by
// reference (two indirect calls per tick). No RTTI, no allocation, no exceptions: every call
// returns a PortStatus, and the component never trusts a reading without checking it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace gyro {

enum class PortStatus : std::uint8_t {
  kOk = 0,
  kNotReady,       // no conversion available yet (power-up, electronics in reset)
  kTimeout,        // the electronics did not answer in time
  kBusError,       // transfer failed (CRC, NACK)
  kHardwareFault,  // the electronics report a fault of their own
};

// The names of the port statuses in logs and messages, in enum order.
[[nodiscard]] constexpr std::array<const char*, 5> enum_names(PortStatus /*tag*/) noexcept {
  return {"ok", "not_ready", "timeout", "bus_error", "hardware_fault"};
}

// One conversion of the pickoffs. Angles follow docs/conventions (and gyro/attitude.hpp):
// positive pitch = spin axis above the body x-y plane, positive yaw = to the right.
template <typename T>
struct PickoffReading {
  Eigen::Matrix<T, 2, 1> gimbal_angle_rad{Eigen::Matrix<T, 2, 1>::Zero()};  // (pitch, yaw)
  std::uint32_t sequence{0};  // +1 per new conversion (wraps); unchanged means stale data
  bool valid{false};          // the electronics' own data-valid bit
  T spin_hz{};                // spin-rate readback (tachometer), meaningful if spin_valid
  bool spin_valid{false};     // false when there is no readback or it failed
};

template <typename T>
class GyroPort {
 public:
  // Latest pickoff conversion. kOk: `out` holds what the electronics reported (still to be
  // validated by the caller). Anything else: nothing was read and `out` is unchanged.
  [[nodiscard]] virtual PortStatus read_pickoffs(PickoffReading<T>& out) noexcept = 0;

  // Torques to hold until the next write: T1 about the pitch gimbal axis (it precesses yaw),
  // T2 about the yaw gimbal axis (it precesses pitch), in the units of the gyro parameters
  // (N*m with SI inertias). A driver converts with its torquer constant:
  //   current_A = torque / Kt_Nm_per_A,   duty = current_A / full_scale_current_A.
  [[nodiscard]] virtual PortStatus write_torquer(const Eigen::Matrix<T, 2, 1>& torque) noexcept = 0;

 protected:
  GyroPort() = default;
  GyroPort(const GyroPort&) = default;
  GyroPort(GyroPort&&) noexcept = default;
  GyroPort& operator=(const GyroPort&) = default;
  GyroPort& operator=(GyroPort&&) noexcept = default;
  ~GyroPort() = default;  // not deleted through the interface: no heap, no ownership
};

}  // namespace gyro
