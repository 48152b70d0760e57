// The nutation tracker: the rotor's nutation frequency at the spin flown, whether the tick
// aliases it, and the torque shaper's design for it (gyro/torque_shaper.hpp).
//
// All are kept until the spin moves kSpinTolerance away from the spin they were made for. A
// spinning-down rotor's readback changes every tick; the notch is not that narrow (a relative
// error e in beta lets through about 2 e of the nutation a step of torque excites, and the
// plant's own beta moves by more with the gimbal angles), so the design is redone every few
// hundred ticks of a spin-down, not every tick. (The estimator follows every readback: its
// transition is physics.)
#pragma once

#include <cmath>

#include "gyro/rotor_parameters.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {

template <typename T>
struct NutationUpdate {
  bool redesigned{false};  // the spin moved: `shaper` is the new design
  ShaperDesign<T> shaper{};
};

template <typename T>
class NutationTracker {
 public:
  // The design follows the spin within this fraction.
  static constexpr T kSpinTolerance = T(1e-3);

  // Once per tick, at the spin flown (finite, >= 0); the inertias and friction were checked
  // by the configuration contract: the rate-matrix terms alone (compute_modes() without its
  // checks and other modes).
  template <typename Config>
  [[nodiscard]] NutationUpdate<T> follow(T spin, const Config& c) noexcept {
    NutationUpdate<T> u;
    if (spin >= spin_low_ && spin <= spin_high_) return u;
    const RotorParameters<T> p{c.pitch_inertia, c.yaw_inertia, c.friction, angular_momentum(spin, c.spin_inertia)};
    const T beta_sq = detail::rate_matrix_terms(p).beta_sq;
    beta_ = (beta_sq > T(0) && std::isfinite(beta_sq)) ? std::sqrt(beta_sq) : T(0);
    spin_low_ = spin * (T(1) - kSpinTolerance);
    spin_high_ = spin * (T(1) + kSpinTolerance);
    const T per_tick = beta_ * c.tick_s;  // nutation phase a tick
    // Fewer than two ticks per nutation period: the pickoffs alias the nutation.
    aliased_ = per_tick > kPi<T>;
    u.redesigned = true;
    u.shaper = design_shaper(per_tick);
    return u;
  }

  // A new rotor: the next tick designs afresh.
  void forget() noexcept {
    spin_low_ = T(-1);
    spin_high_ = T(-2);
  }

  [[nodiscard]] T beta_rad_s() const noexcept { return beta_; }  // 0 if the modes cannot be computed
  [[nodiscard]] bool aliased() const noexcept { return aliased_; }

 private:
  T spin_low_{-1};  // the spins the design is kept for
  T spin_high_{-2};
  T beta_{};
  bool aliased_{false};
};

}  // namespace gyro
