// A reference GyroPort for a register-mapped board (docs/porting.md): two 16-bit pickoff
// ADC channels, a 12-bit two-channel torquer DAC, a tachometer period counter. It shows what
// a driver converts and what it must detect itself: a channel at its rail (the rail is
// within the component's range check), a stuck channel, a conversion not yet renewed (the
// hardware counter is passed on, never invented), the DAC's clamping and its rounding.
//
// No heap, no exceptions, no RTTI, bounded work (no loops); float or double.
#pragma once

#include <cmath>
#include <cstdint>

#include "gyro/gyro_port.hpp"

namespace gyro::board {

// The converters as the board maps them (one struct placed at their base address, e.g.
// `*reinterpret_cast<GyroBoardRegisters*>(0x4001'2000)`).
struct GyroBoardRegisters {
  // Pickoff ADC, converting both channels on the tick timer's trigger.
  volatile std::int16_t adc_data[2];     // (pitch, yaw), two's complement, +-32767 = +-full scale
  volatile std::uint16_t adc_status;     // kAdcReady | kAdcFault
  volatile std::uint16_t adc_sequence;   // +1 per completed conversion (wraps at 2^16)
  // Tachometer: timer clocks between spin pulses, latched at each pulse.
  volatile std::uint32_t tach_period;    // 0: no pulse yet
  volatile std::uint16_t tach_status;    // kTachOverflow: no pulse within the counter's range
  // Torquer DAC, double-buffered: both inputs load together when dac_load is written.
  volatile std::uint16_t dac_input[2];   // (inner T1, outer T2), offset binary, 2048 = zero
  volatile std::uint16_t dac_load;       // write anything: both channels take their input
};

inline constexpr std::uint16_t kAdcReady = 1u << 0;   // a conversion has completed since reset
inline constexpr std::uint16_t kAdcFault = 1u << 1;   // the converter's own fault (reference, clock)
inline constexpr std::uint16_t kTachOverflow = 1u << 0;
inline constexpr std::int16_t kAdcFullScaleCode = 32767;
inline constexpr std::uint16_t kDacZeroCode = 2048;
inline constexpr std::uint16_t kDacMaxCode = 4095;
inline constexpr std::int32_t kDacHalfSpanCodes = 2047;  // codes 1..4095: symmetric about 2048

template <typename T>
struct BoardPortConfig {
  T pickoff_full_scale_rad{};          // the angle at code +32767 (= the component's pickoff_range_rad)
  std::uint16_t rail_margin_codes{2};  // |code| >= 32767 - margin: at the rail, not a reading
  std::uint32_t stuck_conversions{0};  // an unchanged code over this many conversions: stuck (0: off)
  T torque_full_scale{};               // torque at code 2048 +- 2047 (>= the component's max_torque)
  T tach_clock_hz{};                   // the capture timer's clock
  std::uint32_t tach_pulses_per_rev{1};
  T tach_min_hz{};                     // readbacks outside [min, max]: spin_valid false
  T tach_max_hz{};
};

// What the driver saw, for the board's own telemetry (the component flags the reading).
struct BoardPortDiagnostics {
  std::uint32_t not_ready{};           // reads before the first conversion
  std::uint32_t adc_faults{};          // reads with the converter's fault bit
  std::uint32_t rail_readings{};       // conversions with a channel at its rail
  std::uint32_t stuck_readings{};      // conversions with a channel stuck
  std::uint32_t missed_conversions{};  // conversions never read (the counter jumped by more than 1)
  std::uint32_t dac_clamped{};         // writes beyond the DAC's full scale
  std::uint32_t dac_rejected{};        // writes that could not be encoded (non-finite)
};

template <typename T>
class RegisterBoardPort final : public GyroPort<T> {
 public:
  RegisterBoardPort(GyroBoardRegisters& regs, const BoardPortConfig<T>& config) noexcept
      : regs_(regs),
        config_(config),
        adc_lsb_rad_(config.pickoff_full_scale_rad / T(kAdcFullScaleCode)),
        dac_codes_per_torque_(T(kDacHalfSpanCodes) / config.torque_full_scale) {}

  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    const std::uint16_t status = regs_.adc_status;
    if ((status & kAdcFault) != 0u) {
      ++diagnostics_.adc_faults;
      return PortStatus::kHardwareFault;
    }
    if ((status & kAdcReady) == 0u) {
      ++diagnostics_.not_ready;
      return PortStatus::kNotReady;
    }
    // The counter is read before and after the data: a conversion completing in between
    // would pair one conversion's pitch with the next's yaw. Read again once; if it moved
    // twice the bus is too slow for the converter.
    std::uint16_t seq = regs_.adc_sequence;
    std::int16_t code[2] = {regs_.adc_data[0], regs_.adc_data[1]};
    if (regs_.adc_sequence != seq) {
      seq = regs_.adc_sequence;
      code[0] = regs_.adc_data[0];
      code[1] = regs_.adc_data[1];
      if (regs_.adc_sequence != seq) return PortStatus::kBusError;
    }

    // The 16-bit counter widened to the port's 32 bits. Unchanged: the same conversion again
    // (the component flags it stale). A jump of n: n - 1 conversions were never read; the
    // latest is still this tick's.
    const auto advance = static_cast<std::uint16_t>(seq - last_hw_sequence_);
    const bool fresh = !have_sequence_ || advance != 0u;
    if (have_sequence_ && advance > 1u) diagnostics_.missed_conversions += advance - 1u;
    sequence_ += have_sequence_ ? advance : 1u;
    last_hw_sequence_ = seq;
    have_sequence_ = true;

    bool rail = false;
    bool stuck = false;
    for (int i = 0; i < 2; ++i) {
      const std::int32_t c = code[i];
      rail = rail || (c >= kAdcFullScaleCode - config_.rail_margin_codes) ||
             (c <= -(kAdcFullScaleCode - config_.rail_margin_codes));
      if (fresh) {
        same_code_[i] = (have_code_ && c == last_code_[i]) ? same_code_[i] + 1u : 0u;
        last_code_[i] = code[i];
      }
      stuck = stuck || (config_.stuck_conversions != 0u && same_code_[i] >= config_.stuck_conversions);
    }
    have_code_ = true;
    if (fresh && rail) ++diagnostics_.rail_readings;
    if (fresh && stuck) ++diagnostics_.stuck_readings;

    out.gimbal_angle_rad = Eigen::Matrix<T, 2, 1>(T(code[0]) * adc_lsb_rad_, T(code[1]) * adc_lsb_rad_);
    out.sequence = sequence_;
    out.valid = !rail && !stuck;  // the angle at a rail is only "beyond": no reading
    out.spin_hz = T(0);
    out.spin_valid = false;
    const std::uint32_t period = regs_.tach_period;
    if ((regs_.tach_status & kTachOverflow) == 0u && period != 0u) {
      const T hz = config_.tach_clock_hz / (T(period) * T(config_.tach_pulses_per_rev));
      if (hz >= config_.tach_min_hz && hz <= config_.tach_max_hz) {
        out.spin_hz = hz;
        out.spin_valid = true;
      }
    }
    return PortStatus::kOk;
  }

  // Torque (component units, N m here) to DAC codes. Clamped at the DAC's full scale (the
  // component already scales to max_torque, so a clamp means the two disagree: counted).
  // Rounded with error feedback: the rounding error of one write is added to the next, so
  // the torque held over any run of ticks is the commanded one to within one code, not
  // half a code every tick (a precession bias of 0.5 LSB / H otherwise).
  [[nodiscard]] PortStatus write_torquer(const Eigen::Matrix<T, 2, 1>& torque) noexcept override {
    if (!std::isfinite(torque(0)) || !std::isfinite(torque(1))) {
      ++diagnostics_.dac_rejected;
      return PortStatus::kBusError;  // the DAC keeps the last code
    }
    std::uint16_t code[2] = {};
    bool clamped = false;
    for (int i = 0; i < 2; ++i) {
      T want = torque(i) * dac_codes_per_torque_;
      const T limit = T(kDacHalfSpanCodes);
      if (want > limit || want < -limit) {
        want = want > limit ? limit : -limit;
        clamped = true;
        rounding_carry_[i] = T(0);
      }
      const T with_carry = want + rounding_carry_[i];
      std::int32_t c = static_cast<std::int32_t>(std::lround(with_carry));
      if (c > kDacHalfSpanCodes) c = kDacHalfSpanCodes;
      if (c < -kDacHalfSpanCodes) c = -kDacHalfSpanCodes;
      rounding_carry_[i] = with_carry - T(c);
      code[i] = static_cast<std::uint16_t>(std::int32_t{kDacZeroCode} + c);
    }
    if (clamped) ++diagnostics_.dac_clamped;
    regs_.dac_input[0] = code[0];
    regs_.dac_input[1] = code[1];
    regs_.dac_load = 1u;
    return PortStatus::kOk;
  }

  [[nodiscard]] const BoardPortDiagnostics& diagnostics() const noexcept { return diagnostics_; }
  [[nodiscard]] T adc_lsb_rad() const noexcept { return adc_lsb_rad_; }
  [[nodiscard]] T dac_lsb_torque() const noexcept { return T(1) / dac_codes_per_torque_; }

 private:
  GyroBoardRegisters& regs_;
  BoardPortConfig<T> config_;
  T adc_lsb_rad_;
  T dac_codes_per_torque_;
  std::uint32_t sequence_{0};
  std::uint16_t last_hw_sequence_{0};
  bool have_sequence_{false};
  bool have_code_{false};
  std::int16_t last_code_[2] = {0, 0};
  std::uint32_t same_code_[2] = {0u, 0u};
  T rounding_carry_[2] = {T(0), T(0)};
  BoardPortDiagnostics diagnostics_{};
};

}  // namespace gyro::board
