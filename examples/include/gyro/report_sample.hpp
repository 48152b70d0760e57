// The report's sample run (GYMAIN with INITG), driven through GyroModel with the listing's
// errors fixed: spin 100 Hz, f = 5, J0 = 3, J1 = 2.25, J2 = 2 (slug*ft^2), body turning at
// 2.3 and 1.8 times 0.1745329 rad/s in pitch and yaw, commanded slew -0.19 (limited to
// 0.1745329) in pitch and 0.013 rad/s in yaw, step 1/floor(20 x nutation Hz), 801 steps.
#pragma once

#include <cmath>

#include "gyro/gyro_model.hpp"

namespace gyro {

// INITG's step for any rotor: 1/floor(20 x nutation Hz), so that 20 steps or more resolve a
// nutation cycle; 0 when the rotor does not nutate at 0.05 Hz or more (the listing divides by
// zero there, or takes the root of a negative number when overdamped: docs/seed-errata.md, 7
// and 17).
template <typename T>
[[nodiscard]] T initg_step(const RotorParameters<T>& rotor) noexcept {
  RotorModes<T> m;
  if (compute_modes(rotor, m) != Status::kOk) return T(0);
  const T per_second = std::floor(T(20) * m.nutation_hz);
  return per_second >= T(1) ? T(1) / per_second : T(0);
}

template <typename T>
struct ReportSample {
  static constexpr T kDegPerSecond = T(0.1745329);  // the listing's 10 deg/s
  static constexpr T kSpinHz = T(100);
  static constexpr T kBodyPitchRate = T(2.3) * kDegPerSecond;
  static constexpr T kBodyYawRate = T(1.8) * kDegPerSecond;
  static constexpr int kSteps = 801;

  static GyroModelConfig<T> config() noexcept {
    GyroModelConfig<T> c;
    c.pitch_inertia = T(2.25);
    c.yaw_inertia = T(2.0);
    c.spin_inertia = T(3.0);
    c.friction = T(5.0);
    c.gimbal_cone_limit_rad = T(0.4363323);
    c.max_pitch_rate_rad_s = kDegPerSecond;
    c.max_yaw_rate_rad_s = kDegPerSecond;
    c.gravity = T(32.1725);  // ft/s^2
    return c;
  }
  static RotorParameters<T> rotor() noexcept {
    const GyroModelConfig<T> c = config();
    return {c.pitch_inertia, c.yaw_inertia, c.friction, angular_momentum(kSpinHz, c.spin_inertia)};
  }
  static Vector2<T> slew_command() noexcept { return Vector2<T>(T(-0.19), T(0.013)); }

  // INITG's step: 1/floor(20 x nutation Hz).
  static T initg_step() noexcept { return gyro::initg_step(rotor()); }
};

struct SampleRunSummary {
  int steps_completed = 0;
  Status status = Status::kOk;
  std::uint32_t stop_flags = 0;  // the flag that ended the run early, if any
};

// Runs `steps` steps of length `dt` and calls on_step(k, t, model, R_earth_to_body) after
// each. Stops, as the report's driver does, on a gimbal-limit or small-angle flag.
template <typename T, typename OnStep>
[[nodiscard]] SampleRunSummary run_report_sample(T dt, int steps, OnStep&& on_step) noexcept {
  using S = ReportSample<T>;
  SampleRunSummary sum;
  GyroModel<T> g;
  if (!g.configure(S::config()).ok()) {
    sum.status = Status::kOutOfRange;
    return sum;
  }
  Matrix3<T> r_eb = Matrix3<T>::Identity();
  sum.status = g.uncage(r_eb, Vector2<T>(S::kBodyPitchRate, S::kBodyYawRate));
  if (sum.status != Status::kOk) return sum;
  // The body turns about its own pitch then yaw axes, exactly (GYMAIN: ROTZ*ROTY*ROTEB).
  const Matrix3<T> turn = frame_rotation_z(S::kBodyYawRate * dt) * frame_rotation_y(S::kBodyPitchRate * dt);
  GyroStepInput<T> in;
  in.dt_s = dt;
  in.spin_hz = S::kSpinHz;
  for (int k = 0; k < steps; ++k) {
    r_eb = turn * r_eb;  // the body first: the gimbal angles are those of the step's end
    in.R_earth_to_body = r_eb;
    sum.status = g.step_slew(in, S::slew_command());
    if (sum.status != Status::kOk) return sum;
    on_step(k, static_cast<T>(k + 1) * dt, g, r_eb);
    if (g.flags() != 0u) {
      sum.stop_flags = g.flags();
      sum.steps_completed = k;  // as the listing counts: the flagged step ends the run
      return sum;
    }
  }
  sum.steps_completed = steps;
  return sum;
}

}  // namespace gyro
