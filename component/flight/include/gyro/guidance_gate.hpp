// The guidance gate: what of guidance's input for this tick the component may use.
//
// An unknown request is dropped and a non-finite slew command ignored (the last usable one is
// held). Navigation is used when marked valid and usable: a rotation, finite rates within
// max_body_rate_rad_s. Otherwise the last good attitude is kept (for the estimator's prediction,
// whose residual test is then suspended) and the rates are taken as unknown. Navigation marked
// invalid by the caller is information, not an error: only a field marked valid yet unusable is a
// rejected command.
#pragma once

#include <array>
#include <cstdint>

#include "gyro/component_types.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/inline_step.hpp"

namespace gyro {

// The last usable navigation: what the estimator starts and steps with.
template <typename T>
class Navigation {
 public:
  Navigation() noexcept = default;  // identity attitude, body at rest
  Navigation(const CheckedRotation<T>& attitude, const Vector3<T>& body_rate_rad_s) noexcept
      : attitude_(attitude), rates_{body_rate_rad_s, body_rate_rad_s} {}

  [[nodiscard]] const CheckedRotation<T>& attitude() const noexcept { return attitude_; }       // earth to body
  [[nodiscard]] const Vector3<T>& body_rate_rad_s() const noexcept { return rates_[latest_]; }  // (p, q, r)
  // The mean of the last two: the rate held over the step between them (the sum's order does not
  // change it).
  [[nodiscard]] Vector3<T> mean_body_rate_rad_s() const noexcept { return T(0.5) * (rates_[0] + rates_[1]); }

 private:
  template <typename>
  friend class GuidanceGate;
  CheckedRotation<T> attitude_{};
  std::array<Vector3<T>, 2> rates_{Vector3<T>::Zero(), Vector3<T>::Zero()};  // the last two
  std::uint32_t latest_{0};
};

struct GuidanceVerdict {
  ModeRequest request{ModeRequest::kNone};  // kNone when the request was unknown
  bool nav_ok{false};                       // navigation usable this tick
  std::uint32_t flags{0};                   // kCommandRejected, kNavInvalid
};

template <typename T>
class GuidanceGate {
 public:
  [[nodiscard]] GYRO_INLINE_STEP GuidanceVerdict accept(const GuidanceInput<T>& in, T max_body_rate_rad_s) noexcept {
    GuidanceVerdict v;
    v.request = in.request;
    if (!valid_request(v.request)) {
      v.request = ModeRequest::kNone;
      v.flags |= kCommandRejected;
    }
    if (all_finite(in.slew_rate_cmd_rad_s)) {
      slew_cmd_ = in.slew_rate_cmd_rad_s;
    } else {
      v.flags |= kCommandRejected;
    }
    const bool usable = in.nav_valid && all_finite(in.body_rate_rad_s) &&
                        in.body_rate_rad_s.cwiseAbs().maxCoeff() <= max_body_rate_rad_s &&
                        GyroModel<T>::check_body_attitude(in.R_earth_to_body, nav_.attitude_);
    if (!usable) {
      v.flags |= kNavInvalid;
      if (in.nav_valid) v.flags |= kCommandRejected;  // marked valid, yet unusable
      return v;
    }
    nav_.latest_ ^= 1u;  // the older rate is overwritten: the latest becomes the previous
    nav_.rates_[nav_.latest_] = in.body_rate_rad_s;
    v.nav_ok = true;
    return v;
  }

  [[nodiscard]] const Vector2<T>& slew_cmd_rad_s() const noexcept { return slew_cmd_; }  // the last usable
  [[nodiscard]] const Navigation<T>& navigation() const noexcept { return nav_; }        // the last usable

 private:
  [[nodiscard]] static bool valid_request(ModeRequest r) noexcept {
    return r == ModeRequest::kNone || r == ModeRequest::kCage || r == ModeRequest::kUncage;
  }

  Vector2<T> slew_cmd_{Vector2<T>::Zero()};
  Navigation<T> nav_{};
};

}  // namespace gyro
