// SimulatedGyro: the software-in-the-loop gyro behind the hardware port. Every test drives
// it through the port (write_torquer / read_pickoffs) and the scenario side (start /
// advance), and checks the readings against the truth and against GyroModel stepped by hand.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "gyro/attitude.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro {
namespace {

using Sim = SimulatedGyro<double>;
using Config = SimulatedGyroConfig<double>;
using V2 = Vector2<double>;
using M3 = Matrix3<double>;

constexpr double kDt = 1e-3;  // 1 kHz: 7 ticks per nutation period of the report's gyro
constexpr double kSpinHz = 100.0;

// The report's gyro (slug*ft^2, 100 Hz spin), a clean pickoff and torquer.
Config base_config() {
  Config c;
  c.gyro = ReportSample<double>::config();
  c.tick_s = kDt;
  c.spin_hz = kSpinHz;
  return c;
}

// A body turning at constant pitch and yaw rates about its own axes (the report's driver).
struct Body {
  V2 rate_rad_s{V2::Zero()};
  M3 R{M3::Identity()};
  void step() { R = frame_rotation_z(rate_rad_s(1) * kDt) * frame_rotation_y(rate_rad_s(0) * kDt) * R; }
};

// H of the report's gyro at spin_hz.
double h_of(double spin_hz) { return angular_momentum(spin_hz, ReportSample<double>::config().spin_inertia); }

// The report's plant's model (every configuration here uses the report's plant).
const GyroModel<double>& model_of(const Sim& sim) {
  const GyroModel<double>* m = sim.report_model();
  if (m == nullptr) std::abort();
  return *m;
}

PickoffReading<double> read(Sim& sim) {
  PickoffReading<double> r;
  EXPECT_EQ(sim.read_pickoffs(r), PortStatus::kOk);
  return r;
}

V2 truth_angles(const Sim& sim) { return V2(model_of(sim).gimbal_pitch_rad(), model_of(sim).gimbal_yaw_rad()); }

const V2 kTurnForNoise(0.3, -0.2);

bool bit_equal(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// ---- lifecycle and the port contract ------------------------------------------------------

TEST(SimulatedGyroLifecycle, GivenNotStartedWhenPortCalledThenNotReady) {
  Sim sim;
  PickoffReading<double> r;
  EXPECT_EQ(sim.read_pickoffs(r), PortStatus::kNotReady);
  EXPECT_EQ(sim.write_torquer(V2(1, 1)), PortStatus::kNotReady);
  EXPECT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kNotConfigured);
  ASSERT_TRUE(sim.configure(base_config()).ok());
  EXPECT_EQ(sim.read_pickoffs(r), PortStatus::kNotReady);
  EXPECT_EQ(sim.advance(1, M3::Identity(), V2::Zero()), Status::kNotConfigured);
}

TEST(SimulatedGyroLifecycle, GivenStartedThenPowerUpConversionIsAlignedWithTheBody) {
  Sim sim;
  ASSERT_TRUE(sim.configure(base_config()).ok());
  Body body;
  body.R = frame_rotation_z(0.3) * frame_rotation_y(0.2);
  ASSERT_EQ(sim.start(body.R, V2(0.1, -0.2)), Status::kOk);
  const PickoffReading<double> r = read(sim);
  EXPECT_EQ(r.sequence, 1u);
  EXPECT_TRUE(r.valid);
  EXPECT_NEAR(r.gimbal_angle_rad(0), 0.0, 1e-12);
  EXPECT_NEAR(r.gimbal_angle_rad(1), 0.0, 1e-12);
  EXPECT_TRUE(r.spin_valid);
  EXPECT_EQ(r.spin_hz, kSpinHz);
  EXPECT_EQ(sim.tick(), 0u);
  EXPECT_EQ(model_of(sim).rate_rad_s(), V2(0.1, -0.2));
}

TEST(SimulatedGyroLifecycle, GivenBadAdvanceInputsThenRefusedAndNothingChanges) {
  Sim sim;
  ASSERT_TRUE(sim.configure(base_config()).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2(0.2, 0.1)), Status::kOk);
  ASSERT_EQ(sim.advance(1, M3::Identity(), V2::Zero()), Status::kOk);
  const PickoffReading<double> before = read(sim);
  const Quaternion<double> q = model_of(sim).attitude_gyro_to_earth();

  EXPECT_EQ(sim.advance(1, M3::Identity(), V2::Zero()), Status::kOutOfRange);  // repeated tick
  EXPECT_EQ(sim.advance(3, M3::Identity(), V2::Zero()), Status::kOutOfRange);  // skipped tick
  EXPECT_EQ(sim.advance(2, M3::Identity(), V2(std::nan(""), 0)), Status::kNonFiniteInput);
  M3 not_rotation = M3::Identity();
  not_rotation(0, 0) = 1.1;
  EXPECT_EQ(sim.advance(2, not_rotation, V2::Zero()), Status::kInvalidRotation);
  M3 nan_r = M3::Identity();
  nan_r(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(sim.advance(2, nan_r, V2::Zero()), Status::kInvalidRotation);

  EXPECT_EQ(sim.tick(), 1u);
  const PickoffReading<double> after = read(sim);
  EXPECT_EQ(after.sequence, before.sequence);
  EXPECT_EQ(after.gimbal_angle_rad, before.gimbal_angle_rad);
  EXPECT_EQ(model_of(sim).attitude_gyro_to_earth().coeffs(), q.coeffs());
  EXPECT_EQ(sim.advance(2, M3::Identity(), V2::Zero()), Status::kOk);
}

TEST(SimulatedGyroLifecycle, GivenNonFiniteTorqueCommandThenBusErrorAndPreviousCommandHeld) {
  Sim sim;
  ASSERT_TRUE(sim.configure(base_config()).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kOk);
  ASSERT_EQ(sim.write_torquer(V2(0.5, -0.25)), PortStatus::kOk);
  EXPECT_EQ(sim.write_torquer(V2(std::nan(""), 0)), PortStatus::kBusError);
  EXPECT_EQ(sim.write_torquer(V2(0, std::numeric_limits<double>::infinity())), PortStatus::kBusError);
  EXPECT_EQ(sim.applied_torque(), V2(0.5, -0.25));
}

// ---- zero-order hold: the torque of tick k acts over [k, k+1] -----------------------------

TEST(SimulatedGyroHold, GivenTorqueWrittenEachTickWhenAdvancedThenTruthIsGyroModelSteppedByHand) {
  Config c = base_config();
  c.gyro.errors.pitch.static_drift_rad_s = 1e-3;  // error sources go through the model as is
  c.gyro.errors.yaw.torquer_cross_coupling = 0.02;
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  GyroModel<double> ref;
  ASSERT_TRUE(ref.configure(c.gyro).ok());
  Body body;
  body.rate_rad_s = V2(0.4, -0.3);
  ASSERT_EQ(sim.start(body.R, body.rate_rad_s), Status::kOk);
  ASSERT_EQ(ref.uncage(body.R, body.rate_rad_s), Status::kOk);

  const double h = h_of(kSpinHz);
  for (std::size_t k = 0; k < 300; ++k) {
    // A command that changes every 7 ticks (held in between: no write).
    const double t = static_cast<double>(k / 7) * 7 * kDt;
    const V2 cmd(h * 0.05 * std::sin(3 * t), -h * 0.04 * std::cos(2 * t));
    if (k % 7 == 0) {
      const Quaternion<double> q_before = model_of(sim).attitude_gyro_to_earth();
      ASSERT_EQ(sim.write_torquer(cmd), PortStatus::kOk);
      // Writing does not move the rotor: it acts from now to the next tick.
      ASSERT_EQ(model_of(sim).attitude_gyro_to_earth().coeffs(), q_before.coeffs());
    }
    ASSERT_EQ(sim.applied_torque(), cmd);
    body.step();
    GyroStepInput<double> in;
    in.dt_s = kDt;
    in.R_earth_to_body = body.R;
    in.spin_hz = kSpinHz;
    ASSERT_EQ(ref.step_torque(in, cmd), Status::kOk);
    ASSERT_EQ(sim.advance(k + 1, body.R, V2::Zero()), Status::kOk);
    ASSERT_EQ(model_of(sim).attitude_gyro_to_earth().coeffs(), ref.attitude_gyro_to_earth().coeffs()) << k;
    ASSERT_EQ(model_of(sim).rate_rad_s(), ref.rate_rad_s()) << k;
    const PickoffReading<double> r = read(sim);
    ASSERT_EQ(r.gimbal_angle_rad, V2(ref.gimbal_pitch_rad(), ref.gimbal_yaw_rad())) << k;
    ASSERT_EQ(r.sequence, k + 2);
  }
  // The run did something: the commanded and drift precession moved the gyro.
  EXPECT_GT(truth_angles(sim).norm(), 1e-3);
}

// ---- pickoff chain ------------------------------------------------------------------------

// A run with the body turning, returning (reading, truth) per tick.
struct Sample {
  PickoffReading<double> reading;
  V2 truth;
  double spin_hz;
  std::uint32_t faults;
  V2 applied_torque;
};

std::vector<Sample> run(const Config& c, int ticks, const V2& body_rate, const V2& torque_cmd = V2::Zero()) {
  std::vector<Sample> out;
  Sim sim;
  EXPECT_TRUE(sim.configure(c).ok());
  Body body;
  body.rate_rad_s = body_rate;
  EXPECT_EQ(sim.start(body.R, V2::Zero()), Status::kOk);
  out.push_back({read(sim), truth_angles(sim), sim.spin_hz(), sim.active_faults(), sim.applied_torque()});
  for (int k = 1; k <= ticks; ++k) {
    EXPECT_EQ(sim.write_torquer(torque_cmd), PortStatus::kOk);
    body.step();
    EXPECT_EQ(sim.advance(static_cast<std::uint64_t>(k), body.R, V2::Zero()), Status::kOk);
    out.push_back({read(sim), truth_angles(sim), sim.spin_hz(), sim.active_faults(), sim.applied_torque()});
  }
  return out;
}

TEST(SimulatedGyroPickoff, GivenLsbThenReadingsAreIntegerMultiplesWithinHalfAnLsbOfTruth) {
  Config c = base_config();
  c.pickoff.lsb_rad = 1.0 / 4096.0 * 0.01;  // not a power of two in rad: a real scaling
  const std::vector<Sample> s = run(c, 500, V2(0.3, -0.2));
  int distinct_codes = 0;
  double last = 0;
  for (const Sample& x : s) {
    for (int i = 0; i < 2; ++i) {
      const double code = x.reading.gimbal_angle_rad(i) / c.pickoff.lsb_rad;
      ASSERT_NEAR(code, std::round(code), 1e-9);
      ASSERT_LE(std::abs(x.reading.gimbal_angle_rad(i) - x.truth(i)), c.pickoff.lsb_rad / 2 * (1 + 1e-9));
    }
    if (x.reading.gimbal_angle_rad(0) != last) ++distinct_codes;
    last = x.reading.gimbal_angle_rad(0);
  }
  EXPECT_GT(distinct_codes, 50);  // the body moved the gimbal across many codes
}

TEST(SimulatedGyroPickoff, GivenRangeThenReadingsSaturateAtTheLargestCodeInRange) {
  Config c = base_config();
  c.gyro.gimbal_cone_limit_rad = 1.0;
  c.pickoff.range_rad = 0.0105;
  c.pickoff.lsb_rad = 0.001;
  const std::vector<Sample> s = run(c, 100, V2(0.5, 0.0));  // pitch gimbal goes to -0.05
  EXPECT_LT(s.back().truth(0), -0.04);
  EXPECT_DOUBLE_EQ(s.back().reading.gimbal_angle_rad(0), -0.010);  // floor(range/lsb) codes
  for (const Sample& x : s) ASSERT_LE(std::abs(x.reading.gimbal_angle_rad(0)), c.pickoff.range_rad);

  c.pickoff.lsb_rad = 0;  // no quantisation: the range itself
  const std::vector<Sample> t = run(c, 100, V2(0.5, 0.0));
  EXPECT_DOUBLE_EQ(t.back().reading.gimbal_angle_rad(0), -0.0105);
}

// A resolution so fine that a reading's code (angle / lsb) overflows: 5e-324 rad was accepted
// and every reading came out infinite, marked valid. Refused with the field, the value and the
// bound: the full scale (the range, or pi without one) over the 32-bit count's 2^31 - 1 codes.
TEST(SimulatedGyroPickoff, GivenAResolutionTooFineForTheCountThenRefusedNamingFieldValueAndBound) {
  struct Case {
    double lsb, range, bound;
  };
  const Case cases[] = {
      {5e-324, 0.0, 3.141592653589793 / 2147483647.0},  // the smallest double
      {1e-300, 0.0, 3.141592653589793 / 2147483647.0},
      {1.4e-9, 0.0, 3.141592653589793 / 2147483647.0},  // just below pi / (2^31 - 1) = 1.463e-9
      {1e-12, 0.5, 0.5 / 2147483647.0},
      {2.3e-10, 0.5, 0.5 / 2147483647.0},               // just below 0.5 / (2^31 - 1) = 2.328e-10
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.lsb);
    Config c = base_config();
    c.pickoff.lsb_rad = k.lsb;
    c.pickoff.range_rad = k.range;
    Sim sim;
    const ConfigCheck r = sim.configure(c);
    EXPECT_EQ(r.status, Status::kOutOfRange);
    ASSERT_NE(r.field, nullptr);
    EXPECT_STREQ(r.field, "pickoff.lsb_rad");
    EXPECT_EQ(r.value, k.lsb);
    EXPECT_DOUBLE_EQ(r.bound, k.bound);
    EXPECT_EQ(r.relation, Relation::kBelow);
    EXPECT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kNotConfigured);
    std::array<char, 256> text{};
    (void)format_refusal(r, "gyro.", text.data(), text.size());
    EXPECT_NE(std::string(text.data()).find("gyro.pickoff.lsb_rad = "), std::string::npos) << text.data();
    EXPECT_NE(std::string(text.data()).find("is below"), std::string::npos) << text.data();
  }
  // In float the same bound holds (the smallest float, 1.4e-45, overflowed as well).
  SimulatedGyroConfig<float> f;
  cast_fields(base_config(), f);
  f.pickoff.lsb_rad = std::numeric_limits<float>::denorm_min();
  SimulatedGyro<float> fsim;
  const ConfigCheck fr = fsim.configure(f);
  EXPECT_EQ(fr.status, Status::kOutOfRange);
  ASSERT_NE(fr.field, nullptr);
  EXPECT_STREQ(fr.field, "pickoff.lsb_rad");
  EXPECT_EQ(fr.relation, Relation::kBelow);
}

TEST(SimulatedGyroPickoff, GivenTheFinestResolutionAcceptedThenEveryReadingIsFiniteOnItsCode) {
  for (const double range : {0.0, 0.5}) {
    SCOPED_TRACE(range);
    Config c = base_config();
    c.pickoff.range_rad = range;
    c.pickoff.lsb_rad = (range > 0 ? range : 3.141592653589793) / 2147483647.0 * (1 + 1e-12);
    {
      Sim sim;
      ASSERT_TRUE(sim.configure(c).ok());
    }
    const std::vector<Sample> s = run(c, 200, V2(0.3, -0.2));
    for (const Sample& x : s) {
      ASSERT_TRUE(x.reading.valid);
      for (int i = 0; i < 2; ++i) {
        const double v = x.reading.gimbal_angle_rad(i);
        ASSERT_TRUE(std::isfinite(v)) << v;
        ASSERT_LE(std::abs(v / c.pickoff.lsb_rad), 2147483647.0);
        ASSERT_NEAR(v, x.truth(i), c.pickoff.lsb_rad);
      }
    }
  }
}

// The pickoff's resolution above its range (no code within it) names the range as its bound.
TEST(SimulatedGyroPickoff, GivenAResolutionCoarserThanTheRangeThenRefusedWithTheRangeAsBound) {
  Config c = base_config();
  c.pickoff.range_rad = 0.01;
  c.pickoff.lsb_rad = 0.02;
  Sim sim;
  const ConfigCheck r = sim.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  ASSERT_NE(r.field, nullptr);
  EXPECT_STREQ(r.field, "pickoff.lsb_rad");
  EXPECT_EQ(r.relation, Relation::kAbove);
  EXPECT_EQ(r.value, 0.02);
  EXPECT_EQ(r.bound, 0.01);
  ASSERT_NE(r.bound_name, nullptr);
  EXPECT_STREQ(r.bound_name, "pickoff.range_rad");
}

TEST(SimulatedGyroPickoff, GivenBiasThenReadingIsTruthPlusBias) {
  Config c = base_config();
  c.pickoff.bias_rad = V2(1.5e-3, -2.5e-3);
  for (const Sample& x : run(c, 200, V2(0.2, 0.3))) {
    ASSERT_NEAR(x.reading.gimbal_angle_rad(0) - x.truth(0), 1.5e-3, 1e-15);
    ASSERT_NEAR(x.reading.gimbal_angle_rad(1) - x.truth(1), -2.5e-3, 1e-15);
  }
}

TEST(SimulatedGyroPickoff, GivenLagWhenGimbalStepsThenReadingReaches63PercentAfterLag) {
  Config c = base_config();
  c.pickoff.lag_s = 0.02;  // 20 ticks
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kOk);
  // The body jumps 0.01 rad nose up at tick 1: the inertial gyro's pitch gimbal steps to -0.01.
  const M3 R = frame_rotation_y(0.01);
  std::vector<double> fraction{0.0};
  for (std::size_t k = 1; k <= 100; ++k) {
    ASSERT_EQ(sim.advance(k, R, V2::Zero()), Status::kOk);
    ASSERT_NEAR(model_of(sim).gimbal_pitch_rad(), -0.01, 1e-12);
    fraction.push_back(read(sim).gimbal_angle_rad(0) / model_of(sim).gimbal_pitch_rad());
  }
  EXPECT_NEAR(fraction[20], 1 - std::exp(-1.0), 1e-9);  // 63.2 % after one time constant
  EXPECT_NEAR(fraction[1], 1 - std::exp(-kDt / 0.02), 1e-9);
  EXPECT_NEAR(fraction[60], 1 - std::exp(-3.0), 1e-9);
  for (std::size_t k = 1; k < fraction.size(); ++k) ASSERT_GT(fraction[k], fraction[k - 1]);
}

TEST(SimulatedGyroPickoff, GivenNoiseThenMeasuredSdMatchesNoiseRadAndAxesAreIndependent) {
  Config c = base_config();
  c.pickoff.noise_rad = 2e-4;
  c.seed = 77;
  const int n = 40000;
  const std::vector<Sample> s = run(c, n - 1, V2::Zero());
  double sum[2] = {0, 0}, sq[2] = {0, 0}, cross = 0;
  for (const Sample& x : s) {
    const V2 e = x.reading.gimbal_angle_rad - x.truth;
    for (int i = 0; i < 2; ++i) {
      sum[i] += e(i);
      sq[i] += e(i) * e(i);
    }
    cross += e(0) * e(1);
  }
  const double sd0 = std::sqrt(sq[0] / n), sd1 = std::sqrt(sq[1] / n);
  // CLT bounds (4.5 standard errors): se(mean) = sd/sqrt(n), se(sd) = sd/sqrt(2n).
  EXPECT_NEAR(sum[0] / n, 0.0, 4.5 * 2e-4 / std::sqrt(n));
  EXPECT_NEAR(sum[1] / n, 0.0, 4.5 * 2e-4 / std::sqrt(n));
  EXPECT_NEAR(sd0, 2e-4, 4.5 * 2e-4 / std::sqrt(2.0 * n));
  EXPECT_NEAR(sd1, 2e-4, 4.5 * 2e-4 / std::sqrt(2.0 * n));
  EXPECT_NEAR(cross / n / (sd0 * sd1), 0.0, 4.5 / std::sqrt(n));
  std::printf("[ measured ] pickoff noise sd pitch %.4e yaw %.4e (configured 2e-4), corr %.2e\n", sd0, sd1,
              cross / n / (sd0 * sd1));

  // Another seed gives other noise; the truth is the same.
  c.seed = 78;
  const std::vector<Sample> t = run(c, 10, V2::Zero());
  EXPECT_NE(t[5].reading.gimbal_angle_rad(0), s[5].reading.gimbal_angle_rad(0));
  EXPECT_EQ(t[5].truth, s[5].truth);
}

TEST(SimulatedGyroPickoff, GivenNoiseThenEachAxisDrawsItsOwnNamedStreamIndexedByTick) {
  // Reading - truth = noise_rad * (stream (seed, axis id), sample number = tick): documented,
  // so another program can reproduce it, and the axes cannot shift one another.
  Config c = base_config();
  c.pickoff.noise_rad = 1e-4;
  c.seed = 123;
  const NoiseStream<double> pitch(123, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoisePitch));
  const NoiseStream<double> yaw(123, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoiseYaw));
  const std::vector<Sample> s = run(c, 200, kTurnForNoise);
  for (std::size_t k = 0; k < s.size(); ++k) {
    ASSERT_NEAR(s[k].reading.gimbal_angle_rad(0) - s[k].truth(0), 1e-4 * pitch.gaussian(k), 1e-15) << k;
    ASSERT_NEAR(s[k].reading.gimbal_angle_rad(1) - s[k].truth(1), 1e-4 * yaw.gaussian(k), 1e-15) << k;
  }
}

TEST(SimulatedGyroPickoff, GivenReadbackOrNotThenSpinValidSaysSo) {
  Config c = base_config();
  c.has_spin_readback = false;
  const std::vector<Sample> s = run(c, 3, V2::Zero());
  EXPECT_FALSE(s.back().reading.spin_valid);
  EXPECT_EQ(s.back().reading.spin_hz, 0.0);
  EXPECT_EQ(s.back().spin_hz, kSpinHz);  // the rotor still spins
}

// ---- torquer ------------------------------------------------------------------------------

TEST(SimulatedGyroTorquer, GivenScaleFactorAndSaturationThenAppliedTorqueIsScaledThenClipped) {
  Config c = base_config();
  c.torquer.scale_factor = V2(0.5, 2.0);
  c.torquer.max_torque = 1.5;
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kOk);
  ASSERT_EQ(sim.write_torquer(V2(1.0, 0.2)), PortStatus::kOk);
  EXPECT_EQ(sim.applied_torque(), V2(0.5, 0.4));
  ASSERT_EQ(sim.write_torquer(V2(-4.0, 1.0)), PortStatus::kOk);
  EXPECT_EQ(sim.applied_torque(), V2(-1.5, 1.5));

  // The rotor feels the applied torque, not the command.
  GyroModel<double> ref;
  ASSERT_TRUE(ref.configure(c.gyro).ok());
  ASSERT_EQ(ref.uncage(M3::Identity(), V2::Zero()), Status::kOk);
  for (std::size_t k = 1; k <= 50; ++k) {
    GyroStepInput<double> in;
    in.dt_s = kDt;
    in.spin_hz = kSpinHz;
    ASSERT_EQ(ref.step_torque(in, V2(-1.5, 1.5)), Status::kOk);
    ASSERT_EQ(sim.advance(k, M3::Identity(), V2::Zero()), Status::kOk);
  }
  EXPECT_EQ(model_of(sim).attitude_gyro_to_earth().coeffs(), ref.attitude_gyro_to_earth().coeffs());
  EXPECT_EQ(model_of(sim).applied_torque(), V2(-1.5, 1.5));
}

// ---- mechanical gimbal stop ---------------------------------------------------------------

TEST(SimulatedGyroStop, GivenBodyTurningPastTheStopThenGimbalIsHeldOnTheStopAndDraggedAlong) {
  Config c = base_config();
  c.gimbal_stop_rad = 0.1;
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  Body body;
  body.rate_rad_s = V2(2.0, 1.0);  // cone grows at ~2.2 rad/s: the stop after ~45 ticks
  ASSERT_EQ(sim.start(body.R, V2::Zero()), Status::kOk);
  std::uint64_t first_hit = 0;
  int hits = 0;
  double max_cone = 0;
  for (std::size_t k = 1; k <= 400; ++k) {
    body.step();
    ASSERT_EQ(sim.advance(k, body.R, V2::Zero()), Status::kOk);
    const double cone = model_of(sim).gimbal_cone_rad();
    max_cone = std::max(max_cone, cone);
    if (sim.at_gimbal_stop()) {
      ++hits;
      ASSERT_NEAR(cone, 0.1, 1e-9) << k;
      if (first_hit == 0) {
        first_hit = k;
        // Put on the stop in the direction it was heading: the inertial spin axis lags the
        // body turning nose-up (pitch +2 rad/s) and right (yaw +1 rad/s), in proportion.
        EXPECT_NEAR(model_of(sim).gimbal_pitch_rad(), -0.1 * 2 / std::sqrt(5.0), 2e-3);
        EXPECT_NEAR(model_of(sim).gimbal_yaw_rad(), -0.1 / std::sqrt(5.0), 2e-3);
      }
      const PickoffReading<double> r = read(sim);
      ASSERT_NEAR(std::hypot(r.gimbal_angle_rad(0), r.gimbal_angle_rad(1)), 0.1, 2e-3);
    } else {
      ASSERT_LE(cone, 0.1) << k;
    }
  }
  EXPECT_GT(first_hit, 30u);
  EXPECT_LT(first_hit, 60u);
  EXPECT_GT(hits, 100);  // the body keeps pushing: the gimbal rides the stop
  EXPECT_LE(max_cone, 0.1 + 1e-9);
  // Held against the stop, the gyro precesses under the stop's reaction: the spin axis walks
  // round the rim (here from (-0.089, -0.045) to about (-0.068, +0.074) rad) but stays on it.
  std::printf("[ measured ] stop at 0.1 rad first hit at tick %llu, %d ticks on the stop, max cone %.12f, "
              "final (pitch, yaw) = (%.4f, %.4f)\n",
              static_cast<unsigned long long>(first_hit), hits, max_cone, model_of(sim).gimbal_pitch_rad(),
              model_of(sim).gimbal_yaw_rad());
}

TEST(SimulatedGyroStop, GivenImpactThenGimbalRatesAreTheBodyRates) {
  Config c = base_config();
  c.gimbal_stop_rad = 0.05;
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  Body body;
  body.rate_rad_s = V2(3.0, 0.0);
  ASSERT_EQ(sim.start(body.R, V2::Zero()), Status::kOk);
  for (std::size_t k = 1; k <= 100; ++k) {
    body.step();
    ASSERT_EQ(sim.advance(k, body.R, V2::Zero()), Status::kOk);
    if (sim.at_gimbal_stop()) {
      EXPECT_NEAR(model_of(sim).rate_rad_s()(0), 3.0, 1e-9);
      EXPECT_NEAR(model_of(sim).rate_rad_s()(1), 0.0, 1e-9);
      EXPECT_NEAR(model_of(sim).gimbal_pitch_rad(), -0.05, 1e-9);
      return;
    }
  }
  FAIL() << "never reached the stop";
}

TEST(SimulatedGyroStop, GivenNoStopConfiguredThenGimbalGoesPastWithOnlyTheModelFlag) {
  Config c = base_config();
  const std::vector<Sample> s = run(c, 300, V2(2.0, 0.0));
  EXPECT_LT(s.back().truth(0), -0.5);  // past the 0.436 rad cone limit: flagged, not stopped
}

// ---- spin ---------------------------------------------------------------------------------

TEST(SimulatedGyroSpin, GivenSpinDownTimeConstantThenSpinFollowsExponential) {
  Config c = base_config();
  c.spin_down_time_constant_s = 0.5;
  const std::vector<Sample> s = run(c, 1000, V2(0.1, 0.1), V2(0.5, 0.5));
  double worst = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double expected = kSpinHz * std::exp(-static_cast<double>(k) * kDt / 0.5);
    worst = std::max(worst, std::abs(s[k].spin_hz / expected - 1));
    ASSERT_EQ(s[k].reading.spin_hz, s[k].spin_hz);
  }
  EXPECT_LT(worst, 1e-13);
  EXPECT_NEAR(s[500].spin_hz, kSpinHz * std::exp(-1.0), 1e-11);  // 36.8 % after tau
  std::printf("[ measured ] spin-down: spin(tau) = %.10f Hz (100 e^-1 = %.10f), worst rel. error %.2e\n",
              s[500].spin_hz, kSpinHz * std::exp(-1.0), worst);
}

TEST(SimulatedGyroSpin, GivenSpinDownThenEachStepUsesTheMidStepSpin) {
  Config c = base_config();
  c.spin_down_time_constant_s = 0.3;
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  GyroModel<double> ref;
  ASSERT_TRUE(ref.configure(c.gyro).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2(0.1, 0.0)), Status::kOk);
  ASSERT_EQ(ref.uncage(M3::Identity(), V2(0.1, 0.0)), Status::kOk);
  ASSERT_EQ(sim.write_torquer(V2(1.0, 0.0)), PortStatus::kOk);
  for (std::size_t k = 1; k <= 100; ++k) {
    GyroStepInput<double> in;
    in.dt_s = kDt;
    in.spin_hz = kSpinHz * std::exp(-(static_cast<double>(k) - 0.5) * kDt / 0.3);
    ASSERT_EQ(ref.step_torque(in, V2(1.0, 0.0)), Status::kOk);
    ASSERT_EQ(sim.advance(k, M3::Identity(), V2::Zero()), Status::kOk);
  }
  EXPECT_LT((model_of(sim).attitude_gyro_to_earth().coeffs() - ref.attitude_gyro_to_earth().coeffs()).norm(), 1e-12);
}

// ---- faults -------------------------------------------------------------------------------

Config with_fault(FaultKind kind, std::uint64_t start, std::uint64_t duration, int axis, double magnitude = 0) {
  Config c = base_config();
  c.faults[2] = FaultEvent<double>{kind, start, duration, axis, magnitude};
  return c;
}

constexpr std::size_t kStart = 100, kDuration = 50, kEnd = kStart + kDuration;
const V2 kTurn(0.3, -0.2);  // the body turns: the gimbal angles change every tick

void expect_active_exactly_in_window(const std::vector<Sample>& s, FaultKind kind) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const bool in = k >= kStart && k < kEnd;
    ASSERT_EQ(s[k].faults, in ? fault_bit(kind) : 0u) << "tick " << k;
  }
}

TEST(SimulatedGyroFaults, GivenStuckPickoffThenReadingFreezesSequenceCountsAndItRecovers) {
  const std::vector<Sample> s = run(with_fault(FaultKind::kStuckPickoff, kStart, kDuration, 0), 200, kTurn);
  expect_active_exactly_in_window(s, FaultKind::kStuckPickoff);
  const double frozen = s[kStart - 1].reading.gimbal_angle_rad(0);
  for (std::size_t k = kStart; k < kEnd; ++k) {
    ASSERT_EQ(s[k].reading.gimbal_angle_rad(0), frozen) << k;                      // stuck
    ASSERT_EQ(s[k].reading.gimbal_angle_rad(1), s[k].truth(1)) << k;               // yaw alive
    ASSERT_EQ(s[k].reading.sequence, k + 1) << k;                                  // counting
    ASSERT_TRUE(s[k].reading.valid);
  }
  EXPECT_NE(s[kStart].truth(0), frozen);
  for (std::size_t k = kEnd; k < s.size(); ++k) ASSERT_EQ(s[k].reading.gimbal_angle_rad(0), s[k].truth(0));
}

TEST(SimulatedGyroFaults, GivenInvalidReadingOnOneAxisThenNanWithValidSet) {
  const std::vector<Sample> s = run(with_fault(FaultKind::kInvalidReading, kStart, kDuration, 1), 200, kTurn);
  expect_active_exactly_in_window(s, FaultKind::kInvalidReading);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const bool in = k >= kStart && k < kEnd;
    ASSERT_TRUE(s[k].reading.valid) << k;
    ASSERT_EQ(std::isnan(s[k].reading.gimbal_angle_rad(1)), in) << k;
    ASSERT_TRUE(std::isfinite(s[k].reading.gimbal_angle_rad(0))) << k;
    ASSERT_EQ(s[k].reading.sequence, k + 1);
  }
}

TEST(SimulatedGyroFaults, GivenInvalidReadingOnBothAxesThenNanWithValidClear) {
  const std::vector<Sample> s = run(with_fault(FaultKind::kInvalidReading, kStart, kDuration, -1), 200, kTurn);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const bool in = k >= kStart && k < kEnd;
    ASSERT_EQ(s[k].reading.valid, !in) << k;
    ASSERT_EQ(std::isnan(s[k].reading.gimbal_angle_rad(0)), in) << k;
    ASSERT_EQ(std::isnan(s[k].reading.gimbal_angle_rad(1)), in) << k;
  }
  EXPECT_EQ(s[kEnd].reading.gimbal_angle_rad, s[kEnd].truth);  // recovered
}

TEST(SimulatedGyroFaults, GivenDropoutThenWholeReadingIsStaleUntilItEnds) {
  const std::vector<Sample> s = run(with_fault(FaultKind::kDropout, kStart, kDuration, -1), 200, kTurn);
  expect_active_exactly_in_window(s, FaultKind::kDropout);
  const PickoffReading<double>& last = s[kStart - 1].reading;
  for (std::size_t k = kStart; k < kEnd; ++k) {
    ASSERT_EQ(s[k].reading.sequence, last.sequence) << k;
    ASSERT_EQ(s[k].reading.gimbal_angle_rad, last.gimbal_angle_rad) << k;
  }
  EXPECT_EQ(s[kEnd].reading.sequence, last.sequence + 1);
  EXPECT_EQ(s[kEnd].reading.gimbal_angle_rad, s[kEnd].truth);
}

TEST(SimulatedGyroFaults, GivenBiasJumpThenBiasAddsOnItsAxisInItsWindow) {
  for (int axis : {-1, 0, 1}) {
    const std::vector<Sample> s = run(with_fault(FaultKind::kBiasJump, kStart, kDuration, axis, 3e-3), 200, kTurn);
    expect_active_exactly_in_window(s, FaultKind::kBiasJump);
    for (std::size_t k = 0; k < s.size(); ++k) {
      const bool in = k >= kStart && k < kEnd;
      for (int i = 0; i < 2; ++i) {
        const double expected = (in && (axis < 0 || axis == i)) ? 3e-3 : 0.0;
        ASSERT_NEAR(s[k].reading.gimbal_angle_rad(i) - s[k].truth(i), expected, 1e-15) << k << " axis " << axis;
      }
    }
  }
}

TEST(SimulatedGyroFaults, GivenDeadTorquerThenAppliedTorqueIsZeroOnItsAxisInItsWindow) {
  const V2 cmd(0.8, -0.6);
  const std::vector<Sample> s = run(with_fault(FaultKind::kDeadTorquer, kStart, kDuration, 0), 200, kTurn, cmd);
  expect_active_exactly_in_window(s, FaultKind::kDeadTorquer);
  for (std::size_t k = 1; k < s.size(); ++k) {
    const bool in = k >= kStart && k < kEnd;
    ASSERT_EQ(s[k].applied_torque, V2(in ? 0.0 : 0.8, -0.6)) << k;
  }
}

TEST(SimulatedGyroFaults, GivenSaturatedTorquerThenAppliedTorqueIsPinnedWhateverTheCommand) {
  const std::vector<Sample> s =
      run(with_fault(FaultKind::kSaturatedTorquer, kStart, kDuration, 1, 2.5), 200, kTurn, V2(0.1, -0.3));
  expect_active_exactly_in_window(s, FaultKind::kSaturatedTorquer);
  for (std::size_t k = 1; k < s.size(); ++k) {
    const bool in = k >= kStart && k < kEnd;
    ASSERT_EQ(s[k].applied_torque, V2(0.1, in ? 2.5 : -0.3)) << k;
  }
}

TEST(SimulatedGyroFaults, GivenTorquerFaultThenRotorFeelsItOverTheTicksOfItsWindow) {
  // Dead torquer on both axes over ticks [100, 150): the rotor gets no torque over
  // [100, 150] and the command again from 150.
  const V2 cmd(0.8, -0.6);
  Config c = with_fault(FaultKind::kDeadTorquer, kStart, kDuration, -1);
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  GyroModel<double> ref;
  ASSERT_TRUE(ref.configure(c.gyro).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kOk);
  ASSERT_EQ(ref.uncage(M3::Identity(), V2::Zero()), Status::kOk);
  ASSERT_EQ(sim.write_torquer(cmd), PortStatus::kOk);
  for (std::size_t k = 0; k < 200; ++k) {
    GyroStepInput<double> in;
    in.dt_s = kDt;
    in.spin_hz = kSpinHz;
    const bool dead = k >= kStart && k < kEnd;
    ASSERT_EQ(ref.step_torque(in, dead ? V2::Zero() : cmd), Status::kOk);
    ASSERT_EQ(sim.advance(k + 1, M3::Identity(), V2::Zero()), Status::kOk);
    ASSERT_EQ(model_of(sim).attitude_gyro_to_earth().coeffs(), ref.attitude_gyro_to_earth().coeffs()) << k;
  }
}

TEST(SimulatedGyroFaults, GivenSpinMotorFailureThenSpinDecaysInItsWindowAndHoldsAfter) {
  const double tau = 0.2;
  const std::vector<Sample> s = run(with_fault(FaultKind::kSpinMotorFailure, kStart, kDuration, -1, tau), 200, kTurn);
  expect_active_exactly_in_window(s, FaultKind::kSpinMotorFailure);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double t_fail = static_cast<double>(std::min(std::max(k, kStart), kEnd) - kStart) * kDt;
    ASSERT_NEAR(s[k].spin_hz, kSpinHz * std::exp(-t_fail / tau), 1e-11) << k;
    ASSERT_EQ(s[k].reading.spin_hz, s[k].spin_hz);
  }
  EXPECT_EQ(s[kStart].spin_hz, kSpinHz);
  EXPECT_LT(s[kStart + 1].spin_hz, kSpinHz);
  EXPECT_EQ(s[kEnd].spin_hz, s.back().spin_hz);  // run-down stops with the fault
}

TEST(SimulatedGyroFaults, GivenSpinMotorFailureOnAFrictionlessGyroThenItRunsDownToExactlyZero) {
  // The rotor stops within the run: the stub keeps stepping (H = 0, f = 0: free gimbals).
  for (double friction : {0.0, 5.0}) {
    Config c = with_fault(FaultKind::kSpinMotorFailure, 10, 0, -1, 1e-3);
    c.gyro.friction = friction;
    const std::vector<Sample> s = run(c, 1000, kTurn, V2(1.0, 0.0));
    EXPECT_EQ(s.back().spin_hz, 0.0);
    EXPECT_EQ(s.back().reading.spin_hz, 0.0);
    EXPECT_TRUE(std::isfinite(s.back().reading.gimbal_angle_rad(0)));
  }
}

TEST(SimulatedGyroFaults, GivenPermanentFaultThenItNeverEnds) {
  const std::vector<Sample> s = run(with_fault(FaultKind::kDropout, 10, 0, -1), 300, kTurn);
  for (std::size_t k = 10; k < s.size(); ++k) {
    ASSERT_EQ(s[k].faults, fault_bit(FaultKind::kDropout));
    ASSERT_EQ(s[k].reading.sequence, 10u);
  }
}

TEST(SimulatedGyroFaults, GivenFaultFromPowerUpThenStuckAtThePowerUpConversion) {
  Config c = with_fault(FaultKind::kStuckPickoff, 0, 0, -1);
  c.pickoff.bias_rad = V2(1e-3, 2e-3);
  const std::vector<Sample> s = run(c, 50, kTurn);
  for (const Sample& x : s) ASSERT_EQ(x.reading.gimbal_angle_rad, V2(1e-3, 2e-3));
}

// ---- configuration ------------------------------------------------------------------------

TEST(SimulatedGyroConfigure, GivenBadFieldsThenRefusedWithTheFieldNamed) {
  struct Case {
    void (*mutate)(Config&);
    Status status;
    const char* field;
  };
  const Case cases[] = {
      {[](Config& c) { c.gyro.pitch_inertia = 0; }, Status::kNonPositiveInertia, "pitch_inertia"},
      {[](Config& c) { c.tick_s = 0; }, Status::kNonPositiveStep, "tick_s"},
      {[](Config& c) { c.tick_s = std::nan(""); }, Status::kNonFiniteInput, "tick_s"},
      {[](Config& c) { c.spin_hz = -1; }, Status::kOutOfRange, "spin_hz"},
      {[](Config& c) { c.spin_hz = std::numeric_limits<double>::infinity(); }, Status::kNonFiniteInput, "spin_hz"},
      {[](Config& c) { c.spin_down_time_constant_s = -1; }, Status::kOutOfRange, "spin_down_time_constant_s"},
      {[](Config& c) { c.pickoff.lsb_rad = -1e-3; }, Status::kOutOfRange, "pickoff.lsb_rad"},
      {[](Config& c) { c.pickoff.lag_s = std::nan(""); }, Status::kNonFiniteInput, "pickoff.lag_s"},
      {[](Config& c) { c.pickoff.noise_rad = -1; }, Status::kOutOfRange, "pickoff.noise_rad"},
      {[](Config& c) { c.pickoff.range_rad = -1; }, Status::kOutOfRange, "pickoff.range_rad"},
      {[](Config& c) { c.pickoff.range_rad = 0.01; c.pickoff.lsb_rad = 0.02; }, Status::kOutOfRange, "pickoff.lsb_rad"},
      {[](Config& c) { c.pickoff.bias_rad(1) = std::nan(""); }, Status::kNonFiniteInput, "pickoff.bias_rad"},
      {[](Config& c) { c.torquer.scale_factor(0) = std::nan(""); }, Status::kNonFiniteInput, "torquer.scale_factor"},
      {[](Config& c) { c.torquer.max_torque = -2; }, Status::kOutOfRange, "torquer.max_torque"},
      {[](Config& c) { c.gimbal_stop_rad = 4; }, Status::kOutOfRange, "gimbal_stop_rad"},
      {[](Config& c) { c.faults[3] = {FaultKind::kDropout, 0, 0, 2, 0}; }, Status::kOutOfRange, "faults[3].axis"},
      {[](Config& c) { c.faults[0].kind = static_cast<FaultKind>(99); }, Status::kOutOfRange, "faults[0].kind"},
      {[](Config& c) { c.faults[1] = {FaultKind::kSpinMotorFailure, 5, 0, -1, 0}; }, Status::kOutOfRange,
       "faults[1].magnitude"},
      {[](Config& c) { c.faults[7] = {FaultKind::kBiasJump, 5, 0, -1, std::nan("")}; }, Status::kNonFiniteInput,
       "faults[7].magnitude"},
      {[](Config& c) { c.faults[5] = {FaultKind::kDropout, ~std::uint64_t{0}, 2, -1, 0}; }, Status::kOutOfRange,
       "faults[5].duration_ticks"},
  };
  for (const Case& k : cases) {
    Config c = base_config();
    k.mutate(c);
    Sim sim;
    const ConfigCheck r = sim.configure(c);
    EXPECT_EQ(r.status, k.status) << k.field;
    ASSERT_NE(r.field, nullptr) << k.field;
    EXPECT_STREQ(r.field, k.field);
    EXPECT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kNotConfigured) << k.field;
  }
}

TEST(SimulatedGyroConfigure, GivenTheGimbalPlantThenReportOnlyFieldsAndUnresolvableSpinFailuresAreRefused) {
  Config c = SeekerExample<double>::stub();
  ASSERT_EQ(c.plant, PlantKind::kGimbal);
  Sim sim;
  ASSERT_TRUE(sim.configure(c).ok());
  c.spin_down_time_constant_s = 20.0;  // the report plant's: never silently ignored
  ConfigCheck r = sim.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_STREQ(r.field, "spin_down_time_constant_s");
  c = SeekerExample<double>::stub();
  c.faults[2] = {FaultKind::kSpinMotorFailure, 5, 0, -1, 1e-300};  // faster than the sub-steps resolve
  r = sim.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_STREQ(r.field, "faults[2].magnitude");
  c.faults[2].magnitude = 0.3;
  EXPECT_TRUE(sim.configure(c).ok());
}

TEST(SimulatedGyroConfigure, GivenRefusedReconfigurationThenTheRunningGyroIsUntouched) {
  Sim sim;
  ASSERT_TRUE(sim.configure(base_config()).ok());
  ASSERT_EQ(sim.start(M3::Identity(), V2::Zero()), Status::kOk);
  Config bad = base_config();
  bad.tick_s = -1;
  EXPECT_FALSE(sim.configure(bad).ok());
  EXPECT_EQ(sim.advance(1, M3::Identity(), V2::Zero()), Status::kOk);
  EXPECT_EQ(sim.config().tick_s, kDt);
}

// ---- determinism, float -------------------------------------------------------------------

Config everything_on() {
  Config c = base_config();
  c.spin_down_time_constant_s = 3.0;
  c.pickoff = PickoffModel<double>{1e-5, V2(2e-4, -1e-4), 4e-3, 3e-4, 0.3};
  c.torquer = TorquerModel<double>{V2(0.97, 1.02), 40.0};
  c.gimbal_stop_rad = 0.3;
  c.seed = 0xfeedu;
  c.gyro.errors.pitch.in_plane_erection_1_s = 0.01;
  c.gyro.errors.yaw.g_sensitive_drift_rad_s = 1e-3;
  c.faults[0] = {FaultKind::kBiasJump, 300, 100, 0, 1e-3};
  c.faults[1] = {FaultKind::kDropout, 500, 3, -1, 0};
  c.faults[2] = {FaultKind::kSpinMotorFailure, 800, 0, -1, 2.0};
  return c;
}

TEST(SimulatedGyroDeterminism, GivenTwoRunsWithEverythingOnThenBitIdentical) {
  const V2 cmd(3.0, -2.0);
  const std::vector<Sample> a = run(everything_on(), 1500, V2(0.7, -0.5), cmd);
  const std::vector<Sample> b = run(everything_on(), 1500, V2(0.7, -0.5), cmd);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    for (int i = 0; i < 2; ++i) {
      ASSERT_TRUE(bit_equal(a[k].reading.gimbal_angle_rad(i), b[k].reading.gimbal_angle_rad(i))) << k;
      ASSERT_TRUE(bit_equal(a[k].truth(i), b[k].truth(i))) << k;
    }
    ASSERT_EQ(a[k].reading.sequence, b[k].reading.sequence);
    ASSERT_TRUE(bit_equal(a[k].spin_hz, b[k].spin_hz));
  }
}

TEST(SimulatedGyroFloat, GivenFloatStubThenItTracksTheDoubleStub) {
  SimulatedGyroConfig<float> cf;
  cf.gyro = ReportSample<float>::config();
  cf.tick_s = 1e-3f;
  cf.spin_hz = 100.0f;
  cf.pickoff.lsb_rad = 1e-5f;
  SimulatedGyro<float> f;
  ASSERT_TRUE(f.configure(cf).ok());
  Config cd = base_config();
  cd.pickoff.lsb_rad = 1e-5;
  Sim d;
  ASSERT_TRUE(d.configure(cd).ok());
  Matrix3<float> Rf = Matrix3<float>::Identity();
  Body body;
  body.rate_rad_s = V2(0.3, 0.2);
  ASSERT_EQ(f.start(Rf, Vector2<float>::Zero()), Status::kOk);
  ASSERT_EQ(d.start(body.R, V2::Zero()), Status::kOk);
  ASSERT_EQ(f.write_torquer(Vector2<float>(1.0f, -1.0f)), PortStatus::kOk);
  ASSERT_EQ(d.write_torquer(V2(1.0, -1.0)), PortStatus::kOk);
  for (std::size_t k = 1; k <= 500; ++k) {
    body.step();
    Rf = body.R.cast<float>();
    ASSERT_EQ(f.advance(k, Rf, Vector2<float>::Zero()), Status::kOk);
    ASSERT_EQ(d.advance(k, body.R, V2::Zero()), Status::kOk);
  }
  PickoffReading<float> rf;
  ASSERT_EQ(f.read_pickoffs(rf), PortStatus::kOk);
  const PickoffReading<double> rd = read(d);
  EXPECT_NEAR(static_cast<double>(rf.gimbal_angle_rad(0)), rd.gimbal_angle_rad(0), 1e-4);
  EXPECT_NEAR(static_cast<double>(rf.gimbal_angle_rad(1)), rd.gimbal_angle_rad(1), 1e-4);
  EXPECT_EQ(rf.sequence, rd.sequence);
}

}  // namespace
}  // namespace gyro
