// The spin the tick flies: the port's spin readback when the hardware has one and it is usable,
// else the configured nominal spin; and whether it is below the gyro's minimum.
#pragma once

#include <cmath>
#include <cstdint>

#include "gyro/component_types.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/rotor_parameters.hpp"

namespace gyro {

template <typename T>
struct SpinFlown {
  T hz{};
  std::uint32_t flags{0};  // kSpinLow
};

// `port_ok`: the port's read succeeded.
template <typename T>
[[nodiscard]] SpinFlown<T> spin_flown(const PickoffReading<T>& raw, bool port_ok,
                                      const GyroComponentConfig<T>& c) noexcept {
  SpinFlown<T> s{c.nominal_spin_hz, 0u};
  // A readback whose angular momentum is not representable is no spin: the nominal is used.
  if (c.use_spin_readback && port_ok && raw.spin_valid && std::isfinite(raw.spin_hz) && raw.spin_hz >= T(0) &&
      std::isfinite(angular_momentum(raw.spin_hz, c.spin_inertia))) {
    s.hz = raw.spin_hz;
  }
  if (s.hz < c.min_spin_hz) s.flags |= kSpinLow;
  return s;
}

}  // namespace gyro
