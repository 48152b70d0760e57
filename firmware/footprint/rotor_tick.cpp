// Footprint image: the smallest program that runs the rotor dynamics tick, to measure
// flash, RAM and stack (scripts/footprint.sh). One transition is built at start-up
// (make_transition, as a flight program does at initialisation or when the spin rate
// changes), then every tick advances the rotor one step under the commanded torque
// (advance). The scalar is float on a single-precision FPU (Cortex-M4F), else double.
//
// Stack is measured by painting (stack_paint.hpp). The image prints
//   stack make_transition <bytes>
//   stack tick <bytes>
// and exits 0 when every call returned kOk.
#include <cstdint>

#include "fw_io.hpp"
#include "gyro/rotor_transition.hpp"
#include "stack_paint.hpp"
#include "target_scalar.hpp"

using Scalar = gyro_fw::TargetScalar;

namespace {

constexpr int kTicks = 1000;

// Inputs and outputs through volatile objects: nothing is folded at compile time.
volatile Scalar g_torque_pitch = static_cast<Scalar>(0.5);
volatile Scalar g_torque_yaw = static_cast<Scalar>(0.2);
volatile Scalar g_dt = static_cast<Scalar>(0.01);
volatile Scalar g_sink = 0;
gyro::RotorParameters<Scalar> g_params{static_cast<Scalar>(2.25), static_cast<Scalar>(2.0),
                                       static_cast<Scalar>(5.0), static_cast<Scalar>(1884.9556)};
gyro::RotorTransition<Scalar> g_transition;
gyro::RotorState<Scalar> g_state;

}  // namespace

// The per-tick work: one exact step of the rotor under the commanded torque.
extern "C" __attribute__((noinline)) int gyro_fw_rotor_tick() noexcept {
  const gyro::Vector2<Scalar> torque(g_torque_pitch, g_torque_yaw);
  return static_cast<int>(gyro::advance(g_transition, torque, g_state));
}

// Initialisation (or a change of spin rate): the step's transition matrices.
extern "C" __attribute__((noinline)) int gyro_fw_rotor_init() noexcept {
  return static_cast<int>(gyro::make_transition(g_params, static_cast<Scalar>(g_dt), g_transition));
}

int main() {
  int failures = 0;
  const std::uintptr_t init_stack =
      gyro_fw::stack_used_by([&] { failures += gyro_fw_rotor_init() != 0 ? 1 : 0; });
  const std::uintptr_t tick_stack = gyro_fw::stack_used_by([&] {
    for (int k = 0; k < kTicks; ++k) failures += gyro_fw_rotor_tick() != 0 ? 1 : 0;
  });
  g_sink = g_state.angle_rad(0);

  gyro_fw::Line() << "stack make_transition " << static_cast<unsigned long>(init_stack) << '\n';
  gyro_fw::Line() << "stack tick " << static_cast<unsigned long>(tick_stack) << '\n';
  return failures == 0 ? 0 : 1;
}
