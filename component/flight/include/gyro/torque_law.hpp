// The torque law: from the mode and the gimbal frame, the spin-axis rate to fly this tick (caging
// loop or slew command, after stop protection and the rate limits), and the torquer commands that
// hold it against the bearings' friction on the gimbal rates (or without friction compensation, the
// report's H*rate), saturated by scaling so the slew keeps its direction (gyro/gimbal_geometry.hpp
// has the law and its inverse; docs/component.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gyro/component_types.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "gyro/inline_step.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/saturate.hpp"
#include "gyro/stop_protection.hpp"

namespace gyro {

// Spin-axis rates to fly this tick on the gimbal axes (pitch about y_I, yaw about z_I), after stop
// protection and limits, and what the torque law is to do with them.
template <typename T>
struct RateCommand {
  Vector2<T> rate_rad_s{Vector2<T>::Zero()};
  bool torquing{false};                    // the torquers are driven this tick
  bool protecting{false};                  // stop protection moved the rate
  Vector2<T> outward{Vector2<T>::Zero()};  // unit outward direction, when protecting
  T outward_rate_rad_s{};                  // and the spin axis's rate along it that keeps the
                                           // bound
  std::uint32_t flags{0};                  // kGimbalStopProtect, kSlewRateLimited
};

template <typename T>
struct TorqueCommand {
  Vector2<T> torque{Vector2<T>::Zero()};  // (inner, outer), within +-max_torque
  std::uint32_t flags{0};                 // kTorquerSaturated, kStopBeyondAuthority
};

template <typename T>
class TorqueLaw {
 public:
  TorqueLaw() noexcept = default;
  // From a configuration check() accepted.
  explicit TorqueLaw(const GyroComponentConfig<T>& c) noexcept
      : max_pitch_rate_rad_s_(c.max_pitch_rate_rad_s),
        max_yaw_rate_rad_s_(c.max_yaw_rate_rad_s),
        max_torque_(c.max_torque),
        friction_(c.friction_compensation ? c.friction : T(0)),
        spin_inertia_(c.spin_inertia),
        cage_gain_1_s_(c.cage_gain_1_s),
        stop_bound_{std::sin(c.gimbal_cone_limit_rad - c.gimbal_stop_margin_rad), c.cage_gain_1_s} {}

  // The rate to fly in `mode`, the body turning at `body` (on y_I, z_I; zero when unknown). Caged,
  // the spin axis follows the body and the gimbal angles `gimbal_rad` close at the cage gain (th' =
  // -k th, ps' = -k ps) when `gimbal_fresh`; free, it flies `slew_cmd`.
  [[nodiscard]] GYRO_INLINE_STEP RateCommand<T> rate_command(GyroMode mode, const GimbalFrame<T>& frame,
                                                             const Vector2<T>& body, const Vector2<T>& gimbal_rad,
                                                             bool gimbal_fresh,
                                                             const Vector2<T>& slew_cmd) const noexcept {
    RateCommand<T> c;
    if (mode == GyroMode::kFault) return c;  // safe mode: torquers off
    Vector2<T> w = Vector2<T>::Zero();       // uncaging: torquers off while it settles
    if (mode == GyroMode::kCaged) {
      const Vector2<T>& g = gimbal_rad;
      w = body;
      if (gimbal_fresh) w -= cage_gain_1_s_ * Vector2<T>(g(0), g(1) * frame.cos_pitch);
    } else if (mode == GyroMode::kFree) {
      w = slew_cmd;
    }
    // The gimbal's outward motion is bounded whatever drives it, the body's turn included
    // (gyro/stop_protection.hpp); uncaging torques only while the bound acts.
    const ProtectedRate<T> p = protect_stop(frame, w, body, stop_bound_);
    c.torquing = mode != GyroMode::kUncaging || p.acting;
    c.protecting = p.acting;
    c.outward = p.outward;
    c.outward_rate_rad_s = p.outward_rate_rad_s;
    if (p.acting) c.flags |= kGimbalStopProtect;
    w = p.rate_rad_s;
    c.rate_rad_s = limited(w);
    if (c.rate_rad_s != w)
      c.flags |= kSlewRateLimited;  // guidance (or the body) asks more than may
                                    // be flown
    return c;
  }

  // The torquer commands that fly `rate` at `spin_hz`, the inner gimbal rolling at `roll_rad_s`.
  // When stop protection acts and the torquer cannot give it all, the command's part across the
  // outward direction is dropped first; kStopBeyondAuthority when the rate the torquers then hold
  // still moves the gimbal outward, faster than the bound allows.
  [[nodiscard]] GYRO_INLINE_STEP TorqueCommand<T> torque_command(const GimbalFrame<T>& frame,
                                                                 const RateCommand<T>& rate, const Vector2<T>& body,
                                                                 T spin_hz, T roll_rad_s) const noexcept {
    TorqueCommand<T> t;
    if (!rate.torquing) return t;
    // The rotor's momentum: the motor-held spin's plus that of the inner gimbal's roll.
    const T h = angular_momentum(spin_hz, spin_inertia_) + spin_inertia_ * roll_rad_s;
    const T f = friction_;
    Saturated s = saturated_torque(frame, h, f, rate.rate_rad_s, body);
    const bool short_of_rate = (rate.flags & kSlewRateLimited) != 0u || s.saturated;
    if (rate.protecting && s.saturated) {
      const Vector2<T> outward_only = limited(Vector2<T>(rate.outward * rate.outward_rate_rad_s));
      s = saturated_torque(frame, h, f, outward_only, body);
    }
    if (s.saturated) t.flags |= kTorquerSaturated;
    if (short_of_rate) {
      // The rate the torque written holds (the law's inverse), against the bound.
      const Vector2<T> flown = s.saturated ? rate_for_torquers(frame, h, f, s.value, body) : rate.rate_rad_s;
      // Beyond the bound and still moving out (beyond c_p a pull-back slower than the bound asks is
      // no danger: the gimbal is on its way in).
      const OutwardExcess<T> e = outward_excess(frame, flown, body, stop_bound_);
      if (e.rate_rad_s > T(0) && e.rate_rad_s + e.allowed_rad_s > T(0)) t.flags |= kStopBeyondAuthority;
    }
    t.torque = s.value;
    return t;
  }

 private:
  struct Saturated {
    Vector2<T> value{Vector2<T>::Zero()};
    bool saturated{false};
  };

  [[nodiscard]] Vector2<T> limited(const Vector2<T>& w) const noexcept {
    return Vector2<T>(saturate(w(0), max_pitch_rate_rad_s_), saturate(w(1), max_yaw_rate_rad_s_));
  }

  [[nodiscard]] Saturated saturated_torque(const GimbalFrame<T>& frame, T h, T f, const Vector2<T>& rate,
                                           const Vector2<T>& body) const noexcept {
    Saturated s;
    s.value = torquers_for_rate(frame, h, f, rate, body);
    if (!all_finite(s.value)) {
      // The products overflowed (huge rate limits or spin; f, h and the rates are finite and not
      // all zero here): the same direction from factors scaled to at most 1, then saturated without
      // overflow. (h can be negative: the inner gimbal rolling against a slow spin.)
      const T k = std::max(f, std::abs(h));
      const T r = std::max(rate.cwiseAbs().maxCoeff(), body.cwiseAbs().maxCoeff());
      s.value = torquers_for_rate(frame, h / k, f / k, Vector2<T>(rate / r), Vector2<T>(body / r));
      s.value = (s.value / s.value.cwiseAbs().maxCoeff()) * max_torque_;
      s.saturated = true;
      return s;
    }
    const T largest = s.value.cwiseAbs().maxCoeff();
    if (largest > max_torque_) {
      // Divide first: the largest component becomes exactly 1, so the result never exceeds
      // max_torque (max_torque / largest can be subnormal and lose the digits that keep it).
      s.value = (s.value / largest) * max_torque_;
      s.saturated = true;
    }
    return s;
  }

  T max_pitch_rate_rad_s_{};
  T max_yaw_rate_rad_s_{};
  T max_torque_{};
  T friction_{};  // 0 without friction compensation
  T spin_inertia_{};
  T cage_gain_1_s_{};
  StopBound<T> stop_bound_{};  // sin(gimbal_cone_limit_rad -
                               // gimbal_stop_margin_rad), cage_gain_1_s
};

}  // namespace gyro
