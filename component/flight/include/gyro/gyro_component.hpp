// GyroComponent: the flight software of a two-axis gimballed gyro. Once per fixed-rate tick it
// reads the pickoffs through the port, validates them, predicts the gyro with the exact dynamics,
// decides the mode, computes the torque law and writes the torquer.
//
// Guarantees: no heap, no exceptions, no RTTI; every tick's work is bounded (every loop has a fixed
// bound; a new spin readback rebuilds the estimator's transition, the costliest tick:
// docs/performance.md measures each); the same inputs give bit-identical outputs; once active no
// input stops a tick (unusable fields are ignored, flagged and counted); a refused call (before
// activation, or configure() while active) leaves the state as it was, flagged and counted.
#pragma once

#include <cstdint>

#include "gyro/component_config.hpp"
#include "gyro/component_types.hpp"
#include "gyro/estimator.hpp"
#include "gyro/fault_monitors.hpp"
#include "gyro/flag_counters.hpp"
#include "gyro/guidance_gate.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/inline_step.hpp"
#include "gyro/mode_logic.hpp"
#include "gyro/nutation_tracker.hpp"
#include "gyro/pickoff_gate.hpp"
#include "gyro/spin_readback.hpp"
#include "gyro/tick_tracker.hpp"
#include "gyro/torque_law.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {

template <typename T>
class GyroComponent {
 public:
  explicit GyroComponent(GyroPort<T>& port) noexcept : port_(port) {}

  // Validates and stores the configuration; only while idle (before activate()).
  [[nodiscard]] ConfigCheck configure(const GyroComponentConfig<T>& config) noexcept {
    if (mode_ != GyroMode::kIdle) return {Status::kWrongMode, "mode"};
    const ConfigCheck c = check(config);
    if (!c.ok()) return c;
    const ConfigCheck m = estimator_.configure(config);
    if (!m.ok()) return m;
    config_ = config;
    torque_law_ = TorqueLaw<T>(config);
    nutation_.forget();  // the nutation and the shaper follow the new rotor
    return c;
  }

  // Starts the component caged. Refused unless configured and idle.
  [[nodiscard]] Status activate() noexcept {
    if (!configured()) return Status::kNotConfigured;
    if (mode_ != GyroMode::kIdle) return Status::kWrongMode;
    mode_ = GyroMode::kCaged;
    telemetry_.mode = mode_;
    return Status::kOk;
  }

  // One tick, once per release of the rate group. Fail-operational: once active, every call reads
  // the pickoffs, monitors and writes a torque, whatever the input; a field that cannot be used is
  // ignored, flagged and counted (kInputIgnored), and a condition that persists latches a fault.
  // `tick` should advance by one per call; docs/component.md says what happens when it does not.
  // Before activate() the call is refused (kNotConfigured, counted). Each part returns what it
  // decided with its flags; the tick's flags are combined here.
  [[nodiscard]] Status step(std::uint64_t tick, const GuidanceInput<T>& in) noexcept {
    if (mode_ == GyroMode::kIdle) return refuse(Status::kNotConfigured, kNotActive);

    const ElapsedTicks ticks = tick_tracker_.advance(tick, config_.max_tick_gap);
    const GuidanceVerdict guidance = guidance_.accept(in, config_.max_body_rate_rad_s);
    const bool input_bad = ((ticks.flags | guidance.flags) & kUnusableInput) != 0u;

    PickoffReading<T> raw{};
    const bool port_ok = port_.read_pickoffs(raw) == PortStatus::kOk;
    // In safe mode without the jump test (gyro/pickoff_gate.hpp).
    const PickoffVerdict pick = pickoffs_.accept(raw, port_ok, ticks.ticks, mode_ != GyroMode::kFault,
                                                 {config_.pickoff_range_rad, config_.max_pickoff_step_rad});
    const SpinFlown<T> spin = spin_flown(raw, port_ok, config_);

    const bool measurable = pick.accepted && guidance.nav_ok;
    const Prediction prediction =
        estimator_.predict(ticks.ticks, spin.hz, guidance_.navigation(), measurable, pickoffs_.measured());
    const std::uint32_t residual_flags =
        prediction.compared ? monitors_.test_residual(estimator_.residual_rad(), mode_ == GyroMode::kFault, config_)
                            : 0u;
    const FaultVerdict fault =
        monitors_.update(FaultConditions{!pick.accepted, (spin.flags & kSpinLow) != 0u, input_bad}, config_);
    const std::uint32_t mode_flags = enter(
        next_mode(mode_, {guidance.request, measurable, fault.fault, settle_ticks_, config_.uncage_settle_ticks}));

    const GimbalFrame<T>& frame = estimator_.frame(guidance.nav_ok, pickoffs_.measured());
    const T roll = estimator_.inner_gimbal_roll_rad_s();
    const NutationUpdate<T> nutation = nutation_.follow(spin.hz, roll, frame, config_);
    if (nutation.redesigned) shaper_.use(nutation.shaper);
    const Vector2<T> body =
        guidance.nav_ok ? body_rate_on_gimbal(frame, guidance_.navigation().body_rate_rad_s()) : Vector2<T>::Zero();
    const RateCommand<T> rate =
        torque_law_.rate_command(mode_, frame, body, pickoffs_.measured(), pick.accepted, guidance_.slew_cmd_rad_s());
    const TorqueCommand<T> wanted =
        torque_law_.torque_command(frame, rate, body, spin.hz, roll);
    const Vector2<T> torque = shape_torque(wanted.torque);
    const bool written = port_.write_torquer(torque) == PortStatus::kOk;
    monitors_.torquer_written(written);
    if (written) estimator_.hold_torque(torque);  // else the hardware keeps what it had

    std::uint32_t flags = ticks.flags | guidance.flags | pick.flags | spin.flags | prediction.flags | residual_flags |
                          fault.flags | mode_flags | rate.flags | wanted.flags;
    if (!written) flags |= kTorquerWriteFailed;
    if (mode_ == GyroMode::kFault) flags |= kFaultLatched;
    if (estimator_.ready() && nutation_.aliased()) flags |= kNutationUnresolved;
    publish(tick, flags, rate.rate_rad_s, spin.hz);
    return input_bad ? Status::kInputIgnored : Status::kOk;
  }

  [[nodiscard]] const GyroTelemetry<T>& telemetry() const noexcept { return telemetry_; }
  [[nodiscard]] GyroMode mode() const noexcept { return mode_; }
  [[nodiscard]] const GyroComponentConfig<T>& config() const noexcept { return config_; }

 private:
  // Input the caller sent that the tick could not use (navigation marked invalid by the caller is
  // not among them: that is information, not an error).
  static constexpr std::uint32_t kUnusableInput = kCommandRejected | kTickInvalid;

  // check() refuses a tick_s that is not positive: a stored one is a configuration.
  [[nodiscard]] bool configured() const noexcept { return config_.tick_s > T(0); }

  // A refused call: nothing read or written, state unchanged; flagged and counted so that the
  // ground sees it.
  [[nodiscard]] Status refuse(Status s, std::uint32_t flag) noexcept {
    telemetry_.flags = flag;
    count_flags(telemetry_.counters, flag);
    return s;
  }

  // Carries out the mode logic's transition (gyro/mode_logic.hpp); its flags, and kRequestRefused
  // when the estimator cannot start (the gyro stays caged).
  [[nodiscard]] std::uint32_t enter(const ModeTransition& m) noexcept {
    if (m.estimator == EstimatorAction::kStart) {
      if (!estimator_.start(guidance_.navigation(), pickoffs_.measured())) return kRequestRefused;
    } else if (m.estimator == EstimatorAction::kRestart) {
      estimator_.restart();
      monitors_.reset_residual();
    }
    mode_ = m.mode;
    settle_ticks_ = m.settle_ticks;
    return m.flags;
  }

  // The torque law's torque through the nutation shaper (gyro/torque_shaper.hpp): a step of torque
  // then excites no nutation at the rotor's beta. Safe mode cuts at once, and leaving it starts the
  // shaper from rest.
  [[nodiscard]] GYRO_INLINE_STEP Vector2<T> shape_torque(const Vector2<T>& wanted) noexcept {
    if (mode_ == GyroMode::kFault) {
      shaper_.clear();  // leaving safe mode starts from rest
      return wanted;
    }
    return shaper_.shape(wanted, config_.max_torque);
  }

  void publish(std::uint64_t tick, std::uint32_t flags, const Vector2<T>& rate_cmd, T spin_hz) noexcept {
    const GyroModel<T>& model = estimator_.model();
    GyroTelemetry<T>& t = telemetry_;
    t.tick = tick;
    t.mode = mode_;
    t.flags = flags;
    count_flags(t.counters, flags);
    t.gimbal_measured_rad = pickoffs_.measured();
    t.gimbal_predicted_rad = estimator_.predicted_rad();
    t.residual_rad = estimator_.residual_rad();
    t.attitude_gyro_to_earth = model.attitude_gyro_to_earth();
    t.precession_rate_rad_s = model.rate_on_gimbal_rad_s();
    t.rate_cmd_rad_s = rate_cmd;
    t.torque_cmd = estimator_.torque_held();
    t.nutation_amplitude_rad = model.nutation_amplitude_rad();
    t.spin_hz = spin_hz;
  }

  GyroPort<T>& port_;
  GyroComponentConfig<T> config_{};
  GyroMode mode_{GyroMode::kIdle};
  std::uint32_t settle_ticks_{0};  // ticks uncaging so far
  TickTracker tick_tracker_{};
  GuidanceGate<T> guidance_{};
  PickoffGate<T> pickoffs_{};
  Estimator<T> estimator_{};
  FaultMonitors monitors_{};
  NutationTracker<T> nutation_{};
  TorqueShaper<T> shaper_{};
  TorqueLaw<T> torque_law_{};
  GyroTelemetry<T> telemetry_{};
};

}  // namespace gyro
