// The pickoff electronics of the SIL stub: what turns the true gimbal angles into the
// conversion the port returns.
//
// Per axis: truth -> first-order lag (exact per tick: y += (1 - exp(-dt/lag)) (x - y)) ->
// + bias (+ bias-jump faults) -> + white Gaussian noise -> saturation at +-range -> rounding to
// the nearest lsb (and, when both are set, clamped to the largest code within the range). The
// codes fit a signed 32-bit count (check(): lsb_rad >= range / (2^31 - 1)).
// Sequence +1 per conversion, starting at 1 for the power-up conversion. Faults (from the
// tick's ActiveFaults): stuck converters hold their output, a dropout repeats the whole
// reading, invalid readings carry NaN angles (valid bit kept for one axis, cleared for both).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "gyro/config_fields.hpp"
#include "gyro/fault_schedule.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/noise.hpp"
#include "gyro/saturate.hpp"

namespace gyro {

template <typename T>
struct PickoffModel {
  T lsb_rad{};                              // quantisation step (0 = none)
  Vector2<T> bias_rad{Vector2<T>::Zero()};  // (pitch, yaw)
  T lag_s{};                                // first-order lag time constant (0 = none)
  T noise_rad{};                            // 1-sigma white noise per reading
  T range_rad{};                            // readings saturate at +-range (0 = none)
};

// The fields (gyro/config_fields.hpp), named as SimulatedGyroConfig's check names them; each
// optional (0: none).
template <typename T>
struct FieldTable<PickoffModel<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Rule kNonNeg = Rule::kNonNegative;
    constexpr Status kRange = Status::kOutOfRange;
    constexpr Presence kOpt = Presence::kOptional;
    v(Field{"pickoff.lsb_rad", kNonNeg, kRange, kOpt, nullptr, 0.0, 0.1, "rad", "0 (none) to 0.1 rad: a 4-bit converter over +-pi/2"}, c.lsb_rad...);
    v(Field{"pickoff.bias_rad", Rule::kFinite, kRange, kOpt, nullptr, -0.1, 0.1, "rad", "within 0.1 rad: beyond, no pickoff to fly with"}, c.bias_rad...);
    v(Field{"pickoff.lag_s", kNonNeg, kRange, kOpt, nullptr, 0.0, 1.0, "s", "0 (none) to 1 s"}, c.lag_s...);
    v(Field{"pickoff.noise_rad", kNonNeg, kRange, kOpt, nullptr, 0.0, 0.1, "rad", "0 (none) to 0.1 rad, 1 sigma"}, c.noise_rad...);
    v(Field{"pickoff.range_rad", kNonNeg, kRange, kOpt, nullptr, 0.0, 1.5707963267948966, "rad", "0 (none) or up to pi/2: no gimbal angle of the readout is beyond"}, c.range_rad...);
  }
};

// The converter's code is a signed 32-bit count: the largest reading (the range, or without one
// the readout's widest angle, the yaw azimuth's pi) over lsb_rad must fit it. A finer step
// made the code (reading / lsb_rad) overflow to infinity in the conversion: at 5e-324 rad every
// reading came out infinite and marked valid. At the bound the codes of a reading, and the
// range over lsb_rad, stay below 2^31 in float and double.
inline constexpr double kPickoffMaxCode = 2147483647.0;               // 2^31 - 1
inline constexpr double kPickoffReadoutFullScaleRad = 3.141592653589793;  // without a range

template <typename T>
[[nodiscard]] ConfigCheck check(const PickoffModel<T>& p) noexcept {
  const FieldRefusal r = first_refusal<RealFields>(p);
  if (r.status != Status::kOk) return r.check;
  const double lsb = static_cast<double>(p.lsb_rad), range = static_cast<double>(p.range_rad);
  if (range > 0.0 && lsb > range) {
    return refuse_above("pickoff.lsb_rad", lsb, range, "pickoff.range_rad",
                        "a converter has at least one code within its range");
  }
  const double full_scale = range > 0.0 ? range : kPickoffReadoutFullScaleRad;
  const double finest = full_scale / kPickoffMaxCode;
  if (lsb > 0.0 && lsb < finest) {
    return refuse_below("pickoff.lsb_rad", lsb, finest,
                        range > 0.0 ? "pickoff.range_rad over 2^31 - 1 codes" : "pi rad over 2^31 - 1 codes",
                        "the code of a reading (angle / lsb_rad) must fit the converter's signed 32-bit count");
  }
  return {};
}

// Noise stream ids (one per axis and per random term).
enum class NoiseStreamId : std::uint64_t {
  kPickoffNoisePitch = 1,
  kPickoffNoiseYaw = 2,
};

template <typename T>
class PickoffElectronics {
 public:
  void configure(const PickoffModel<T>& model, T tick_s, std::uint64_t seed) noexcept {
    model_ = model;
    lag_gain_ = (model.lag_s > T(0)) ? -std::expm1(-tick_s / model.lag_s) : T(1);
    noise_[0] = NoiseStream<T>(seed, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoisePitch));
    noise_[1] = NoiseStream<T>(seed, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoiseYaw));
    power_down();
  }

  void power_down() noexcept {
    lag_out_.setZero();
    converter_out_.setZero();
    reading_ = PickoffReading<T>{};
  }

  // One conversion at `tick` of the true gimbal angles; `spin_hz` is the readback reported
  // with it (spin_valid false: no readback). The power-up conversion ignores lag, stuck
  // converters and dropouts.
  void sample(const Vector2<T>& truth_rad, std::uint64_t tick, const ActiveFaults<T>& faults, bool power_up,
              T spin_hz, bool spin_valid) noexcept {
    if (power_up || !(model_.lag_s > T(0))) {
      lag_out_ = truth_rad;  // no lag: exactly the truth (x + (y - x) need not round to y)
    } else {
      lag_out_ += lag_gain_ * (truth_rad - lag_out_);
    }
    Vector2<T> v = lag_out_ + model_.bias_rad + faults.bias_jump_rad;
    for (std::size_t i = 0; i < 2; ++i) {
      const auto axis = static_cast<Eigen::Index>(i);
      if (model_.noise_rad > T(0)) v(axis) += model_.noise_rad * noise_[i].gaussian(tick);
      if (power_up || !faults.stuck[i]) converter_out_(axis) = quantise(v(axis));  // stuck: held
    }
    if (faults.dropout && !power_up) return;  // stale: nothing new, sequence included

    PickoffReading<T> r;
    r.gimbal_angle_rad = converter_out_;
    r.sequence = reading_.sequence + 1u;
    r.valid = !faults.invalid;
    for (std::size_t i = 0; i < 2; ++i) {
      if (faults.invalid || faults.nan_angle[i]) {
        r.gimbal_angle_rad(static_cast<Eigen::Index>(i)) = std::numeric_limits<T>::quiet_NaN();
      }
    }
    r.spin_valid = spin_valid;
    r.spin_hz = spin_valid ? spin_hz : T(0);
    reading_ = r;
  }

  [[nodiscard]] const PickoffReading<T>& reading() const noexcept { return reading_; }

 private:
  [[nodiscard]] T quantise(T v) const noexcept {
    if (model_.range_rad > T(0)) v = saturate(v, model_.range_rad);
    if (model_.lsb_rad > T(0)) {
      T code = std::round(v / model_.lsb_rad);
      if (model_.range_rad > T(0)) {
        const T max_code = std::floor(model_.range_rad / model_.lsb_rad);
        code = saturate(code, max_code);
      }
      v = code * model_.lsb_rad;
    }
    return v;
  }

  PickoffModel<T> model_{};
  T lag_gain_{T(1)};
  std::array<NoiseStream<T>, 2> noise_{};
  Vector2<T> lag_out_{Vector2<T>::Zero()};
  Vector2<T> converter_out_{Vector2<T>::Zero()};
  PickoffReading<T> reading_{};
};

}  // namespace gyro
