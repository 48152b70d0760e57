// The reference board port with the flight component, compiled as a flight image is
// (examples/CMakeLists.txt: C++17, -fno-exceptions -fno-rtti, EIGEN_NO_MALLOC, no SIL
// headers on the include path), instantiated in float and double.
#include "gyro/board/register_board_port.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/seeker_component_example.hpp"

#if defined(__cpp_exceptions) || defined(__cpp_rtti)
#error "the board port's check must be built with -fno-exceptions -fno-rtti"
#endif
#if defined(__has_include)
#if __has_include("gyro/simulated_gyro.hpp")
#error "the flight-side check must not see the SIL stub's headers"
#endif
#endif

namespace gyro::board {
template class RegisterBoardPort<float>;
template class RegisterBoardPort<double>;

// What a board's start-up does: the port over its registers, the component configured from
// the flight-side example and activated.
bool board_start(GyroBoardRegisters& regs, const BoardPortConfig<float>& port_config) noexcept {
  static RegisterBoardPort<float> port(regs, port_config);
  static GyroComponent<float> component(port);
  return component.configure(SeekerComponentExample<float>::component()).ok() &&
         component.activate() == Status::kOk;
}
}  // namespace gyro::board
