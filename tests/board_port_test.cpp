// RegisterBoardPort (examples/board): the reference port of a register-mapped board, against
// the SIL stub's electronics. The "registers" are filled from SimulatedGyro's conversions
// (pickoff angles quantised into 16-bit ADC codes, the spin into tachometer periods) and the
// DAC codes the port writes are turned back into torque for the stub: the real GyroComponent
// flies the seeker through the port, and each detection the driver owns is shown flagged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "gyro/board/register_board_port.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro::board {
namespace {

using F = float;

constexpr F kTachClockHz = F(10e6);

BoardPortConfig<F> board_config() {
  BoardPortConfig<F> c;
  c.pickoff_full_scale_rad = SeekerExample<F>::component().pickoff_range_rad;  // 0.6 rad: 18.3 urad a code
  c.rail_margin_codes = 2;
  c.stuck_conversions = 40;  // 20 ms; the converter's noise (about 1 code rms) moves every healthy code
  c.torque_full_scale = SeekerExample<F>::component().max_torque;  // 0.1 N m: 4.9e-5 N m a code
  c.tach_clock_hz = kTachClockHz;
  c.tach_pulses_per_rev = 1;
  c.tach_min_hz = F(10);
  c.tach_max_hz = F(1000);
  return c;
}

// The seeker's stub with converter noise of about one ADC code (what keeps a healthy code
// moving: the stuck check needs it).
SimulatedGyroConfig<F> noisy_stub() {
  SimulatedGyroConfig<F> s = SeekerExample<F>::stub();
  s.pickoff.noise_rad = F(2e-5);
  return s;
}

// The board's converters, emulated from the stub: what the hardware would put in the
// registers, and the torque its DAC and drive would apply. Faults are injected here, at the
// registers, where a real board would show them.
class BoardHardware {
 public:
  // A stuck channel's code: 0.9 mrad, far from the caged gimbal's few codes, within the
  // component's pickoff step and residual limit (the driver must catch it, nobody else can).
  static constexpr std::int16_t kStuckCode = 50;
  GyroBoardRegisters regs{};
  int rail_axis{-1};           // this channel reads +full scale (at its rail)
  int stuck_axis{-1};          // this channel's code stops changing (held at kStuckCode)
  bool sequence_frozen{false}; // the converter did not complete a conversion (no new data)
  bool adc_fault{false};
  std::uint16_t sequence_offset{0};
  // The conversion taken this many ticks after the tick (negative: before it), extrapolated
  // from the stub's last two conversions (the gimbal moves smoothly over a tick).
  F sample_shift_ticks{0};

  explicit BoardHardware(const BoardPortConfig<F>& c)
      : lsb_rad_(c.pickoff_full_scale_rad / F(kAdcFullScaleCode)),
        torque_lsb_(c.torque_full_scale / F(kDacHalfSpanCodes)) {
    regs.dac_input[0] = kDacZeroCode;
    regs.dac_input[1] = kDacZeroCode;
  }

  // A conversion of the stub's reading (its angles, sequence and spin).
  void convert(const PickoffReading<F>& r) {
    regs.adc_status = static_cast<std::uint16_t>(kAdcReady | (adc_fault ? kAdcFault : 0u));
    if (sequence_frozen) return;
    const Vector2<F> angle = r.gimbal_angle_rad + sample_shift_ticks * (r.gimbal_angle_rad - last_angle_);
    last_angle_ = r.gimbal_angle_rad;
    for (int i = 0; i < 2; ++i) {
      const F counts = std::round(angle(i) / lsb_rad_);
      const F clamped = std::fmin(F(kAdcFullScaleCode), std::fmax(-F(kAdcFullScaleCode), counts));
      std::int16_t code = static_cast<std::int16_t>(clamped);
      if (i == stuck_axis) code = kStuckCode;
      if (i == rail_axis) code = kAdcFullScaleCode;
      regs.adc_data[i] = code;
    }
    regs.adc_sequence = static_cast<std::uint16_t>(r.sequence + sequence_offset);
    regs.tach_period = r.spin_valid ? static_cast<std::uint32_t>(std::lround(kTachClockHz / r.spin_hz)) : 0u;
    regs.tach_status = r.spin_valid ? std::uint16_t{0} : kTachOverflow;
  }

  // The torque the drive applies: the codes latched at the last load, held until the next.
  Vector2<F> torque() {
    if (regs.dac_load != 0u) {
      held_[0] = regs.dac_input[0];
      held_[1] = regs.dac_input[1];
      regs.dac_load = 0u;
    }
    return Vector2<F>(F(static_cast<int>(held_[0]) - kDacZeroCode) * torque_lsb_,
                      F(static_cast<int>(held_[1]) - kDacZeroCode) * torque_lsb_);
  }

  [[nodiscard]] F lsb_rad() const { return lsb_rad_; }

 private:
  F lsb_rad_;
  F torque_lsb_;
  std::uint16_t held_[2] = {kDacZeroCode, kDacZeroCode};
  Vector2<F> last_angle_{Vector2<F>::Zero()};
};

// The flight computer of the SIL loop: each tick the stub's conversion goes into the
// registers, the component steps through the board port, the DAC's torque goes to the stub.
class BoardRig {
 public:
  BoardRig(SimulatedGyro<F>& stub, const BoardPortConfig<F>& c) : stub_(stub), hardware(c), port(hardware.regs, c) {}

  Status activate() { return component.activate(); }
  Status step(std::uint64_t tick, const GuidanceInput<F>& in) {
    PickoffReading<F> r;
    if (stub_.read_pickoffs(r) == PortStatus::kOk) hardware.convert(r);
    const Status s = component.step(tick, in);
    (void)stub_.write_torquer(hardware.torque());
    return s;
  }

 private:
  SimulatedGyro<F>& stub_;

 public:
  BoardHardware hardware;
  RegisterBoardPort<F> port;
  GyroComponent<F> component{port};
};

// Component (directly on the stub, or a BoardRig) in the SIL loop, body at rest, one tick at
// a time.
template <typename Computer>
class Flight {
 public:
  SimulatedGyro<F>& stub;
  Computer& computer;
  SilLoop<F, Computer> loop{stub, computer};
  GuidanceCommand<F> command{};
  std::uint64_t tick{0};

  Flight(SimulatedGyro<F>& s, Computer& c) : stub(s), computer(c) {}

  bool start() {
    const SilStatus<Status> s = loop.start(BodySample<F>{});
    return s.stub == Status::kOk && s.component == Status::kOk;
  }
  Status step(ModeRequest request = ModeRequest::kNone) {
    command.request = request;
    const SilStatus<Status> s = loop.tick(++tick, BodySample<F>{}, command);
    return s.stub != Status::kOk ? s.stub : s.component;
  }
  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) (void)step();
  }
  // Mean true spin-axis rate over `ticks` ticks at the slew command `cmd`, after `settle`.
  Vector2<double> mean_rate(const Vector2<F>& cmd, int settle, int ticks) {
    command.slew_rate_cmd_rad_s = cmd;
    run(settle);
    Vector2<double> sum = Vector2<double>::Zero();
    for (int k = 0; k < ticks; ++k) {
      (void)step();
      sum += stub.spin_axis_rate_rad_s().cast<double>();
    }
    return sum / ticks;
  }
};

struct SlewResult {
  Vector2<double> slew_error;  // mean true rate - command while slewing
  Vector2<double> hold_rate;   // mean true rate while holding (command zero)
  GyroMode mode{};
  std::uint32_t residual_faults{};
  std::uint32_t pickoff_flags{};  // invalid + stale + jump counters
};

// Cage (200 ticks), uncage and settle, slew at (0.3, -0.2) rad/s (settle 0.3 s, average
// 0.2 s), hold (settle 0.1 s, average 0.2 s): the SIL's closed-loop slew case.
template <typename Computer>
SlewResult fly_cage_uncage_slew_hold(SimulatedGyro<F>& stub, Computer& computer, const GyroComponent<F>& component) {
  Flight<Computer> flight(stub, computer);
  SlewResult out;
  if (!flight.start()) return out;
  flight.run(200);
  (void)flight.step(ModeRequest::kUncage);
  flight.run(static_cast<int>(SeekerExample<F>::component().uncage_settle_ticks));
  const Vector2<F> cmd(F(0.3), F(-0.2));
  out.slew_error = flight.mean_rate(cmd, 600, 400) - cmd.cast<double>();
  out.hold_rate = flight.mean_rate(Vector2<F>::Zero(), 200, 400);
  const GyroTelemetry<F>& tm = component.telemetry();
  out.mode = tm.mode;
  out.residual_faults = tm.counters[6];
  out.pickoff_flags = tm.counters[3] + tm.counters[4] + tm.counters[5];
  return out;
}

TEST(BoardPortSil, GivenTheSeekerThenItSlewsThroughThePortAsOnTheStub) {
  SimulatedGyro<F> plain_stub;
  ASSERT_TRUE(plain_stub.configure(noisy_stub()).ok());
  GyroComponent<F> plain(plain_stub);
  ASSERT_TRUE(plain.configure(SeekerExample<F>::component()).ok());
  const SlewResult sil = fly_cage_uncage_slew_hold(plain_stub, plain, plain);

  SimulatedGyro<F> stub;
  ASSERT_TRUE(stub.configure(noisy_stub()).ok());
  BoardRig rig(stub, board_config());
  ASSERT_TRUE(rig.component.configure(SeekerExample<F>::component()).ok());
  const SlewResult board = fly_cage_uncage_slew_hold(stub, rig, rig.component);

  std::printf("slew error (pitch, yaw) rad/s: on the stub %.2e %.2e, through the board port %.2e %.2e\n",
              sil.slew_error(0), sil.slew_error(1), board.slew_error(0), board.slew_error(1));
  std::printf("hold rate rad/s: on the stub %.2e %.2e, through the board port %.2e %.2e\n", sil.hold_rate(0),
              sil.hold_rate(1), board.hold_rate(0), board.hold_rate(1));
  const double cmd_norm = std::hypot(0.3, 0.2);
  // The SIL's closed-loop bound (tests/component_torque_test.cpp): 1e-4 of the command.
  EXPECT_LT(sil.slew_error.cwiseAbs().maxCoeff(), 1e-4 * cmd_norm);
  EXPECT_LT(board.slew_error.cwiseAbs().maxCoeff(), 1e-4 * cmd_norm);
  EXPECT_LT(board.hold_rate.cwiseAbs().maxCoeff(), 1e-4 * cmd_norm);
  EXPECT_EQ(board.mode, GyroMode::kFree);
  EXPECT_EQ(board.residual_faults, 0u);
  EXPECT_EQ(board.pickoff_flags, 0u) << "no healthy conversion refused (rail, stuck, stale)";
  const BoardPortDiagnostics& d = rig.port.diagnostics();
  EXPECT_EQ(d.rail_readings + d.stuck_readings + d.missed_conversions + d.dac_clamped + d.dac_rejected, 0u);
}

// What a sample taken off the tick costs: the estimator takes the reading as the angle at the
// tick, so a sample d late (early) is off by the gimbal's rate relative to the body times d,
// and the estimate follows it (the residual feedback pulls the attitude onto the readings).
TEST(BoardPortSil, GivenPickoffsSampledOffTheTickThenTheEstimateIsOffByRateTimesDelay) {
  const F tick = SeekerExample<F>::kTick;
  const Vector2<F> cmd(F(0.3), F(-0.2));  // the gimbal's rate relative to the body at rest
  const double rate = std::hypot(0.3, 0.2);
  for (const F shift : {F(0), F(0.25), F(0.5), F(1), F(-0.5)}) {
    SimulatedGyro<F> stub;
    ASSERT_TRUE(stub.configure(noisy_stub()).ok());
    BoardRig rig(stub, board_config());
    ASSERT_TRUE(rig.component.configure(SeekerExample<F>::component()).ok());
    rig.hardware.sample_shift_ticks = shift;
    Flight<BoardRig> flight(stub, rig);
    ASSERT_TRUE(flight.start());
    flight.run(200);
    (void)flight.step(ModeRequest::kUncage);
    flight.run(static_cast<int>(SeekerExample<F>::component().uncage_settle_ticks));
    flight.command.slew_rate_cmd_rad_s = cmd;
    double worst_residual = 0.0;
    double error_sum = 0.0;
    const int ticks = 1000;  // 0.5 s: the estimate settles in 1 / (gain x rate) = 0.1 s
    for (int k = 0; k < ticks; ++k) {
      (void)flight.step();
      const GyroTelemetry<F>& tm = rig.component.telemetry();
      worst_residual = std::max(worst_residual, static_cast<double>(tm.residual_rad.cwiseAbs().maxCoeff()));
      if (k >= ticks / 2) error_sum += (tm.gimbal_predicted_rad - stub.gimbal_angle_rad()).cast<double>().norm();
    }
    const double estimate_error = error_sum / (ticks / 2);
    const double expected = rate * std::abs(static_cast<double>(shift * tick));
    std::printf("sample %+.2f tick (%+5.0f us): estimate off by %.2e rad (rate x delay %.2e), worst residual %.2e\n",
                static_cast<double>(shift), 1e6 * static_cast<double>(shift * tick), estimate_error, expected,
                worst_residual);
    EXPECT_EQ(rig.component.mode(), GyroMode::kFree);
    if (shift != F(0)) {
      EXPECT_NEAR(estimate_error, expected, 0.3 * expected + 1e-5);
    } else {
      EXPECT_LT(estimate_error, 1e-5);
    }
  }
}

// A board flown caged for 100 ticks, for the detections.
class BoardPortDetection : public ::testing::Test {
 protected:
  SimulatedGyro<F> stub;
  BoardRig rig{stub, board_config()};
  Flight<BoardRig> flight{stub, rig};

  void SetUp() override {
    ASSERT_TRUE(stub.configure(noisy_stub()).ok());
    ASSERT_TRUE(rig.component.configure(SeekerExample<F>::component()).ok());
    ASSERT_TRUE(flight.start());
    flight.run(100);
    ASSERT_EQ(rig.component.telemetry().flags, 0u);
  }
  [[nodiscard]] std::uint32_t flags() const { return rig.component.telemetry().flags; }
};

TEST_F(BoardPortDetection, GivenAChannelAtItsRailThenTheReadingIsInvalid) {
  // The rail is inside the component's own range check: only the driver can tell.
  ASSERT_LE(F(kAdcFullScaleCode) * rig.hardware.lsb_rad(), SeekerExample<F>::component().pickoff_range_rad);
  rig.hardware.rail_axis = 0;
  (void)flight.step();
  EXPECT_NE(flags() & kPickoffInvalid, 0u);
  EXPECT_EQ(rig.port.diagnostics().rail_readings, 1u);
  rig.hardware.rail_axis = -1;
  (void)flight.step();
  EXPECT_EQ(flags() & (kPickoffInvalid | kPickoffStale | kPickoffJump), 0u) << "accepted again at once";
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
}

TEST_F(BoardPortDetection, GivenAChannelStuckThenInvalidFromTheNthRepeatOn) {
  rig.hardware.stuck_axis = 1;
  const auto n = static_cast<int>(board_config().stuck_conversions);
  (void)flight.step();  // the channel jumps to its stuck code: a change
  ASSERT_EQ(flags() & kPickoffInvalid, 0u);
  for (int k = 1; k < n; ++k) {
    (void)flight.step();
    ASSERT_EQ(flags() & kPickoffInvalid, 0u) << "repeat " << k << " of " << n;
  }
  (void)flight.step();
  EXPECT_NE(flags() & kPickoffInvalid, 0u);
  EXPECT_EQ(rig.port.diagnostics().stuck_readings, 1u);
  rig.hardware.stuck_axis = -1;
  flight.run(2);  // the code moves again (noise): accepted
  EXPECT_EQ(flags() & kPickoffInvalid, 0u);
}

TEST_F(BoardPortDetection, GivenNoNewConversionThenTheSameSequenceIsStale) {
  rig.hardware.sequence_frozen = true;
  (void)flight.step();
  EXPECT_NE(flags() & kPickoffStale, 0u);
  EXPECT_EQ(flags() & kPickoffInvalid, 0u) << "stale, not invalid: the driver passes the counter on";
  EXPECT_EQ(rig.port.diagnostics().stuck_readings, 0u) << "a repeated conversion is not a stuck code";
  rig.hardware.sequence_frozen = false;
  (void)flight.step();
  EXPECT_EQ(flags() & (kPickoffStale | kPickoffInvalid), 0u);
  EXPECT_EQ(rig.port.diagnostics().missed_conversions, 1u) << "the conversion of the frozen tick was lost";
}

TEST_F(BoardPortDetection, GivenTheConverterFaultBitThenHardwareFaultAndInvalid) {
  rig.hardware.adc_fault = true;
  (void)flight.step();
  EXPECT_NE(flags() & kPickoffInvalid, 0u);
  PickoffReading<F> r;
  EXPECT_EQ(rig.port.read_pickoffs(r), PortStatus::kHardwareFault);
  EXPECT_EQ(rig.port.diagnostics().adc_faults, 2u);
}

// The port alone, on a register block of its own.
class BoardPortUnit : public ::testing::Test {
 protected:
  GyroBoardRegisters regs{};
  RegisterBoardPort<F> port{regs, board_config()};
  PickoffReading<F> r;

  [[nodiscard]] std::uint16_t dac(int i) const { return regs.dac_input[i]; }
  [[nodiscard]] std::uint16_t load() const { return regs.dac_load; }
  PortStatus read_with_sequence(std::uint16_t seq, std::int16_t pitch = 100) {
    regs.adc_status = kAdcReady;
    regs.adc_sequence = seq;
    regs.adc_data[0] = pitch;
    regs.adc_data[1] = static_cast<std::int16_t>(-pitch);
    return port.read_pickoffs(r);
  }
};

TEST_F(BoardPortUnit, GivenNoConversionYetThenNotReady) {
  EXPECT_EQ(port.read_pickoffs(r), PortStatus::kNotReady);
  EXPECT_EQ(port.diagnostics().not_ready, 1u);
}

TEST_F(BoardPortUnit, GivenTheCounterWrapsOrJumpsThenTheSequenceFollowsIt) {
  ASSERT_EQ(read_with_sequence(65534), PortStatus::kOk);
  const std::uint32_t first = r.sequence;
  ASSERT_EQ(read_with_sequence(65535, 101), PortStatus::kOk);
  EXPECT_EQ(r.sequence, first + 1u);
  ASSERT_EQ(read_with_sequence(0, 102), PortStatus::kOk);
  EXPECT_EQ(r.sequence, first + 2u) << "across the 16-bit wrap";
  ASSERT_EQ(read_with_sequence(3, 103), PortStatus::kOk);
  EXPECT_EQ(r.sequence, first + 5u) << "a jump is passed on";
  EXPECT_EQ(port.diagnostics().missed_conversions, 2u);
  ASSERT_EQ(read_with_sequence(3, 103), PortStatus::kOk);
  EXPECT_EQ(r.sequence, first + 5u) << "no new conversion: the same sequence";
  EXPECT_TRUE(r.valid);
  EXPECT_NEAR(r.gimbal_angle_rad(0), 103.0F * port.adc_lsb_rad(), 1e-9F);
  EXPECT_NEAR(r.gimbal_angle_rad(1), -103.0F * port.adc_lsb_rad(), 1e-9F);
}

TEST_F(BoardPortUnit, GivenTheNegativeRailThenInvalid) {
  ASSERT_EQ(read_with_sequence(1, -32768), PortStatus::kOk);
  EXPECT_FALSE(r.valid);
  ASSERT_EQ(read_with_sequence(2, static_cast<std::int16_t>(-(kAdcFullScaleCode - 3))), PortStatus::kOk);
  EXPECT_TRUE(r.valid) << "three codes inside the rail: a reading";
}

TEST_F(BoardPortUnit, GivenTheTachometerThenSpinFromThePeriodAndNoneWhenStopped) {
  regs.tach_period = 25000;  // 10 MHz / 25,000 = 400 Hz
  ASSERT_EQ(read_with_sequence(1), PortStatus::kOk);
  EXPECT_TRUE(r.spin_valid);
  EXPECT_FLOAT_EQ(r.spin_hz, 400.0F);
  regs.tach_status = kTachOverflow;
  ASSERT_EQ(read_with_sequence(2), PortStatus::kOk);
  EXPECT_FALSE(r.spin_valid);
  regs.tach_status = 0;
  regs.tach_period = 5000000;  // 2 Hz: below tach_min_hz
  ASSERT_EQ(read_with_sequence(3), PortStatus::kOk);
  EXPECT_FALSE(r.spin_valid);
}

TEST_F(BoardPortUnit, GivenTorquesThenCodesClampedAtFullScaleAndNanRefused) {
  const F full = board_config().torque_full_scale;
  ASSERT_EQ(port.write_torquer(Vector2<F>(F(0), F(0))), PortStatus::kOk);
  EXPECT_EQ(dac(0), kDacZeroCode);
  EXPECT_EQ(load(), 1u);
  ASSERT_EQ(port.write_torquer(Vector2<F>(F(2) * full, -F(2) * full)), PortStatus::kOk);
  EXPECT_EQ(dac(0), kDacMaxCode);
  EXPECT_EQ(dac(1), 1u);
  EXPECT_EQ(port.diagnostics().dac_clamped, 1u);
  regs.dac_load = 0;
  EXPECT_EQ(port.write_torquer(Vector2<F>(std::nanf(""), F(0))), PortStatus::kBusError);
  EXPECT_EQ(dac(0), kDacMaxCode) << "the DAC keeps the last code";
  EXPECT_EQ(load(), 0u) << "nothing loaded";
  EXPECT_EQ(port.diagnostics().dac_rejected, 1u);
}

TEST_F(BoardPortUnit, GivenAConstantTorqueBetweenCodesThenTheMeanCodeIsExact) {
  // 0.3 codes: plain rounding writes 0 every time (a torque bias of 0.3 codes, 2e-4 rad/s
  // of precession on the seeker); error feedback writes 0 and 1 so that the sum is right.
  const F torque = F(0.3) * port.dac_lsb_torque();
  long sum = 0;
  for (int k = 1; k <= 1000; ++k) {
    ASSERT_EQ(port.write_torquer(Vector2<F>(torque, -torque)), PortStatus::kOk);
    sum += static_cast<long>(regs.dac_input[0]) - kDacZeroCode;
    ASSERT_LE(std::abs(static_cast<double>(sum) - 0.3 * k), 1.0) << "after " << k << " writes";
  }
  EXPECT_NEAR(static_cast<double>(sum), 300.0, 1.0);
}

}  // namespace
}  // namespace gyro::board
