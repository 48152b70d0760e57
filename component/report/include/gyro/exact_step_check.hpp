// Configuration check shared by the component and the SIL stub: the rotor's exact step over
// one tick must be representable, and when it is not, the refusal names the input responsible
// rather than always the tick.
#pragma once

#include <algorithm>
#include <cmath>

#include "gyro/gyro_model.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/rotor_transition.hpp"
#include "gyro/status.hpp"

namespace gyro {

// The names, in the caller's configuration, of the inputs of the exact step.
struct ExactStepFields {
  const char* pitch_inertia;
  const char* yaw_inertia;
  const char* spin_inertia;
  const char* friction;
  const char* spin_hz;
  const char* tick;
};

namespace detail {

// How far a positive value is from 1 in magnitude (0 for 0): the input furthest from 1 is
// the one that pushes a product or quotient of them out of range.
template <typename T>
[[nodiscard]] T extremeness(T v) noexcept {
  return v > T(0) ? std::abs(std::log(v)) : T(0);
}

template <typename T>
[[nodiscard]] const char* more_extreme(T a, const char* a_name, T b, const char* b_name) noexcept {
  return extremeness(b) > extremeness(a) ? b_name : a_name;
}

}  // namespace detail

// Inputs already checked finite and in range (inertias > 0, friction >= 0, spin > 0, tick
// > 0). kNumericalOverflow names:
//   - when the rotor itself is not representable (H = 2 pi spin J0, or the rate terms of
//     J1, J2, f and H, overflow): the input furthest from 1 in magnitude among those in the
//     quantity that overflowed (the spin or J0 when it is H);
//   - when the rotor is but its exact step over the tick is not: the tick (a shorter one
//     would do).
template <typename T>
[[nodiscard]] ConfigCheck check_exact_step(T pitch_inertia, T yaw_inertia, T spin_inertia, T friction, T spin_hz,
                                           T tick_s, const ExactStepFields& names) noexcept {
  const char* const spin_part = detail::more_extreme(spin_hz, names.spin_hz, spin_inertia, names.spin_inertia);
  const T h = angular_momentum(spin_hz, spin_inertia);
  if (!std::isfinite(h)) return {Status::kNumericalOverflow, spin_part};
  const RotorParameters<T> rotor{pitch_inertia, yaw_inertia, friction, h};
  RotorModes<T> modes;
  if (compute_modes(rotor, modes) != Status::kOk) {
    const char* culprit = detail::more_extreme(pitch_inertia, names.pitch_inertia, yaw_inertia, names.yaw_inertia);
    T worst = std::max(detail::extremeness(pitch_inertia), detail::extremeness(yaw_inertia));
    if (detail::extremeness(friction) > worst) {
      culprit = names.friction;
      worst = detail::extremeness(friction);
    }
    if (detail::extremeness(h) > worst) culprit = spin_part;
    return {Status::kNumericalOverflow, culprit};
  }
  RotorTransition<T> tr;
  if (make_transition(rotor, tick_s, tr) != Status::kOk) return {Status::kNumericalOverflow, names.tick};
  return {};
}

}  // namespace gyro
