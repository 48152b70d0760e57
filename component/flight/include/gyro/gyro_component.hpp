// GyroComponent: the flight software of a two-axis gimballed gyro. Once per fixed-rate
// tick it reads the pickoffs through the port, validates them, predicts the gyro with the
// exact dynamics, decides the mode, computes the torque law and writes the torquer.
//
// Guarantees: no heap, no exceptions, no RTTI; every tick's work is bounded (every loop has a
// fixed bound; a new spin readback rebuilds the estimator's transition, the costliest tick:
// docs/performance.md measures each); the same inputs give bit-identical outputs; once active no input
// stops a tick (unusable fields are ignored, flagged and counted); a refused call (before
// activation, or configure() while active) leaves the state as it was, flagged and counted.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gyro/component_config.hpp"
#include "gyro/component_types.hpp"
#include "gyro/fault_monitors.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/mode_logic.hpp"
#include "gyro/nutation_tracker.hpp"
#include "gyro/pickoff_gate.hpp"
#include "gyro/saturate.hpp"
#include "gyro/stop_protection.hpp"
#include "gyro/tick_tracker.hpp"
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
    GyroModel<T> est;
    const ConfigCheck m = est.configure(estimator_config(config));
    if (!m.ok()) return m;
    config_ = config;
    estimator_ = est;
    stop_bound_ = {std::sin(config.gimbal_cone_limit_rad - config.gimbal_stop_margin_rad), config.cage_gain_1_s};
    nutation_.forget();  // the nutation and the shaper follow the new rotor
    configured_ = true;
    return c;
  }

  // Starts the component caged. Refused unless configured and idle.
  [[nodiscard]] Status activate() noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (mode_ != GyroMode::kIdle) return Status::kWrongMode;
    mode_ = GyroMode::kCaged;
    telemetry_.mode = mode_;
    return Status::kOk;
  }

  // One tick, once per release of the rate group. Fail-operational: once active, every call
  // reads the pickoffs, monitors and writes a torque, whatever the input; a field that cannot
  // be used is ignored, flagged and counted (kInputIgnored), and a condition that persists
  // latches a fault. `tick` should advance by one per call; docs/component.md says what
  // happens when it does not. Before activate() the call is refused (kNotConfigured, counted).
  [[nodiscard]] Status step(std::uint64_t tick, const GuidanceInput<T>& in) noexcept {
    if (mode_ == GyroMode::kIdle) return refuse(Status::kNotConfigured, kNotActive);

    const ElapsedTicks ticks = tick_tracker_.advance(tick, config_.max_tick_gap);
    std::uint32_t flags = ticks.flags;
    const std::uint64_t elapsed = ticks.ticks;
    const ModeRequest request = accept_command(in, flags);
    const bool nav_ok = accept_navigation(in, flags);
    const bool input_bad = (flags & kUnusableInput) != 0u;

    Reading r;
    r.port_ok = port_.read_pickoffs(r.raw) == PortStatus::kOk;
    // The pickoffs through the gate (gyro/pickoff_gate.hpp); in safe mode without the jump test.
    const PickoffVerdict pick = pickoffs_.accept(r.raw, r.port_ok, elapsed, mode_ != GyroMode::kFault,
                                                 {config_.pickoff_range_rad, config_.max_pickoff_step_rad});
    flags |= pick.flags;
    const T spin = spin_hz(r);
    if (spin < config_.min_spin_hz) flags |= kSpinLow;
    const NutationUpdate<T> nutation = nutation_.follow(spin, config_);
    if (nutation.redesigned) shaper_.use(nutation.shaper);

    predict_and_check(elapsed, spin, pick.accepted && nav_ok, flags);
    const FaultVerdict fault = monitors_.update(FaultConditions{!pick.accepted, (flags & kSpinLow) != 0u, input_bad}, config_);
    flags |= fault.flags;
    flags |= enter(next_mode(mode_, {request, pick.accepted && nav_ok, fault.fault, settle_ticks_, config_.uncage_settle_ticks}));

    const GimbalFrame<T>& frame = frame_now(nav_ok);
    const Vector2<T> body = nav_ok ? body_rate_on_gimbal(frame, body_rate_) : Vector2<T>::Zero();
    const RateCommand rate = rate_command(frame, body, pick.accepted);
    const TorqueCommand wanted = torque_command(frame, rate, body, spin);
    flags |= rate.flags | wanted.flags;
    const Vector2<T> torque = shape_torque(wanted.torque);
    const bool written = port_.write_torquer(torque) == PortStatus::kOk;
    monitors_.torquer_written(written);
    if (written) {
      torque_held_ = torque;
    } else {
      flags |= kTorquerWriteFailed;  // the hardware keeps whatever it had: assume the last
    }
    if (mode_ == GyroMode::kFault) flags |= kFaultLatched;

    publish(tick, flags, rate.rate_rad_s, spin);
    return input_bad ? Status::kInputIgnored : Status::kOk;
  }

  [[nodiscard]] const GyroTelemetry<T>& telemetry() const noexcept { return telemetry_; }
  [[nodiscard]] GyroMode mode() const noexcept { return mode_; }
  [[nodiscard]] const GyroComponentConfig<T>& config() const noexcept { return config_; }

 private:
  // Input the caller sent that the tick could not use (navigation marked invalid by the
  // caller is not among them: that is information, not an error).
  static constexpr std::uint32_t kUnusableInput = kCommandRejected | kTickInvalid;

  struct Reading {
    bool port_ok{false};
    PickoffReading<T> raw{};
  };

  [[nodiscard]] static bool valid_request(ModeRequest r) noexcept {
    return r == ModeRequest::kNone || r == ModeRequest::kCage || r == ModeRequest::kUncage;
  }
  [[nodiscard]] static std::uint32_t sat_inc(std::uint32_t v) noexcept {
    return v == std::numeric_limits<std::uint32_t>::max() ? v : v + 1u;
  }

  // A refused call: nothing read or written, state unchanged; flagged and counted so that the
  // ground sees it.
  [[nodiscard]] Status refuse(Status s, std::uint32_t flag) noexcept {
    telemetry_.flags = flag;
    count(flag);
    return s;
  }

  // The request (an unknown value is dropped) and the slew command (a non-finite one is
  // ignored: the last usable command is held).
  [[nodiscard]] ModeRequest accept_command(const GuidanceInput<T>& in, std::uint32_t& flags) noexcept {
    ModeRequest request = in.request;
    if (!valid_request(request)) {
      request = ModeRequest::kNone;
      flags |= kCommandRejected;
    }
    if (all_finite(in.slew_rate_cmd_rad_s)) {
      slew_cmd_ = in.slew_rate_cmd_rad_s;
    } else {
      flags |= kCommandRejected;
    }
    return request;
  }

  // Navigation is used when marked valid and usable: a rotation, finite rates within
  // max_body_rate_rad_s. Otherwise the last good attitude is kept (for the estimator's
  // prediction, whose residual test is then suspended) and the rates are taken as unknown.
  [[nodiscard]] bool accept_navigation(const GuidanceInput<T>& in, std::uint32_t& flags) noexcept {
    const bool usable = in.nav_valid && all_finite(in.body_rate_rad_s) &&
                        in.body_rate_rad_s.cwiseAbs().maxCoeff() <= config_.max_body_rate_rad_s &&
                        GyroModel<T>::check_body_attitude(in.R_earth_to_body, attitude_);
    if (!usable) {
      flags |= kNavInvalid;
      if (in.nav_valid) flags |= kCommandRejected;  // marked valid, yet unusable
      return false;
    }
    body_rate_prev_ = body_rate_;
    body_rate_ = in.body_rate_rad_s;
    return true;
  }

  [[nodiscard]] T spin_hz(const Reading& r) const noexcept {
    // A readback whose angular momentum is not representable is no spin: the nominal is used.
    if (config_.use_spin_readback && r.port_ok && r.raw.spin_valid && std::isfinite(r.raw.spin_hz) &&
        r.raw.spin_hz >= T(0) && std::isfinite(angular_momentum(r.raw.spin_hz, config_.spin_inertia))) {
      return r.raw.spin_hz;
    }
    return config_.nominal_spin_hz;
  }

  // The report's uncaging of the estimator at the measured gimbal angles, rates from the body.
  [[nodiscard]] bool start_estimator() noexcept {
    if (estimator_.uncage_on_gimbal(attitude_.matrix(), body_rate_, pickoffs_.measured()) != Status::kOk) return false;
    predicted_ = Vector2<T>(estimator_.gimbal_pitch_rad(), estimator_.gimbal_yaw_rad());
    return true;
  }

  // Advances the estimator over the elapsed ticks with the torque held, compares with the
  // accepted reading, and feeds a fraction of the residual back into the attitude (turned at
  // the start of the next step, with its rotation). In safe mode the residual is not
  // monitored (the estimator restarts when the gyro is caged again).
  void predict_and_check(std::uint64_t elapsed, T spin, bool measurable, std::uint32_t& flags) noexcept {
    if (!estimator_ready_) {
      if (measurable) estimator_ready_ = start_estimator();
      residual_.setZero();
      return;
    }
    GyroStepInput<T>& s = step_input_;  // a member: its unread attitude is not rebuilt each tick
    s.dt_s = config_.tick_s * static_cast<T>(elapsed);
    s.spin_hz = spin;
    s.body_rate_rad_s = T(0.5) * (body_rate_prev_ + body_rate_);
    if (estimator_.step_torque(s, attitude_, torque_held_) != Status::kOk) {
      estimator_ready_ = false;  // re-initialised from the next good reading
      return;
    }
    if (estimator_.small_angle_exceeded()) flags |= kSmallAngleExceeded;
    if (estimator_.gimbal_limit_exceeded()) flags |= kGimbalLimit;
    predicted_ = Vector2<T>(estimator_.gimbal_pitch_rad(), estimator_.gimbal_yaw_rad());
    if (!measurable) return;
    residual_ = pickoffs_.measured() - predicted_;
    if (mode_ == GyroMode::kFault) {
      monitors_.reset_residual();
    } else if (monitors_.residual(residual_.cwiseAbs().maxCoeff() > config_.residual_limit_rad,
                                  config_.residual_persistence_ticks)) {
      flags |= kResidualFault;
    }
    (void)estimator_.correct_gimbal_angles_at_next_step(Vector2<T>(config_.estimator_gain * residual_));
  }

  // Carries out the mode logic's transition (gyro/mode_logic.hpp); its flags, and
  // kRequestRefused when the estimator cannot start.
  [[nodiscard]] std::uint32_t enter(const ModeTransition& m) noexcept {
    if (m.estimator == EstimatorAction::kStart) {
      if (!start_estimator()) return kRequestRefused;  // stays caged
      estimator_ready_ = true;
      residual_.setZero();  // the caged estimator's residual means nothing to the new start
    } else if (m.estimator == EstimatorAction::kRestart) {
      estimator_ready_ = false;  // restarts from the next good reading
      monitors_.reset_residual();  // its fill from before the fault is gone
    }
    mode_ = m.mode;
    settle_ticks_ = m.settle_ticks;
    return m.flags;
  }

  // The gimbal frame the torque law and the stop protection resolve on: the estimator's, else
  // the pickoffs' (before the estimator runs, and without navigation, when the prediction
  // holds the last good body attitude while the body turns on).
  [[nodiscard]] const GimbalFrame<T>& frame_now(bool nav_ok) noexcept {
    if (estimator_ready_ && nav_ok) return estimator_.gimbal_frame_now();
    pickoff_frame_ = gimbal_frame_at(pickoffs_.measured());
    return pickoff_frame_;
  }

  // Spin-axis rates to fly this tick on the gimbal axes (pitch about y_I, yaw about z_I),
  // after stop protection and limits, and what the torque law is to do with them.
  struct RateCommand {
    Vector2<T> rate_rad_s{Vector2<T>::Zero()};
    bool torquing{false};    // the torquers are driven this tick
    bool protecting{false};  // stop protection moved the rate
    Vector2<T> outward{Vector2<T>::Zero()};  // unit outward direction, when protecting
    T outward_rate_rad_s{};  // and the spin axis's rate along it that keeps the bound
    std::uint32_t flags{0};
  };
  [[nodiscard]] RateCommand rate_command(const GimbalFrame<T>& frame, const Vector2<T>& body,
                                         bool accepted) const noexcept {
    RateCommand c;
    if (mode_ == GyroMode::kFault) return c;  // safe mode: torquers off
    Vector2<T> w = Vector2<T>::Zero();         // uncaging: torquers off while it settles
    if (mode_ == GyroMode::kCaged) {
      // Electrical caging: the spin axis follows the body and the gimbal angles close at
      // cage_gain (th' = -k th, ps' = -k ps); without navigation, the gimbal loop alone.
      const Vector2<T>& g = pickoffs_.measured();
      w = body;
      if (accepted) w -= config_.cage_gain_1_s * Vector2<T>(g(0), g(1) * frame.cos_pitch);
    } else if (mode_ == GyroMode::kFree) {
      w = slew_cmd_;
    }
    // The gimbal's outward motion is bounded whatever drives it, the body's turn included
    // (gyro/stop_protection.hpp); uncaging torques only while the bound acts.
    const ProtectedRate<T> p = protect_stop(frame, w, body, stop_bound_);
    c.torquing = mode_ != GyroMode::kUncaging || p.acting;
    c.protecting = p.acting;
    c.outward = p.outward;
    c.outward_rate_rad_s = p.outward_rate_rad_s;
    if (p.acting) c.flags |= kGimbalStopProtect;
    w = p.rate_rad_s;
    c.rate_rad_s = Vector2<T>(saturate(w(0), config_.max_pitch_rate_rad_s), saturate(w(1), config_.max_yaw_rate_rad_s));
    if (c.rate_rad_s != w) c.flags |= kSlewRateLimited;  // guidance (or the body) asks more than may be flown
    return c;
  }

  // The torque law (gyro/gimbal_geometry.hpp): torquer commands that hold the spin axis at the
  // commanded rate against the bearings' friction on the gimbal rates (or without friction,
  // the report's H*rate), saturated by scaling so the slew keeps its direction. When stop
  // protection acts and the torquer cannot give it all, the command's part across the outward
  // direction is dropped first; kStopBeyondAuthority when the rate the torquers then hold
  // still moves the gimbal outward, faster than the protection's bound allows.
  struct TorqueCommand {
    Vector2<T> torque{Vector2<T>::Zero()};
    std::uint32_t flags{0};
  };
  [[nodiscard]] TorqueCommand torque_command(const GimbalFrame<T>& frame, const RateCommand& rate,
                                             const Vector2<T>& body, T spin) const noexcept {
    TorqueCommand t;
    if (!rate.torquing) return t;
    // The rotor's momentum: the motor-held spin's plus that of the inner gimbal's roll.
    const T roll = estimator_ready_ ? estimator_.inner_gimbal_roll_rad_s() : T(0);
    const T h = angular_momentum(spin, config_.spin_inertia) + config_.spin_inertia * roll;
    const T f = config_.friction_compensation ? config_.friction : T(0);
    Saturated s = saturated_torque(frame, h, f, rate.rate_rad_s, body);
    const bool short_of_rate = (rate.flags & kSlewRateLimited) != 0u || s.saturated;
    if (rate.protecting && s.saturated) {
      const Vector2<T> outward = rate.outward * rate.outward_rate_rad_s;
      const Vector2<T> outward_only(saturate(outward(0), config_.max_pitch_rate_rad_s),
                                    saturate(outward(1), config_.max_yaw_rate_rad_s));
      s = saturated_torque(frame, h, f, outward_only, body);
    }
    if (s.saturated) t.flags |= kTorquerSaturated;
    if (short_of_rate) {
      // The rate the torque written holds (the law's inverse), against the bound.
      const Vector2<T> flown = s.saturated ? rate_for_torquers(frame, h, f, s.value, body) : rate.rate_rad_s;
      // Beyond the bound and still moving out (beyond c_p a pull-back slower than the bound
      // asks is no danger: the gimbal is on its way in).
      const OutwardExcess<T> e = outward_excess(frame, flown, body, stop_bound_);
      if (e.rate_rad_s > T(0) && e.rate_rad_s + e.allowed_rad_s > T(0)) t.flags |= kStopBeyondAuthority;
    }
    t.torque = s.value;
    return t;
  }

  struct Saturated {
    Vector2<T> value{Vector2<T>::Zero()};
    bool saturated{false};
  };
  [[nodiscard]] Saturated saturated_torque(const GimbalFrame<T>& frame, T h, T f, const Vector2<T>& rate,
                                           const Vector2<T>& body) const noexcept {
    Saturated s;
    s.value = torquers_for_rate(frame, h, f, rate, body);
    if (!all_finite(s.value)) {
      // The products overflowed (huge rate limits or spin; f, h and the rates are finite and
      // not all zero here): the same direction from factors scaled to at most 1, then
      // saturated without overflow. (h can be negative: the inner gimbal rolling against a
      // slow spin.)
      const T k = std::max(f, std::abs(h));
      const T r = std::max(rate.cwiseAbs().maxCoeff(), body.cwiseAbs().maxCoeff());
      s.value = torquers_for_rate(frame, h / k, f / k, Vector2<T>(rate / r), Vector2<T>(body / r));
      s.value = (s.value / s.value.cwiseAbs().maxCoeff()) * config_.max_torque;
      s.saturated = true;
      return s;
    }
    const T largest = s.value.cwiseAbs().maxCoeff();
    if (largest > config_.max_torque) {
      // Divide first: the largest component becomes exactly 1, so the result never exceeds
      // max_torque (max_torque / largest can be subnormal and lose the digits that keep it).
      s.value = (s.value / largest) * config_.max_torque;
      s.saturated = true;
    }
    return s;
  }

  // A step of torque sets the rotor nutating (amplitude dT / (H beta)), and the plant's
  // nutation then drifts out of phase with the estimator's (the gimbal's inertias change with
  // its angles, the rotor's momentum with the inner gimbal's roll). So the torque written is
  // the torque law's through a three-tap filter with a zero at the nutation frequency
  // (gyro/torque_shaper.hpp), m ticks of delay: a step excites no nutation at beta. Off when
  // m would pass kShaperMaxSpacing; safe mode cuts at once.
  [[nodiscard]] Vector2<T> shape_torque(const Vector2<T>& wanted) noexcept {
    if (mode_ == GyroMode::kFault) {
      shaper_.clear();  // leaving safe mode starts from rest
      return wanted;
    }
    return shaper_.shape(wanted, config_.max_torque);
  }

  // One saturating count per raised flag: a loop over the raised flags only (at most
  // kComponentFlagCount passes; none on a clean tick).
  void count(std::uint32_t flags) noexcept {
    std::uint32_t left = flags & ((1u << static_cast<unsigned>(kComponentFlagCount)) - 1u);
    for (int pass = 0; pass < kComponentFlagCount && left != 0u; ++pass) {
      const std::uint32_t lowest = left & (~left + 1u);  // the lowest raised flag
      std::uint32_t& c = telemetry_.counters[bit_index(lowest)];
      c = sat_inc(c);
      left ^= lowest;
    }
  }
  [[nodiscard]] static std::size_t bit_index(std::uint32_t single_bit) noexcept {
    std::size_t i = 0;  // five halvings: a fixed cost, without compiler builtins
    if ((single_bit & 0xFFFF0000u) != 0u) i += 16u;
    if ((single_bit & 0xFF00FF00u) != 0u) i += 8u;
    if ((single_bit & 0xF0F0F0F0u) != 0u) i += 4u;
    if ((single_bit & 0xCCCCCCCCu) != 0u) i += 2u;
    if ((single_bit & 0xAAAAAAAAu) != 0u) i += 1u;
    return i;
  }

  void publish(std::uint64_t tick, std::uint32_t flags, const Vector2<T>& rate_cmd, T spin) noexcept {
    if (estimator_ready_ && nutation_.aliased()) flags |= kNutationUnresolved;
    GyroTelemetry<T>& t = telemetry_;
    t.tick = tick;
    t.mode = mode_;
    t.flags = flags;
    count(flags);
    t.gimbal_measured_rad = pickoffs_.measured();
    t.gimbal_predicted_rad = predicted_;
    t.residual_rad = residual_;
    t.attitude_gyro_to_earth = estimator_.attitude_gyro_to_earth();
    t.precession_rate_rad_s = estimator_.rate_on_gimbal_rad_s();
    t.rate_cmd_rad_s = rate_cmd;
    t.torque_cmd = torque_held_;
    t.nutation_amplitude_rad = estimator_.nutation_amplitude_rad();
    t.spin_hz = spin;
  }

  GyroPort<T>& port_;
  GyroComponentConfig<T> config_{};
  bool configured_{false};
  StopBound<T> stop_bound_{};  // sin(gimbal_cone_limit_rad - gimbal_stop_margin_rad), cage_gain_1_s
  GyroMode mode_{GyroMode::kIdle};
  GyroModel<T> estimator_{};
  bool estimator_ready_{false};
  CheckedRotation<T> attitude_{};  // the last usable body attitude (earth to body)
  Vector3<T> body_rate_{Vector3<T>::Zero()};       // the last usable body rate (p, q, r)
  Vector3<T> body_rate_prev_{Vector3<T>::Zero()};  // the one before it
  Vector2<T> slew_cmd_{Vector2<T>::Zero()};  // the last usable slew command
  Vector2<T> residual_{Vector2<T>::Zero()};
  Vector2<T> predicted_{Vector2<T>::Zero()};  // the estimator's gimbal angles before correction
  GimbalFrame<T> pickoff_frame_{};  // the frame at the pickoffs' angles, before the estimator runs
  GyroStepInput<T> step_input_{};   // the estimator's step input (its attitude is passed checked)
  Vector2<T> torque_held_{Vector2<T>::Zero()};
  TickTracker tick_tracker_{};
  PickoffGate<T> pickoffs_{};
  FaultMonitors monitors_{};
  std::uint32_t settle_ticks_{0};
  NutationTracker<T> nutation_{};
  TorqueShaper<T> shaper_{};
  GyroTelemetry<T> telemetry_{};
};

}  // namespace gyro
