// Configuration of the nonlinear two-axis gimbal plant (gyro/gimbal_plant.hpp): the device's
// inertias, bearings, spin drive, mass unbalance and stop, the envelope of inputs it accepts,
// and the accuracy of its integration. docs/gimbal-plant.md derives the equations and says how
// each field enters them; docs/conventions.md fixes the frames and signs.
//
// Units: any consistent set (SI below: kg m^2, N m, N m s, rad/s, m/s^2).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>

#include "gyro/attitude.hpp"  // Vector3
#include "gyro/config_check.hpp"
#include "gyro/config_fields.hpp"
#include "gyro/rotor_parameters.hpp"  // all_finite, kPi, Vector2
#include "gyro/torquer_axes.hpp"

namespace gyro {

// How the rotor's spin relative to the inner gimbal is driven.
enum class SpinDrive : std::uint8_t {
  kMotor = 0,  // a motor holds the commanded relative spin rate, within its torque limit
  kFree,       // no motor: the rotor runs down against its bearing drag (if any)
};
// The names of SpinDrive's values in configuration files, in enum order.
[[nodiscard]] constexpr std::array<const char*, 2> enum_names(SpinDrive /*tag*/) noexcept { return {"motor", "free"}; }

template <typename T>
struct GimbalPlantConfig {
  // Rotor, axisymmetric about the spin axis (inner gimbal x).
  T spin_inertia{};              // J0, about the spin axis
  T rotor_transverse_inertia{};  // A, about any axis normal to it through the gimbal centre
  // Principal moments of each gimbal about its own axes (x, y, z); zero for a massless gimbal.
  Vector3<T> inner_gimbal_inertia{Vector3<T>::Zero()};  // inner: y is the pitch axis
  Vector3<T> outer_gimbal_inertia{Vector3<T>::Zero()};  // outer: z is the yaw axis (body z)

  // Bearing friction on the gimbal rates (relative to the carrier in kGimbal axes).
  T inner_friction{};          // viscous, torque per rad/s, pitch axis
  T outer_friction{};          // viscous, yaw axis
  T inner_coulomb_torque{};    // dry friction magnitude, pitch axis
  T outer_coulomb_torque{};    // dry friction magnitude, yaw axis
  // Dry friction is C tanh(rate / scale): smooth, so a fixed-step high-order method stays
  // accurate; within 0.5 % of C sign(rate) once |rate| > 3 scale, viscous C/scale below.
  T coulomb_rate_scale_rad_s{T(0.01)};

  // Spin, relative to the inner gimbal.
  SpinDrive spin_drive{SpinDrive::kMotor};
  T max_spin_hz{};                 // the fastest spin start() and the motor accept
  T motor_torque_limit{};          // kMotor: the largest torque the motor gives (> 0)
  T spin_servo_bandwidth_rad_s{};  // kMotor: spin acceleration = bandwidth * (command - spin);
                                   // 0 holds the spin's acceleration at zero
  T spin_down_time_s{};            // bearing drag J0 / spin_down_time_s (0: no drag)

  // Mass unbalance of the rotor along +spin axis (mass times offset): torque
  // -mass_unbalance * spin_axis x specific_force on the rotor (g-sensitive drift).
  T mass_unbalance{};

  // Mechanical stop on the total cone angle between spin axis and body x.
  T stop_cone_rad{};      // kMinGimbalStopCone <= stop <= kMaxGimbalStopCone (gimbal lock out of reach)
  T stop_restitution{};   // in [0, 1]: 0 a dead stop, 1 an elastic bounce

  TorquerAxes torquer_axes{TorquerAxes::kGimbal};

  // Envelope of step inputs; beyond it a step is refused (kOutOfRange).
  T max_body_rate_rad_s{};   // |(p, q, r)|; also enters the sub-step rule
  T max_torque{};            // |T1|, |T2|
  T max_specific_force{};    // |specific force|

  // Integration accuracy (docs/gimbal-plant.md). The bound: no sub-step spans more than this
  // phase (rad) of the fastest motion, which fixes the most sub-steps a tick takes.
  T max_substep_phase_rad{T(0.5)};
  // The requirement: the gimbal-angle error the integration may add per simulated second.
  // Each tick takes the fewest sub-steps (up to the bound) whose estimated error stays within
  // its share of it. 0: the tight setting, every tick at the bound (the reference); the SIL
  // stub puts its pickoff's target in place of 0 (gyro/simulated_gyro.hpp).
  T error_target_rad{};
};

// The fields (gyro/config_fields.hpp). A scenario gives the rotor's spin inertia, its spin and
// the stop in its "rotor" and "limits" (implied here); check() adds the cross-field rules.
template <typename T>
struct FieldTable<GimbalPlantConfig<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Rule kPos = Rule::kPositive, kNonNeg = Rule::kNonNegative;
    constexpr Status kRange = Status::kOutOfRange, kInertia = Status::kNonPositiveInertia;
    constexpr Status kFriction = Status::kNegativeFriction;
    constexpr Presence kReq = Presence::kRequired, kOpt = Presence::kOptional, kImplied = Presence::kImplied;
    constexpr const char* kUnits = "consistent units: products with rates and spins stay within float's range";
    constexpr const char* kTime = "0 (none) or up to 10 times the longest run (1e8 ticks of at most 1 s)";
    v(Field{"spin_inertia", kPos, kInertia, kImplied, nullptr, 1e-12, 1e12, "inertia", kUnits}, c.spin_inertia...);
    v(Field{"rotor_transverse_inertia", kPos, kInertia, kReq, nullptr, 1e-12, 1e12, "inertia",
            "J0/2 up to a million times J0 (a rigid rotor; check()); consistent units"}, c.rotor_transverse_inertia...);
    v(Field{"inner_gimbal_inertia", kNonNeg, kInertia, kReq, nullptr, 0.0, 1e12, "inertia",
            "0 (a massless ring) up to a million times J0, each moment within the sum of the others"},
      c.inner_gimbal_inertia...);
    v(Field{"outer_gimbal_inertia", kNonNeg, kInertia, kReq, nullptr, 0.0, 1e12, "inertia",
            "0 (a massless ring) up to a million times J0, each moment within the sum of the others"},
      c.outer_gimbal_inertia...);
    v(Field{"inner_friction", kNonNeg, kFriction, kOpt, nullptr, 0.0, 1e12, "torque/(rad/s)",
            "a scenario's default is rotor.friction; consistent units"}, c.inner_friction...);
    v(Field{"outer_friction", kNonNeg, kFriction, kOpt, nullptr, 0.0, 1e12, "torque/(rad/s)",
            "a scenario's default is rotor.friction; consistent units"}, c.outer_friction...);
    v(Field{"inner_coulomb_torque", kNonNeg, kFriction, kOpt, nullptr, 0.0, 1e12, "torque",
            "dry friction's magnitude; consistent units"}, c.inner_coulomb_torque...);
    v(Field{"outer_coulomb_torque", kNonNeg, kFriction, kOpt, nullptr, 0.0, 1e12, "torque",
            "dry friction's magnitude; consistent units"}, c.outer_coulomb_torque...);
    v(Field{"coulomb_rate_scale_rad_s", kPos, kRange, kOpt, nullptr, 1e-6, 1.0, "rad/s",
            "the tanh's width: below 1 urad/s its slope C/scale would set the sub-steps; above 1 rad/s the dry "
            "friction is viscous at every gimbal rate"},
      c.coulomb_rate_scale_rad_s...);
    v(Field{"spin_drive", Rule::kNone, kRange, kOpt, nullptr, -kNoBound, kNoBound, "",
            "a motor holds the spin relative to the inner ring, or the rotor runs down free"},
      c.spin_drive...);
    v(Field{"max_spin_hz", kPos, kRange, kImplied, nullptr, 1e-3, 1e5, "Hz", "a rotor spins at up to 100 kHz"},
      c.max_spin_hz...);
    v(Field{"motor_torque_limit", kNonNeg, kRange, kOpt, nullptr, 0.0, 1e12, "torque",
            "> 0 and required with spin_drive \"motor\" (check()); unused by a free rotor"},
      c.motor_torque_limit...);
    v(Field{"spin_servo_bandwidth_rad_s", kNonNeg, kRange, kOpt, nullptr, 0.0, 1e6, "rad/s",
            "0 (the spin's acceleration held at zero) to 1e6 rad/s, beyond any motor's loop; it adds to the "
            "fastest rate the sub-steps resolve"},
      c.spin_servo_bandwidth_rad_s...);
    v(Field{"spin_down_time_s", kNonNeg, kRange, kOpt, nullptr, 0.0, 1e9, "s", kTime}, c.spin_down_time_s...);
    v(Field{"mass_unbalance", Rule::kFinite, kRange, kOpt, nullptr, -1e12, 1e12, "mass x length",
            "rotor mass times its offset, either way along the spin axis; consistent units"},
      c.mass_unbalance...);
    v(Field{"stop_cone_rad", kPos, kRange, kImplied, nullptr, 1e-3, 1.3962634015954636, "rad", "1 mrad to 80 deg: gimbal lock out of reach"}, c.stop_cone_rad...);
    v(Field{"stop_restitution", kNonNeg, kRange, kOpt, nullptr, 0.0, 1.0, "", "0 a dead stop to 1 an elastic bounce"}, c.stop_restitution...);
    v(Field{"torquer_axes", Rule::kNone, kRange, kOpt, nullptr, -kNoBound, kNoBound, "",
            "about the gimbal axes (the device) or the gyro's own (the report's idealisation)"},
      c.torquer_axes...);
    v(Field{"max_body_rate_rad_s", kPos, kRange, kOpt, nullptr, 1e-4, 1e4, "rad/s",
            "the component's envelope of body rates, 0.006 deg/s to 1e4 rad/s"},
      c.max_body_rate_rad_s...);
    v(Field{"max_torque", kPos, kRange, kOpt, nullptr, 1e-12, 1e12, "torque", kUnits}, c.max_torque...);
    v(Field{"max_specific_force", kPos, kRange, kOpt, nullptr, 1e-3, 1e7, "accel",
            "in the units of gyro.gravity: up to 1e6 g in m/s^2 (a gun launch is 2e4 g)"},
      c.max_specific_force...);
    v(Field{"max_substep_phase_rad", kPos, kRange, kOpt, nullptr, 1e-6, 2.0, "rad",
            "the bound of the sub-step rule: the most sub-steps a tick takes (docs/gimbal-plant.md)"},
      c.max_substep_phase_rad...);
    v(Field{"error_target_rad", kNonNeg, kRange, kOpt, nullptr, 0.0, 1e-2, "rad",
            "the integration's gimbal-angle error per simulated second; 0: the SIL stub's, from the pickoff "
            "(docs/gimbal-plant.md)"},
      c.error_target_rad...);
  }
};

// 80 deg: the outer axis's effective inertia falls as cos^2 of the pitch angle (gimbal lock at
// 90 deg); a stop up to here keeps it above 3 % of its value at zero.
template <typename T>
inline constexpr T kMaxGimbalStopCone = T(1.3962634015954636);
// A stop closer than a milliradian is no gimbal freedom (and its contact's sub-steps
// would not resolve it).
template <typename T>
inline constexpr T kMinGimbalStopCone = T(1e-3);
// The most sub-steps a configuration may ask for per tick (bounds the cost of one step).
inline constexpr int kMaxGimbalSubsteps = 4096;

namespace gimbal_detail {
// Principal moments of a rigid body: each no larger than the sum of the other two.
template <typename T>
[[nodiscard]] bool is_physical(const Vector3<T>& m) noexcept {
  return m(0) <= m(1) + m(2) && m(1) <= m(0) + m(2) && m(2) <= m(0) + m(1);
}
}  // namespace gimbal_detail

// The largest transverse (rotor or ring) inertia, as a multiple of the spin inertia.
template <typename T>
inline constexpr T kMaxInertiaRatio = T(1e6);

template <typename T>
[[nodiscard]] ConfigCheck check(const GimbalPlantConfig<T>& c) noexcept {
  const FieldRefusal r = first_refusal<RealFields>(c);
  if (r.status != Status::kOk) return r.check;
  if (!(c.spin_inertia <= T(2) * c.rotor_transverse_inertia)) {
    return {Status::kOutOfRange, "rotor_transverse_inertia"};  // J0 <= 2A for a rigid rotor
  }
  const Vector3<T>* gimbals[] = {&c.inner_gimbal_inertia, &c.outer_gimbal_inertia};
  const char* gimbal_names[] = {"inner_gimbal_inertia", "outer_gimbal_inertia"};
  for (int i = 0; i < 2; ++i) {
    if (!gimbal_detail::is_physical(*gimbals[i])) return {Status::kOutOfRange, gimbal_names[i]};
  }
  // Transverse inertias beyond a million times the spin inertia are no gyro (and their sums
  // with the rotor's overflow first).
  if (!(c.rotor_transverse_inertia <= kMaxInertiaRatio<T> * c.spin_inertia)) {
    return {Status::kOutOfRange, "rotor_transverse_inertia"};
  }
  for (int i = 0; i < 2; ++i) {
    if (!(gimbals[i]->maxCoeff() <= kMaxInertiaRatio<T> * c.spin_inertia)) return {Status::kOutOfRange, gimbal_names[i]};
  }
  if (c.spin_drive != SpinDrive::kMotor && c.spin_drive != SpinDrive::kFree) {
    return {Status::kOutOfRange, "spin_drive"};
  }
  if (c.torquer_axes != TorquerAxes::kGimbal && c.torquer_axes != TorquerAxes::kGyro) {
    return {Status::kOutOfRange, "torquer_axes"};
  }
  if (c.spin_drive == SpinDrive::kMotor) {
    if (!std::isfinite(c.motor_torque_limit)) return {Status::kNonFiniteInput, "motor_torque_limit"};
    if (!(c.motor_torque_limit > T(0))) return {Status::kOutOfRange, "motor_torque_limit"};
  }
  if (!(c.stop_cone_rad <= kMaxGimbalStopCone<T> && c.stop_cone_rad >= kMinGimbalStopCone<T>)) {
    return {Status::kOutOfRange, "stop_cone_rad"};
  }
  if (!(c.stop_restitution <= T(1))) return {Status::kOutOfRange, "stop_restitution"};
  if (!(c.max_substep_phase_rad <= T(2))) return {Status::kOutOfRange, "max_substep_phase_rad"};
  return {};
}

}  // namespace gyro
