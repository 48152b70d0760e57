// The faults the SIL stub can inject, their schedule, and what is active at a tick.
//
// A fault is active for ticks in [start_tick, start_tick + duration_ticks) (duration 0 =
// permanent), on axis 0 (pitch), 1 (yaw) or -1 (both):
//   kStuckPickoff      the converter's output freezes at its last value before the fault; the
//                      sequence keeps counting
//   kInvalidReading    NaN angles: on one axis with valid = true (axis >= 0, tests the
//                      caller's finiteness check), on both with valid = false (axis = -1)
//   kDropout           no new conversion: the whole reading (sequence included) repeats
//   kBiasJump          `magnitude` rad added to the bias of the axis
//   kDeadTorquer       applied torque 0 on the axis
//   kSaturatedTorquer  applied torque pinned at +magnitude on the axis, whatever the command
//   kSpinMotorFailure  the spin motor stops driving and its winding brakes the rotor: it runs
//                      down with time constant `magnitude` s
// Torquer faults act on the interval that starts at their tick: [k, k+1] for a fault active
// at tick k. The schedule is scanned once per tick into an ActiveFaults summary.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "gyro/attitude.hpp"
#include "gyro/config_check.hpp"
#include "gyro/config_fields.hpp"

namespace gyro {

enum class FaultKind : std::uint8_t {
  kNone = 0,
  kStuckPickoff,
  kInvalidReading,
  kDropout,
  kBiasJump,
  kDeadTorquer,
  kSaturatedTorquer,
  kSpinMotorFailure,
};
// The fault kinds' names in scenario files and logs, in enum order.
[[nodiscard]] constexpr std::array<const char*, 8> enum_names(FaultKind /*tag*/) noexcept {
  return {"none",      "stuck_pickoff",     "invalid_reading",   "dropout",
          "bias_jump", "dead_torquer",      "saturated_torquer", "spin_motor_failure"};
}
inline constexpr int kFaultKindCount = static_cast<int>(enum_names(FaultKind{}).size());

// The fault kind's name in scenario files and logs ("stuck_pickoff"); "" for kNone or an
// unknown value.
[[nodiscard]] constexpr const char* fault_kind_name(FaultKind k) noexcept {
  return k == FaultKind::kNone ? "" : enum_name_or(k, "");
}

// Whether a fault of this kind acts through its `magnitude` (a file giving the kind must give
// it): the bias jump, the saturated torquer's level, the spin failure's time constant.
[[nodiscard]] constexpr bool fault_needs_magnitude(FaultKind k) noexcept {
  return k == FaultKind::kBiasJump || k == FaultKind::kSaturatedTorquer || k == FaultKind::kSpinMotorFailure;
}

// The bit of a fault kind in active-fault words.
[[nodiscard]] constexpr std::uint32_t fault_bit(FaultKind k) noexcept {
  return 1u << static_cast<std::uint32_t>(k);
}

template <typename T>
struct FaultEvent {
  FaultKind kind{FaultKind::kNone};
  std::uint64_t start_tick{};
  std::uint64_t duration_ticks{};  // 0 = permanent
  int axis{-1};                    // 0 pitch, 1 yaw, -1 both
  T magnitude{};  // bias jump (rad); saturated torquer level (torque); spin failure time constant (s)
};

// The fields (gyro/config_fields.hpp); check(FaultList) checks them per slot. A scenario
// gives a fault in its own terms (start_s, duration_s).
template <typename T>
struct FieldTable<FaultEvent<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Presence kImplied = Presence::kImplied;
    constexpr const char* kTicks = "any tick count; start + duration within 64 bits (check())";
    v(Field{"kind", Rule::kNone, Status::kOutOfRange, kImplied}, c.kind...);
    v(Field{"start_tick", Rule::kNone, Status::kOutOfRange, kImplied, nullptr, -kNoBound, kNoBound, "ticks", kTicks},
      c.start_tick...);
    v(Field{"duration_ticks", Rule::kNone, Status::kOutOfRange, kImplied, nullptr, -kNoBound, kNoBound, "ticks",
            kTicks},
      c.duration_ticks...);
    v(Field{"axis", Rule::kFinite, Status::kOutOfRange, kImplied, nullptr, -1.0, 1.0, "",
            "0 pitch, 1 yaw, -1 both"}, c.axis...);
    v(Field{"magnitude", Rule::kFinite, Status::kOutOfRange, kImplied, nullptr, -1e12, 1e12, "rad, torque or s",
            "a bias jump's rad or a saturated torquer's torque (consistent units), or a spin failure's time "
            "constant (> 0, check())"},
      c.magnitude...);
  }
};

inline constexpr int kMaxFaultEvents = 8;

template <typename T>
using FaultList = std::array<FaultEvent<T>, kMaxFaultEvents>;

// What the schedule makes of one tick, per axis.
template <typename T>
struct ActiveFaults {
  std::uint32_t bits{0};  // fault_bit() of each kind active
  Vector2<T> bias_jump_rad{Vector2<T>::Zero()};
  std::array<bool, 2> stuck{false, false};
  std::array<bool, 2> nan_angle{false, false};  // one axis NaN, valid bit kept
  bool invalid{false};                          // both axes NaN, valid bit clear
  bool dropout{false};
  std::array<bool, 2> dead_torquer{false, false};
  std::array<bool, 2> saturated_torquer{false, false};
  Vector2<T> saturated_level{Vector2<T>::Zero()};
  bool spin_motor_failed{false};
  T spin_failure_time_constant_s{};  // the shortest of the active spin motor failures
};

[[nodiscard]] inline bool fault_active(FaultKind kind, std::uint64_t start, std::uint64_t duration,
                                       std::uint64_t tick) noexcept {
  if (kind == FaultKind::kNone || tick < start) return false;
  return duration == 0u || tick - start < duration;
}

// One pass over the schedule.
template <typename T>
[[nodiscard]] ActiveFaults<T> active_faults_at(const FaultList<T>& faults, std::uint64_t tick) noexcept {
  ActiveFaults<T> a;
  for (const FaultEvent<T>& f : faults) {
    if (!fault_active(f.kind, f.start_tick, f.duration_ticks, tick)) continue;
    a.bits |= fault_bit(f.kind);
    for (std::size_t i = 0; i < 2; ++i) {
      if (f.axis >= 0 && static_cast<std::size_t>(f.axis) != i) continue;
      const auto axis = static_cast<Eigen::Index>(i);
      switch (f.kind) {
        case FaultKind::kStuckPickoff: a.stuck[i] = true; break;
        case FaultKind::kInvalidReading:
          if (f.axis >= 0) a.nan_angle[i] = true;
          break;
        case FaultKind::kBiasJump: a.bias_jump_rad(axis) += f.magnitude; break;
        case FaultKind::kDeadTorquer: a.dead_torquer[i] = true; break;
        case FaultKind::kSaturatedTorquer:
          a.saturated_torquer[i] = true;
          a.saturated_level(axis) = f.magnitude;
          break;
        default: break;
      }
    }
    if (f.kind == FaultKind::kInvalidReading && f.axis < 0) a.invalid = true;
    if (f.kind == FaultKind::kDropout) a.dropout = true;
    if (f.kind == FaultKind::kSpinMotorFailure) {
      if (!a.spin_motor_failed || f.magnitude < a.spin_failure_time_constant_s) a.spin_failure_time_constant_s = f.magnitude;
      a.spin_motor_failed = true;
    }
  }
  return a;
}

// The field names of a fault slot ("faults[3].axis"), for refusals.
struct FaultFieldNames {
  const char* kind;
  const char* axis;
  const char* magnitude;
  const char* duration_ticks;
};
inline constexpr FaultFieldNames kFaultFieldNames[kMaxFaultEvents] = {
    {"faults[0].kind", "faults[0].axis", "faults[0].magnitude", "faults[0].duration_ticks"},
    {"faults[1].kind", "faults[1].axis", "faults[1].magnitude", "faults[1].duration_ticks"},
    {"faults[2].kind", "faults[2].axis", "faults[2].magnitude", "faults[2].duration_ticks"},
    {"faults[3].kind", "faults[3].axis", "faults[3].magnitude", "faults[3].duration_ticks"},
    {"faults[4].kind", "faults[4].axis", "faults[4].magnitude", "faults[4].duration_ticks"},
    {"faults[5].kind", "faults[5].axis", "faults[5].magnitude", "faults[5].duration_ticks"},
    {"faults[6].kind", "faults[6].axis", "faults[6].magnitude", "faults[6].duration_ticks"},
    {"faults[7].kind", "faults[7].axis", "faults[7].magnitude", "faults[7].duration_ticks"},
};
static_assert(kMaxFaultEvents == 8, "one name row per fault slot");

template <typename T>
[[nodiscard]] ConfigCheck check(const FaultList<T>& faults) noexcept {
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const FaultEvent<T>& f = faults[i];
    const FaultFieldNames& n = kFaultFieldNames[i];
    const auto kind = static_cast<std::uint8_t>(f.kind);
    if (kind >= static_cast<std::uint8_t>(kFaultKindCount)) return {Status::kOutOfRange, n.kind};
    if (f.kind == FaultKind::kNone) continue;
    // The slot's own numbers against their rows, named with the slot.
    ConfigCheck own = first_refusal<CountFields>(f).check;
    if (own.ok()) own = first_refusal<RealFields>(f).check;
    if (!own.ok()) {
      own.field = own.field != nullptr && std::string_view(own.field) == "axis" ? n.axis : n.magnitude;
      return own;
    }
    if (f.duration_ticks > ~std::uint64_t{0} - f.start_tick) return {Status::kOutOfRange, n.duration_ticks};
    if (f.kind == FaultKind::kSpinMotorFailure && !(f.magnitude > T(0))) return {Status::kOutOfRange, n.magnitude};
  }
  return {};
}

}  // namespace gyro
