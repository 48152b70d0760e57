// The pickoff gate: which gimbal-angle readings the component may use.
//
// A reading is checked against the last accepted one, with a bound of max_step_rad per tick
// that passed without information (invalid or stale readings, lost ticks): a gap in the
// readings never locks them out. A reading that jumped does not widen the bound: a bias jump
// stays rejected until its persistence latches the fault. Without the jump test (safe mode,
// torquers off) the reference follows the pickoffs, so a wrong one cannot hold the gyro in
// safe mode.
#pragma once

#include <cstdint>

#include "gyro/component_types.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/rotor_parameters.hpp"

namespace gyro {

template <typename T>
struct PickoffLimits {
  T range_rad{};     // |angle| beyond it is no reading
  T max_step_rad{};  // per tick without information
};

struct PickoffVerdict {
  bool accepted{false};
  std::uint32_t flags{0};  // kPickoffInvalid, kPickoffStale or kPickoffJump
};

template <typename T>
class PickoffGate {
 public:
  // `port_ok`: the port's read succeeded; `elapsed`: ticks since the last call.
  [[nodiscard]] PickoffVerdict accept(const PickoffReading<T>& raw, bool port_ok, std::uint64_t elapsed,
                                      bool jump_test, const PickoffLimits<T>& limits) noexcept {
    PickoffVerdict v;
    const Vector2<T>& a = raw.gimbal_angle_rad;
    const T bound = limits.max_step_rad * (static_cast<T>(blind_ticks_) + static_cast<T>(elapsed));
    if (!port_ok || !raw.valid || !all_finite(a) || a.cwiseAbs().maxCoeff() > limits.range_rad) {
      v.flags |= kPickoffInvalid;
      blind_ticks_ = blind_ticks_ + elapsed;
    } else if (have_reading_ && raw.sequence == last_sequence_) {
      v.flags |= kPickoffStale;
      blind_ticks_ = blind_ticks_ + elapsed;
    } else if (have_reading_ && jump_test && (a - measured_).cwiseAbs().maxCoeff() > bound) {
      v.flags |= kPickoffJump;
      last_sequence_ = raw.sequence;
    } else {
      v.accepted = true;
      measured_ = a;
      last_sequence_ = raw.sequence;
      have_reading_ = true;
      blind_ticks_ = 0;
    }
    return v;
  }

  // The last accepted gimbal angles (pitch, yaw); zero before the first.
  [[nodiscard]] const Vector2<T>& measured() const noexcept { return measured_; }

 private:
  Vector2<T> measured_{Vector2<T>::Zero()};
  std::uint32_t last_sequence_{0};
  bool have_reading_{false};
  std::uint64_t blind_ticks_{0};  // ticks without an informative reading since the last accepted
};

}  // namespace gyro
