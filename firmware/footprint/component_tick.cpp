// Footprint image: the gyro component alone behind a minimal port, to measure what a flight
// program pays for it (scripts/footprint.sh): flash, RAM and stack per tick. No SIL stub,
// no rotor truth: the port is what a driver over memory-mapped converters would be, two
// volatile pickoff registers in and two torquer registers out.
//
// The program configures a small seeker gyro (2 kHz tick), activates it, uncages it and
// ticks it held still (zero slew command, body at rest, pickoffs steady), so every tick
// takes the nominal path: read and validate, predict, check the residual, estimate, torque
// law, write, telemetry. Stack is measured by painting (stack_paint.hpp). It prints
//   stack configure <bytes>
//   stack tick <bytes>
// and exits 0 when every call returned kOk and the component ends free with no flag raised.
#include <cstdint>

#include "fw_io.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/seeker_component_example.hpp"  // flight-side: no SIL header
#include "stack_paint.hpp"
#include "target_scalar.hpp"

using Scalar = gyro_fw::TargetScalar;

namespace {

constexpr std::uint32_t kUncageTick = 10;
constexpr std::uint32_t kTicks = 2000;

// The "hardware": converter registers, volatile so nothing is folded at compile time.
volatile Scalar g_pickoff_pitch_rad = static_cast<Scalar>(0.01);
volatile Scalar g_pickoff_yaw_rad = static_cast<Scalar>(-0.02);
volatile Scalar g_tachometer_hz = static_cast<Scalar>(400);
volatile Scalar g_torquer_pitch = 0;
volatile Scalar g_torquer_yaw = 0;

// The smallest real port: a new conversion every read, torques straight to the registers.
class RegisterPort final : public gyro::GyroPort<Scalar> {
 public:
  gyro::PortStatus read_pickoffs(gyro::PickoffReading<Scalar>& out) noexcept override {
    out.gimbal_angle_rad = gyro::Vector2<Scalar>(g_pickoff_pitch_rad, g_pickoff_yaw_rad);
    out.sequence = ++sequence_;
    out.valid = true;
    out.spin_hz = g_tachometer_hz;
    out.spin_valid = true;
    return gyro::PortStatus::kOk;
  }
  gyro::PortStatus write_torquer(const gyro::Vector2<Scalar>& torque) noexcept override {
    g_torquer_pitch = torque(0);
    g_torquer_yaw = torque(1);
    return gyro::PortStatus::kOk;
  }

 private:
  std::uint32_t sequence_ = 0;
};

// The example seeker gyro (J = 2e-5, J0 = 3e-5 kg m^2, f = 4e-4 N m s, 400 Hz, 2 kHz tick),
// with the fault campaign's estimator gain and residual limit (docs/fault-campaign.md).
gyro::GyroComponentConfig<Scalar> seeker_config() noexcept {
  gyro::GyroComponentConfig<Scalar> c = gyro::SeekerComponentExample<Scalar>::component();
  c.estimator_gain = static_cast<Scalar>(0.02);
  c.residual_limit_rad = static_cast<Scalar>(1.7e-3);
  c.uncage_settle_ticks = 100;
  return c;
}

RegisterPort g_port;
gyro::GyroComponent<Scalar> g_component(g_port);
gyro::GuidanceInput<Scalar> g_input;

}  // namespace

// The per-tick work: one GyroComponent::step (port read and write included).
extern "C" __attribute__((noinline)) int gyro_fw_component_tick(std::uint32_t tick) noexcept {
  g_input.request = tick == kUncageTick ? gyro::ModeRequest::kUncage : gyro::ModeRequest::kNone;
  return static_cast<int>(g_component.step(tick, g_input));
}

// Initialisation: validate the configuration (derived constants, transition) and activate.
extern "C" __attribute__((noinline)) int gyro_fw_component_init() noexcept {
  const gyro::ConfigCheck check = g_component.configure(seeker_config());
  if (!check.ok()) {
    gyro_fw::Line() << "configure: " << check.field << ": " << gyro::to_string(check.status) << '\n';
    return 1;
  }
  return static_cast<int>(g_component.activate());
}

int main() {
  int failures = 0;
  g_input.nav_valid = true;
  const std::uintptr_t init_stack =
      gyro_fw::stack_used_by([&] { failures += gyro_fw_component_init() != 0 ? 1 : 0; });
  const std::uintptr_t tick_stack = gyro_fw::stack_used_by([&] {
    for (std::uint32_t k = 1; k <= kTicks; ++k) failures += gyro_fw_component_tick(k) != 0 ? 1 : 0;
  });

  const gyro::GyroTelemetry<Scalar>& tm = g_component.telemetry();
  const bool nominal = tm.mode == gyro::GyroMode::kFree && tm.flags == 0U;
  gyro_fw::Line() << "stack configure " << static_cast<unsigned long>(init_stack) << '\n';
  gyro_fw::Line() << "stack tick " << static_cast<unsigned long>(tick_stack) << '\n';
  gyro_fw::Line() << "mode " << gyro::enum_name_or(tm.mode, "?") << " flags " << static_cast<unsigned long>(tm.flags)
                  << '\n';
  return failures == 0 && nominal ? 0 : 1;
}
