// The body's motion in a scenario: its attitude, rates and specific force tick by tick. The
// truth environment of the software-in-the-loop run, so it is computed in double whatever
// scalar the component and the stub run in.
//
// Profile: a start attitude (roll, pitch, yaw Euler angles, 3-2-1), constant body rates p
// (roll, about body x), q (pitch, about body y) and r (yaw, about body z), an optional
// sinusoidal weave on q and r,
//   q(t) = q0 + Aq sin(2 pi f t),   r(t) = r0 + Ar sin(2 pi f t + phase),
// and a constant specific force (body axes; the report's plant uses its lateral y and normal
// z components).
//
// Per tick the body turns by an exact rotation (no first-order matrices): with the rotation
// vector composition the body's angular velocity (p, q_mean, r_mean) is held over the tick,
// q_mean and r_mean being the exact means of q(t) and r(t) over the tick (the rotation is
// then exact for constant rates; with a weave, the second-order coning term within one tick
// is neglected). The pitch-then-yaw composition reproduces the report's driver GYMAIN
// (ROTZ * ROTY * ROTEB, with exact matrices). The attitude is composed as a unit quaternion,
// normalised every tick, so it stays a rotation over any number of ticks.
//
// Trajectory: a recorded table (body_trajectory.hpp) in place of the profile; the attitude,
// rates and specific force at each tick are the table's interpolating curve at the tick's
// time (no composition from tick to tick).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>

#include "body_trajectory.hpp"
#include "gyro/attitude.hpp"

namespace gyro::sil {

enum class RotationComposition : std::uint8_t {
  kRotationVector,  // angular velocity held over the tick (exact for constant rates)
  kPitchThenYaw,    // the report's GYMAIN: pitch by q*dt about body y, then yaw by r*dt about z
};
[[nodiscard]] constexpr std::array<const char*, 2> enum_names(RotationComposition /*tag*/) noexcept {
  return {"rotation_vector", "pitch_then_yaw"};
}

struct WeaveProfile {
  double pitch_amplitude_rad_s{0};
  double yaw_amplitude_rad_s{0};
  double frequency_hz{0};
  double yaw_phase_rad{0};  // of the yaw weave relative to the pitch weave (pi/2: coning)
};

struct BodyProfile {
  std::array<double, 3> attitude_rad{0, 0, 0};  // (roll, pitch, yaw) at t = 0, 3-2-1 Euler
  std::array<double, 3> rate_rad_s{0, 0, 0};    // constant (p, q, r)
  RotationComposition composition{RotationComposition::kRotationVector};
  WeaveProfile weave{};
  std::array<double, 3> specific_force{0, 0, 0};  // body (x, y, z), units of gyro.gravity
  // body.trajectory: the motion comes from the table instead (the fields above unused).
  std::optional<TrajectorySpec> trajectory_spec;
  std::shared_ptr<const BodyTrajectory> trajectory;  // loaded and checked once
};

inline constexpr double kTwoPi = 6.283185307179586476925286766559;

// R_earth_to_body of a 3-2-1 (yaw, pitch, roll) Euler attitude.
[[nodiscard]] inline Eigen::Matrix3d euler_321_to_R_earth_to_body(const std::array<double, 3>& rpy) {
  const double c = std::cos(rpy[0]), s = std::sin(rpy[0]);
  Eigen::Matrix3d roll = Eigen::Matrix3d::Zero();
  roll << 1, 0, 0, 0, c, s, 0, -s, c;
  const Eigen::Matrix3d pitch_yaw = frame_rotation_y(rpy[1]) * frame_rotation_z(rpy[2]);
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  r.noalias() = roll * pitch_yaw;
  return r;
}

class BodyMotion {
 public:
  BodyMotion(const BodyProfile& profile, double tick_s)
      : profile_(profile),
        tick_s_(tick_s),
        q_body_to_earth_(Eigen::Matrix3d(euler_321_to_R_earth_to_body(profile.attitude_rad).transpose())) {
    q_body_to_earth_.normalize();
    if (profile_.trajectory) {
      sample_trajectory();
      return;
    }
    R_earth_to_body_ = q_body_to_earth_.toRotationMatrix().transpose();
  }

  // Below this phase advance per tick, the weave's mean over a tick is its midpoint value.
  static constexpr double kShortSpanRad = 1e-5;

  // Body (p, q, r) at time t.
  [[nodiscard]] Eigen::Vector3d rate_at(double t) const {
    const WeaveProfile& w = profile_.weave;
    const double a = kTwoPi * w.frequency_hz * t;
    return Eigen::Vector3d(profile_.rate_rad_s[0], profile_.rate_rad_s[1] + w.pitch_amplitude_rad_s * std::sin(a),
                           profile_.rate_rad_s[2] + w.yaw_amplitude_rad_s * std::sin(a + w.yaw_phase_rad));
  }

  // Exact mean of (p, q, r) over [t0, t1].
  [[nodiscard]] Eigen::Vector3d mean_rate(double t0, double t1) const {
    const WeaveProfile& w = profile_.weave;
    Eigen::Vector3d m(profile_.rate_rad_s[0], profile_.rate_rad_s[1], profile_.rate_rad_s[2]);
    const double omega = kTwoPi * w.frequency_hz;
    if (omega > 0 && (w.pitch_amplitude_rad_s != 0 || w.yaw_amplitude_rad_s != 0)) {
      const double span = omega * (t1 - t0);
      const double a0 = omega * t0, a1 = omega * t1;
      if (span < kShortSpanRad) {
        // The closed form cancels (and is 0/0 once span underflows): the midpoint value is
        // the mean to span^2/24 relative, below 4.2e-12 here.
        const double mid = 0.5 * (a0 + a1);
        m(1) += w.pitch_amplitude_rad_s * std::sin(mid);
        m(2) += w.yaw_amplitude_rad_s * std::sin(mid + w.yaw_phase_rad);
      } else {
        m(1) += w.pitch_amplitude_rad_s * (std::cos(a0) - std::cos(a1)) / span;
        m(2) += w.yaw_amplitude_rad_s * (std::cos(a0 + w.yaw_phase_rad) - std::cos(a1 + w.yaw_phase_rad)) / span;
      }
    }
    return m;
  }

  // The passive rotation of one tick, R_new = step * R_old, for mean rates `omega` (p, q, r)
  // over dt (the report's pitch-then-yaw composition has no roll).
  [[nodiscard]] static Eigen::Matrix3d tick_rotation(const Eigen::Vector3d& omega, double dt,
                                                     RotationComposition composition) {
    if (composition == RotationComposition::kPitchThenYaw) {
      Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
      r.noalias() = frame_rotation_z(omega(2) * dt) * frame_rotation_y(omega(1) * dt);
      return r;
    }
    const double angle = omega.norm() * dt;
    if (!(angle > 0)) return Eigen::Matrix3d::Identity();
    // The body turns by +angle about omega; body components of fixed vectors turn by -angle.
    return Eigen::AngleAxisd(-angle, omega.normalized()).toRotationMatrix();
  }

  // Moves the body from its current tick to the next.
  void advance() {
    const double t0 = time_s();
    ++tick_;
    if (profile_.trajectory) {
      sample_trajectory();
      return;
    }
    const double t1 = time_s();
    const Eigen::Matrix3d step = tick_rotation(mean_rate(t0, t1), tick_s_, profile_.composition);
    // R_new = step * R_old  <=>  q_new (body to earth) = q_old * step^T.
    const Eigen::Quaterniond step_q(Eigen::Matrix3d(step.transpose()));
    q_body_to_earth_ = q_body_to_earth_ * step_q;
    q_body_to_earth_.normalize();
    R_earth_to_body_ = q_body_to_earth_.toRotationMatrix().transpose();
  }

  [[nodiscard]] std::uint64_t tick() const { return tick_; }
  [[nodiscard]] double time_s() const { return static_cast<double>(tick_) * tick_s_; }
  [[nodiscard]] const Eigen::Matrix3d& R_earth_to_body() const { return R_earth_to_body_; }
  [[nodiscard]] Eigen::Vector3d rate_rad_s() const {
    return profile_.trajectory ? point_.rate_rad_s : rate_at(time_s());
  }
  [[nodiscard]] Eigen::Vector3d specific_force() const {
    if (profile_.trajectory) return point_.specific_force;
    return Eigen::Vector3d(profile_.specific_force[0], profile_.specific_force[1], profile_.specific_force[2]);
  }

 private:
  void sample_trajectory() {
    point_ = trajectory_at(*profile_.trajectory, time_s(), cursor_);
    q_body_to_earth_ = point_.q_body_to_earth;
    R_earth_to_body_ = q_body_to_earth_.toRotationMatrix().transpose();
  }

  BodyProfile profile_;
  double tick_s_;
  std::uint64_t tick_{0};
  Eigen::Quaterniond q_body_to_earth_{Eigen::Quaterniond::Identity()};
  Eigen::Matrix3d R_earth_to_body_{Eigen::Matrix3d::Identity()};
  std::size_t cursor_{0};
  TrajectoryPoint point_{};
};

}  // namespace gyro::sil
