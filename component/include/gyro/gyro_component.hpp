// GyroComponent: the flight software of a two-axis gimballed gyro. Once per fixed-rate
// tick it reads the pickoffs through the port, validates them, predicts the gyro with the
// exact dynamics, decides the mode, computes the torque law and writes the torquer.
//
// Guarantees: no heap, no exceptions, no RTTI; every tick does the same bounded work (no
// loop depends on data); the same inputs give bit-identical outputs; a refused call leaves
// the state as it was (its refusal is flagged and counted in telemetry).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gyro/component_config.hpp"
#include "gyro/component_types.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"

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

  // One tick. `tick` must advance by one each call (a gap is flagged and bridged).
  [[nodiscard]] Status step(std::uint64_t tick, const GuidanceInput<T>& in) noexcept {
    if (mode_ == GyroMode::kIdle) return Status::kNotConfigured;
    if (!all_finite(in.slew_rate_cmd_rad_s, in.body_rate_rad_s) || !valid_request(in.request)) {
      return refuse(Status::kNonFiniteInput, kCommandRejected);
    }
    if (have_tick_ && tick <= last_tick_) return refuse(Status::kOutOfRange, kTickSkipped);

    std::uint32_t flags = 0;
    const std::uint64_t elapsed = have_tick_ ? tick - last_tick_ : 1u;
    if (elapsed != 1u) flags |= kTickSkipped;

    const bool nav_ok = in.nav_valid && is_rotation(in.R_earth_to_body);
    if (nav_ok) {
      R_earth_to_body_ = in.R_earth_to_body;
      body_rate_ = in.body_rate_rad_s;
    } else {
      flags |= kNavInvalid;
    }

    const Reading r = read_and_validate(elapsed, flags);
    const T spin = spin_hz(r);
    if (spin < config_.min_spin_hz) flags |= kSpinLow;

    predict_and_check(elapsed, spin, r.accepted && nav_ok, flags);
    const bool fault_now = update_fault_counters(r.accepted, flags);
    update_mode(in.request, r.accepted && nav_ok, fault_now);

    const Vector2<T> rate_cmd = rate_command(in, r.accepted, flags);
    const Vector2<T> torque = torque_command(rate_cmd, spin, flags);
    if (port_.write_torquer(torque) == PortStatus::kOk) {
      torque_held_ = torque;
      torquer_fail_run_ = 0;
    } else {
      flags |= kTorquerWriteFailed;  // the hardware keeps whatever it had: assume the last
      torquer_fail_run_ = sat_inc(torquer_fail_run_);
    }
    if (mode_ == GyroMode::kFault) flags |= kFaultLatched;

    publish(tick, flags, rate_cmd, spin);
    last_tick_ = tick;
    have_tick_ = true;
    return Status::kOk;
  }

  [[nodiscard]] const GyroTelemetry<T>& telemetry() const noexcept { return telemetry_; }
  [[nodiscard]] GyroMode mode() const noexcept { return mode_; }
  [[nodiscard]] const GyroComponentConfig<T>& config() const noexcept { return config_; }

 private:
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

  // A refused tick: nothing read or written, state unchanged; the refusal is flagged and
  // counted so that the ground sees it.
  [[nodiscard]] Status refuse(Status s, std::uint32_t flag) noexcept {
    telemetry_.flags = flag;
    count(flag);
    return s;
  }

  [[nodiscard]] Reading read_and_validate(std::uint64_t elapsed, std::uint32_t& flags) noexcept {
    Reading r;
    r.port_ok = port_.read_pickoffs(r.raw) == PortStatus::kOk;
    const Vector2<T>& a = r.raw.gimbal_angle_rad;
    if (!r.port_ok || !r.raw.valid || !all_finite(a) || a.cwiseAbs().maxCoeff() > config_.pickoff_range_rad) {
      flags |= kPickoffInvalid;
    } else if (have_reading_ && r.raw.sequence == last_sequence_) {
      flags |= kPickoffStale;
    } else if (have_reading_ && (a - measured_).cwiseAbs().maxCoeff() >
                                    config_.max_pickoff_step_rad * static_cast<T>(elapsed)) {
      flags |= kPickoffJump;
      last_sequence_ = r.raw.sequence;
    } else {
      r.accepted = true;
      measured_ = a;
      last_sequence_ = r.raw.sequence;
      have_reading_ = true;
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

  // Advances the estimator over the elapsed ticks with the torque held, compares with the
  // accepted reading, and feeds a fraction of the residual back into the attitude.
  void predict_and_check(std::uint64_t elapsed, T spin, bool measurable, std::uint32_t& flags) noexcept {
    if (!estimator_ready_) {
      if (measurable) {
        estimator_ready_ = estimator_.uncage(R_earth_to_body_, body_rate_, measured_) == Status::kOk;
      }
      residual_.setZero();
      return;
    }
    GyroStepInput<T> s;
    s.dt_s = config_.tick_s * static_cast<T>(elapsed);
    s.R_earth_to_body = R_earth_to_body_;
    s.spin_hz = spin;
    if (estimator_.step_torque(s, torque_held_) != Status::kOk) {
      estimator_ready_ = false;  // re-initialised from the next good reading
      return;
    }
    if (estimator_.small_angle_exceeded()) flags |= kSmallAngleExceeded;
    if (!measurable) return;
    const Vector2<T> predicted(estimator_.gimbal_pitch_rad(), estimator_.gimbal_yaw_rad());
    residual_ = measured_ - predicted;
    if (residual_.cwiseAbs().maxCoeff() > config_.residual_limit_rad) {
      residual_run_ = sat_inc(residual_run_);
    } else {
      residual_run_ = 0;
    }
    // Pitching the gyro up raises its gimbal pitch angle, yawing it right its yaw angle.
    (void)estimator_.correct_attitude(config_.estimator_gain * residual_, R_earth_to_body_);
  }

  // Persistence counters; true when a fault condition has lasted long enough.
  [[nodiscard]] bool update_fault_counters(bool accepted, std::uint32_t& flags) noexcept {
    bad_reading_run_ = accepted ? 0u : sat_inc(bad_reading_run_);
    spin_low_run_ = ((flags & kSpinLow) != 0u) ? sat_inc(spin_low_run_) : 0u;
    if (residual_run_ >= config_.residual_persistence_ticks) flags |= kResidualFault;
    return bad_reading_run_ >= config_.invalid_persistence_ticks ||
           residual_run_ >= config_.residual_persistence_ticks ||
           spin_low_run_ >= config_.spin_low_persistence_ticks ||
           torquer_fail_run_ >= config_.torquer_fail_persistence_ticks;
  }

  void update_mode(ModeRequest request, bool measurable, bool fault_now) noexcept {
    if (fault_now) {
      mode_ = GyroMode::kFault;
      return;
    }
    switch (mode_) {
      case GyroMode::kCaged:
        if (request == ModeRequest::kUncage && measurable) {
          // The report's uncaging: rates from the body, attitude from the body plus the
          // measured gimbal offset.
          if (estimator_.uncage(R_earth_to_body_, body_rate_, measured_) == Status::kOk) {
            estimator_ready_ = true;
            residual_.setZero();
            settle_ticks_ = 0;
            mode_ = GyroMode::kUncaging;
          }
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
        // Leaves safe mode only on request, once nothing is wrong; the estimator restarts.
        if (request == ModeRequest::kCage) {
          mode_ = GyroMode::kCaged;
          estimator_ready_ = false;
          residual_run_ = 0;
        }
        break;
      case GyroMode::kIdle:
        break;
    }
  }

  [[nodiscard]] static T clamp(T v, T limit) noexcept { return std::min(limit, std::max(-limit, v)); }

  // Precession rates wanted this tick (theta', psi'), after limits and stop protection.
  [[nodiscard]] Vector2<T> rate_command(const GuidanceInput<T>& in, bool accepted, std::uint32_t& flags) noexcept {
    Vector2<T> w = Vector2<T>::Zero();
    if (mode_ == GyroMode::kCaged) {
      // Electrical caging: follow the body and close the gimbal angles at cage_gain.
      w = body_rate_;
      if (accepted) w -= config_.cage_gain_1_s * measured_;
    } else if (mode_ == GyroMode::kFree) {
      w = in.slew_rate_cmd_rad_s;
      // No slewing further into a gimbal stop: withhold the outward part of the command.
      if (estimator_ready_ &&
          estimator_.gimbal_cone_rad() > config_.gimbal_cone_limit_rad - config_.gimbal_stop_margin_rad) {
        const Vector2<T> g(estimator_.gimbal_pitch_rad(), estimator_.gimbal_yaw_rad());
        for (int i = 0; i < 2; ++i) {
          if (w(i) * g(i) > T(0)) {
            w(i) = T(0);
            flags |= kGimbalStopProtect;
          }
        }
      }
    }
    return Vector2<T>(clamp(w(0), config_.max_pitch_rate_rad_s), clamp(w(1), config_.max_yaw_rate_rad_s));
  }

  // The torque law: the exact inverse of the friction-coupled steady precession (or the
  // report's frictionless H*rate), saturated by scaling so the slew keeps its direction.
  [[nodiscard]] Vector2<T> torque_command(const Vector2<T>& rate, T spin, std::uint32_t& flags) const noexcept {
    if (mode_ != GyroMode::kCaged && mode_ != GyroMode::kFree) return Vector2<T>::Zero();
    const T h = angular_momentum(spin, config_.spin_inertia);
    const T f = config_.friction_compensation ? config_.friction : T(0);
    Vector2<T> torque(f * rate(0) + h * rate(1), f * rate(1) - h * rate(0));
    if (!all_finite(torque)) {
      // The products overflowed (huge rate limits or spin; f, h and the rates are finite and
      // not all zero here): the same direction from factors scaled to at most 1, whose largest
      // component is at least 1/sqrt(2), then saturated without overflow.
      const T k = std::max(f, h);
      const Vector2<T> u = rate / rate.cwiseAbs().maxCoeff();
      torque = Vector2<T>((f / k) * u(0) + (h / k) * u(1), (f / k) * u(1) - (h / k) * u(0));
      torque = (torque / torque.cwiseAbs().maxCoeff()) * config_.max_torque;
      flags |= kTorquerSaturated;
      return torque;
    }
    const T largest = torque.cwiseAbs().maxCoeff();
    if (largest > config_.max_torque) {
      // Divide first: the largest component becomes exactly 1, so the result never exceeds
      // max_torque (max_torque / largest can be subnormal and lose the digits that keep it).
      torque = (torque / largest) * config_.max_torque;
      flags |= kTorquerSaturated;
    }
    return torque;
  }

  void count(std::uint32_t flags) noexcept {
    for (int i = 0; i < kComponentFlagCount; ++i) {
      if ((flags & (1u << static_cast<unsigned>(i))) != 0u) {
        std::uint32_t& c = telemetry_.counters[static_cast<std::size_t>(i)];
        c = sat_inc(c);
      }
    }
  }

  void publish(std::uint64_t tick, std::uint32_t flags, const Vector2<T>& rate_cmd, T spin) noexcept {
    if (estimator_ready_) {
      if (estimator_.gimbal_limit_exceeded()) flags |= kGimbalLimit;
      if (nutation_unresolved(spin)) flags |= kNutationUnresolved;
    }
    GyroTelemetry<T>& t = telemetry_;
    t.tick = tick;
    t.mode = mode_;
    t.flags = flags;
    count(flags);
    t.gimbal_measured_rad = measured_;
    t.gimbal_predicted_rad = Vector2<T>(estimator_.gimbal_pitch_rad(), estimator_.gimbal_yaw_rad());
    t.residual_rad = residual_;
    t.attitude_gyro_to_earth = estimator_.attitude_gyro_to_earth();
    t.precession_rate_rad_s = estimator_.rate_rad_s();
    t.rate_cmd_rad_s = rate_cmd;
    t.torque_cmd = torque_held_;
    t.nutation_amplitude_rad = estimator_.nutation_amplitude_rad();
    t.spin_hz = spin;
  }

  // Fewer than two ticks per nutation period: the pickoffs alias the nutation.
  [[nodiscard]] bool nutation_unresolved(T spin) noexcept {
    if (!(spin == nutation_spin_)) {
      const RotorParameters<T> p{config_.pitch_inertia, config_.yaw_inertia, config_.friction,
                                 angular_momentum(spin, config_.spin_inertia)};
      RotorModes<T> m;
      nutation_beta_ = (compute_modes(p, m) == Status::kOk) ? m.beta_rad_s : T(0);
      nutation_spin_ = spin;
    }
    return nutation_beta_ * config_.tick_s > kPi<T>;
  }

  GyroPort<T>& port_;
  GyroComponentConfig<T> config_{};
  bool configured_{false};
  GyroMode mode_{GyroMode::kIdle};
  GyroModel<T> estimator_{};
  bool estimator_ready_{false};
  Matrix3<T> R_earth_to_body_{Matrix3<T>::Identity()};
  Vector2<T> body_rate_{Vector2<T>::Zero()};
  Vector2<T> measured_{Vector2<T>::Zero()};
  Vector2<T> residual_{Vector2<T>::Zero()};
  Vector2<T> torque_held_{Vector2<T>::Zero()};
  std::uint32_t last_sequence_{0};
  bool have_reading_{false};
  std::uint64_t last_tick_{0};
  bool have_tick_{false};
  std::uint32_t bad_reading_run_{0};
  std::uint32_t residual_run_{0};
  std::uint32_t spin_low_run_{0};
  std::uint32_t torquer_fail_run_{0};
  std::uint32_t settle_ticks_{0};
  T nutation_spin_{-1};
  T nutation_beta_{};
  GyroTelemetry<T> telemetry_{};
};

}  // namespace gyro
