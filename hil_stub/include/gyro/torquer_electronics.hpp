// The torquer electronics of the SIL stub: the torque that acts on the gimbals for a command
// latched by write_torquer (zero-order hold): command -> scale factor -> saturation ->
// torquer faults (dead: 0, saturated: pinned at the fault's level).
#pragma once

#include <cmath>
#include <cstddef>

#include "gyro/config_fields.hpp"
#include "gyro/fault_schedule.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

template <typename T>
struct TorquerModel {
  Vector2<T> scale_factor{Vector2<T>::Ones()};  // actual/commanded torque per axis
  T max_torque{};                               // saturation per axis (0 = none)
};

// The fields (gyro/config_fields.hpp), named as SimulatedGyroConfig's check names them.
template <typename T>
struct FieldTable<TorquerModel<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    v(Field{"torquer.scale_factor", Rule::kFinite, Status::kOutOfRange, Presence::kOptional, nullptr, 0.1, 10.0, "", "a scale error within a factor 10 (a dead torquer is a fault)"}, c.scale_factor...);
    v(Field{"torquer.max_torque", Rule::kNonNegative, Status::kOutOfRange, Presence::kOptional, nullptr, 0.0, 1e12, "torque", "0 (none) or what the electronics drive"}, c.max_torque...);
  }
};

template <typename T>
[[nodiscard]] ConfigCheck check(const TorquerModel<T>& t) noexcept {
  const FieldRefusal r = first_refusal<RealFields>(t);
  return r.check;
}

template <typename T>
[[nodiscard]] Vector2<T> torquer_output(const TorquerModel<T>& model, const Vector2<T>& command,
                                        const ActiveFaults<T>& faults) noexcept {
  Vector2<T> t = command.cwiseProduct(model.scale_factor);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto axis = static_cast<Eigen::Index>(i);
    if (model.max_torque > T(0)) t(axis) = saturate(t(axis), model.max_torque);
    if (faults.dead_torquer[i]) t(axis) = T(0);
    if (faults.saturated_torquer[i]) t(axis) = faults.saturated_level(axis);
  }
  return t;
}

}  // namespace gyro
