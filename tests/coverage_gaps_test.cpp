// Behaviour of component/ and port/ that the other suites left unexercised (found by
// scripts/coverage.sh): the status and mode texts, a cage request while uncaging, the
// configuration accessor, the nominal spin fallback, failing torquer writes, a prediction that
// cannot be represented, a nominal rotor that cannot be stepped, an out-of-range pickoff
// reading, the small-angle flag in telemetry, the refusals of GyroModel::correct_attitude,
// torque_for_precession_rate and make_nutation_map, an unrepresentable drift torque, and the
// nutation map's saturated and underflow cases. Each test asserts what the flight software must do, not only
// that the line runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "gyro/component_types.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/nutation.hpp"
#include "gyro/report_sample.hpp"
#include "gyro/status.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::SeekerGyro;
using testing::Sil;
using testing::telemetry_finite;

// Texts of `count` enumerators 0..count-1: each non-empty and distinct from the others.
template <typename E>
void expect_distinct_texts(int count, const char* what) {
  std::set<std::string> seen;
  for (int i = 0; i < count; ++i) {
    const char* s = to_string(static_cast<E>(i));
    ASSERT_NE(s, nullptr) << what << " " << i;
    EXPECT_GT(std::strlen(s), 0U) << what << " " << i;
    EXPECT_TRUE(seen.insert(s).second) << what << " " << i << " repeats \"" << s << "\"";
  }
}

TEST(StatusText, GivenEveryStatusWhenNamedThenEachTextIsDistinctAndAnUnknownValueSaysSo) {
  expect_distinct_texts<Status>(static_cast<int>(Status::kWrongMode) + 1, "Status");
  EXPECT_STREQ(to_string(Status::kOk), "ok");
  EXPECT_STREQ(to_string(Status::kNumericalOverflow), "result not representable");
  // A corrupted value (e.g. from telemetry) is named, never an out-of-bounds read.
  EXPECT_STREQ(to_string(static_cast<Status>(200)), "unknown status");
}

TEST(ComponentConfig, GivenAcceptedConfigWhenARefusedOneFollowsThenConfigStillReturnsTheAcceptedOne) {
  Sil<double> sil;
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.use_spin_readback = false;
  c.residual_persistence_ticks = 33;
  ASSERT_TRUE(sil.component.configure(c).ok());
  GyroComponentConfig<double> bad = c;
  bad.tick_s = -1.0;
  bad.residual_persistence_ticks = 7;
  EXPECT_EQ(sil.component.configure(bad).status, Status::kNonPositiveStep);
  const GyroComponentConfig<double>& kept = sil.component.config();
  EXPECT_EQ(kept.tick_s, c.tick_s);
  EXPECT_EQ(kept.residual_persistence_ticks, 33U);
  EXPECT_FALSE(kept.use_spin_readback);
  EXPECT_EQ(kept.nominal_spin_hz, c.nominal_spin_hz);
}

TEST(ComponentModes, GivenUncagingWhenCageRequestedThenCagedAtOnceAndNeverFreedBySettling) {
  Sil<double> sil;
  sil.body_rate = Vector2<double>(0.4, -0.3);
  ASSERT_TRUE(sil.start());
  sil.run(200);
  ASSERT_EQ(sil.step(ModeRequest::kUncage), Status::kOk);
  ASSERT_EQ(sil.component.mode(), GyroMode::kUncaging);
  sil.run(10);
  EXPECT_EQ(sil.tm().torque_cmd, Vector2<double>::Zero()) << "torquers off while uncaging";
  ASSERT_EQ(sil.step(ModeRequest::kCage), Status::kOk);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(sil.tm().mode, GyroMode::kCaged);
  // Caged in the same tick: the caging law drives the torquers to follow the turning body.
  EXPECT_GT(sil.tm().torque_cmd.cwiseAbs().maxCoeff(), 0.0);
  // The settle count of the abandoned uncaging does not carry on into free mode.
  sil.run(static_cast<int>(SeekerGyro<double>::component().uncage_settle_ticks) + 10);
  EXPECT_EQ(sil.component.mode(), GyroMode::kCaged);
}

TEST(ComponentSpin, GivenNoUsableSpinReadbackWhenSteppedThenTheNominalSpinIsUsed) {
  SimulatedGyroConfig<double> stub = SeekerGyro<double>::stub();
  stub.spin_hz = 380.0;  // the hardware's true spin differs from the configured nominal (400)
  const double nominal = SeekerGyro<double>::component().nominal_spin_hz;
  struct Case {
    bool has_readback;
    bool use_readback;
    double expected_hz;
  };
  const Case cases[] = {
      {true, true, 380.0},      // readback valid and used
      {false, true, nominal},   // no readback: the nominal spin
      {true, false, nominal},   // readback ignored by configuration
  };
  for (const Case& k : cases) {
    Sil<double> sil;
    stub.has_spin_readback = k.has_readback;
    GyroComponentConfig<double> c = SeekerGyro<double>::component();
    c.use_spin_readback = k.use_readback;
    ASSERT_TRUE(sil.start(c, stub));
    sil.run(5);
    EXPECT_EQ(sil.tm().spin_hz, k.expected_hz) << k.has_readback << k.use_readback;
  }
}

// The SIL gyro behind a faulty harness: readings pass through (the spin readback replaced when
// `spin_override` is set, the angles when `angle_override` is), torquer writes fail with `write_status` unless it is kOk, and then
// never reach the gyro. A wiring fault between the flight computer and a healthy gyro.
template <typename T>
class FaultyHarness final : public GyroPort<T> {
 public:
  explicit FaultyHarness(SimulatedGyro<T>& gyro) noexcept : gyro_(gyro) {}

  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    const PortStatus st = gyro_.read_pickoffs(out);
    if (st == PortStatus::kOk && spin_override) {
      out.spin_hz = spin_hz;
      out.spin_valid = true;
    }
    if (st == PortStatus::kOk && angle_override) out.gimbal_angle_rad = angle_rad;
    return st;
  }
  [[nodiscard]] PortStatus write_torquer(const Vector2<T>& torque) noexcept override {
    if (write_status != PortStatus::kOk) return write_status;
    return gyro_.write_torquer(torque);
  }

  PortStatus write_status{PortStatus::kOk};
  bool spin_override{false};
  T spin_hz{};
  bool angle_override{false};  // valid bit and sequence stay the gyro's
  Vector2<T> angle_rad{Vector2<T>::Zero()};

 private:
  SimulatedGyro<T>& gyro_;
};

// The component on the faulty harness, the body turning at constant rates.
template <typename T>
struct FaultyRig {
  SimulatedGyro<T> gyro;
  FaultyHarness<T> harness{gyro};
  GyroComponent<T> component{harness};
  SilLoop<T, GyroComponent<T>> loop{gyro, component, StubBodyFeed::kAttitude};
  GuidanceCommand<T> guidance;
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};
  Vector2<T> body_rate{T(0.4), T(-0.3)};
  std::uint64_t tick{0};

  bool start() {
    if (!gyro.configure(SeekerGyro<T>::stub()).ok() || !component.configure(SeekerGyro<T>::component()).ok()) {
      return false;
    }
    const SilStatus<Status> started = loop.start(turning_body(R_earth_to_body, body_rate));
    return started.stub == Status::kOk && started.component == Status::kOk;
  }
  Status step() {
    R_earth_to_body = pitch_then_yaw_turn(body_rate, SeekerGyro<T>::kTick) * R_earth_to_body;
    ++tick;
    const SilStatus<Status> ran = loop.tick(tick, turning_body(R_earth_to_body, body_rate), guidance);
    return ran.stub != Status::kOk ? ran.stub : ran.component;
  }
  [[nodiscard]] const GyroTelemetry<T>& tm() const { return component.telemetry(); }
};

constexpr int kWriteFailedBit = 9;  // index of kTorquerWriteFailed in telemetry.counters
static_assert((1u << kWriteFailedBit) == kTorquerWriteFailed, "counter index of the flag");

TEST(ComponentTorquer, GivenTorquerWritesFailingWhenSteppedThenFlaggedCountedLastTorqueHeldAndFaultAfterPersistence) {
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 50; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<double> accepted = rig.gyro.torque_command();
  ASSERT_GT(accepted.cwiseAbs().maxCoeff(), 0.0) << "caging a turning body needs torque";
  ASSERT_EQ(rig.tm().torque_cmd, accepted);

  rig.harness.write_status = PortStatus::kBusError;
  const std::uint32_t persistence = SeekerGyro<double>::component().torquer_fail_persistence_ticks;
  // The fault is decided before the tick's write: it latches in the tick after the
  // persistence-th consecutive failure.
  for (std::uint32_t n = 1; n <= persistence; ++n) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kTorquerWriteFailed, 0U) << n;
    EXPECT_EQ(rig.tm().counters[kWriteFailedBit], n);
    EXPECT_EQ(rig.tm().torque_cmd, accepted) << "telemetry reports the torque the hardware holds";
    EXPECT_EQ(rig.gyro.torque_command(), accepted) << "no failed write reached the gyro";
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_NE(rig.tm().flags & kFaultLatched, 0U);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
}

TEST(ComponentTorquer, GivenFailedWritesFewerThanOneInThreeThenCountedButNoFault) {
  // Bursts of persistence - 1 failures, each followed by twice as many good writes: the
  // persistence monitor drains between the bursts and never trips.
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  const std::uint32_t persistence = SeekerGyro<double>::component().torquer_fail_persistence_ticks;
  for (int burst = 0; burst < 4; ++burst) {
    rig.harness.write_status = PortStatus::kTimeout;
    for (std::uint32_t n = 0; n + 1 < persistence; ++n) ASSERT_EQ(rig.step(), Status::kOk);
    rig.harness.write_status = PortStatus::kOk;
    for (std::uint32_t n = 0; n < 2 * (persistence - 1); ++n) {
      ASSERT_EQ(rig.step(), Status::kOk);
      EXPECT_EQ(rig.tm().flags & kTorquerWriteFailed, 0U);
    }
    EXPECT_EQ(rig.tm().torque_cmd, rig.gyro.torque_command()) << "the successful write is held";
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(rig.tm().counters[kWriteFailedBit], 4U * (persistence - 1U));
}

TEST(ComponentTorquer, GivenWritesFailingFourTimesInFiveThenTheFaultLatches) {
  // The same bursts with a single good write between them: an intermittent torquer cannot
  // dodge the persistence by succeeding now and then.
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  const std::uint32_t persistence = SeekerGyro<double>::component().torquer_fail_persistence_ticks;
  for (int burst = 0; burst < 4 && rig.component.mode() != GyroMode::kFault; ++burst) {
    rig.harness.write_status = PortStatus::kTimeout;
    for (std::uint32_t n = 0; n + 1 < persistence; ++n) ASSERT_EQ(rig.step(), Status::kOk);
    rig.harness.write_status = PortStatus::kOk;
    ASSERT_EQ(rig.step(), Status::kOk);
  }
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
}

// A spin readback so large that the exact transition over a tick overflows the scalar type
// (H^2 / (J1 J2) is not representable): the estimator cannot predict and must not poison the
// state; it restarts from the next good reading.
template <typename T>
void expect_estimator_restarts_after_unrepresentable_prediction(T huge_spin_hz) {
  FaultyRig<T> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 20; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<T> predicted_before = rig.tm().gimbal_predicted_rad;
  ASSERT_EQ(rig.step(), Status::kOk);
  ASSERT_NE(rig.tm().gimbal_predicted_rad, predicted_before) << "a turning body moves the prediction";

  rig.harness.spin_override = true;
  rig.harness.spin_hz = huge_spin_hz;
  const Vector2<T> predicted_last = rig.tm().gimbal_predicted_rad;
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.tm().spin_hz, huge_spin_hz) << "a finite, non-negative readback is used";
  EXPECT_EQ(rig.tm().gimbal_predicted_rad, predicted_last) << "no prediction this tick";
  EXPECT_NE(rig.tm().flags & kTorquerSaturated, 0U) << "H that large asks beyond the torquer";
  EXPECT_LE(rig.tm().torque_cmd.cwiseAbs().maxCoeff(), SeekerGyro<T>::component().max_torque);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
  // While the readback stays that large the estimator alternates between re-initialising from
  // the reading and failing to predict; nothing it publishes is non-finite.
  for (int k = 0; k < 2; ++k) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_TRUE(telemetry_finite(rig.tm())) << k;
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << k;
  }

  rig.harness.spin_override = false;
  ASSERT_EQ(rig.step(), Status::kOk);
  // Re-initialised from this tick's accepted reading: the prediction is the measurement.
  EXPECT_EQ(rig.tm().residual_rad, Vector2<T>::Zero());
  EXPECT_NEAR(static_cast<double>(rig.tm().gimbal_predicted_rad(0)),
              static_cast<double>(rig.tm().gimbal_measured_rad(0)), 1e-6);
  EXPECT_NEAR(static_cast<double>(rig.tm().gimbal_predicted_rad(1)),
              static_cast<double>(rig.tm().gimbal_measured_rad(1)), 1e-6);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kCaged);
  EXPECT_EQ(rig.tm().flags & kResidualFault, 0U);
  EXPECT_TRUE(telemetry_finite(rig.tm()));
}

TEST(ComponentEstimator, GivenSpinReadbackBeyondWhatDoubleCanSquareWhenSteppedThenPredictionSkippedAndEstimatorRestarts) {
  expect_estimator_restarts_after_unrepresentable_prediction<double>(1e200);
}

TEST(ComponentEstimator, GivenSpinReadbackBeyondWhatFloatCanSquareWhenSteppedThenPredictionSkippedAndEstimatorRestarts) {
  expect_estimator_restarts_after_unrepresentable_prediction<float>(1e30f);
}

TEST(ComponentSpin, GivenNonFiniteOrNegativeSpinReadbackWhenSteppedThenTheNominalSpinIsUsed) {
  const double nominal = SeekerGyro<double>::component().nominal_spin_hz;
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.0}) {
    FaultyRig<double> rig;
    ASSERT_TRUE(rig.start());
    rig.harness.spin_override = true;
    rig.harness.spin_hz = bad;
    for (int k = 0; k < 5; ++k) ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_EQ(rig.tm().spin_hz, nominal) << bad;
    EXPECT_TRUE(telemetry_finite(rig.tm())) << bad;
  }
}

// A rotor whose transient map cannot be represented in T (J2/J1 of 1e300 with next to no spin
// and no friction: A^-1 overflows): the map says so, the amplitude is the largest finite T
// (GyroModel then raises its small-angle flag), and the one-call form refuses it untouched.
template <typename T>
void expect_saturated_map(const RotorParameters<T>& prm) {
  NutationMap<T> map;
  ASSERT_EQ(make_nutation_map(prm, map), Status::kOk);
  EXPECT_TRUE(map.saturated);
  EXPECT_FALSE(map.has_transient);
  EXPECT_TRUE(map.has_steady);
  EXPECT_EQ(map.envelope, std::numeric_limits<T>::max());
  EXPECT_TRUE(all_finite(map.steady_from_torque, map.transient_from_rate, map.rotated_from_rate));
  const Vector2<T> rate(T(1e-3), T(-2e-3));
  const Vector2<T> torque(T(0), T(0));
  const Vector2<T> amp = nutation_amplitude(map, rate, torque);
  EXPECT_EQ(amp, Vector2<T>::Constant(std::numeric_limits<T>::max()));
  Vector2<T> out(T(7), T(7));
  EXPECT_EQ(nutation_amplitude(prm, rate, torque, out), Status::kNumericalOverflow);
  EXPECT_EQ(out, Vector2<T>(T(7), T(7))) << "a refused call leaves its output as it was";
}

TEST(NutationMap, GivenATransientTooLargeForDoubleWhenMappedThenSaturatedAndTheAmplitudeIsTheLargestDouble) {
  expect_saturated_map(RotorParameters<double>{1e-150, 1e150, 0.0, 1e-161});
}

TEST(NutationMap, GivenATransientTooLargeForFloatWhenMappedThenSaturatedAndTheAmplitudeIsTheLargestFloat) {
  expect_saturated_map(RotorParameters<float>{1e-20f, 1e20f, 0.0f, 1e-22f});
}

// Friction with no spin on gimbals so heavy that omega0^2 = f^2/(J1 J2) underflows to 0 while
// f^2 does not: a steady precession exists (w = T/f), a transient does not (as for f = H = 0).
TEST(NutationMap, GivenOmega0SquaredUnderflowingWhenMappedThenSteadyPrecessionOnlyAndZeroAmplitude) {
  const RotorParameters<double> prm{1e200, 1e200, 1e-150, 0.0};
  NutationMap<double> map;
  ASSERT_EQ(make_nutation_map(prm, map), Status::kOk);
  EXPECT_TRUE(map.has_steady);
  EXPECT_FALSE(map.has_transient);
  EXPECT_FALSE(map.saturated);
  EXPECT_EQ(map.steady_from_torque(0, 0), 1e150);  // f / (f^2 + H^2) = 1/f
  EXPECT_EQ(map.steady_from_torque(1, 0), 0.0);
  Vector2<double> out(7.0, 7.0);
  ASSERT_EQ(nutation_amplitude(prm, Vector2<double>(0.5, -0.25), Vector2<double>(1e-160, 0.0), out),
            Status::kOk);
  EXPECT_EQ(out, Vector2<double>::Zero());
}

// The configured nominal rotor must have a finite transition over a tick: a nominal spin so
// high that H^2 overflows is refused at configure, not discovered in flight.
// Since the contract bounds the spin (100 kHz), such a spin is refused by its own range first.
TEST(ComponentConfig, GivenANominalSpinOf1e200WhenConfiguredThenRefusedByItsRange) {
  Sil<double> sil;
  GyroComponentConfig<double> c = SeekerGyro<double>::component();
  c.nominal_spin_hz = 1e200;  // finite and above min_spin_hz
  const ConfigCheck r = sil.component.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_EQ(r.bound, 1e5);
  ASSERT_NE(r.field, nullptr);
  EXPECT_STREQ(r.field, "nominal_spin_hz");  // the field responsible, not the tick
  EXPECT_EQ(sil.component.activate(), Status::kNotConfigured) << "a refused config is not kept";
}

TEST(SteadyPrecession, GivenBadInputWhenTorqueForPrecessionRateThenEachRefusalHasItsStatusAndOutputUntouched) {
  const RotorParameters<double> rotor{2.25, 2.0, 5.0, angular_momentum(100.0, 3.0)};
  const Vector2<double> untouched(7.0, -7.0);
  Vector2<double> out = untouched;
  RotorParameters<double> no_inertia = rotor;
  no_inertia.yaw_inertia = 0.0;
  EXPECT_EQ(torque_for_precession_rate(no_inertia, Vector2<double>(0.1, 0.2), out), Status::kNonPositiveInertia);
  EXPECT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.1, std::nan("")), out), Status::kNonFiniteInput);
  // H w2 beyond the largest double: not representable, refused rather than returned as inf.
  EXPECT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.0, 1e306), out), Status::kNumericalOverflow);
  EXPECT_EQ(out, untouched);
  // And the accepted case is the exact inverse of the steady precession.
  ASSERT_EQ(torque_for_precession_rate(rotor, Vector2<double>(0.1, 0.2), out), Status::kOk);
  Vector2<double> back;
  ASSERT_EQ(steady_precession_rate(rotor, out, back), Status::kOk);
  EXPECT_NEAR(back(0), 0.1, 1e-15);
  EXPECT_NEAR(back(1), 0.2, 1e-15);
}

// A reading beyond the pickoffs' physical range (valid bit set, sequence advancing) is not
// believed: flagged invalid, not accepted, and a fault once it persists.
TEST(ComponentPickoffs, GivenAReadingBeyondThePickoffRangeWhenSteppedThenInvalidNotAcceptedAndAFaultOnceItPersists) {
  FaultyRig<double> rig;
  ASSERT_TRUE(rig.start());
  for (int k = 0; k < 20; ++k) ASSERT_EQ(rig.step(), Status::kOk);
  const Vector2<double> accepted = rig.tm().gimbal_measured_rad;
  const GyroComponentConfig<double> c = SeekerGyro<double>::component();
  rig.harness.angle_override = true;
  rig.harness.angle_rad = Vector2<double>(0.0, -(c.pickoff_range_rad + 0.01));
  for (std::uint32_t n = 1; n < c.invalid_persistence_ticks; ++n) {
    ASSERT_EQ(rig.step(), Status::kOk);
    EXPECT_NE(rig.tm().flags & kPickoffInvalid, 0U) << n;
    EXPECT_EQ(rig.tm().gimbal_measured_rad, accepted) << "the last accepted reading stands";
    EXPECT_EQ(rig.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(rig.step(), Status::kOk);
  EXPECT_EQ(rig.component.mode(), GyroMode::kFault);
  EXPECT_EQ(rig.tm().counters[3], c.invalid_persistence_ticks);  // kPickoffInvalid
}

// The estimator's small-angle check reaches the component's telemetry: with a limit below one
// tick's rotation of the turning body every predicted tick is flagged and counted.
TEST(ComponentTelemetry, GivenASmallAngleLimitBelowOneTicksRotationWhenSteppedThenSmallAngleExceededFlaggedAndCounted) {
  for (const double limit : {1e-3, 0.01}) {
    Sil<double> sil;
    sil.body_rate = Vector2<double>(2.4, -1.8);  // 1.5e-3 rad per 0.5 ms tick
    GyroComponentConfig<double> c = SeekerGyro<double>::component();
    c.small_angle_limit_rad = limit;
    // What the contract asks of a 1e-3 limit: one tick's slew within it, a full-torque
    // step's nutation within a tenth of it, and the torquer's authority.
    c.max_pitch_rate_rad_s = c.max_yaw_rate_rad_s = 0.5;
    c.max_torque = 0.025;
    ASSERT_TRUE(sil.start(c, SeekerGyro<double>::stub()));
    sil.run(50);
    if (limit < 1.5e-3) {
      // Flagged and counted (not every tick: caging at its 0.5 rad/s limit lags the body).
      EXPECT_GE(sil.tm().counters[1], 10U);
    } else {
      EXPECT_EQ(sil.tm().flags & kSmallAngleExceeded, 0U);
      EXPECT_EQ(sil.tm().counters[1], 0U);
    }
    EXPECT_EQ(sil.component.mode(), GyroMode::kCaged) << "a flag, not a fault";
  }
}

// GyroModel::correct_attitude refuses what it cannot use and then changes nothing.
TEST(GyroModelCorrection, GivenEachBadCorrectionInputThenRefusedWithItsStatusAndStateBitIdentical) {
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(ReportSample<double>::config()).ok());
  const Matrix3<double> r = Matrix3<double>::Identity();
  EXPECT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), r), Status::kNotConfigured) << "caged";
  ASSERT_EQ(g.uncage(r, Vector2<double>(0.1, -0.2), Vector2<double>(0.02, -0.01)), Status::kOk);
  const Quaternion<double> q0 = g.attitude_gyro_to_earth();
  const double pitch0 = g.gimbal_pitch_rad(), yaw0 = g.gimbal_yaw_rad();
  const std::uint32_t flags0 = g.flags();
  Matrix3<double> sheared = r;
  sheared(0, 1) = 0.1;
  EXPECT_EQ(g.correct_attitude(Vector2<double>(std::nan(""), 0.0), r), Status::kNonFiniteInput);
  EXPECT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), sheared), Status::kInvalidRotation);
  EXPECT_TRUE(testing::same_bits(g.attitude_gyro_to_earth().coeffs(), q0.coeffs()));
  EXPECT_TRUE(testing::same_bits(g.gimbal_pitch_rad(), pitch0));
  EXPECT_TRUE(testing::same_bits(g.gimbal_yaw_rad(), yaw0));
  EXPECT_EQ(g.flags(), flags0);
  // Accepted: pitching the gyro up by 1 mrad raises its gimbal pitch angle by as much.
  ASSERT_EQ(g.correct_attitude(Vector2<double>(1e-3, 0.0), r), Status::kOk);
  EXPECT_NEAR(g.gimbal_pitch_rad() - pitch0, 1e-3, 2e-5);
  EXPECT_NEAR(g.gimbal_yaw_rad() - yaw0, 0.0, 2e-5);
}

// A drift torque (H times the drift) that is not representable: the step is refused and the
// model keeps its state, rather than carrying an infinite torque into it. configure() bounds
// the drifts; the g-sensitive one still grows with the step's acceleration.
TEST(GyroModelErrorSources, GivenADriftTorqueBeyondTheLargestDoubleWhenSteppedThenRefusedAndStateBitIdentical) {
  GyroModelConfig<double> c = ReportSample<double>::config();
  c.errors.pitch.g_sensitive_drift_rad_s = 1.0;  // its bound: accepted by configure
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  ASSERT_EQ(g.uncage(Matrix3<double>::Identity(), Vector2<double>(0.1, -0.2)), Status::kOk);
  GyroStepInput<double> in;
  in.dt_s = 1e-3;
  in.spin_hz = ReportSample<double>::kSpinHz;  // H = 1885: H * 1e306 overflows
  in.body_accel = Vector2<double>(1e306 * c.gravity, 0.0);  // a drift of 1e306 rad/s
  const Quaternion<double> q0 = g.attitude_gyro_to_earth();
  const Vector2<double> rate0 = g.rate_rad_s();
  const Status st = g.step_torque(in, Vector2<double>::Zero());
  EXPECT_NE(st, Status::kOk);
  std::printf("drift torque step refused: %s\n", to_string(st));
  EXPECT_TRUE(testing::same_bits(g.attitude_gyro_to_earth().coeffs(), q0.coeffs()));
  EXPECT_TRUE(testing::same_bits(g.rate_rad_s(), rate0));
  EXPECT_TRUE(all_finite(g.rate_rad_s(), g.gimbal_pitch_rad(), g.gimbal_yaw_rad()));
}

TEST(NutationMap, GivenInvalidParametersWhenMappedThenRefusedAndTheMapUntouched) {
  NutationMap<double> map;
  map.envelope = 42.0;
  EXPECT_EQ(make_nutation_map(RotorParameters<double>{2.25, 2.0, -1.0, 100.0}, map), Status::kNegativeFriction);
  EXPECT_EQ(make_nutation_map(RotorParameters<double>{0.0, 2.0, 5.0, 100.0}, map), Status::kNonPositiveInertia);
  EXPECT_EQ(map.envelope, 42.0);
  EXPECT_FALSE(map.has_steady);
}

}  // namespace
}  // namespace gyro
