// The SIL stub's nonlinear gimbal plant (gyro/gimbal_plant.hpp), one tick at a time, for
// counting its instructions: the seeker example's device at its 2 kHz tick, and the report's
// sample gyro as a device at INITG's step. The body rolls and turns, its specific force is
// gravity plus a lateral load, and the torques slew the gimbals back and forth inside the
// stop (no contact), as a SIL run would.
//
// The report's gyro as a device (slug ft^2), from ReportSample's configuration: its J0, A = 1.6
// (J0 <= 2A), gimbal inertias split so that the effective inertias at zero angles are the
// report's J1 = Iy + A and J2 = Oz + Iz + A; its friction on each bearing.
#pragma once

#include <string>

#include "bench_problem.hpp"
#include "gyro/gimbal_plant.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/seeker_gimbal.hpp"

namespace gyro::bench {

template <typename T>
GimbalPlantConfig<T> report_sample_gimbal_config() {
  const GyroModelConfig<T> r = ReportSample<T>::config();
  const T a = T(1.6);  // the rotor's transverse inertia A: J0 <= 2A
  GimbalPlantConfig<T> c;
  c.spin_inertia = r.spin_inertia;
  c.rotor_transverse_inertia = a;
  c.inner_gimbal_inertia = Vector3<T>(T(0.45), r.pitch_inertia - a, T(0.2));         // J1 = Iy + A
  c.outer_gimbal_inertia = Vector3<T>(T(0.4), T(0.2), r.yaw_inertia - T(0.2) - a);  // J2 = Oz + Iz + A
  c.inner_friction = r.friction;
  c.outer_friction = r.friction;
  c.spin_drive = SpinDrive::kMotor;
  c.max_spin_hz = ReportSample<T>::kSpinHz;
  c.motor_torque_limit = T(50.0);
  c.spin_servo_bandwidth_rad_s = T(5.0);
  c.stop_cone_rad = r.gimbal_cone_limit_rad;  // 25 deg
  c.stop_restitution = T(0.2);
  c.max_body_rate_rad_s = T(10.0);
  c.max_torque = T(1e4);
  c.max_specific_force = T(1e3);  // ft/s^2
  return c;
}

struct GimbalWorkloadSpec {
  bool report = false;  // the report's sample gyro, else the seeker
  double phase = 0.5;   // max_substep_phase_rad
};

inline GimbalWorkloadSpec gimbal_workload_spec(const std::string& kind) {
  if (kind == "seeker") return {false, 0.5};
  if (kind == "seeker_coarse") return {false, 1.0};
  if (kind == "report") return {true, 0.5};
  fail("unknown gimbal workload");
}

template <typename T>
class GimbalWorkload {
 public:
  explicit GimbalWorkload(const GimbalWorkloadSpec& spec) {
    GimbalPlantConfig<T> c = spec.report ? report_sample_gimbal_config<T>() : seeker_gimbal_config<T>();
    c.max_substep_phase_rad = static_cast<T>(spec.phase);
    tick_s_ = spec.report ? ReportSample<T>::initg_step() : SeekerExample<T>::kTick;
    if (!plant_.configure(c, tick_s_).ok()) fail("GimbalPlant::configure");
    GimbalStart<T> s;
    s.spin_hz = c.max_spin_hz;
    body_.rate_rad_s = Vector3<T>(T(5), T(0.2), T(-0.1));
    body_.specific_force = Vector3<T>(T(0), T(3), spec.report ? T(-32.1725) : T(-9.80665));
    if (plant_.start(s, body_) != Status::kOk) fail("GimbalPlant::start");
    // Torques that slew at 0.2 rad/s (report) or 0.25 rad/s (seeker) in both axes.
    const T h = c.spin_inertia * T(2) * kPi<T> * c.max_spin_hz;
    const T rate = spec.report ? T(0.2) : T(0.25);
    torque_[0] = Vector2<T>(h * rate, -h * rate);
    torque_[1] = -torque_[0];
    reverse_every_ = static_cast<unsigned long>(T(0.25) / tick_s_);
  }

  // One tick; the torque reverses every 0.25 s (the gimbals sweep +-0.03 rad).
  [[nodiscard]] Status step() noexcept {
    const Vector2<T>& torque = torque_[(tick_ / reverse_every_) & 1U];
    ++tick_;
    return plant_.step(torque, body_, body_);
  }

  [[nodiscard]] T output() const noexcept { return plant_.gimbal_angle_rad()(0); }
  [[nodiscard]] int substeps() const noexcept { return plant_.substeps(); }
  [[nodiscard]] T tick_s() const noexcept { return tick_s_; }
  [[nodiscard]] bool contact() const noexcept { return plant_.in_contact(); }

 private:
  GimbalPlant<T> plant_;
  BodyState<T> body_;
  T tick_s_{};
  Vector2<T> torque_[2]{Vector2<T>::Zero(), Vector2<T>::Zero()};
  unsigned long tick_{0};
  unsigned long reverse_every_{1};
};

}  // namespace gyro::bench
