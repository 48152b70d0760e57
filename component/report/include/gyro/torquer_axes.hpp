// Where the torquers push and what the gimbal friction rubs on: one choice shared by the
// report's model (GyroModel) and the SIL stub's gimbal plant.
#pragma once

#include <array>
#include <cstdint>

namespace gyro {

//   kGyro    the report's idealisation: torques about the gyro's own non-rolling pitch and yaw
//            axes, friction on the gyro's inertial rates about them (the rotor alone);
//   kGimbal  the device (gyro/gimbal_geometry.hpp): torquer commands (inner, outer) about the
//            gimbal axes, the outer one fixed in the body; friction on each gimbal's rate
//            relative to its carrier.
enum class TorquerAxes : std::uint8_t { kGyro = 0, kGimbal };
// The names of its values in configuration files and bindings, in enum order.
[[nodiscard]] constexpr std::array<const char*, 2> enum_names(TorquerAxes /*tag*/) noexcept { return {"gyro", "gimbal"}; }

}  // namespace gyro
