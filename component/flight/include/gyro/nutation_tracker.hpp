// The nutation tracker: the rotor's nutation frequency at the spin flown and the gimbal's
// pitch angle, whether the tick aliases it, and the torque shaper's design for it
// (gyro/torque_shaper.hpp).
//
// The nutation is the device's at this tick's geometry, as the torquers see it: the rotor's
// momentum with the inner gimbal's roll r (H + J0 r, as the torque law's), the yaw inertia for
// the spin axis's rate on z_I with the motor-held spin's share, J2 + J0 tan^2 th, and less the
// roll the torquers turn with (docs/component.md). All are kept
// until that frequency moves kBetaTolerance away from the one they were made for: a
// spinning-down rotor's readback and a slewing gimbal change it every tick; the notch is not
// that narrow (a relative error e in beta lets through about 2 e of the nutation a step of
// torque excites), so the design is redone every few hundred ticks of a spin-down or every
// few tenths of a degree of pitch, not every tick. (The estimator follows every readback:
// its transition is physics.)
#pragma once

#include <algorithm>
#include <cmath>

#include "gyro/gimbal_geometry.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {

template <typename T>
struct NutationUpdate {
  bool redesigned{false};  // the nutation moved: `shaper` is the new design
  ShaperDesign<T> shaper{};
};

// The yaw inertia the spin axis's rate on z_I meets at pitch angle th, the spin held by its
// motor relative to the inner gimbal: the configured J2 (at zero angles) plus the spin
// inertia's C tan^2 th (docs/gimbal-geometry.md; the rings' own share is not configured).
template <typename T>
[[nodiscard]] T yaw_inertia_at_pitch(T yaw_inertia, T spin_inertia, T tan_pitch) noexcept {
  return yaw_inertia + spin_inertia * (tan_pitch * tan_pitch);
}

template <typename T>
class NutationTracker {
 public:
  // The design follows the nutation frequency within this fraction.
  static constexpr T kBetaTolerance = T(1e-3);

  // Once per tick, at the spin flown (finite, >= 0), the inner gimbal's roll rate and the
  // gimbal frame the torque law resolves on; the inertias and friction were checked by the
  // configuration contract: the rate-matrix terms alone (compute_modes() without its checks
  // and other modes).
  template <typename Config>
  [[nodiscard]] NutationUpdate<T> follow(T spin, T roll_rad_s, const GimbalFrame<T>& frame, const Config& c) noexcept {
    NutationUpdate<T> u;
    // The geometry within the envelope the configuration covers: the cone and the body's rate
    // (a gimbal estimate or a roll beyond them, as after a fault, designs for their edge).
    const T roll = std::clamp(roll_rad_s, -c.max_body_rate_rad_s, c.max_body_rate_rad_s);
    const T tan_cone = std::tan(c.gimbal_cone_limit_rad);
    const T tan_pitch = std::clamp(frame.sin_pitch / frame.cos_pitch, -tan_cone, tan_cone);
    const T h = angular_momentum(spin, c.spin_inertia) + c.spin_inertia * roll;
    const T j2 = yaw_inertia_at_pitch(c.yaw_inertia, c.spin_inertia, tan_pitch);
    const RotorParameters<T> p{c.pitch_inertia, j2, c.friction, h};
    const T beta_sq = detail::rate_matrix_terms(p).beta_sq;
    // The torquers roll with the inner gimbal about the spin axis; the nutation turns with the
    // spin, so they see it slower by the roll.
    const T beta = (beta_sq > T(0) && std::isfinite(beta_sq)) ? std::abs(std::sqrt(beta_sq) - roll) : T(0);
    if (beta >= beta_low_ && beta <= beta_high_) return u;
    beta_ = beta;
    beta_low_ = beta * (T(1) - kBetaTolerance);
    beta_high_ = beta * (T(1) + kBetaTolerance);
    const T per_tick = beta_ * c.tick_s;  // nutation phase a tick
    // Fewer than two ticks per nutation period: the pickoffs alias the nutation.
    aliased_ = per_tick > kPi<T>;
    u.redesigned = true;
    u.shaper = design_shaper(per_tick);
    return u;
  }

  // A new rotor: the next tick designs afresh.
  void forget() noexcept {
    beta_low_ = T(-1);
    beta_high_ = T(-2);
  }

  [[nodiscard]] T beta_rad_s() const noexcept { return beta_; }  // 0 if the modes cannot be computed
  [[nodiscard]] bool aliased() const noexcept { return aliased_; }

 private:
  T beta_low_{-1};  // the nutation frequencies the design is kept for
  T beta_high_{-2};
  T beta_{};
  bool aliased_{false};
};

}  // namespace gyro
