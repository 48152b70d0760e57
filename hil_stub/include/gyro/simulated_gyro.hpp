// The software-in-the-loop gyro: the other side of the hardware port. It emulates the gyro
// hardware: a plant (the nonlinear two-axis gimbal, gyro/gimbal_plant.hpp, or the report's
// linear model, gyro/report_plant.hpp), the pickoff electronics (gyro/pickoff_electronics.hpp),
// the torquer electronics (gyro/torquer_electronics.hpp) and scheduled faults
// (gyro/fault_schedule.hpp).
//
// One tick, driven by the scenario (host) side:
//   write_torquer(torque)   (flight side, at tick k) latches the command (zero-order hold)
//   advance(k+1, body)      steps the plant over [k, k+1] with the torque that acts over that
//                           interval (command -> scale factor -> saturation -> torquer faults,
//                           faults as at tick k), the body's motion from tick k to k+1; then
//                           samples the pickoffs for read_pickoffs
//   read_pickoffs(out)      (flight side, at tick k+1) returns that conversion
//
// The gimbal plant reads the body's rate and specific force at both ends of the tick (linear
// in between); the report's plant the body attitude at the end and the (lateral, normal)
// specific force. The spin readback is the spin relative to the inner gimbal (a tachometer on
// the motor) for the gimbal plant, the scheduled spin for the report's. A spin motor failure
// stops the gimbal plant's motor and brakes the rotor with the fault's time constant; the
// motor drives it back when the failure ends.
//
// No heap, no exceptions, no RTTI; every call returns a status; a refused call changes
// nothing. float or double.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyro/attitude.hpp"
#include "gyro/exact_step_check.hpp"
#include "gyro/fault_schedule.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "gyro/gimbal_plant.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/pickoff_electronics.hpp"
#include "gyro/report_plant.hpp"
#include "gyro/status.hpp"
#include "gyro/torquer_electronics.hpp"

namespace gyro {

enum class PlantKind : std::uint8_t {
  kReport = 0,  // the report's linear model (GyroModel): torques about the gyro's own axes
  kGimbal,      // the device: a rotor on two gimbals, integrated from its nonlinear equations
};

// The names of the plants in scenario files and logs, in enum order.
[[nodiscard]] constexpr std::array<const char*, 2> enum_names(PlantKind /*tag*/) noexcept { return {"report", "gimbal"}; }

template <typename T>
struct SimulatedGyroConfig {
  PlantKind plant{PlantKind::kReport};
  // The report's plant (plant = kReport).
  GyroModelConfig<T> gyro{};      // rotor, limits and the report's error sources
  T spin_down_time_constant_s{};  // 0 = constant spin; else spin(t) = spin_hz*exp(-t/tau)
  T gimbal_stop_rad{};            // mechanical stop on the total cone angle (0 = none)
  // The gimbal plant (plant = kGimbal): inertias, bearings, motor, unbalance, stop.
  GimbalPlantConfig<T> gimbal{};
  // Common to both.
  T tick_s{};
  T spin_hz{};                    // spin at start (the gimbal plant's motor command)
  bool has_spin_readback{true};
  PickoffModel<T> pickoff{};
  TorquerModel<T> torquer{};
  std::uint64_t seed{};           // base seed of every noise stream
  FaultList<T> faults{};
};

// The fields (gyro/config_fields.hpp). A scenario gives the report plant's in "rotor" and
// "limits" with the model's (GyroModelConfig), the faults in its own terms.
template <typename T>
struct FieldTable<SimulatedGyroConfig<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Status kRange = Status::kOutOfRange;
    constexpr Presence kReq = Presence::kRequired, kOpt = Presence::kOptional, kImplied = Presence::kImplied;
    v(Field{"plant", Rule::kNone, kRange, kImplied}, c.plant...);
    v(Field{"gyro", Rule::kNone, kRange, kImplied}, c.gyro...);
    v(Field{"spin_down_time_constant_s", Rule::kNonNegative, kRange, kOpt, "rotor", 0.0, 1e9, "s",
            "0 (constant spin) or up to 10 times the longest run (1e8 ticks of at most 1 s)"},
      c.spin_down_time_constant_s...);
    v(Field{"gimbal_stop_rad", Rule::kNonNegative, kRange, kOpt, "limits", 0.0, 3.141592653589793, "rad",
            "0 (none) or a cone below pi; the gimbal plant's stop, 1 mrad to 80 deg"},
      c.gimbal_stop_rad...);
    v(Field{"gimbal", Rule::kNone, kRange, kImplied}, c.gimbal...);
    v(Field{"tick_s", Rule::kPositive, Status::kNonPositiveStep, kImplied, nullptr, 1e-6, 1.0, "s", "the SIL loop's tick"}, c.tick_s...);
    v(Field{"spin_hz", Rule::kPositive, kRange, kReq, "rotor", 1e-3, 1e5, "Hz", "a rotor at power-up spins at up to 100 kHz"}, c.spin_hz...);
    v(Field{"has_spin_readback", Rule::kNone, kRange, kReq, "rotor"}, c.has_spin_readback...);
    v(Field{"pickoff", Rule::kNone, kRange, kOpt}, c.pickoff...);
    v(Field{"torquer", Rule::kNone, kRange, kOpt}, c.torquer...);
    v(Field{"seed", Rule::kNone, kRange, kOpt, nullptr, -kNoBound, kNoBound, "",
            "any 64-bit value: it only names the noise streams"},
      c.seed...);
    v(Field{"faults", Rule::kNone, kRange, kImplied}, c.faults...);
  }
};

// The report's plant: its exact step over a tick at the spin it starts with (the largest: the
// spin only runs down) must be representable, or advance() would refuse every tick; the
// refusal names the field responsible (gyro/exact_step_check.hpp).
template <typename T>
[[nodiscard]] ConfigCheck check_exact_step_at_start(const SimulatedGyroConfig<T>& c) noexcept {
  constexpr ExactStepFields kFields{"pitch_inertia", "yaw_inertia", "spin_inertia", "friction", "spin_hz", "tick_s"};
  return check_exact_step(c.gyro.pitch_inertia, c.gyro.yaw_inertia, c.gyro.spin_inertia, c.gyro.friction, c.spin_hz,
                          c.tick_s, kFields);
}

template <typename T>
[[nodiscard]] ConfigCheck check(const SimulatedGyroConfig<T>& c) noexcept {
  if (c.plant != PlantKind::kReport && c.plant != PlantKind::kGimbal) return {Status::kOutOfRange, "plant"};
  if (c.plant == PlantKind::kReport) {
    const ConfigCheck r = check(ReportPlantConfig<T>{c.gyro, c.spin_down_time_constant_s, c.gimbal_stop_rad});
    if (!r.ok()) return r;
  } else {
    const ConfigCheck g = check(c.gimbal);
    if (!g.ok()) return g;
    // The report plant's spin-down: the gimbal plant runs down with gimbal.spin_drive kFree
    // (refused rather than ignored).
    if (c.spin_down_time_constant_s != T(0)) return {Status::kOutOfRange, "spin_down_time_constant_s"};
  }
  // The stub's own numbers against their rows (tick, spin, spin-down, stop).
  const FieldRefusal own = first_refusal<RealFields>(c);
  if (own.status != Status::kOk) return own.check;
  if (c.plant == PlantKind::kGimbal && c.spin_hz > c.gimbal.max_spin_hz) return {Status::kOutOfRange, "spin_hz"};
  if (c.plant == PlantKind::kReport) {
    const ConfigCheck step = check_exact_step_at_start(c);
    if (!step.ok()) return step;
  }
  const ConfigCheck p = check(c.pickoff);
  if (!p.ok()) return p;
  const ConfigCheck t = check(c.torquer);
  if (!t.ok()) return t;
  const ConfigCheck f = check(c.faults);
  if (!f.ok() || c.plant != PlantKind::kGimbal) return f;
  // The gimbal plant's sub-steps resolve a spin run-down no faster than its fastest rate.
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const FaultEvent<T>& e = c.faults[i];
    if (e.kind == FaultKind::kSpinMotorFailure && T(1) / e.magnitude > gimbal_fastest_rate(c.gimbal)) {
      return {Status::kOutOfRange, kFaultFieldNames[i].magnitude};
    }
  }
  return {};
}

// The body's motion at a tick (the truth the scenario drives the stub with).
template <typename T>
struct BodySample {
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector3<T> rate_rad_s{Vector3<T>::Zero()};      // (p, q, r), body axes
  Vector3<T> specific_force{Vector3<T>::Zero()};  // body axes, in the units of the gravity
                                                  // of the report's plant (m/s^2 for SI)
};

// The gimbal plant's error target in the SIL when its configuration leaves it at 0: this
// fraction of the finest angle the pickoff shows (its step or its noise's sigma, the smaller
// of those it has) per simulated second, never below a floor. The plant's error estimate is
// pessimistic: its measured error is about 1/200 of the target (docs/gimbal-plant.md).
inline constexpr double kSilPlantErrorFraction = 1.0;
inline constexpr double kSilPlantErrorFloorRad = 1e-9;

template <typename T>
[[nodiscard]] T sil_plant_error_target(const PickoffModel<T>& p) noexcept {
  T finest = p.lsb_rad;
  if (p.noise_rad > T(0) && (finest <= T(0) || p.noise_rad < finest)) finest = p.noise_rad;
  return std::max(static_cast<T>(kSilPlantErrorFloorRad), static_cast<T>(kSilPlantErrorFraction) * finest);
}

template <typename T>
class SimulatedGyro final : public GyroPort<T> {
 public:
  // Validates and stores the configuration (the field of a refusal is named). Leaves the
  // gyro powered down: start() next.
  [[nodiscard]] ConfigCheck configure(const SimulatedGyroConfig<T>& c) noexcept {
    const ConfigCheck chk = check(c);
    if (!chk.ok()) return chk;
    if (c.plant == PlantKind::kReport) {
      ReportPlant<T> report;
      const ConfigCheck rc =
          report.configure(ReportPlantConfig<T>{c.gyro, c.spin_down_time_constant_s, c.gimbal_stop_rad}, c.tick_s,
                           c.spin_hz, c.faults);
      if (!rc.ok()) return rc;
      report_ = report;
    } else {
      GimbalPlant<T> gimbal;
      GimbalPlantConfig<T> g = c.gimbal;
      if (g.error_target_rad == T(0)) g.error_target_rad = sil_plant_error_target(c.pickoff);
      const ConfigCheck gc = gimbal.configure(g, c.tick_s);
      if (!gc.ok()) return gc;
      gimbal.set_work_bookkeeping(false);  // nothing here reads the works
      gimbal_ = gimbal;
    }
    config_ = c;
    pickoff_.configure(c.pickoff, c.tick_s, c.seed);
    configured_ = true;
    started_ = false;
    return chk;
  }

  // Power-up: the gyro spun up and released aligned with the body (gimbals at rest relative
  // to it), tick 0. The power-up conversion is ready for read_pickoffs.
  [[nodiscard]] Status start(const BodySample<T>& body) noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (!all_finite(body.rate_rad_s, body.specific_force)) return Status::kNonFiniteInput;
    if (config_.plant == PlantKind::kReport) {
      ReportPlant<T> report = report_;
      const Status st = report.start(body.R_earth_to_body, body.rate_rad_s);
      if (st != Status::kOk) return st;
      report_ = report;
    } else {
      if (!is_rotation(body.R_earth_to_body)) return Status::kInvalidRotation;
      GimbalPlant<T> gimbal = gimbal_;
      GimbalStart<T> initial;
      initial.spin_hz = config_.spin_hz;
      const Status st = gimbal.start(initial, BodyState<T>{body.rate_rad_s, body.specific_force});
      if (st != Status::kOk) return st;
      gimbal_ = gimbal;
      motor_failed_ = false;
    }
    tick_ = 0;
    body_ = body;
    torque_cmd_.setZero();
    pickoff_.power_down();
    started_ = true;
    faults_now_ = active_faults_at(config_.faults, tick_);
    sample(true);
    applied_torque_ = torquer_output(config_.torquer, torque_cmd_, faults_now_);
    return Status::kOk;
  }
  // The same with the body's pitch and yaw rates only (no roll, no specific force).
  [[nodiscard]] Status start(const Matrix3<T>& R_earth_to_body, const Vector2<T>& body_rate_rad_s) noexcept {
    BodySample<T> b;
    b.R_earth_to_body = R_earth_to_body;
    b.rate_rad_s = Vector3<T>(T(0), body_rate_rad_s(0), body_rate_rad_s(1));
    return start(b);
  }

  // Advances the emulated gyro from the previous tick to `tick` (must be previous + 1) with
  // the torque latched by the last write_torquer, the body's motion at `tick`; then samples
  // the pickoffs for read_pickoffs.
  [[nodiscard]] Status advance(std::uint64_t tick, const BodySample<T>& body) noexcept {
    if (!started_) return Status::kNotConfigured;
    if (tick != tick_ + 1u) return Status::kOutOfRange;
    if (!all_finite(body.rate_rad_s, body.specific_force)) return Status::kNonFiniteInput;
    if (!is_rotation(body.R_earth_to_body)) return Status::kInvalidRotation;
    if (config_.plant == PlantKind::kReport) {
      ReportPlant<T> report = report_;
      const Vector2<T> lateral_normal(body.specific_force(1), body.specific_force(2));
      const Status st = report.step(tick_, applied_torque_, body.R_earth_to_body, lateral_normal);
      if (st != Status::kOk) return st;
      report_ = report;
    } else {
      GimbalPlant<T> gimbal = gimbal_;
      const ActiveFaults<T> next = active_faults_at(config_.faults, tick);
      // The torquers' electrical limit is the plant's torque envelope.
      const T lim = config_.gimbal.max_torque;
      const Vector2<T> torque = applied_torque_.cwiseMin(lim).cwiseMax(-lim);
      const Status st = gimbal.step(torque, BodyState<T>{body_.rate_rad_s, body_.specific_force},
                                    BodyState<T>{body.rate_rad_s, body.specific_force});
      if (st != Status::kOk) return st;
      // The spin motor from this tick on (its failure acts on the intervals it is active at).
      if (next.spin_motor_failed != motor_failed_) {
        const bool failed = next.spin_motor_failed;
        const Status sd = gimbal.set_spin_drive(failed ? SpinDrive::kFree : config_.gimbal.spin_drive, config_.spin_hz);
        if (sd != Status::kOk) return sd;
        const Status dr = gimbal.set_spin_drag(failed ? next.spin_failure_time_constant_s : config_.gimbal.spin_down_time_s);
        if (dr != Status::kOk) return dr;
        motor_failed_ = failed;
      }
      gimbal_ = gimbal;
    }
    body_ = body;
    tick_ = tick;
    faults_now_ = active_faults_at(config_.faults, tick_);
    sample(false);
    applied_torque_ = torquer_output(config_.torquer, torque_cmd_, faults_now_);
    return Status::kOk;
  }
  // The same from the body attitude alone: the body rate of the tick from the two attitudes
  // (exact for a constant rate), the (lateral y, normal z) specific force given.
  [[nodiscard]] Status advance(std::uint64_t tick, const Matrix3<T>& R_earth_to_body,
                               const Vector2<T>& body_accel) noexcept {
    if (!is_rotation(R_earth_to_body)) return Status::kInvalidRotation;
    BodySample<T> b;
    b.R_earth_to_body = R_earth_to_body;
    b.rate_rad_s = rate_between(body_.R_earth_to_body, R_earth_to_body);
    b.specific_force = Vector3<T>(T(0), body_accel(0), body_accel(1));
    return advance(tick, b);
  }

  // The conversion sampled at the current tick. kNotReady before start().
  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    if (!started_) return PortStatus::kNotReady;
    out = pickoff_.reading();
    return PortStatus::kOk;
  }

  // Latches the torque command until the next write (zero-order hold). kNotReady before
  // start(); a non-finite command cannot be encoded: kBusError, the previous one stays.
  [[nodiscard]] PortStatus write_torquer(const Vector2<T>& torque) noexcept override {
    if (!started_) return PortStatus::kNotReady;
    if (!all_finite(torque)) return PortStatus::kBusError;
    torque_cmd_ = torque;
    applied_torque_ = torquer_output(config_.torquer, torque_cmd_, faults_now_);
    return PortStatus::kOk;
  }

  // Truth, for tests and the scenario runner's CSV.
  [[nodiscard]] Vector2<T> gimbal_angle_rad() const noexcept {
    return config_.plant == PlantKind::kReport ? report_.gimbal_angle_rad() : gimbal_.gimbal_angle_rad();
  }
  // The spin axis's inertial rate on the inner gimbal axes (pitch about y_I, yaw about z_I;
  // gyro/gimbal_geometry.hpp). The report's plant: its (theta', psi'), which never roll.
  [[nodiscard]] Vector2<T> spin_axis_rate_rad_s() const noexcept {
    if (config_.plant == PlantKind::kReport) return report_.model().rate_rad_s();
    const Vector2<T> angles = gimbal_.gimbal_angle_rad();
    const GimbalFrame<T> f = gimbal_frame_at(angles);
    const Vector2<T> joint = gimbal_.gimbal_rate_rad_s();
    return body_rate_on_gimbal(f, body_.rate_rad_s) + Vector2<T>(joint(0), joint(1) * std::cos(angles(0)));
  }
  // The total angle between the spin axis and body x.
  [[nodiscard]] T cone_rad() const noexcept {
    return config_.plant == PlantKind::kReport ? report_.model().gimbal_cone_rad() : gimbal_.cone_rad();
  }
  // The report's plant's model (its attitude, nutation amplitude, flags); nullptr otherwise.
  [[nodiscard]] const GyroModel<T>* report_model() const noexcept {
    return config_.plant == PlantKind::kReport ? &report_.model() : nullptr;
  }
  // The gimbal plant; nullptr otherwise.
  [[nodiscard]] const GimbalPlant<T>* gimbal_plant() const noexcept {
    return config_.plant == PlantKind::kGimbal ? &gimbal_ : nullptr;
  }
  // The torquer torque acting from this tick to the next (after scale factor, saturation
  // and faults).
  [[nodiscard]] const Vector2<T>& applied_torque() const noexcept { return applied_torque_; }
  // The spin the readback reports (relative to the inner gimbal for the gimbal plant).
  [[nodiscard]] T spin_hz() const noexcept { return spin_hz_now(); }
  [[nodiscard]] std::uint64_t tick() const noexcept { return tick_; }
  // Bit fault_bit(kind) = 1u << kind for each kind active at the current tick.
  [[nodiscard]] std::uint32_t active_faults() const noexcept { return faults_now_.bits; }
  // Extras beyond the port: the last torque command, and whether the gimbal was on its stop
  // in the last advance().
  [[nodiscard]] const Vector2<T>& torque_command() const noexcept { return torque_cmd_; }
  [[nodiscard]] bool at_gimbal_stop() const noexcept {
    return config_.plant == PlantKind::kReport ? report_.at_stop() : gimbal_.in_contact();
  }
  [[nodiscard]] const SimulatedGyroConfig<T>& config() const noexcept { return config_; }
  [[nodiscard]] const BodySample<T>& body() const noexcept { return body_; }

 private:
  [[nodiscard]] T spin_hz_now() const noexcept {
    if (config_.plant == PlantKind::kReport) return report_.spin_hz_at(tick_);
    return gimbal_.spin_rate_rad_s() / (T(2) * kPi<T>);
  }

  // The body's angular velocity (body axes) that turns R_from into R_to over a tick.
  [[nodiscard]] Vector3<T> rate_between(const Matrix3<T>& R_from, const Matrix3<T>& R_to) const noexcept {
    // R_to = dR * R_from: dR is the passive rotation of the tick; its transpose is the
    // active rotation of the body about its own axes.
    Matrix3<T> turn = Matrix3<T>::Zero();
    turn.noalias() = R_from * R_to.transpose();
    const Eigen::AngleAxis<T> aa(turn);
    const Vector3<T> w = aa.axis() * (aa.angle() / config_.tick_s);
    return all_finite(w) ? w : Vector3<T>(Vector3<T>::Zero());
  }

  void sample(bool power_up) noexcept {
    pickoff_.sample(gimbal_angle_rad(), tick_, faults_now_, power_up, spin_hz_now(), config_.has_spin_readback);
  }

  SimulatedGyroConfig<T> config_{};
  ReportPlant<T> report_{};
  GimbalPlant<T> gimbal_{};
  PickoffElectronics<T> pickoff_{};
  bool configured_{false};
  bool started_{false};
  bool motor_failed_{false};
  std::uint64_t tick_{0};
  BodySample<T> body_{};
  ActiveFaults<T> faults_now_{};
  Vector2<T> torque_cmd_{Vector2<T>::Zero()};
  Vector2<T> applied_torque_{Vector2<T>::Zero()};
};

}  // namespace gyro
