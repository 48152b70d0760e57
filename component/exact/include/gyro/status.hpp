// Status values returned by every fallible call in gyro. A call that returns anything
// but Status::kOk or Status::kInputIgnored has left its object's state exactly as it was.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace gyro {

enum class Status : std::uint8_t {
  kOk = 0,
  kNonFiniteInput,          // a NaN or an infinity among the inputs
  kNonPositiveInertia,      // J1, J2 or the spin inertia is <= 0
  kNegativeFriction,        // f < 0
  kNegativeAngularMomentum, // H < 0 (or a negative spin rate)
  kNonPositiveStep,         // dt <= 0
  kNoSteadyState,           // f = H = 0: torque accelerates the gimbals without bound
  kOutOfRange,              // a finite input outside its physical range
  kNumericalOverflow,       // the result would not be representable in the scalar type
  kNotConfigured,           // called before a successful configure()
  kInvalidRotation,         // a rotation matrix that is not orthonormal
  kWrongMode,               // not allowed in the current mode (e.g. configure while active)
  kInputIgnored,            // the call ran, without some unusable input fields (flags say which)
};

// Each status's name (as the Python binding spells it: gyro.Status), in enumerator order.
[[nodiscard]] constexpr std::array<const char*, 13> enum_names(Status /*tag*/) noexcept {
  return {"ok", "non_finite_input", "non_positive_inertia", "negative_friction", "negative_angular_momentum",
          "non_positive_step", "no_steady_state", "out_of_range", "numerical_overflow", "not_configured",
          "invalid_rotation", "wrong_mode", "input_ignored"};
}
static_assert(enum_names(Status{}).size() == static_cast<std::size_t>(Status::kInputIgnored) + 1,
              "a name for every Status");

[[nodiscard]] constexpr const char* to_string(Status s) noexcept {
  switch (s) {
    case Status::kOk: return "ok";
    case Status::kNonFiniteInput: return "non-finite input";
    case Status::kNonPositiveInertia: return "inertia must be > 0";
    case Status::kNegativeFriction: return "friction must be >= 0";
    case Status::kNegativeAngularMomentum: return "angular momentum must be >= 0";
    case Status::kNonPositiveStep: return "time step must be > 0";
    case Status::kNoSteadyState: return "no steady precession without spin or friction";
    case Status::kOutOfRange: return "input out of range";
    case Status::kNumericalOverflow: return "result not representable";
    case Status::kNotConfigured: return "not configured";
    case Status::kInvalidRotation: return "rotation matrix not orthonormal";
    case Status::kWrongMode: return "not allowed in this mode";
    case Status::kInputIgnored: return "ran with unusable inputs ignored";
  }
  return "unknown status";
}

}  // namespace gyro
