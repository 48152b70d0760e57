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
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/persistence.hpp"
#include "gyro/saturate.hpp"
#include "gyro/stop_protection.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {

template <typename T>
class GyroComponent {
 public:
  explicit GyroComponent(GyroPort<T>& port) noexcept : port_(port) { wanted_history_.fill(Vector2<T>::Zero()); }

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
    nutation_spin_low_ = T(-1);  // the nutation and the shaper follow the new rotor
    nutation_spin_high_ = T(-2);
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

    std::uint32_t flags = 0;
    const std::uint64_t elapsed = elapsed_ticks(tick, flags);
    const ModeRequest request = accept_command(in, flags);
    const bool nav_ok = accept_navigation(in, flags);
    const bool input_bad = (flags & kUnusableInput) != 0u;

    const Reading r = read_and_validate(elapsed, flags);
    const T spin = spin_hz(r);
    if (spin < config_.min_spin_hz) flags |= kSpinLow;
    follow_nutation(spin);

    predict_and_check(elapsed, spin, r.accepted && nav_ok, flags);
    const bool fault_now = update_monitors(r.accepted, input_bad, flags);
    flags |= update_mode(request, r.accepted && nav_ok, fault_now);

    const GimbalFrame<T>& frame = frame_now(nav_ok);
    const Vector2<T> body = nav_ok ? body_rate_on_gimbal(frame, body_rate_) : Vector2<T>::Zero();
    const RateCommand rate = rate_command(frame, body, r.accepted);
    const TorqueCommand wanted = torque_command(frame, rate, body, spin);
    flags |= rate.flags | wanted.flags;
    const Vector2<T> torque = shape_torque(wanted.torque);
    if (port_.write_torquer(torque) == PortStatus::kOk) {
      torque_held_ = torque;
      torquer_fail_ = false;
    } else {
      flags |= kTorquerWriteFailed;  // the hardware keeps whatever it had: assume the last
      torquer_fail_ = true;
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
    bool accepted{false};
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

  // Ticks since the last call, from the tick count. The call itself is the clock (one per
  // release of the rate group): a jump of 2..max_tick_gap after a trusted count is lost
  // ticks, bridged (the held torque acted all along); anything else (a repeat, a step back,
  // a longer jump, or any jump right after an untrusted count) is taken as one tick and the
  // count resynchronised to it, to be trusted once the next call follows it by one.
  [[nodiscard]] std::uint64_t elapsed_ticks(std::uint64_t tick, std::uint32_t& flags) noexcept {
    std::uint64_t elapsed = 1;
    bool trusted = true;
    if (have_tick_ && tick != last_tick_ + 1u) {
      const bool bridgeable = tick_trusted_ && tick > last_tick_ && tick - last_tick_ <= config_.max_tick_gap;
      if (bridgeable) {
        elapsed = tick - last_tick_;
        flags |= kTickSkipped;
      } else {
        flags |= kTickInvalid;
        trusted = false;
      }
    }
    last_tick_ = tick;
    have_tick_ = true;
    tick_trusted_ = trusted;
    return elapsed;
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

  // A reading is checked against the last accepted one, with a bound of max_pickoff_step_rad
  // per tick that passed without information (invalid or stale readings, lost ticks): a gap
  // in the readings never locks them out. A reading that jumped does not widen the bound: a
  // bias jump stays rejected until its persistence latches the fault. In safe mode (torquers
  // off) there is no jump test, so the reference follows the pickoffs and a wrong one cannot
  // hold the gyro in safe mode.
  [[nodiscard]] Reading read_and_validate(std::uint64_t elapsed, std::uint32_t& flags) noexcept {
    Reading r;
    r.port_ok = port_.read_pickoffs(r.raw) == PortStatus::kOk;
    const Vector2<T>& a = r.raw.gimbal_angle_rad;
    const T bound = config_.max_pickoff_step_rad * (static_cast<T>(blind_ticks_) + static_cast<T>(elapsed));
    if (!r.port_ok || !r.raw.valid || !all_finite(a) || a.cwiseAbs().maxCoeff() > config_.pickoff_range_rad) {
      flags |= kPickoffInvalid;
      blind_ticks_ = blind_ticks_ + elapsed;
    } else if (have_reading_ && r.raw.sequence == last_sequence_) {
      flags |= kPickoffStale;
      blind_ticks_ = blind_ticks_ + elapsed;
    } else if (have_reading_ && mode_ != GyroMode::kFault && (a - measured_).cwiseAbs().maxCoeff() > bound) {
      flags |= kPickoffJump;
      last_sequence_ = r.raw.sequence;
    } else {
      r.accepted = true;
      measured_ = a;
      last_sequence_ = r.raw.sequence;
      have_reading_ = true;
      blind_ticks_ = 0;
    }
    return r;
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
    if (estimator_.uncage_on_gimbal(attitude_.matrix(), body_rate_, measured_) != Status::kOk) return false;
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
    residual_ = measured_ - predicted_;
    if (mode_ == GyroMode::kFault) {
      residual_monitor_.reset();
    } else if (residual_monitor_.update(residual_.cwiseAbs().maxCoeff() > config_.residual_limit_rad,
                                        config_.residual_persistence_ticks)) {
      flags |= kResidualFault;
    }
    (void)estimator_.correct_gimbal_angles_at_next_step(Vector2<T>(config_.estimator_gain * residual_));
  }

  // The persistence monitors (gyro/persistence.hpp); true when any fault condition has lasted
  // long enough. The torquer's is fed by the write of the previous tick.
  [[nodiscard]] bool update_monitors(bool accepted, bool input_bad, std::uint32_t& flags) noexcept {
    const GyroComponentConfig<T>& c = config_;
    const bool reading = reading_monitor_.update(!accepted, c.invalid_persistence_ticks);
    const bool spin = spin_monitor_.update((flags & kSpinLow) != 0u, c.spin_low_persistence_ticks);
    const bool torquer = torquer_monitor_.update(torquer_fail_, c.torquer_fail_persistence_ticks);
    const bool input = input_monitor_.update(input_bad, c.input_persistence_ticks);
    if (input) flags |= kInputFault;
    return reading || spin || torquer || input || residual_monitor_.tripped(c.residual_persistence_ticks);
  }

  // The mode's transition for this tick's request; kRequestRefused when the request could not
  // be carried out (a request lasts one tick: it is dropped, never kept for later).
  [[nodiscard]] std::uint32_t update_mode(ModeRequest request, bool measurable, bool fault_now) noexcept {
    if (fault_now) {
      mode_ = GyroMode::kFault;
      return request == ModeRequest::kNone ? 0u : static_cast<std::uint32_t>(kRequestRefused);
    }
    switch (mode_) {
      case GyroMode::kCaged:
        if (request == ModeRequest::kUncage) {
          // The report's uncaging: rates from the body, attitude from the body plus the
          // measured gimbal offset. (The torque shaper keeps the cage loop's torques from
          // leaving a nutation this start cannot know.)
          if (!measurable || !start_estimator()) return kRequestRefused;
          estimator_ready_ = true;
          residual_.setZero();
          settle_ticks_ = 0;
          mode_ = GyroMode::kUncaging;
        }
        break;
      case GyroMode::kUncaging:
        if (request == ModeRequest::kCage) {
          mode_ = GyroMode::kCaged;
        } else if (++settle_ticks_ >= config_.uncage_settle_ticks) {
          mode_ = GyroMode::kFree;
        }
        break;
      case GyroMode::kFree:
        if (request == ModeRequest::kCage) mode_ = GyroMode::kCaged;
        break;
      case GyroMode::kFault:
        // Leaves safe mode on request as soon as no fault condition holds; the estimator
        // restarts from the next good reading. Only caging leaves it.
        if (request == ModeRequest::kUncage) return kRequestRefused;
        if (request == ModeRequest::kCage) {
          mode_ = GyroMode::kCaged;
          estimator_ready_ = false;
          residual_monitor_.reset();
        }
        break;
      case GyroMode::kIdle:
        break;
    }
    return 0u;
  }

  // The gimbal frame the torque law and the stop protection resolve on: the estimator's, else
  // the pickoffs' (before the estimator runs, and without navigation, when the prediction
  // holds the last good body attitude while the body turns on).
  [[nodiscard]] const GimbalFrame<T>& frame_now(bool nav_ok) noexcept {
    if (estimator_ready_ && nav_ok) return estimator_.gimbal_frame_now();
    pickoff_frame_ = gimbal_frame_at(measured_);
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
      w = body;
      if (accepted) w -= config_.cage_gain_1_s * Vector2<T>(measured_(0), measured_(1) * frame.cos_pitch);
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
      wanted_history_.fill(Vector2<T>::Zero());  // leaving safe mode starts from rest
      return wanted;
    }
    wanted_head_ = (wanted_head_ + 1u) & kShaperMask;
    wanted_history_[wanted_head_] = wanted;
    if (shaper_spacing_ == 0u) return wanted;
    const Vector2<T>& mid = wanted_history_[(wanted_head_ - shaper_spacing_) & kShaperMask];
    const Vector2<T>& old = wanted_history_[(wanted_head_ - 2u * shaper_spacing_) & kShaperMask];
    // Written about the middle tap (equal taps give it back exactly); rounding can still pass
    // the limit by an ulp, hence the clamp.
    const Vector2<T> out = mid + shaper_edge_ * ((wanted - mid) + (old - mid));
    return Vector2<T>(saturate(out(0), config_.max_torque), saturate(out(1), config_.max_torque));
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
    if (estimator_ready_ && nutation_aliased_) flags |= kNutationUnresolved;
    GyroTelemetry<T>& t = telemetry_;
    t.tick = tick;
    t.mode = mode_;
    t.flags = flags;
    count(flags);
    t.gimbal_measured_rad = measured_;
    t.gimbal_predicted_rad = predicted_;
    t.residual_rad = residual_;
    t.attitude_gyro_to_earth = estimator_.attitude_gyro_to_earth();
    t.precession_rate_rad_s = estimator_.rate_on_gimbal_rad_s();
    t.rate_cmd_rad_s = rate_cmd;
    t.torque_cmd = torque_held_;
    t.nutation_amplitude_rad = estimator_.nutation_amplitude_rad();
    t.spin_hz = spin;
  }

  // Once per tick: the nutation frequency at this spin (0 if the modes cannot be computed),
  // whether the tick aliases it, and the shaper designed for it, all kept until the spin moves
  // kShaperSpinTolerance away from the spin they were made for. A spinning-down rotor's
  // readback changes every tick; the notch is not that narrow (a relative error e in beta lets
  // through about 2 e of the nutation a step of torque excites, and the plant's own beta moves
  // by more with the gimbal angles), so the design is redone every few hundred ticks of a
  // spin-down, not every tick. (The estimator follows every readback: its transition is
  // physics.)
  void follow_nutation(T spin) noexcept {
    if (!(spin >= nutation_spin_low_ && spin <= nutation_spin_high_)) {
      // The spin is finite and >= 0 and the inertias and friction were checked at configure():
      // the rate-matrix terms alone (compute_modes() without its checks and other modes).
      const RotorParameters<T> p{config_.pitch_inertia, config_.yaw_inertia, config_.friction,
                                 angular_momentum(spin, config_.spin_inertia)};
      const T beta_sq = detail::rate_matrix_terms(p).beta_sq;
      nutation_beta_ = (beta_sq > T(0) && std::isfinite(beta_sq)) ? std::sqrt(beta_sq) : T(0);
      nutation_spin_low_ = spin * (T(1) - kShaperSpinTolerance<T>);
      nutation_spin_high_ = spin * (T(1) + kShaperSpinTolerance<T>);
      const T per_tick = nutation_beta_ * config_.tick_s;  // nutation phase a tick
      // Fewer than two ticks per nutation period: the pickoffs alias the nutation.
      nutation_aliased_ = per_tick > kPi<T>;
      const ShaperDesign<T> shaper = design_shaper(per_tick);
      shaper_spacing_ = shaper.spacing;
      shaper_edge_ = shaper.edge;
    }
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
  Vector2<T> measured_{Vector2<T>::Zero()};
  Vector2<T> residual_{Vector2<T>::Zero()};
  Vector2<T> predicted_{Vector2<T>::Zero()};  // the estimator's gimbal angles before correction
  GimbalFrame<T> pickoff_frame_{};  // the frame at the pickoffs' angles, before the estimator runs
  GyroStepInput<T> step_input_{};   // the estimator's step input (its attitude is passed checked)
  Vector2<T> torque_held_{Vector2<T>::Zero()};
  std::uint32_t last_sequence_{0};
  bool have_reading_{false};
  std::uint64_t blind_ticks_{0};  // ticks without an informative reading since the last accepted
  std::uint64_t last_tick_{0};
  bool have_tick_{false};
  bool tick_trusted_{false};
  bool torquer_fail_{false};
  PersistenceMonitor reading_monitor_{};
  PersistenceMonitor residual_monitor_{};
  PersistenceMonitor spin_monitor_{};
  PersistenceMonitor torquer_monitor_{};
  PersistenceMonitor input_monitor_{};
  std::uint32_t settle_ticks_{0};
  T nutation_spin_low_{-1};  // the spins the shaper's design is kept for (follow_nutation)
  T nutation_spin_high_{-2};
  T nutation_beta_{};
  bool nutation_aliased_{false};
  // The shaper's design follows the spin within this fraction (follow_nutation).
  template <typename S>
  static constexpr S kShaperSpinTolerance = S(1e-3);
  // The torque shaper (shape_torque): the torque law's last outputs (2 kShaperMaxSpacing + 1 read).
  // A power of two of at least 2 kShaperMaxSpacing + 1 entries: the ring's index is masked (the
  // unsigned difference wraps to the same entry), not divided.
  static constexpr std::uint32_t kShaperLength = 32;
  static constexpr std::uint32_t kShaperMask = kShaperLength - 1u;
  static_assert((kShaperLength & kShaperMask) == 0u && kShaperLength >= 2u * kShaperMaxSpacing + 1u);
  std::array<Vector2<T>, kShaperLength> wanted_history_{};
  std::uint32_t wanted_head_{0};
  std::uint32_t shaper_spacing_{0};  // m; 0: not shaped
  T shaper_edge_{};                  // a
  GyroTelemetry<T> telemetry_{};
};

}  // namespace gyro
