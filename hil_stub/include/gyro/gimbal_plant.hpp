// The nonlinear two-axis gimbal plant of the software-in-the-loop stub: a rotor on an inner
// (pitch) and an outer (yaw) gimbal in a body whose motion is prescribed, written from the
// device's physics (docs/gimbal-plant.md), independent of the component's linear model.
//
//   configure(config, tick_s)          validates; fixes the bound of the sub-steps per tick
//   start(initial, body)               joint angles and rates, relative spin, body at t0
//   step(torque, body_start, body_end) one tick: torques held (zero-order hold), body rate and
//                                      specific force linear in time between the two values
//
// Per tick: n eighth-order Runge-Kutta sub-steps (gyro/dormand_prince8.hpp), n at most
// n_max = ceil(tick * fastest rate / max_substep_phase_rad) from configure(); with an error
// target, the fewest whose error estimate meets it (gyro/gimbal_substep_control.hpp: at most
// three tries a tick), else n_max every tick. After each sub-step the stop contact is resolved
// (gyro/gimbal_stop.hpp). No heap, no exceptions; float or double. A refused call changes
// nothing.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "gyro/dormand_prince8.hpp"
#include "gyro/gimbal_dynamics.hpp"
#include "gyro/gimbal_kinematics.hpp"
#include "gyro/gimbal_plant_config.hpp"
#include "gyro/gimbal_stop.hpp"
#include "gyro/gimbal_substep_control.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

// The body's motion at a tick, body axes.
template <typename T>
struct BodyState {
  Vector3<T> rate_rad_s{Vector3<T>::Zero()};      // (p, q, r)
  Vector3<T> specific_force{Vector3<T>::Zero()};  // accelerometer reading at the gimbal centre
};

template <typename T>
struct GimbalStart {
  Vector2<T> gimbal_angle_rad{Vector2<T>::Zero()};  // (pitch theta, yaw psi): the joint angles
  Vector2<T> gimbal_rate_rad_s{Vector2<T>::Zero()}; // their rates, relative to the carriers
  T spin_hz{};  // relative to the inner gimbal; the motor's command in SpinDrive::kMotor
};

// Work done on the joints since start() (sum over each step of the integrated powers).
template <typename T>
struct GimbalWork {
  T torquer{};    // by the torquers
  T friction{};   // by the bearing friction (<= 0)
  T spin{};       // by the spin motor and the spin bearing drag
  T unbalance{};  // by the mass unbalance's torque
};

// The fastest rate (1/s) of the plant's motion over the stop cone: nutation at the largest
// spin, plus the body rate, plus the friction and spin-servo rates (docs/gimbal-plant.md).
template <typename T>
[[nodiscard]] T gimbal_fastest_rate(const GimbalPlantConfig<T>& c) noexcept {
  const T a = c.rotor_transverse_inertia;
  const T j_pitch = c.inner_gimbal_inertia(1) + a;
  const T s = std::sin(c.stop_cone_rad), co = std::cos(c.stop_cone_rad);
  // The yaw joint's inertia with a free spin, at zero pitch and at the stop (linear in sin^2).
  const T d0 = c.outer_gimbal_inertia(2) + c.inner_gimbal_inertia(2) + a;
  const T d1 =
      c.outer_gimbal_inertia(2) + c.inner_gimbal_inertia(0) * s * s + (c.inner_gimbal_inertia(2) + a) * co * co;
  const T h = c.spin_inertia * (T(2) * kPi<T> * c.max_spin_hz + c.max_body_rate_rad_s);
  const T nutation = std::max(h / std::sqrt(j_pitch * d0), h * co / std::sqrt(j_pitch * d1));
  const T pitch_damping = (c.inner_friction + c.inner_coulomb_torque / c.coulomb_rate_scale_rad_s) / j_pitch;
  const T yaw_damping = (c.outer_friction + c.outer_coulomb_torque / c.coulomb_rate_scale_rad_s) / std::min(d0, d1);
  const T spin = c.spin_servo_bandwidth_rad_s + (c.spin_down_time_s > T(0) ? T(1) / c.spin_down_time_s : T(0));
  return nutation + c.max_body_rate_rad_s + std::max(pitch_damping, yaw_damping) + spin;
}

// Sub-steps per tick for a valid configuration: ceil(tick * rate / phase), at least 1; 0 when
// more than kMaxGimbalSubsteps would be needed.
template <typename T>
[[nodiscard]] int gimbal_substeps(const GimbalPlantConfig<T>& c, T tick_s) noexcept {
  const T n = std::ceil(tick_s * gimbal_fastest_rate(c) / c.max_substep_phase_rad);
  if (!(n <= static_cast<T>(kMaxGimbalSubsteps))) return 0;
  return n < T(1) ? 1 : static_cast<int>(n);
}

template <typename T>
class GimbalPlant {
 public:
  // Validates the configuration and the tick, and fixes the sub-step count. Leaves the plant
  // waiting for start().
  [[nodiscard]] ConfigCheck configure(const GimbalPlantConfig<T>& config, T tick_s) noexcept {
    const ConfigCheck c = check(config);
    if (!c.ok()) return c;
    if (!std::isfinite(tick_s)) return {Status::kNonFiniteInput, "tick_s"};
    if (!(tick_s > T(0))) return {Status::kNonPositiveStep, "tick_s"};
    const int n = gimbal_substeps(config, tick_s);
    if (n == 0) return {Status::kOutOfRange, "tick_s"};  // too long for the fastest motion
    config_ = config;
    prm_ = make_gimbal_parameters(config);
    stop_ = make_gimbal_stop(config.stop_cone_rad, config.stop_restitution);
    tick_s_ = tick_s;
    max_substeps_ = n;
    tolerance_ = config.error_target_rad * tick_s;  // the tick's share of the error per second
    // The error norm: angles as they are, rates (and the spin) as the angle their error makes
    // over the fastest motion's 1/rate.
    const T inv_rate = T(1) / gimbal_fastest_rate(config);
    error_weight_ << T(1), T(1), inv_rate, inv_rate, inv_rate, T(1);
    configured_ = true;
    started_ = false;
    return c;
  }

  // Sets the joints, the spin (and the motor's command) and the body's motion at t0.
  [[nodiscard]] Status start(const GimbalStart<T>& initial, const BodyState<T>& body) noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (!all_finite(initial.gimbal_angle_rad, initial.gimbal_rate_rad_s, initial.spin_hz, body.rate_rad_s,
                    body.specific_force)) {
      return Status::kNonFiniteInput;
    }
    if (!within_envelope(body)) return Status::kOutOfRange;
    if (initial.spin_hz < T(0) || initial.spin_hz > config_.max_spin_hz) return Status::kOutOfRange;
    const T pitch = initial.gimbal_angle_rad(0), yaw = initial.gimbal_angle_rad(1);
    if (!(std::cos(pitch) * std::cos(yaw) >= stop_.cos_stop)) return Status::kOutOfRange;
    GimbalJointState<T> s;
    s.pitch_rad = pitch;
    s.yaw_rad = yaw;
    s.pitch_rate_rad_s = initial.gimbal_rate_rad_s(0);
    s.yaw_rate_rad_s = initial.gimbal_rate_rad_s(1);
    s.spin_rate_rad_s = T(2) * kPi<T> * initial.spin_hz;
    state_ = s;
    prm_ = make_gimbal_parameters(config_);
    drive_.torque.setZero();
    drive_.spin_command_rad_s = s.spin_rate_rad_s;
    body_ = body;
    work_ = GimbalWork<T>{};
    motor_torque_ = T(0);
    motor_saturated_ = false;
    contact_ = false;
    next_substeps_ = max_substeps_;
    last_substeps_ = 0;
    started_ = true;
    return Status::kOk;
  }

  // The spin drive from now on (a motor failure: kFree); the motor's command in Hz. start()
  // restores the configured drive.
  [[nodiscard]] Status set_spin_drive(SpinDrive drive, T spin_command_hz) noexcept {
    if (!started_) return Status::kNotConfigured;
    if (!all_finite(spin_command_hz)) return Status::kNonFiniteInput;
    if (drive != SpinDrive::kMotor && drive != SpinDrive::kFree) return Status::kOutOfRange;
    if (spin_command_hz < T(0) || spin_command_hz > config_.max_spin_hz) return Status::kOutOfRange;
    if (drive == SpinDrive::kMotor && !(config_.motor_torque_limit > T(0))) return Status::kOutOfRange;
    prm_.spin_drive = drive;
    drive_.spin_command_rad_s = T(2) * kPi<T> * spin_command_hz;
    return Status::kOk;
  }

  // The spin bearing's drag from now on, as a run-down time constant (0: none): a failed
  // motor whose winding brakes the rotor, say. Refused (kOutOfRange) when its rate 1/tau is
  // beyond the fastest rate the sub-steps were sized for at configure(). start() restores the
  // configured drag.
  [[nodiscard]] Status set_spin_drag(T spin_down_time_s) noexcept {
    if (!started_) return Status::kNotConfigured;
    if (!std::isfinite(spin_down_time_s)) return Status::kNonFiniteInput;
    if (spin_down_time_s < T(0)) return Status::kOutOfRange;
    if (spin_down_time_s > T(0) && T(1) / spin_down_time_s > gimbal_fastest_rate(config_)) return Status::kOutOfRange;
    prm_.spin_drag = spin_down_time_s > T(0) ? config_.spin_inertia / spin_down_time_s : T(0);
    return Status::kOk;
  }

  // One tick with the torques (T1 inner/pitch axis, T2 outer/yaw axis) held, the body's rate
  // and specific force going linearly from body_start to body_end.
  [[nodiscard]] Status step(const Vector2<T>& torque, const BodyState<T>& body_start,
                            const BodyState<T>& body_end) noexcept {
    if (!started_) return Status::kNotConfigured;
    if (!all_finite(torque, body_start.rate_rad_s, body_start.specific_force, body_end.rate_rad_s,
                    body_end.specific_force)) {
      return Status::kNonFiniteInput;
    }
    if (!within_envelope(body_start) || !within_envelope(body_end)) return Status::kOutOfRange;
    if (torque.cwiseAbs().maxCoeff() > config_.max_torque) return Status::kOutOfRange;

    GimbalDrive<T> drive = drive_;
    drive.torque = torque;
    const Vector3<T> rate_dot = (body_end.rate_rad_s - body_start.rate_rad_s) / tick_s_;
    const Vector3<T> force_dot = (body_end.specific_force - body_start.specific_force) / tick_s_;
    const bool unbalance = prm_.mass_unbalance != T(0);
    const GimbalPowers powers = work_bookkeeping_ ? GimbalPowers::kCompute : GimbalPowers::kSkip;
    SinCosNear<T> near_pitch, near_yaw;  // the sub-step's start: the stages' angles are near it
    bool saturated = false;
    auto rhs = [&](T t, const State& x, State& dx, Integrals* q) noexcept {
      BodyInstant<T> body;
      body.rate_rad_s = body_start.rate_rad_s + rate_dot * t;
      body.rate_dot_rad_s2 = rate_dot;
      if (unbalance) body.specific_force = body_start.specific_force + force_dot * t;
      const GimbalJointState<T> s = unpack(x);
      const GimbalFrames<T> f = gimbal_frames(near_pitch, near_yaw, s.pitch_rad, s.yaw_rad);
      const GimbalAccelerations<T> acc = gimbal_accelerations(prm_, s, f, drive, body, powers);
      dx(0) = x(2);
      dx(1) = x(3);
      dx(2) = acc.pitch_acc;
      dx(3) = acc.yaw_acc;
      dx(4) = acc.spin_acc;
      dx(5) = acc.twist_rate;
      if (q != nullptr) {
        *q << acc.torquer_power, acc.friction_power, acc.spin_power, acc.unbalance_power, acc.motor_torque;
      }
      saturated = saturated || acc.motor_saturated;
    };

    // One try of n sub-steps from the tick's start: the state, the integrals, contact, and
    // the sum of the sub-steps' error estimates (when the count is chosen from it).
    const State x0 = pack(state_);
    State x;
    Integrals integral;
    Integrals* integral_wanted = work_bookkeeping_ ? &integral : nullptr;
    const State* weight = adaptive() ? &error_weight_ : nullptr;
    bool contact = false;
    T error{};
    auto integrate = [&](int n) noexcept {
      const T h = tick_s_ / static_cast<T>(n);
      x = x0;
      integral.setZero();
      contact = false;
      saturated = false;
      error = T(0);
      for (int i = 0; i < n; ++i) {  // n <= max_substeps_ <= kMaxGimbalSubsteps
        near_pitch = SinCosNear<T>::at(x(0));
        near_yaw = SinCosNear<T>::at(x(1));
        error += dormand_prince8_step(rhs, static_cast<T>(i) * h, h, x, integral_wanted, weight);
        GimbalJointState<T> s = unpack(x);
        if (resolve_gimbal_stop(stop_, prm_.inertia, s)) {
          contact = true;
          x = pack(s);
        }
      }
    };
    // gyro/gimbal_substep_control.hpp: at most three tries, the last at the bound. A tick with
    // stop contact takes the bound, as the contact's timing is resolved to a sub-step.
    int n = adaptive() ? next_substeps_ : max_substeps_;
    for (int tries = 1;; ++tries) {
      integrate(n);
      if (n == max_substeps_ || (!contact && error <= tolerance_)) break;
      n = (tries == 1 && !contact) ? substeps_after_failure(n, error, tolerance_, max_substeps_) : max_substeps_;
    }
    if (!all_finite(x, integral)) return Status::kNumericalOverflow;

    if (adaptive()) next_substeps_ = substeps_after_success(n, error, tolerance_);
    last_substeps_ = n;
    state_ = unpack(x);
    state_.twist_rad = std::remainder(state_.twist_rad, T(2) * kPi<T>);
    drive_ = drive;
    body_ = body_end;
    work_.torquer += integral(0);
    work_.friction += integral(1);
    work_.spin += integral(2);
    work_.unbalance += integral(3);
    motor_torque_ = work_bookkeeping_ ? integral(4) / tick_s_ : T(0);
    motor_saturated_ = saturated;
    contact_ = contact;
    return Status::kOk;
  }

  // Joint angles (pitch theta, yaw psi) = the gimbal angles of docs/conventions.md, and rates.
  [[nodiscard]] Vector2<T> gimbal_angle_rad() const noexcept { return Vector2<T>(state_.pitch_rad, state_.yaw_rad); }
  [[nodiscard]] Vector2<T> gimbal_rate_rad_s() const noexcept {
    return Vector2<T>(state_.pitch_rate_rad_s, state_.yaw_rate_rad_s);
  }
  [[nodiscard]] const GimbalJointState<T>& joint_state() const noexcept { return state_; }
  // Total angle between spin axis and body x.
  [[nodiscard]] T cone_rad() const noexcept {
    const T c = std::cos(state_.pitch_rad) * std::cos(state_.yaw_rad);
    return std::acos(saturate(c, T(1)));
  }
  [[nodiscard]] Vector3<T> spin_axis_body() const noexcept { return spin_axis_in_body(frames()); }
  // Spin relative to the inner gimbal, and the rotor's inertial rate about its axis.
  [[nodiscard]] T spin_rate_rad_s() const noexcept { return state_.spin_rate_rad_s; }
  [[nodiscard]] T spin_inertial_rad_s() const noexcept { return rates().rotor(0); }
  // Angular momentum about the gimbal centre, body axes: the rotor's, and all three bodies'.
  [[nodiscard]] Vector3<T> rotor_angular_momentum_body() const noexcept {
    const GimbalFrames<T> f = frames();
    return f.outer_to_body(f.inner_to_outer(prm_.inertia.rotor.cwiseProduct(rates().rotor)));
  }
  [[nodiscard]] Vector3<T> angular_momentum_body() const noexcept {
    return gimbal_angular_momentum(prm_.inertia, frames(), rates());
  }
  [[nodiscard]] T kinetic_energy() const noexcept { return gimbal_kinetic_energy(prm_.inertia, rates()); }
  // dT/d(theta', psi', phi').
  [[nodiscard]] Vector3<T> generalised_momentum() const noexcept {
    return gimbal_generalised_momentum(prm_.inertia, frames(), rates());
  }
  [[nodiscard]] const GimbalWork<T>& work() const noexcept { return work_; }
  // Whether step() integrates the works and the motor torque (work(), motor_torque()): on
  // unless turned off. The equations then skip the powers: the SIL stub reads neither.
  void set_work_bookkeeping(bool on) noexcept { work_bookkeeping_ = on; }
  [[nodiscard]] bool work_bookkeeping() const noexcept { return work_bookkeeping_; }
  // The last step: mean spin-motor torque (0 without the bookkeeping), whether the motor hit its
  // limit, stop contact.
  [[nodiscard]] T motor_torque() const noexcept { return motor_torque_; }
  [[nodiscard]] bool motor_saturated() const noexcept { return motor_saturated_; }
  [[nodiscard]] bool in_contact() const noexcept { return contact_; }
  // The bound: the most sub-steps a tick takes (every tick's, in the tight setting); and the
  // sub-steps the last tick kept.
  [[nodiscard]] int substeps() const noexcept { return max_substeps_; }
  [[nodiscard]] int last_substeps() const noexcept { return last_substeps_; }
  [[nodiscard]] T tick_s() const noexcept { return tick_s_; }
  [[nodiscard]] bool started() const noexcept { return started_; }
  [[nodiscard]] const GimbalPlantConfig<T>& config() const noexcept { return config_; }

 private:
  static constexpr int kStateSize = 6;  // theta, psi, theta', psi', phi', chi
  using State = Eigen::Matrix<T, kStateSize, 1>;
  using Integrals = Eigen::Matrix<T, 5, 1>;  // the four works and the motor torque's integral

  [[nodiscard]] static State pack(const GimbalJointState<T>& s) noexcept {
    State x;
    x << s.pitch_rad, s.yaw_rad, s.pitch_rate_rad_s, s.yaw_rate_rad_s, s.spin_rate_rad_s, s.twist_rad;
    return x;
  }
  [[nodiscard]] static GimbalJointState<T> unpack(const State& x) noexcept {
    GimbalJointState<T> s;
    s.pitch_rad = x(0);
    s.yaw_rad = x(1);
    s.pitch_rate_rad_s = x(2);
    s.yaw_rate_rad_s = x(3);
    s.spin_rate_rad_s = x(4);
    s.twist_rad = x(5);
    return s;
  }
  [[nodiscard]] bool adaptive() const noexcept { return tolerance_ > T(0); }
  [[nodiscard]] bool within_envelope(const BodyState<T>& b) const noexcept {
    return b.rate_rad_s.norm() <= config_.max_body_rate_rad_s && b.specific_force.norm() <= config_.max_specific_force;
  }
  [[nodiscard]] GimbalFrames<T> frames() const noexcept { return gimbal_frames(state_.pitch_rad, state_.yaw_rad); }
  [[nodiscard]] GimbalBodyRates<T> rates() const noexcept {
    return gimbal_body_rates(frames(), state_, body_.rate_rad_s);
  }

  GimbalPlantConfig<T> config_{};
  GimbalParameters<T> prm_{};
  GimbalStop<T> stop_{};
  T tick_s_{};
  int max_substeps_{0};
  T tolerance_{};  // error_target_rad * tick_s; 0: the tight setting
  Eigen::Matrix<T, 6, 1> error_weight_{Eigen::Matrix<T, 6, 1>::Ones()};
  int next_substeps_{0};
  int last_substeps_{0};
  bool configured_{false};
  bool started_{false};
  GimbalJointState<T> state_{};
  GimbalDrive<T> drive_{};
  BodyState<T> body_{};
  GimbalWork<T> work_{};
  T motor_torque_{};
  bool motor_saturated_{false};
  bool contact_{false};
  bool work_bookkeeping_{true};
};

}  // namespace gyro
