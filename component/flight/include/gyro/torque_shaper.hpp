// The torque shaper's design: a three-tap filter with a zero at the nutation frequency,
//   a w[k] + (1 - 2a) w[k-m] + a w[k-2m],  a = 1 / (2 (1 - cos(m phi))),
// m the fewest ticks with m phi >= pi/2 (every tap >= 0, so the output never exceeds the
// largest input). phi is the nutation's phase a tick folded into [0, pi]: the ticks sample
// the torque, so a tick of beta dt and one of 2 pi n +- beta dt excite the nutation alike;
// the notch is kept while m beta dt is within a turn (below).
// One design for the component (which applies it) and for the configuration contract (which
// asks for the bearings' damping where there is none; docs/component.md).
// No heap, no exceptions, no RTTI; C++17.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "gyro/rotor_parameters.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

// The longest spacing m the component's history holds (2 m + 1 torques).
inline constexpr std::uint32_t kShaperMaxSpacing = 15;

template <typename T>
struct ShaperDesign {
  std::uint32_t spacing{0};  // m; 0: no shaper (phi is 0, m would pass kShaperMaxSpacing, or m beta dt a turn)
  T edge{};                  // a
};

// A phase a tick folded into [0, pi]: what the ticks' samples of it see.
template <typename T>
[[nodiscard]] T folded_phase(T per_tick) noexcept {
  const T turn = T(2) * kPi<T>;
  const T wrapped = per_tick - turn * std::floor(per_tick / turn);
  const T folded = std::min(wrapped, turn - wrapped);
  return folded;
}

// The design for a nutation phase of `per_tick` rad a tick (beta dt, >= 0 and finite).
template <typename T>
[[nodiscard]] ShaperDesign<T> design_shaper(T per_tick) noexcept {
  ShaperDesign<T> d;
  const T turn = T(2) * kPi<T>;
  const T folded = folded_phase(per_tick);
  if (!(folded > T(0))) return d;
  const T spacing = std::ceil(kPi<T> / (T(2) * folded));
  // A relative error e in beta lets through about e m beta dt of a step's nutation: past a
  // turn of m beta dt (a tick aliasing the nutation by a turn or more) the notch is no better
  // than none, and its 2 m ticks of delay only slow the loops.
  if (!(spacing <= T(kShaperMaxSpacing)) || !(spacing * per_tick <= turn)) return d;
  d.spacing = static_cast<std::uint32_t>(spacing);
  d.edge = T(1) / (T(2) * (T(1) - std::cos(spacing * folded)));
  return d;
}

// The share of a nutation of `per_tick` rad a tick that a design lets through: its gain there,
// |a + (1 - 2a) e^-i m phi + a e^-2i m phi| = |1 - 2a (1 - cos m phi)| (0 at the design's
// phase, 1 at zero frequency and with no shaper).
template <typename T>
[[nodiscard]] T shaper_leakage(const ShaperDesign<T>& d, T per_tick) noexcept {
  if (d.spacing == 0u) return T(1);
  return std::abs(T(1) - T(2) * d.edge * (T(1) - std::cos(static_cast<T>(d.spacing) * folded_phase(per_tick))));
}

// The filter itself: the torque law's last outputs through the design in use. A step of
// torque sets the rotor nutating (amplitude dT / (H beta)), and the plant's nutation then
// drifts out of phase with the estimator's; through the shaper a step excites no nutation at
// beta, for m ticks of delay.
template <typename T>
class TorqueShaper {
 public:
  TorqueShaper() noexcept { clear(); }  // Eigen leaves its vectors unset
  void use(const ShaperDesign<T>& d) noexcept { design_ = d; }

  // The torque to write for the law's `wanted`, within +-max_torque.
  [[nodiscard]] Vector2<T> shape(const Vector2<T>& wanted, T max_torque) noexcept {
    head_ = (head_ + 1u) & kMask;
    history_[head_] = wanted;
    if (design_.spacing == 0u) return wanted;
    const Vector2<T>& mid = history_[(head_ - design_.spacing) & kMask];
    const Vector2<T>& old = history_[(head_ - 2u * design_.spacing) & kMask];
    // Written about the middle tap (equal taps give it back exactly); rounding can still pass
    // the limit by an ulp, hence the clamp.
    const Vector2<T> out = mid + design_.edge * ((wanted - mid) + (old - mid));
    return Vector2<T>(saturate(out(0), max_torque), saturate(out(1), max_torque));
  }

  // Forgets the history: the next torques start from rest.
  void clear() noexcept { history_.fill(Vector2<T>::Zero()); }

 private:
  // A power of two of at least 2 kShaperMaxSpacing + 1 entries: the ring's index is masked (the
  // unsigned difference wraps to the same entry), not divided.
  static constexpr std::uint32_t kLength = 32;
  static constexpr std::uint32_t kMask = kLength - 1u;
  static_assert((kLength & kMask) == 0u && kLength >= 2u * kShaperMaxSpacing + 1u);
  std::array<Vector2<T>, kLength> history_;
  std::uint32_t head_{0};
  ShaperDesign<T> design_{};
};

}  // namespace gyro
