// The flight component's interface types: configuration, per-tick guidance input, modes,
// flags and telemetry. Kept apart from the logic so ground tools can include them alone.
#pragma once

#include <array>
#include <cstdint>

#include "gyro/attitude.hpp"
#include "gyro/config_fields.hpp"
#include "gyro/status.hpp"

namespace gyro {

// Modes (see docs/component.md for the transitions):
//   kIdle      constructed or configured, not yet activated: no port traffic
//   kCaged     electrically caged: the torquers slave the spin axis to the body x axis
//   kUncaging  the report's uncaging initialisation done; torquers off while it settles
//   kFree      free gyro: precesses at the commanded slew rates (zero = hold inertially)
//   kFault     safe mode: torquers off; left only by a cage request once the fault clears
enum class GyroMode : std::uint8_t { kIdle = 0, kCaged, kUncaging, kFree, kFault };

// The names of the modes in logs, CSV files and bindings, in enum order.
[[nodiscard]] constexpr std::array<const char*, 5> enum_names(GyroMode /*tag*/) noexcept {
  return {"idle", "caged", "uncaging", "free", "fault"};
}

// What guidance asks for this tick.
enum class ModeRequest : std::uint8_t { kNone = 0, kCage, kUncage };
// The names of the requests in scenario files and logs, in enum order.
[[nodiscard]] constexpr std::array<const char*, 3> enum_names(ModeRequest /*tag*/) noexcept {
  return {"none", "cage", "uncage"};
}

// Flag bits, raised for the tick in which the condition holds (telemetry.flags) and counted
// (telemetry.counters, index = bit number). The inputs a tick ignored are flagged here too:
// the tick still ran (docs/component.md, "Corrupt input").
enum ComponentFlag : std::uint32_t {
  kGimbalLimit = 1u << 0,        // estimated spin axis outside the gimbal cone / axis limits
  kSmallAngleExceeded = 1u << 1, // a tick's angles or nutation amplitude beyond the limit
  kNutationUnresolved = 1u << 2, // fewer than 2 ticks per nutation period: pickoffs alias it
  kPickoffInvalid = 1u << 3,     // port failed, valid bit clear, non-finite or out of range
  kPickoffStale = 1u << 4,       // sequence counter did not advance
  kPickoffJump = 1u << 5,        // implausible change since the last accepted reading
  kResidualFault = 1u << 6,      // |measured - predicted| over its bound for long enough
  kTorquerSaturated = 1u << 7,   // the torque law asked more than the torquer gives
  kSpinLow = 1u << 8,            // spin below its minimum (readback or configured)
  kTorquerWriteFailed = 1u << 9, // the port refused the torquer command
  kNavInvalid = 1u << 10,        // navigation marked invalid, or its attitude/rates unusable
  kCommandRejected = 1u << 11,   // a guidance command field unusable: ignored (slew held)
  kTickSkipped = 1u << 12,       // tick count jumped by 2..max_tick_gap: the gap was bridged
  kGimbalStopProtect = 1u << 13, // stop protection moved the rate: the gimbal is held off its stop
  kFaultLatched = 1u << 14,      // in safe mode
  kTickInvalid = 1u << 15,       // tick count repeated, went back or jumped too far: one tick
  kNotActive = 1u << 16,         // step() before activate(): refused (nothing else changes)
  kInputFault = 1u << 17,        // unusable guidance input (commands, tick) for long enough
  kSlewRateLimited = 1u << 18,   // the rate wanted (slew, or caging on the body) cut to its limit
  kStopBeyondAuthority = 1u << 19, // the torquer cannot hold the gimbal's outward motion: it may reach its stop
  kRequestRefused = 1u << 20,    // a mode request that could not be carried out was dropped
};
inline constexpr int kComponentFlagCount = 21;

// The name of a flag bit as logs and CSV files spell it ("pickoff_invalid"); "" if none.
[[nodiscard]] constexpr const char* flag_name(int bit) noexcept {
  constexpr const char* kNames[kComponentFlagCount] = {
      "gimbal_limit",    "small_angle_exceeded", "nutation_unresolved", "pickoff_invalid",
      "pickoff_stale",   "pickoff_jump",         "residual_fault",      "torquer_saturated",
      "spin_low",        "torquer_write_failed", "nav_invalid",         "command_rejected",
      "tick_skipped",    "gimbal_stop_protect",  "fault_latched",       "tick_invalid",
      "not_active",      "input_fault",          "slew_rate_limited",   "stop_beyond_authority",
      "request_refused"};
  return (bit >= 0 && bit < kComponentFlagCount) ? kNames[bit] : "";
}

// Saturating counts per flag bit (gyro/flag_counters.hpp).
using FlagCounts = std::array<std::uint32_t, kComponentFlagCount>;

template <typename T>
struct GyroComponentConfig {
  T tick_s{};                    // the fixed tick of the rate group
  // Rotor (units consistent with the torques: SI or the report's slug*ft^2).
  T pitch_inertia{};
  T yaw_inertia{};
  T spin_inertia{};
  T friction{};
  T nominal_spin_hz{};           // used when the hardware has no spin readback
  T min_spin_hz{};               // below this the gyro is no reference: spin-low fault
  bool use_spin_readback{true};  // take H from the port's spin readback when it is valid
  // Torque law.
  T max_pitch_rate_rad_s{};      // slew-rate limits
  T max_yaw_rate_rad_s{};
  T max_torque{};                // torquer saturation, per axis (torque units)
  bool friction_compensation{true};  // exact inverse of the friction-coupled precession
  T cage_gain_1_s{};             // caging loop: commanded rate = body rate - gain * gimbal
  // Gimbals.
  T gimbal_cone_limit_rad{};     // mechanical cone
  T gimbal_stop_margin_rad{};    // no slewing toward a stop closer than this
  T small_angle_limit_rad{T(0.01)};
  // Pickoff validation.
  T pickoff_range_rad{};         // physical range of the pickoffs
  T max_pickoff_step_rad{};      // largest believable change between two ticks
  // Estimation and fault detection.
  T estimator_gain{};            // fraction of the residual fed back per tick (0..1)
  T residual_limit_rad{};        // bound on |measured - predicted|
  // Persistences N (gyro/persistence.hpp): N consecutive ticks latch the fault, and so does
  // the condition in more than one tick in three, given time.
  std::uint32_t residual_persistence_ticks{};  // |residual| over its bound -> fault
  std::uint32_t invalid_persistence_ticks{};   // bad/stale/implausible readings -> fault
  std::uint32_t spin_low_persistence_ticks{};
  std::uint32_t torquer_fail_persistence_ticks{};
  std::uint32_t uncage_settle_ticks{};         // ticks in kUncaging before kFree
  // Fail-operational input handling (docs/component.md, "Corrupt input").
  std::uint32_t max_tick_gap{8};               // largest tick-count jump bridged as lost ticks
  std::uint32_t input_persistence_ticks{50};   // unusable guidance input -> fault
  T max_body_rate_rad_s{T(100)};               // navigation rates beyond this are not believed
  // What the board promises of its pickoffs (docs/component.md, "Configuration contract"):
  // 0 = not stated (the rules that use them are then not applied). check() holds the residual
  // limit and the pickoff step above them.
  T pickoff_lsb_rad{};                         // the pickoff's quantisation step
  T pickoff_noise_rad{};                       // 1-sigma noise of one reading
};

// The stated longest time of the contract: no persistence, settle time or bridged gap may
// last longer (a fault left undetected, or the torquers left off, for longer than this is no
// protection in a flight of tens of seconds); the slowest caging loop pulls in within it.
inline constexpr double kLongestConfiguredTime_s = 10.0;

// The fields of GyroComponentConfig (gyro/config_fields.hpp); check() adds the cross-field rules.
template <typename T>
struct FieldTable<GyroComponentConfig<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Rule kPos = Rule::kPositive, kNonNeg = Rule::kNonNegative, kCount = Rule::kNonZero;
    constexpr Rule kAny = Rule::kFinite;
    constexpr Status kRange = Status::kOutOfRange, kInertia = Status::kNonPositiveInertia;
    constexpr Presence kReq = Presence::kRequired, kOpt = Presence::kOptional;
    constexpr const char* kNo = nullptr;
    constexpr double kCountMax = 4294967295.0;  // the counters' range; the longest time bounds them (check_all)
    constexpr const char* kUnits = "consistent units: products with rates and spins stay within float's range";
    constexpr const char* kTime = "with the tick, at most the longest configured span, 10 s";
    v(Field{"tick_s", kPos, Status::kNonPositiveStep, Presence::kImplied, kNo, 1e-5, 0.1, "s",
            "a rate group of 10 Hz to 100 kHz"}, c.tick_s...);
    v(Field{"pitch_inertia", kPos, kInertia, kReq, kNo, 1e-12, 1e12, "inertia", kUnits}, c.pitch_inertia...);
    v(Field{"yaw_inertia", kPos, kInertia, kReq, kNo, 1e-12, 1e12, "inertia", kUnits}, c.yaw_inertia...);
    v(Field{"spin_inertia", kPos, kInertia, kReq, kNo, 1e-12, 1e12, "inertia", kUnits}, c.spin_inertia...);
    v(Field{"friction", kNonNeg, Status::kNegativeFriction, kReq, kNo, 0.0, 1e12, "torque/(rad/s)", kUnits},
      c.friction...);
    v(Field{"nominal_spin_hz", kPos, kRange, kReq, kNo, 1.0, 1e5, "Hz", "a gyro rotor spins at 1 Hz to 100 kHz"},
      c.nominal_spin_hz...);
    v(Field{"min_spin_hz", kNonNeg, kRange, kReq, kNo, 0.0, 1e5, "Hz", "below nominal_spin_hz"}, c.min_spin_hz...);
    v(Field{"use_spin_readback", Rule::kNone, kRange, kOpt}, c.use_spin_readback...);
    v(Field{"max_pitch_rate_rad_s", kPos, kRange, kReq, kNo, 1e-4, 100.0, "rad/s",
            "a slew limit of 0.006 deg/s to 100 rad/s; one tick's turn within the small-angle limit"},
      c.max_pitch_rate_rad_s...);
    v(Field{"max_yaw_rate_rad_s", kPos, kRange, kReq, kNo, 1e-4, 100.0, "rad/s",
            "a slew limit of 0.006 deg/s to 100 rad/s; one tick's turn within the small-angle limit"},
      c.max_yaw_rate_rad_s...);
    v(Field{"max_torque", kPos, kRange, kReq, kNo, 1e-12, 1e12, "torque",
            "precesses at half the larger rate limit or more; a full-torque step's nutation within a tenth of the small-angle limit"},
      c.max_torque...);
    v(Field{"friction_compensation", Rule::kNone, kRange, kOpt}, c.friction_compensation...);
    v(Field{"cage_gain_1_s", kPos, kRange, kReq, kNo, 0.1, 1e5, "1/s",
            "caging pulls in within 10 s; gain x tick <= 1 (a monotone discrete loop); gain x pickoff jitter within a quarter of the rate limit; below a quarter of the nutation frequency; stop protection's gain"},
      c.cage_gain_1_s...);
    v(Field{"gimbal_cone_limit_rad", kPos, kRange, kReq, kNo, 1e-3, 1.5707963267948966, "rad",
            "within the pickoff range; the readout's pitch is within +-pi/2"},
      c.gimbal_cone_limit_rad...);
    v(Field{"gimbal_stop_margin_rad", kNonNeg, kRange, kReq, kNo, 0.0, 1.5707963267948966, "rad",
            "at least one tick at the rate limit and the nutation of stopping twice it; below the cone limit"},
      c.gimbal_stop_margin_rad...);
    v(Field{"small_angle_limit_rad", kPos, kRange, kOpt, kNo, 1e-4, 0.1, "rad",
            "the report's 0.01: beyond 0.1 rad the small-angle step keeps fewer than 3 digits"},
      c.small_angle_limit_rad...);
    v(Field{"pickoff_range_rad", kPos, kRange, kReq, kNo, 1e-3, 1.5707963267948966, "rad",
            "covers the cone limit; no gimbal angle of the readout is beyond pi/2"},
      c.pickoff_range_rad...);
    v(Field{"max_pickoff_step_rad", kPos, kRange, kReq, kNo, 1e-7, 1.5707963267948966, "rad",
            "above 2 ticks at the rate limit plus a full-torque nutation, and the pickoff's resolution and noise; within the range"},
      c.max_pickoff_step_rad...);
    v(Field{"estimator_gain", kNonNeg, kRange, kReq, kNo, 0.0, 1.0, "", "a fraction of the residual per tick"},
      c.estimator_gain...);
    v(Field{"residual_limit_rad", kPos, kRange, kReq, kNo, 1e-7, 1.5707963267948966, "rad",
            "above 2 pickoff LSBs, 9 sigma of its noise and a tick at the rate limit; below the cone limit"},
      c.residual_limit_rad...);
    v(Field{"residual_persistence_ticks", kCount, kRange, kReq, kNo, 1.0, kCountMax, "ticks", kTime},
      c.residual_persistence_ticks...);
    v(Field{"invalid_persistence_ticks", kCount, kRange, kReq, kNo, 1.0, kCountMax, "ticks", kTime},
      c.invalid_persistence_ticks...);
    v(Field{"spin_low_persistence_ticks", kCount, kRange, kReq, kNo, 1.0, kCountMax, "ticks", kTime},
      c.spin_low_persistence_ticks...);
    v(Field{"torquer_fail_persistence_ticks", kCount, kRange, kReq, kNo, 1.0, kCountMax, "ticks", kTime},
      c.torquer_fail_persistence_ticks...);
    v(Field{"uncage_settle_ticks", kAny, kRange, kReq, kNo, 0.0, kCountMax, "ticks", kTime}, c.uncage_settle_ticks...);
    v(Field{"max_tick_gap", kCount, kRange, kOpt, kNo, 1.0, kCountMax, "ticks", kTime}, c.max_tick_gap...);
    v(Field{"input_persistence_ticks", kCount, kRange, kOpt, kNo, 1.0, kCountMax, "ticks", kTime},
      c.input_persistence_ticks...);
    v(Field{"max_body_rate_rad_s", kPos, kRange, kOpt, kNo, 1e-4, 1e4, "rad/s",
            "at least the rate limits (a body turning as the gyro slews is believed); at most pi per tick"},
      c.max_body_rate_rad_s...);
    v(Field{"pickoff_lsb_rad", kNonNeg, kRange, kOpt, kNo, 0.0, 0.1, "rad",
            "the board's quantisation step (0: not stated)"}, c.pickoff_lsb_rad...);
    v(Field{"pickoff_noise_rad", kNonNeg, kRange, kOpt, kNo, 0.0, 0.1, "rad",
            "the board's 1-sigma reading noise (0: not stated)"}, c.pickoff_noise_rad...);
  }
};

// Navigation and guidance for one tick. A field that cannot be used is ignored and flagged;
// it never stops the tick (docs/component.md).
template <typename T>
struct GuidanceInput {
  ModeRequest request{ModeRequest::kNone};
  // (pitch, yaw): the spin axis's inertial rate about the inner gimbal axis y_I and about
  // z_I = x × y_I (docs/conventions.md); used in kFree.
  Vector2<T> slew_rate_cmd_rad_s{Vector2<T>::Zero()};
  bool nav_valid{false};                               // false: attitude and rates ignored
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};  // body attitude at this tick
  Vector3<T> body_rate_rad_s{Vector3<T>::Zero()};      // body (roll p, pitch q, yaw r) rates
};

// Telemetry published every tick (a plain struct: copy it out, log it, downlink it).
template <typename T>
struct GyroTelemetry {
  std::uint64_t tick{};
  GyroMode mode{GyroMode::kIdle};
  std::uint32_t flags{};
  FlagCounts counters{};  // saturating, per flag bit
  Vector2<T> gimbal_measured_rad{Vector2<T>::Zero()};   // last accepted pickoff reading
  Vector2<T> gimbal_predicted_rad{Vector2<T>::Zero()};  // exact-dynamics prediction
  Vector2<T> residual_rad{Vector2<T>::Zero()};          // measured - predicted
  Quaternion<T> attitude_gyro_to_earth{Quaternion<T>::Identity()};  // estimated
  Vector2<T> precession_rate_rad_s{Vector2<T>::Zero()}; // estimated spin-axis rate, gimbal axes
  Vector2<T> rate_cmd_rad_s{Vector2<T>::Zero()};        // after limits and stop protection
  Vector2<T> torque_cmd{Vector2<T>::Zero()};            // written to the torquer (inner, outer)
  Vector2<T> nutation_amplitude_rad{Vector2<T>::Zero()};
  T spin_hz{};                                          // spin used this tick
};

}  // namespace gyro
