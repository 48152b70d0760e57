// The report's gyro error sources (GERROR), as named rate-equivalent drifts per axis.
//
// Each is a drift of the precession rate of its own axis (rad/s), turned into torque with
// the current angular momentum as the report does (T1 = H * yaw rate, T2 = -H * pitch rate).
// Viscous friction is not here: the exact dynamics already couple the axes through f (the
// report's warning not to count it twice). See docs/seed-errata.md for the listing's terms.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <string_view>

#include "gyro/config_fields.hpp"
#include "gyro/rotor_parameters.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

template <typename T>
struct AxisErrorSources {
  T static_drift_rad_s{};        // constant drift
  T in_plane_erection_1_s{};     // drift = -k * (this axis' gimbal angle): erects toward body x
  T cross_plane_erection_1_s{};  // drift = -k * (the other axis' gimbal angle)
  T g_sensitive_drift_rad_s{};   // drift per g of acceleration beyond 1 g (report's form)
  T torquer_cross_coupling{};    // fraction of the other axis' torquer command that leaks in
  T coulomb_friction_rad_s{};    // drift opposing this axis' precession, of constant size
};

template <typename T>
struct GyroErrorSources {
  AxisErrorSources<T> pitch{};  // drifts of theta' (the report's GERROR(:,2))
  AxisErrorSources<T> yaw{};    // drifts of psi'   (the report's GERROR(:,1))
};

// The fields (gyro/config_fields.hpp), each optional (0: none). A drift of 1 rad/s (57 deg/s)
// is far beyond any gyro that still holds a reference (real ones drift degrees per hour).
template <typename T>
struct FieldTable<AxisErrorSources<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Rule kAny = Rule::kFinite;
    constexpr Status kRange = Status::kOutOfRange;
    constexpr Presence kOpt = Presence::kOptional;
    v(Field{"static_drift_rad_s", kAny, kRange, kOpt, nullptr, -1.0, 1.0, "rad/s",
            "within 57 deg/s either way: beyond, the gyro holds no reference"}, c.static_drift_rad_s...);
    v(Field{"in_plane_erection_1_s", kAny, kRange, kOpt, nullptr, -10.0, 10.0, "1/s",
            "an erection time constant of 0.1 s or longer (negative: diverging); its drift at pi rad within 32 rad/s"},
      c.in_plane_erection_1_s...);
    v(Field{"cross_plane_erection_1_s", kAny, kRange, kOpt, nullptr, -10.0, 10.0, "1/s",
            "as the in-plane erection, from the other axis' angle"}, c.cross_plane_erection_1_s...);
    v(Field{"g_sensitive_drift_rad_s", kAny, kRange, kOpt, nullptr, -1.0, 1.0, "rad/s",
            "per g beyond 1 g, within the static drift's range"}, c.g_sensitive_drift_rad_s...);
    v(Field{"torquer_cross_coupling", kAny, kRange, kOpt, nullptr, -1.0, 1.0, "",
            "a fraction of the other axis' command: a larger leak than the axis' own is no torquer axis"},
      c.torquer_cross_coupling...);
    v(Field{"coulomb_friction_rad_s", Rule::kNonNegative, kRange, kOpt, nullptr, 0.0, 1.0, "rad/s",
            "a magnitude (it clamps the precession it opposes), within the static drift's range"},
      c.coulomb_friction_rad_s...);
  }
};

template <typename T>
struct FieldTable<GyroErrorSources<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    v(Field{"pitch", Rule::kFinite, Status::kOutOfRange, Presence::kOptional}, c.pitch...);
    v(Field{"yaw", Rule::kFinite, Status::kOutOfRange, Presence::kOptional}, c.yaw...);
  }
};

// The error sources' names in refusals, per axis in table order (a scenario's keys below gyro).
inline constexpr const char* kErrorSourceFieldNames[2][6] = {
    {"errors.pitch.static_drift_rad_s", "errors.pitch.in_plane_erection_1_s", "errors.pitch.cross_plane_erection_1_s",
     "errors.pitch.g_sensitive_drift_rad_s", "errors.pitch.torquer_cross_coupling",
     "errors.pitch.coulomb_friction_rad_s"},
    {"errors.yaw.static_drift_rad_s", "errors.yaw.in_plane_erection_1_s", "errors.yaw.cross_plane_erection_1_s",
     "errors.yaw.g_sensitive_drift_rad_s", "errors.yaw.torquer_cross_coupling", "errors.yaw.coulomb_friction_rad_s"},
};

// The first error source outside its own range, named with its axis.
template <typename T>
[[nodiscard]] ConfigCheck check(const GyroErrorSources<T>& e) noexcept {
  static_assert(count_fields<AxisErrorSources<T>, AnyField>() == std::size(kErrorSourceFieldNames[0]),
                "a qualified name for each field of an axis");
  const AxisErrorSources<T>* axes[] = {&e.pitch, &e.yaw};
  for (std::size_t a = 0; a < 2; ++a) {
    ConfigCheck r = first_refusal<RealFields>(*axes[a]).check;
    if (r.ok()) continue;
    std::size_t i = 0;
    visit_fields(
        [&](const Field& f, const auto&) noexcept {
          if (std::string_view(f.name) == r.field) r.field = kErrorSourceFieldNames[a][i];
          ++i;
        },
        *axes[a]);
    return r;
  }
  return {};
}

namespace detail {


// The report's g-sensitive factor: only the acceleration beyond 1 g counts, in g.
template <typename T>
[[nodiscard]] T g_excess(T accel, T gravity) noexcept {
  return (std::abs(accel) > gravity) ? accel / gravity - std::copysign(T(1), accel) : T(0);
}

}  // namespace detail

template <typename T>
[[nodiscard]] bool all_finite(const GyroErrorSources<T>& e) noexcept {
  return all_fields_finite(e);
}

// Whether error_drift() depends on the gimbal angles (an erection term is set).
// Whether any error source is set (none: the model's torque is the torquers' alone).
template <typename T>
[[nodiscard]] bool any_error_source(const GyroErrorSources<T>& e) noexcept {
  const auto axis = [](const AxisErrorSources<T>& a) {
    return a.static_drift_rad_s != T(0) || a.in_plane_erection_1_s != T(0) || a.cross_plane_erection_1_s != T(0) ||
           a.g_sensitive_drift_rad_s != T(0) || a.torquer_cross_coupling != T(0) || a.coulomb_friction_rad_s != T(0);
  };
  return axis(e.pitch) || axis(e.yaw);
}

template <typename T>
[[nodiscard]] bool drift_depends_on_gimbal(const GyroErrorSources<T>& e) noexcept {
  return e.pitch.in_plane_erection_1_s != T(0) || e.pitch.cross_plane_erection_1_s != T(0) ||
         e.yaw.in_plane_erection_1_s != T(0) || e.yaw.cross_plane_erection_1_s != T(0);
}

// Drift of (theta', psi') from every source but torquer cross-coupling and Coulomb friction.
//   gimbal_rad: (pitch, yaw) gimbal angles;
//   accel: body (lateral y, normal z) accelerations in the units of `gravity`. A lateral
//   acceleration torques about the yaw axis and so drifts pitch; a normal one drifts yaw.
template <typename T>
[[nodiscard]] Vector2<T> error_drift(const GyroErrorSources<T>& e, const Vector2<T>& gimbal_rad,
                                     const Vector2<T>& accel, T gravity) noexcept {
  const AxisErrorSources<T>& p = e.pitch;
  const AxisErrorSources<T>& y = e.yaw;
  const T pitch = p.static_drift_rad_s - p.in_plane_erection_1_s * gimbal_rad(0) -
                  p.cross_plane_erection_1_s * gimbal_rad(1) +
                  p.g_sensitive_drift_rad_s * detail::g_excess(accel(0), gravity);
  const T yaw = y.static_drift_rad_s - y.in_plane_erection_1_s * gimbal_rad(1) -
                y.cross_plane_erection_1_s * gimbal_rad(0) +
                y.g_sensitive_drift_rad_s * detail::g_excess(accel(1), gravity);
  return Vector2<T>(pitch, yaw);
}

// Coulomb friction's drift of (theta', psi'): against the precession `precession_rad_s` that
// every other torque would hold, of size c_i, and no more than that precession (a gimbal
// the torques cannot push past the friction stays put; friction never reverses it).
//
// It opposes the precession, not the instantaneous rate: the listing's -c*SIGN(rate) flips
// with every swing of the nutation, up to a step after the zero crossing when evaluated at
// the start of a step, and each late flip feeds the nutation. Seeded by a rounding-level
// rate on a still axis (c = 0.02 rad/s, 20 steps a nutation period), the report's gyro
// (f = 5) settles into a 2 rad/s limit cycle and a frictionless one diverges. As a function
// of the torques alone, the drift is constant while they are: the nutation is left to the
// gyro's own dynamics (gyro_model_test, Coulomb friction).
template <typename T>
[[nodiscard]] Vector2<T> coulomb_drift(const GyroErrorSources<T>& e, const Vector2<T>& precession_rad_s) noexcept {
  return Vector2<T>(-saturate(precession_rad_s(0), e.pitch.coulomb_friction_rad_s),
                    -saturate(precession_rad_s(1), e.yaw.coulomb_friction_rad_s));
}

// Torquer cross-coupling in torque form: a pitch-rate drift c_p * (yaw-rate command) is the
// torque -c_p * T1 on axis 2, and a yaw-rate drift c_y * (pitch-rate command) is -c_y * T2 on
// axis 1. Independent of H, so it holds through spin-down.
template <typename T>
[[nodiscard]] Vector2<T> cross_coupled_torque(const GyroErrorSources<T>& e,
                                              const Vector2<T>& torque) noexcept {
  return Vector2<T>(torque(0) - e.yaw.torquer_cross_coupling * torque(1),
                    torque(1) - e.pitch.torquer_cross_coupling * torque(0));
}

// The torque that precesses a frictionless gyro at `rate` (theta', psi'): the report's
// T1 = H * psi', T2 = -H * theta'.
template <typename T>
[[nodiscard]] Vector2<T> torque_for_rate_frictionless(T h, const Vector2<T>& rate_rad_s) noexcept {
  return Vector2<T>(h * rate_rad_s(1), -h * rate_rad_s(0));
}

}  // namespace gyro
