// Test fixture: the flight component against the SIL stub, with a body turning at constant
// rates, one tick at a time. The seeker example gyro (gyro/seeker_example.hpp) at 2 kHz.
#pragma once

#include <cstdint>
#include <cstring>

#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "support/same_bits.hpp"

namespace gyro::testing {

template <typename T>
using SeekerGyro = SeekerExample<T>;

template <typename T>
class Sil {
 public:
  SimulatedGyro<T> gyro;
  GyroComponent<T> component{gyro};
  SilLoop<T, GyroComponent<T>> loop{gyro, component, StubBodyFeed::kAttitude};
  GuidanceInput<T> guidance;  // request, slew command and nav_valid of the next step
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector2<T> body_rate{Vector2<T>::Zero()};  // (pitch q, yaw r)
  bool nav_valid{true};                      // sent with every step
  std::uint64_t tick{0};
  Status last{Status::kOk};

  bool start(const GyroComponentConfig<T>& c = SeekerGyro<T>::component(),
             const SimulatedGyroConfig<T>& s = SeekerGyro<T>::stub()) {
    tick_s_ = c.tick_s;
    if (!gyro.configure(s).ok() || !component.configure(c).ok()) return false;
    const SilStatus<Status> started = loop.start(turning_body(R_earth_to_body, body_rate));
    return started.stub == Status::kOk && started.component == Status::kOk;
  }

  // One tick: the body moves, the stub advances to it, the component runs.
  Status step(ModeRequest request = ModeRequest::kNone) {
    R_earth_to_body = pitch_then_yaw_turn(body_rate, tick_s_) * R_earth_to_body;
    ++tick;
    GuidanceCommand<T> command;
    command.request = request;
    command.slew_rate_cmd_rad_s = guidance.slew_rate_cmd_rad_s;
    command.nav_valid = nav_valid;
    const SilStatus<Status> ran = loop.tick(tick, turning_body(R_earth_to_body, body_rate), command);
    if (ran.stub != Status::kOk) return ran.stub;
    guidance = loop.input();
    last = ran.component;
    return last;
  }

  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) (void)step();
  }

  // `ticks` ticks pass for the body and the stub without the component being called: lost ticks.
  Status lose_ticks(int ticks) {
    for (int k = 0; k < ticks; ++k) {
      R_earth_to_body = pitch_then_yaw_turn(body_rate, tick_s_) * R_earth_to_body;
      ++tick;
      const Status st = gyro.advance(tick, R_earth_to_body, Vector2<T>::Zero());
      if (st != Status::kOk) return st;
    }
    return Status::kOk;
  }

  // Caged for `caged` ticks, then uncaged and settled into free mode.
  bool uncage(int caged = 200) {
    run(caged);
    (void)step(ModeRequest::kUncage);
    run(static_cast<int>(SeekerGyro<T>::component().uncage_settle_ticks));
    return component.mode() == GyroMode::kFree;
  }

  [[nodiscard]] const GyroTelemetry<T>& tm() const { return component.telemetry(); }

 private:
  T tick_s_{};
};

template <typename T>
[[nodiscard]] bool telemetry_finite(const GyroTelemetry<T>& t) {
  return all_finite(t.gimbal_measured_rad, t.gimbal_predicted_rad, t.residual_rad, t.precession_rate_rad_s,
                    t.rate_cmd_rad_s, t.torque_cmd, t.nutation_amplitude_rad, t.spin_hz) &&
         t.attitude_gyro_to_earth.coeffs().allFinite();
}

// Field by field, bit for bit (memcmp of the whole struct would compare padding too).
template <typename T>
[[nodiscard]] bool identical(const GyroTelemetry<T>& a, const GyroTelemetry<T>& b) {
  return a.tick == b.tick && a.mode == b.mode && a.flags == b.flags && a.counters == b.counters &&
         same_bits(a.gimbal_measured_rad, b.gimbal_measured_rad) &&
         same_bits(a.gimbal_predicted_rad, b.gimbal_predicted_rad) && same_bits(a.residual_rad, b.residual_rad) &&
         same_bits(a.attitude_gyro_to_earth.coeffs(), b.attitude_gyro_to_earth.coeffs()) &&
         same_bits(a.precession_rate_rad_s, b.precession_rate_rad_s) &&
         same_bits(a.rate_cmd_rad_s, b.rate_cmd_rad_s) && same_bits(a.torque_cmd, b.torque_cmd) &&
         same_bits(a.nutation_amplitude_rad, b.nutation_amplitude_rad) && same_bits(a.spin_hz, b.spin_hz);
}

}  // namespace gyro::testing
