// The configuration contract between the flight component and the hardware the SIL stub
// emulates: rules that need both (docs/component.md, "Configuration contract"). Each refusal
// names the component's field (the one an integrator sets from the board's data sheet), the
// bound the stub's configuration puts on it, and the rule. No heap; C++17.
#pragma once

#include <algorithm>
#include <cmath>

#include "gyro/component_config.hpp"
#include "gyro/config_check.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {

// Every rule between `c` and the hardware `g`, to sink(const ConfigCheck&). Only rules whose
// stub value is stated (non-zero) are applied.
template <typename T, class Sink>
void check_against_hardware(const SimulatedGyroConfig<T>& g, const GyroComponentConfig<T>& c, Sink&& sink) noexcept {
  const double lsb = static_cast<double>(g.pickoff.lsb_rad), noise = static_cast<double>(g.pickoff.noise_rad);
  // (A static bias is no rule: uncaging takes the attitude from the measured reading.)
  const double residual = static_cast<double>(c.residual_limit_rad);
  if (residual < kResidualLsbs * lsb) {
    sink(refuse_below("residual_limit_rad", residual, kResidualLsbs * lsb, "2 pickoff LSBs",
                      "a healthy gyro would latch a fault"));
  }
  if (residual < kResidualNoiseSigmas * noise) {
    sink(refuse_below("residual_limit_rad", residual, kResidualNoiseSigmas * noise, "9 sigma of pickoff noise",
                      "a healthy gyro would latch a fault"));
  }
  const double slowest = std::min(static_cast<double>(c.max_pitch_rate_rad_s), static_cast<double>(c.max_yaw_rate_rad_s));
  const double jitter = kResidualLsbs * lsb + kJitterNoiseSigmas * noise;
  if (jitter > 0.0 && static_cast<double>(c.cage_gain_1_s) > kJitterRateShare * slowest / jitter) {
    sink(refuse_above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), kJitterRateShare * slowest / jitter,
                      "the smaller rate limit / 4 / (2 LSBs + 3 sigma)",
                      "the pickoffs' rounding and noise alone would drive the caging loop and stop protection onto the rate limit"));
  }
  const double step = static_cast<double>(c.max_pickoff_step_rad);
  if (step < kResidualLsbs * lsb + kResidualNoiseSigmas * noise) {
    sink(refuse_below("max_pickoff_step_rad", step, kResidualLsbs * lsb + kResidualNoiseSigmas * noise,
                      "2 pickoff LSBs + 9 sigma of noise", "a gyro at rest would be refused as jumping"));
  }
  if (g.pickoff.range_rad > T(0) && c.pickoff_range_rad > g.pickoff.range_rad) {
    sink(refuse_above("pickoff_range_rad", static_cast<double>(c.pickoff_range_rad),
                      static_cast<double>(g.pickoff.range_rad), "the pickoff electronics' range_rad",
                      "a saturated reading would be believed"));
  }
  const double max_scale = static_cast<double>(g.torquer.scale_factor.maxCoeff());
  if (g.torquer.max_torque > T(0) &&
      static_cast<double>(c.max_torque) > static_cast<double>(g.torquer.max_torque) / std::max(max_scale, 1e-300)) {
    sink(refuse_above("max_torque", static_cast<double>(c.max_torque),
                      static_cast<double>(g.torquer.max_torque) / max_scale,
                      "the torquer electronics' max_torque / scale_factor",
                      "the electronics would clip the command unseen: the torque law's saturation would lie"));
  }
  const double stop = g.plant == PlantKind::kGimbal ? static_cast<double>(g.gimbal.stop_cone_rad)
                                                    : static_cast<double>(g.gimbal_stop_rad);
  if (stop > 0.0 && static_cast<double>(c.gimbal_cone_limit_rad) > stop) {
    sink(refuse_above("gimbal_cone_limit_rad", static_cast<double>(c.gimbal_cone_limit_rad), stop,
                      "the gimbal's mechanical stop", "the protection cone must lie inside the stop"));
  }
}

}  // namespace gyro
