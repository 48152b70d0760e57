// The report's gyro as a SIL plant (scenario plant "report"): GyroModel (the report's linear
// model, torques about the gyro's own axes) with a scheduled spin and an inelastic stop. The
// gimbal plant (gyro/gimbal_plant.hpp) is the device; this one reproduces the report's runs.
//
// Spin: spin(t) = spin_hz exp(-t/tau) (tau = 0: constant) times, while the spin motor has
// failed, exp(-(time failed)/magnitude): the run-down stops when the failure ends but the lost
// speed is not regained. Each step uses the spin at the middle of the step (H is constant
// within a step of the exact model). A spin below spin_hz * epsilon is taken as stopped.
//
// Stop: if after a step the total cone angle of the spin axis from body x exceeds the stop,
// the impact is inelastic: the model is re-uncaged with the spin axis on the stop in the
// direction it was heading and the gimbal rates those of the body over the step. While the
// body keeps pushing, the gyro is put back every tick and walks round the rim of the stop.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gyro/fault_schedule.hpp"
#include "gyro/gyro_model.hpp"

namespace gyro {

template <typename T>
struct ReportPlantConfig {
  GyroModelConfig<T> gyro{};      // rotor, limits and the report's error sources
  T spin_down_time_constant_s{};  // 0 = constant spin
  T gimbal_stop_rad{};            // stop on the total cone angle (0 = none)
};

template <typename T>
[[nodiscard]] ConfigCheck check(const ReportPlantConfig<T>& c) noexcept {
  const ConfigCheck g = check(c.gyro);
  if (!g.ok()) return g;
  if (!std::isfinite(c.spin_down_time_constant_s)) return {Status::kNonFiniteInput, "spin_down_time_constant_s"};
  if (c.spin_down_time_constant_s < T(0)) return {Status::kOutOfRange, "spin_down_time_constant_s"};
  if (!std::isfinite(c.gimbal_stop_rad)) return {Status::kNonFiniteInput, "gimbal_stop_rad"};
  if (c.gimbal_stop_rad < T(0) || !(c.gimbal_stop_rad < kPi<T>)) return {Status::kOutOfRange, "gimbal_stop_rad"};
  return {};
}

template <typename T>
class ReportPlant {
 public:
  [[nodiscard]] ConfigCheck configure(const ReportPlantConfig<T>& c, T tick_s, T spin_hz,
                                      const FaultList<T>& faults) noexcept {
    const ConfigCheck chk = check(c);
    if (!chk.ok()) return chk;
    GyroModel<T> fresh;
    const ConfigCheck mc = fresh.configure(c.gyro);
    if (!mc.ok()) return mc;
    config_ = c;
    model_ = fresh;
    tick_s_ = tick_s;
    spin_hz_ = spin_hz;
    faults_ = faults;
    return chk;
  }

  // Released aligned with the body, rates = the body's pitch and yaw rates.
  [[nodiscard]] Status start(const Matrix3<T>& R_earth_to_body, const Vector3<T>& body_rate_rad_s) noexcept {
    GyroModel<T> fresh;
    const ConfigCheck mc = fresh.configure(config_.gyro);
    if (!mc.ok()) return mc.status;
    const Status st = fresh.uncage(R_earth_to_body, Vector2<T>(body_rate_rad_s(1), body_rate_rad_s(2)));
    if (st != Status::kOk) return st;
    model_ = fresh;
    R_earth_to_body_ = R_earth_to_body;
    at_stop_ = false;
    return Status::kOk;
  }

  // One tick from `tick` to tick + 1 with the torque held, the body at tick + 1.
  [[nodiscard]] Status step(std::uint64_t tick, const Vector2<T>& torque, const Matrix3<T>& R_earth_to_body,
                            const Vector2<T>& body_accel) noexcept {
    GyroStepInput<T> in;
    in.dt_s = tick_s_;
    in.R_earth_to_body = R_earth_to_body;
    in.body_accel = body_accel;
    in.spin_hz = spin_at_time(static_cast<T>(tick) + T(0.5));
    GyroModel<T> next = model_;
    const Status st = next.step_torque(in, torque);
    if (st != Status::kOk) return st;
    bool hit = false;
    if (config_.gimbal_stop_rad > T(0) && next.gimbal_cone_rad() > config_.gimbal_stop_rad) {
      const Status ss = put_on_stop(next, R_earth_to_body);
      if (ss != Status::kOk) return ss;
      hit = true;
    }
    model_ = next;
    at_stop_ = hit;
    R_earth_to_body_ = R_earth_to_body;
    return Status::kOk;
  }

  [[nodiscard]] Vector2<T> gimbal_angle_rad() const noexcept {
    return Vector2<T>(model_.gimbal_pitch_rad(), model_.gimbal_yaw_rad());
  }
  [[nodiscard]] T spin_hz_at(std::uint64_t tick) const noexcept { return spin_at_time(static_cast<T>(tick)); }
  [[nodiscard]] bool at_stop() const noexcept { return at_stop_; }
  [[nodiscard]] const GyroModel<T>& model() const noexcept { return model_; }

 private:
  // Spin at time t = ticks * tick_s (ticks may be fractional: the middle of a step).
  [[nodiscard]] T spin_at_time(T ticks) const noexcept {
    const T dt = tick_s_;
    T exponent = T(0);
    if (config_.spin_down_time_constant_s > T(0)) exponent += ticks * dt / config_.spin_down_time_constant_s;
    for (const FaultEvent<T>& f : faults_) {
      if (f.kind != FaultKind::kSpinMotorFailure) continue;
      const T fault_start = static_cast<T>(f.start_tick);
      if (ticks <= fault_start) continue;
      T fault_end = ticks;
      if (f.duration_ticks != 0u) fault_end = std::min(ticks, static_cast<T>(f.start_tick + f.duration_ticks));
      exponent += (fault_end - fault_start) * dt / f.magnitude;
    }
    const T spin = spin_hz_ * std::exp(-exponent);
    // Run down below the rounding of the initial spin: stopped. (A vanishing but non-zero H
    // has no use and, squared, underflows inside the exact solution.)
    return (spin < spin_hz_ * std::numeric_limits<T>::epsilon()) ? T(0) : spin;
  }

  // Body pitch and yaw rates over the last step, from the attitudes at its two ends.
  [[nodiscard]] Vector2<T> body_rate(const Matrix3<T>& R_earth_to_body_now) const noexcept {
    // R_now = dR * R_prev: dR is the passive rotation of the step; its transpose is the
    // active rotation of the body about its own axes.
    Matrix3<T> turn = Matrix3<T>::Zero();
    turn.noalias() = R_earth_to_body_ * R_earth_to_body_now.transpose();
    const Eigen::AngleAxis<T> aa(turn);
    const Vector3<T> w = aa.axis() * (aa.angle() / tick_s_);
    if (!all_finite(w)) return Vector2<T>::Zero();
    return Vector2<T>(w(1), w(2));
  }

  // Inelastic impact: spin axis put on the stop in the direction it was heading, gimbal
  // rates those of the body.
  [[nodiscard]] Status put_on_stop(GyroModel<T>& model, const Matrix3<T>& R_earth_to_body_now) const noexcept {
    const T p = model.gimbal_pitch_rad(), y = model.gimbal_yaw_rad();
    // Spin axis in body axes: (cos p cos y, cos p sin y, -sin p); its (y, z) direction.
    const T dy = std::cos(p) * std::sin(y), dz = -std::sin(p);
    const T n = std::hypot(dy, dz);
    if (!(n > T(0))) return Status::kNumericalOverflow;
    // step_rotation((theta, psi)) turns body x by |(theta, psi)| toward (psi, -theta) in (y, z).
    const T s = config_.gimbal_stop_rad / n;
    const Vector2<T> offset(-s * dz, s * dy);
    return model.uncage(R_earth_to_body_now, body_rate(R_earth_to_body_now), offset);
  }

  ReportPlantConfig<T> config_{};
  GyroModel<T> model_{};
  T tick_s_{};
  T spin_hz_{};
  FaultList<T> faults_{};
  Matrix3<T> R_earth_to_body_{Matrix3<T>::Identity()};
  bool at_stop_{false};
};

}  // namespace gyro
