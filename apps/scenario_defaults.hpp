// The values a scenario gives where a struct's own initialiser does not stand (the seed, the
// gimbal plant's envelope). apps/scenario.cpp reads scenarios with them and the docs' tables
// (apps/config_doc.hpp) show them as the defaults.
#pragma once

#include <cstdint>

#include "gyro/gimbal_plant_config.hpp"

namespace gyro::sil {

inline constexpr std::uint64_t kScenarioSeed = 1;

// A wide envelope: 100 rad/s, 1e3 torque units, 1e4 m/s^2 (1000 g).
inline void set_scenario_envelope(GimbalPlantConfig<double>& g) noexcept {
  g.max_body_rate_rad_s = 100;
  g.max_torque = 1e3;
  g.max_specific_force = 1e4;
}

}  // namespace gyro::sil
