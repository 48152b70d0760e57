// Validation of the component's configuration: the contract of docs/component.md
// ("Configuration contract"). Every field has both bounds (its row in the field table,
// gyro/component_types.hpp); the rules here refuse fields that cannot work together. check()
// returns the first refusal, check_all() hands every one to a sink; each names the field, its
// value, the bound and the rule (gyro/config_check.hpp formats it).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gyro/component_types.hpp"
#include "gyro/config_check.hpp"
#include "gyro/exact_step_check.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {

// The nominal rotor has a finite exact step over a tick; a refusal names the field responsible.
template <typename T>
[[nodiscard]] ConfigCheck check_nominal_step(const GyroComponentConfig<T>& c) noexcept {
  constexpr ExactStepFields kFields{"pitch_inertia", "yaw_inertia", "spin_inertia",
                                    "friction",      "nominal_spin_hz", "tick_s"};
  return check_exact_step(c.pitch_inertia, c.yaw_inertia, c.spin_inertia, c.friction, c.nominal_spin_hz, c.tick_s,
                          kFields);
}

// The contract's constants, named where a rule uses them.
inline constexpr double kResidualLsbs = 2.0;        // a residual limit above 2 LSBs of rounding
// and 9 sigma of the pickoff noise: 6 sigma of the difference of two readings (sigma sqrt 2),
// about 1e-9 a reading beyond it.
inline constexpr double kResidualNoiseSigmas = 9.0;
// The pickoff jitter a loop gain multiplies (2 LSBs + 3 sigma), and the share of the rate
// limit it may ask.
inline constexpr double kJitterNoiseSigmas = 3.0;
inline constexpr double kJitterRateShare = 0.25;
inline constexpr double kStepRateTicks = 2.0;       // a reading may move 2 ticks at the rate limit
inline constexpr double kAuthorityFraction = 0.5;   // the torquer precesses at >= half the rate limit
inline constexpr double kNutationShare = 0.1;       // a full-torque nutation within 1/10 of the small-angle limit
inline constexpr double kMaxNutationPhasePerTick = 1e3;  // rad; beyond, float's phase keeps < 4 digits
// The share of a tick's motion the estimator's model may miss: a hundredth (docs/
// model-validity.md: open loop for a second against the gimbal, the corrected model is off by
// at most 3.3e-3 rad over the whole grid, 2.8e-4 inside the envelope).
inline constexpr double kModelRateError = 0.01;
inline constexpr double kCageNutationShare = 0.25;  // a caging loop within a quarter of the nutation frequency
inline constexpr double kShaperLostLeakage = 0.5;   // a shaper passing more than this of the nutation: none

namespace component_detail {
// The count that lasts `seconds` at tick `tick_s`.
[[nodiscard]] inline double ticks_in(double seconds, double tick_s) noexcept { return std::floor(seconds / tick_s); }
}  // namespace component_detail

// Every rule `c` breaks, to sink(const ConfigCheck&), in the order check() takes them: each
// field's own rule and range, then (once every field is within its own range: a rule between
// fields says nothing of a value out of range) the rules between fields, then the exact step.
template <typename T, class Sink>
void check_all(const GyroComponentConfig<T>& c, Sink&& sink) noexcept {
  bool own_ok = true;
  auto own = [&](const ConfigCheck& r) noexcept {
    own_ok = false;
    sink(r);
  };
  check_fields<RealFields>(c, own);
  check_fields<CountFields>(c, own);
  if (!own_ok) return;

  const double tick = static_cast<double>(c.tick_s);
  const double j1 = static_cast<double>(c.pitch_inertia), j2 = static_cast<double>(c.yaw_inertia);
  const double h = 2.0 * 3.14159265358979323846 * static_cast<double>(c.nominal_spin_hz) * static_cast<double>(c.spin_inertia);
  const double rate = std::max(static_cast<double>(c.max_pitch_rate_rad_s), static_cast<double>(c.max_yaw_rate_rad_s));
  const double cone = static_cast<double>(c.gimbal_cone_limit_rad);
  const double range = static_cast<double>(c.pickoff_range_rad);
  const double lsb = static_cast<double>(c.pickoff_lsb_rad), noise = static_cast<double>(c.pickoff_noise_rad);
  const double small = static_cast<double>(c.small_angle_limit_rad);
  auto below = [&sink](const char* f, double v, double bound, const char* what, const char* why) noexcept {
    if (v < bound) sink(refuse_below(f, v, bound, what, why));
  };
  auto above = [&sink](const char* f, double v, double bound, const char* what, const char* why) noexcept {
    if (v > bound) sink(refuse_above(f, v, bound, what, why));
  };

  // Spin.
  if (!(c.min_spin_hz < c.nominal_spin_hz)) {
    sink(refuse_above("min_spin_hz", static_cast<double>(c.min_spin_hz), static_cast<double>(c.nominal_spin_hz),
                      "nominal_spin_hz", "the nominal gyro would be spin-low from its first tick"));
  }
  // Rates against the tick, the torquer and H.
  above("max_pitch_rate_rad_s", static_cast<double>(c.max_pitch_rate_rad_s), small / tick,
        "small_angle_limit_rad / tick_s", "one tick's slew would exceed the small-angle limit");
  above("max_yaw_rate_rad_s", static_cast<double>(c.max_yaw_rate_rad_s), small / tick,
        "small_angle_limit_rad / tick_s", "one tick's slew would exceed the small-angle limit");
  below("max_torque", static_cast<double>(c.max_torque), kAuthorityFraction * h * rate,
        "H x the larger rate limit / 2", "the torquer could not precess at half the rate limit");
  above("max_torque", static_cast<double>(c.max_torque), kNutationShare * small * h * h / std::max(j1, j2),
        "small_angle_limit x H^2 / J / 10", "a full-torque step would start a nutation beyond a tenth of the small-angle limit");
  // Caging loop and stop protection.
  above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), 1.0 / tick, "1 / tick_s",
        "gain x tick > 1: the discrete caging loop overshoots");
  // The caging loop and the stop protection command gain x angle: the pickoffs' rounding and
  // noise alone must not ask a quarter of the smaller rate limit, or the loop chatters on it.
  const double slowest = std::min(static_cast<double>(c.max_pitch_rate_rad_s), static_cast<double>(c.max_yaw_rate_rad_s));
  const double jitter = kResidualLsbs * lsb + kJitterNoiseSigmas * noise;
  if (jitter > 0.0) {
    above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), kJitterRateShare * slowest / jitter,
          "the smaller rate limit / 4 / (2 LSBs + 3 sigma)",
          "the pickoffs' rounding and noise alone would drive the caging loop and stop protection onto the rate limit");
  }
  // A loop that commands the spin axis's rate from the gimbal angles (caging, stop
  // protection) drives the nutation it reads: to first order its growth rate is the gain less
  // the bearings' damping alpha = (f/2)(1/J1 + 1/J2). The torque shaper's zero keeps the loop's
  // torques off the nutation; where no shaper can be designed, the bearings must damp it. And
  // the loop stays below a quarter of the nutation frequency (an overdamped rotor has none).
  const double friction = static_cast<double>(c.friction);
  const detail::RateMatrixTerms<double> terms = detail::rate_matrix_terms(RotorParameters<double>{j1, j2, friction, h});
  const double beta = terms.beta_sq > 0.0 ? std::sqrt(terms.beta_sq) : 0.0;
  const ShaperDesign<T> shaper = design_shaper(static_cast<T>(beta * tick));  // the component's own design
  const std::uint32_t spacing = shaper.spacing;
  if (beta > 0.0) {
    above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), kCageNutationShare * beta,
          "the nutation frequency / 4", "a faster caging loop or stop protection would drive the nutation it reads");
    // Holding the gimbal at the protection cone c_p against the body's turn b, the stop
    // protection steers along the outward direction, which turns with the spin axis: a
    // second loop from the spin axis's position to its rate, of gain b / sin c_p. b is the
    // fastest turn it can hold: the navigation's limit or the torquer's authority T / H.
    // (No protection cone at all is the margin's refusal below, not this rule's.)
    const double protect_cone = cone - static_cast<double>(c.gimbal_stop_margin_rad);
    const double hold = std::min(static_cast<double>(c.max_body_rate_rad_s), static_cast<double>(c.max_torque) / h);
    if (spacing == 0u && protect_cone > 0.0) {
      above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), terms.alpha - hold / std::sin(protect_cone),
            "the bearings' nutation damping (f/2)(1/J1 + 1/J2) less the stop protection's turn gain b / sin c_p",
            "no torque shaper at this tick (gyro/torque_shaper.hpp): the caging loop and the stop protection "
            "would pump the nutation");
    } else if (spacing != 0u && protect_cone > 0.0) {
      // The shaper is made for the nutation at zero gimbal angles. Held at c_p in pitch, the
      // motor-held spin adds C tan^2 c_p to the yaw inertia and slows the nutation; where the
      // shaper passes more than half of that nutation its notch is lost there, and the
      // bearings must damp it as where there is no shaper.
      const double tan_p = std::tan(protect_cone);
      const double j2_at_cone = j2 + static_cast<double>(c.spin_inertia) * tan_p * tan_p;
      const detail::RateMatrixTerms<double> at_cone =
          detail::rate_matrix_terms(RotorParameters<double>{j1, j2_at_cone, friction, h});
      const double beta_at_cone = at_cone.beta_sq > 0.0 ? std::sqrt(at_cone.beta_sq) : 0.0;
      if (static_cast<double>(shaper_leakage(shaper, static_cast<T>(beta_at_cone * tick))) > kShaperLostLeakage) {
        above("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), at_cone.alpha - hold / std::sin(protect_cone),
              "the bearings' nutation damping at the protection cone less the stop protection's turn gain b / sin c_p",
              "the torque shaper passes more than half of the nutation at the protection cone (yaw inertia "
              "J2 + C tan^2 c_p): the caging loop and the stop protection would pump the nutation there");
      }
    }
  }
  // Cone, margin, pickoff range.
  above("gimbal_cone_limit_rad", cone, range, "pickoff_range_rad",
        "the pickoffs would saturate inside the cone: the gimbal could pass it unseen");
  // The shaped torque holds the gimbal 2 m ticks after the protection first acts.
  below("gimbal_stop_margin_rad", static_cast<double>(c.gimbal_stop_margin_rad), (1.0 + 2.0 * spacing) * rate * tick,
        "(1 + 2 m) ticks at the rate limit (m the torque shaper's spacing)",
        "the gimbal could cross the protection zone before the torque holds it");
  // Stopping the fastest outward motion flown (a slew at the rate limit with the body turning
  // as fast the other way) sets the rotor nutating by that rate over the nutation rate
  // sqrt(H^2 + f^2) / sqrt(J1 J2): the protection zone must hold that overshoot.
  const double nutation_rate = std::sqrt(h * h + friction * friction) / std::sqrt(j1 * j2);
  below("gimbal_stop_margin_rad", static_cast<double>(c.gimbal_stop_margin_rad), 2.0 * rate / nutation_rate,
        "2 x the larger rate limit / the nutation rate",
        "stopping the fastest outward motion would nutate the gimbal through the protection zone");
  if (!(c.gimbal_stop_margin_rad < c.gimbal_cone_limit_rad)) {
    sink(refuse_above("gimbal_stop_margin_rad", static_cast<double>(c.gimbal_stop_margin_rad), cone,
                      "gimbal_cone_limit_rad", "no cone left to fly in"));
  }
  // Pickoff validation.
  above("max_pickoff_step_rad", static_cast<double>(c.max_pickoff_step_rad), range, "pickoff_range_rad",
        "a step larger than the range believes any reading");
  // A full-torque step's nutation: amplitude about T J / H^2 (the steady rate T / H over the
  // nutation rate H / J).
  const double nutation_step = static_cast<double>(c.max_torque) * std::max(j1, j2) / (h * h);
  below("max_pickoff_step_rad", static_cast<double>(c.max_pickoff_step_rad),
        kStepRateTicks * (rate * tick + nutation_step), "2 x (a tick at the rate limit + a full-torque nutation)",
        "a slew at the rate limit would be refused as a jump");
  below("max_pickoff_step_rad", static_cast<double>(c.max_pickoff_step_rad), 2.0 * lsb + kResidualNoiseSigmas * noise,
        "2 pickoff LSBs + 9 sigma of noise", "a gyro at rest would be refused as jumping");
  // Residual monitor against the pickoff's resolution and noise, and what the scalar holds.
  below("residual_limit_rad", static_cast<double>(c.residual_limit_rad), kResidualLsbs * lsb, "2 pickoff LSBs",
        "a healthy gyro would latch a fault");
  below("residual_limit_rad", static_cast<double>(c.residual_limit_rad), kResidualNoiseSigmas * noise,
        "9 sigma of pickoff noise", "a healthy gyro would latch a fault");
  below("residual_limit_rad", static_cast<double>(c.residual_limit_rad), rate * tick, "one tick at the rate limit",
        "a reading early or late by part of a tick would latch a fault");
  below("residual_limit_rad", static_cast<double>(c.residual_limit_rad),
        64.0 * static_cast<double>(std::numeric_limits<T>::epsilon()) * range, "64 epsilons of the pickoff range",
        "the scalar's rounding of a reading would latch a fault");
  // The estimator turns its prediction by estimator_gain x the residual a tick: what its model
  // misses of a tick's motion settles at that over the gain, which the residual limit must
  // hold. Without correction the prediction drifts from the gimbal without bound, and the
  // stop protection, which reads it, with it.
  below("estimator_gain", static_cast<double>(c.estimator_gain),
        kModelRateError * rate * tick / static_cast<double>(c.residual_limit_rad),
        "a hundredth of a tick at the rate limit / residual_limit_rad",
        "the model's error in a tick's motion would build up beyond the residual limit");
  if (!(c.residual_limit_rad < c.gimbal_cone_limit_rad)) {
    sink(refuse_above("residual_limit_rad", static_cast<double>(c.residual_limit_rad), cone, "gimbal_cone_limit_rad",
                      "every reading within the cone would pass: no fault detected"));
  }
  // Navigation rates: the rates flown are believed, and one tick's turn is no alias.
  below("max_body_rate_rad_s", static_cast<double>(c.max_body_rate_rad_s), rate, "the larger rate limit",
        "a body turning as the gyro slews would be refused: a lock-out");
  above("max_body_rate_rad_s", static_cast<double>(c.max_body_rate_rad_s), 3.14159265358979323846 / tick,
        "pi / tick_s", "the body's turn in one tick would alias");
  // Counts against the stated longest time.
  const double longest = component_detail::ticks_in(kLongestConfiguredTime_s, tick);
  const char* const kLongest = "10 s of ticks (the longest configured time)";
  const char* const kWhy = "longer than the contract's longest time";
  above("residual_persistence_ticks", static_cast<double>(c.residual_persistence_ticks), longest, kLongest, kWhy);
  above("invalid_persistence_ticks", static_cast<double>(c.invalid_persistence_ticks), longest, kLongest, kWhy);
  above("spin_low_persistence_ticks", static_cast<double>(c.spin_low_persistence_ticks), longest, kLongest, kWhy);
  above("torquer_fail_persistence_ticks", static_cast<double>(c.torquer_fail_persistence_ticks), longest, kLongest,
        kWhy);
  above("uncage_settle_ticks", static_cast<double>(c.uncage_settle_ticks), longest, kLongest,
        "the torquers would stay off longer than the contract's longest time");
  above("max_tick_gap", static_cast<double>(c.max_tick_gap), longest, kLongest, kWhy);
  above("input_persistence_ticks", static_cast<double>(c.input_persistence_ticks), longest, kLongest, kWhy);
  below("cage_gain_1_s", static_cast<double>(c.cage_gain_1_s), 1.0 / kLongestConfiguredTime_s,
        "1 / (the longest configured time)", "caging would not pull in within the longest time");
  // The tick against the nutation: its phase per tick stays representable.
  const double nutation_rad_s = h / std::sqrt(j1 * j2);
  above("tick_s", tick, kMaxNutationPhasePerTick / nutation_rad_s, "1000 rad of nutation phase",
        "the nutation's phase per tick would keep fewer than 4 digits in float");
  const ConfigCheck step = check_nominal_step(c);
  if (!step.ok()) sink(step);
}

// The first refusal of check_all() (ok when none).
template <typename T>
[[nodiscard]] ConfigCheck check(const GyroComponentConfig<T>& c) noexcept {
  FirstRefusal first;
  check_all(c, first);
  return first.first;
}

// The exact-dynamics model the component predicts with: the configured rotor, its limits,
// the torquers and bearings on the gimbal axes, no error sources (those are the hardware's,
// to be caught by the residual).
template <typename T>
[[nodiscard]] GyroModelConfig<T> estimator_config(const GyroComponentConfig<T>& c) noexcept {
  GyroModelConfig<T> m;
  m.pitch_inertia = c.pitch_inertia;
  m.yaw_inertia = c.yaw_inertia;
  m.spin_inertia = c.spin_inertia;
  m.friction = c.friction;
  m.gimbal_cone_limit_rad = c.gimbal_cone_limit_rad;
  m.max_pitch_rate_rad_s = c.max_pitch_rate_rad_s;
  m.max_yaw_rate_rad_s = c.max_yaw_rate_rad_s;
  m.small_angle_limit_rad = c.small_angle_limit_rad;
  m.torquer_axes = TorquerAxes::kGimbal;
  return m;
}

}  // namespace gyro
