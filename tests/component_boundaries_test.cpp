// What a single-line change of component/ can break without another suite noticing
// (scripts/mutation.sh, scripts/mutants.tsv): the tick count's gaps and their trust, a gap
// combined with a pickoff move and with the estimator's step, the exact edges of every range
// test (>= against >), leaving safe mode, the direction of the torque law's overflow path,
// and a correction that brings the spin axis back inside the cone. Each test names the
// behaviour; the mutant list names the test that kills each mutant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "gyro/gyro_component.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"
#include "support/corrupting_port.hpp"
#include "support/scripted_bench.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::Bench;
using testing::CorruptingPort;
using testing::counter_of;
using testing::SeekerGyro;
using testing::Sil;
using testing::telemetry_finite;
using testing::WireFault;

const GyroComponentConfig<double> kSeeker = SeekerGyro<double>::component();

// Lets `ticks` ticks pass for the body and the stub without calling the component.
void lose_ticks(Sil<double>& sil, int ticks) {
  const double dt = SeekerGyro<double>::kTick;
  for (int k = 0; k < ticks; ++k) {
    sil.R_earth_to_body = frame_rotation_z(sil.body_rate(1) * dt) * frame_rotation_y(sil.body_rate(0) * dt) *
                          sil.R_earth_to_body;
    ++sil.tick;
    ASSERT_EQ(sil.gyro.advance(sil.tick, sil.R_earth_to_body, Vector2<double>::Zero()), Status::kOk);
  }
}

// ---- the tick count -------------------------------------------------------------------------

TEST(ComponentTick, GivenGapsOfLostTicksWhenBridgedThenEachIsFlaggedAndCountedOnceAndTheTickRunsClean) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  ASSERT_EQ(b.step_at(b.tick + 3), Status::kOk) << "lost ticks are no bad input";
  EXPECT_TRUE(b.raised(kTickSkipped));
  EXPECT_FALSE(b.raised(kTickInvalid));
  EXPECT_EQ(b.tm().counters[counter_of(kTickSkipped)], 1u);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_FALSE(b.raised(kTickSkipped)) << "the tick after a bridged gap is an ordinary one";
  ASSERT_EQ(b.step_at(b.tick + kSeeker.max_tick_gap), Status::kOk) << "the longest gap bridged";
  EXPECT_TRUE(b.raised(kTickSkipped));
  EXPECT_EQ(b.tm().counters[counter_of(kTickSkipped)], 2u);
  EXPECT_EQ(b.tm().counters[counter_of(kTickInvalid)], 0u);
}

TEST(ComponentTick, GivenAJumpRightAfterAnUntrustedCountThenItIsNotBridgedButTakenAsOneInvalidTick) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  ASSERT_EQ(b.step_at(b.tick + 1000), Status::kInputIgnored);
  EXPECT_TRUE(b.raised(kTickInvalid));
  // Three ahead of an untrusted count: not believed either (the count is resynchronised).
  ASSERT_EQ(b.step_at(b.tick + 3), Status::kInputIgnored);
  EXPECT_TRUE(b.raised(kTickInvalid));
  EXPECT_FALSE(b.raised(kTickSkipped));
  ASSERT_EQ(b.step(), Status::kOk) << "followed by one: an ordinary tick, and trusted";
  EXPECT_EQ(b.tm().flags & (kTickInvalid | kTickSkipped), 0u);
  ASSERT_EQ(b.step_at(b.tick + 2), Status::kOk);
  EXPECT_TRUE(b.raised(kTickSkipped)) << "trusted again: a gap is bridged";
  EXPECT_EQ(b.tm().counters[counter_of(kTickInvalid)], 2u);
}

TEST(ComponentTick, GivenARepeatedCountThenItIsOneInvalidTickNeverABridgeOfZeroTicks) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  ASSERT_EQ(b.step_at(b.tick), Status::kInputIgnored);
  EXPECT_TRUE(b.raised(kTickInvalid));
  EXPECT_FALSE(b.raised(kTickSkipped));
  EXPECT_TRUE(telemetry_finite(b.tm()));
}

TEST(ComponentTick, GivenAFirstCallWithAnyCountThenItIsTrustedAtOnce) {
  Bench b;
  ASSERT_TRUE(b.ok);
  ASSERT_EQ(b.step_at(1'000'000), Status::kOk) << "there is no count before the first to disagree with";
  EXPECT_EQ(b.tm().flags & (kTickInvalid | kTickSkipped), 0u);
  ASSERT_EQ(b.step_at(b.tick + 2), Status::kOk);
  EXPECT_TRUE(b.raised(kTickSkipped));
}

// ---- a gap with a pickoff move and with the estimator ----------------------------------------

// A slew of 1 rad/s moves the gimbal 5e-4 rad a tick; with max_pickoff_step_rad = 1e-3 a gap of
// four ticks (2e-3 rad) is beyond one tick's bound and within four ticks'.
TEST(ComponentTick, GivenLostTicksWhileSlewingWhenTheNextReadingArrivesThenItIsJudgedAgainstTheBoundOfTheElapsedTicks) {
  GyroComponentConfig<double> c = kSeeker;
  c.max_pickoff_step_rad = 1.75e-3;  // the contract's least: 2 (a tick at 1 rad/s + a full-torque nutation)
  Sil<double> sil;
  ASSERT_TRUE(sil.start(c));
  ASSERT_TRUE(sil.uncage());
  sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(1.0, 0.0);
  sil.run(40);
  ASSERT_EQ(sil.tm().flags & (kPickoffJump | kPickoffInvalid | kPickoffStale), 0u);
  const Vector2<double> before = sil.tm().gimbal_measured_rad;
  lose_ticks(sil, 3);
  ASSERT_EQ(sil.step(), Status::kOk);
  EXPECT_NE(sil.tm().flags & kTickSkipped, 0u);
  const double moved = (sil.tm().gimbal_measured_rad - before).cwiseAbs().maxCoeff();
  EXPECT_EQ(sil.tm().flags & kPickoffJump, 0u) << "a move of " << moved << " rad over 4 ticks";
  EXPECT_GT(moved, c.max_pickoff_step_rad) << "the reading after the gap was accepted";
  EXPECT_LT(moved, 4 * c.max_pickoff_step_rad);
}

// The estimator's transition is cached per spin and step: with the spin held at the nominal
// (no readback), a gap changes only the step, and the prediction must span all of it.
TEST(ComponentTick, GivenTheNominalSpinWhenTicksAreLostThenThePredictionSpansTheWholeGap) {
  GyroComponentConfig<double> c = kSeeker;
  c.use_spin_readback = false;
  for (const int gap : {2, 5, 8}) {
    SCOPED_TRACE(gap);
    Sil<double> sil;
    ASSERT_TRUE(sil.start(c));
    ASSERT_TRUE(sil.uncage());
    sil.guidance.slew_rate_cmd_rad_s = Vector2<double>(0.5, -0.4);
    sil.run(50);
    lose_ticks(sil, gap - 1);
    ASSERT_EQ(sil.step(), Status::kOk);
    EXPECT_NE(sil.tm().flags & kTickSkipped, 0u);
    EXPECT_LT(sil.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "predicted over the whole gap";
    ASSERT_EQ(sil.step(), Status::kOk);
    EXPECT_LT(sil.tm().residual_rad.cwiseAbs().maxCoeff(), 2e-5) << "and one tick again after it";
  }
}

// The same at the model: a step of a new dt with the spin unchanged is the step of that dt, bit
// for bit what a model uncaged at the same rates does in one step.
TEST(GyroModelCache, GivenTheSameSpinWhenTheStepChangesThenEachStepUsesItsOwnTransition) {
  const GyroModelConfig<double> c = ReportSample<double>::config();
  const Vector2<double> torque(0.3, -0.2);
  GyroStepInput<double> in;
  in.spin_hz = ReportSample<double>::kSpinHz;
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  ASSERT_EQ(g.uncage(Matrix3<double>::Identity(), Vector2<double>(0.05, -0.02)), Status::kOk);
  for (const double dt : {1e-3, 3e-3, 1e-3, 2.5e-4}) {
    SCOPED_TRACE(dt);
    GyroModel<double> fresh;
    ASSERT_TRUE(fresh.configure(c).ok());
    ASSERT_EQ(fresh.uncage(Matrix3<double>::Identity(), g.rate_rad_s()), Status::kOk);
    in.dt_s = dt;
    ASSERT_EQ(g.step_torque(in, torque), Status::kOk);
    ASSERT_EQ(fresh.step_torque(in, torque), Status::kOk);
    EXPECT_EQ(g.isaf_angle_rad(), fresh.isaf_angle_rad());
    EXPECT_EQ(g.rate_rad_s(), fresh.rate_rad_s());
  }
}

// ---- the pickoff reading's bounds --------------------------------------------------------------

TEST(ComponentPickoffs, GivenAReadingExactlyAtThePickoffRangeThenAcceptedAndJustBeyondItInvalid) {
  GyroComponentConfig<double> c = kSeeker;
  c.pickoff_range_rad = 4e-3;  // within one tick's jump bound of zero
  c.gimbal_cone_limit_rad = 4e-3;  // the contract: the cone within the range, the step within it
  c.gimbal_stop_margin_rad = 2e-3;  // the shaped torque's 3 ticks at the rate limit, and more
  c.max_pickoff_step_rad = 4e-3;
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.run(2);
  for (const Vector2<double>& edge : {Vector2<double>(4e-3, 0.0), Vector2<double>(0.0, -4e-3)}) {
    b.port.reading.gimbal_angle_rad = edge;
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_FALSE(b.raised(kPickoffInvalid)) << edge.transpose();
    EXPECT_EQ(b.tm().gimbal_measured_rad, edge);
    const Vector2<double> beyond(std::nextafter(edge(0), 2 * edge(0)), std::nextafter(edge(1), 2 * edge(1)));
    b.port.reading.gimbal_angle_rad = beyond;
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_TRUE(b.raised(kPickoffInvalid)) << beyond.transpose();
    EXPECT_EQ(b.tm().gimbal_measured_rad, edge) << "the last accepted reading stands";
  }
}

TEST(ComponentPickoffs, GivenTheFirstReadingWithSequenceZeroThenItIsAcceptedNotStale) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.hold_sequence = true;  // sequence 0, as a driver's first conversion may carry
  b.port.reading.gimbal_angle_rad = Vector2<double>(1e-3, -2e-3);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().flags & (kPickoffStale | kPickoffInvalid), 0u);
  EXPECT_EQ(b.tm().gimbal_measured_rad, b.port.reading.gimbal_angle_rad);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kPickoffStale)) << "the same sequence again is stale";
}

TEST(ComponentPickoffs, GivenAReadingRejectedAsAJumpWhenItsSequenceComesAgainThenItIsStale) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(3);
  b.port.reading.gimbal_angle_rad = Vector2<double>(0.05, 0.0);  // ten ticks' bound in one
  ASSERT_EQ(b.step(), Status::kOk);
  ASSERT_TRUE(b.raised(kPickoffJump));
  b.port.hold_sequence = true;
  b.port.reading.gimbal_angle_rad = Vector2<double>(1e-3, 0.0);  // plausible, but no new conversion
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kPickoffStale));
  EXPECT_EQ(b.tm().gimbal_measured_rad, Vector2<double>::Zero());
}

TEST(ComponentPickoffs, GivenInvalidReadingsThenTheBoundWidensByTheTicksWithoutInformationAndResetsOnAcceptance) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(3);
  const double bound = kSeeker.max_pickoff_step_rad;
  b.port.reading.valid = false;
  b.run(3);  // three ticks without information: the next reading may have moved 4 bounds
  b.port.reading.valid = true;
  b.port.reading.gimbal_angle_rad = Vector2<double>(3.5 * bound, 0.0);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().flags & (kPickoffJump | kPickoffInvalid), 0u);
  EXPECT_EQ(b.tm().gimbal_measured_rad(0), 3.5 * bound);
  // Accepted: the bound is one tick's again.
  b.port.reading.gimbal_angle_rad = Vector2<double>(3.5 * bound + 1.5 * bound, 0.0);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kPickoffJump));
  EXPECT_EQ(b.tm().gimbal_measured_rad(0), 3.5 * bound);
}

// ---- the spin readback -------------------------------------------------------------------------

TEST(ComponentSpin, GivenAReadbackOfExactlyZeroThenItIsUsedAndTheSpinIsLow) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = 0.0;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().spin_hz, 0.0) << "a stopped rotor is a reading, not a failed readback";
  EXPECT_TRUE(b.raised(kSpinLow));
  EXPECT_TRUE(telemetry_finite(b.tm()));
}

TEST(ComponentSpin, GivenAReadbackExactlyAtTheMinimumThenNotLowAndJustBelowItLow) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = kSeeker.min_spin_hz;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().spin_hz, kSeeker.min_spin_hz);
  EXPECT_FALSE(b.raised(kSpinLow));
  b.port.reading.spin_hz = std::nextafter(kSeeker.min_spin_hz, 0.0);
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kSpinLow));
}

TEST(ComponentSpin, GivenALowSpinThenTheFaultLatchesExactlyAfterItsPersistence) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.port.reading.spin_hz = 250.0;
  for (std::uint32_t n = 1; n < kSeeker.spin_low_persistence_ticks; ++n) {
    ASSERT_EQ(b.step(), Status::kOk);
    ASSERT_EQ(b.component.mode(), GyroMode::kCaged) << n;
  }
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kFault);
  EXPECT_EQ(b.tm().counters[counter_of(kSpinLow)], kSeeker.spin_low_persistence_ticks);
  EXPECT_EQ(b.tm().torque_cmd, Vector2<double>::Zero()) << "safe mode: torquers off";
}

TEST(ComponentSpin, GivenAReadbackFromAFailedReadOrWithUnrepresentableMomentumThenTheNominalSpinIsUsed) {
  {
    Bench b;
    ASSERT_TRUE(b.ok);
    b.port.read_status = PortStatus::kTimeout;
    b.port.fill_on_failure = true;  // the driver wrote a spin it did not read
    b.port.reading.spin_hz = 350.0;
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_TRUE(b.raised(kPickoffInvalid));
    EXPECT_EQ(b.tm().spin_hz, kSeeker.nominal_spin_hz);
  }
  {
    // J0 = 1: the largest double as a spin has a momentum of 2 pi times it, beyond any double.
    GyroComponentConfig<double> c = kSeeker;  // the seeker scaled to J0 = 1 (as the contract has it)
    c.spin_inertia = 1.0;
    c.pitch_inertia = 1.0;
    c.yaw_inertia = 1.0;
    c.friction = 20.0;
    c.max_torque = 2000.0;
    Bench b(c);
    ASSERT_TRUE(b.ok);
    b.port.reading.spin_hz = std::numeric_limits<double>::max();
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_EQ(b.tm().spin_hz, c.nominal_spin_hz);
    EXPECT_TRUE(telemetry_finite(b.tm()));
  }
}

TEST(ComponentTelemetry, GivenTheSpinDropsBelowTwiceTheTickRateOfNutationThenTheUnresolvedFlagFollowsIt) {
  // 1 kHz tick: the seeker nutates at H/J = 600 Hz at 400 Hz spin (aliased), 150 Hz at 100 Hz.
  GyroComponentConfig<double> c = kSeeker;
  c.tick_s = 1e-3;
  c.cage_gain_1_s = 10;
  c.min_spin_hz = 50;
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.run(3);
  EXPECT_TRUE(b.raised(kNutationUnresolved));
  b.port.reading.spin_hz = 100.0;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_FALSE(b.raised(kNutationUnresolved));
  b.port.reading.spin_hz = 400.0;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kNutationUnresolved));
}

// The flag speaks of the estimate (its nutation cannot be checked against aliased pickoffs):
// none before the estimator has started, raised on the tick it starts.
TEST(ComponentTelemetry, GivenAnAliasedNutationThenUnresolvedIsFlaggedOnlyOnceThereIsAnEstimate) {
  GyroComponentConfig<double> c = kSeeker;
  c.tick_s = 1e-3;  // 600 Hz nutation at a 1 kHz tick: aliased
  c.cage_gain_1_s = 10;
  Bench b(c);
  ASSERT_TRUE(b.ok);
  b.guidance.nav_valid = false;  // no navigation: nothing to start the estimator from
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(b.step(), Status::kOk);
    EXPECT_FALSE(b.raised(kNutationUnresolved)) << "tick " << b.tick;
  }
  b.guidance.nav_valid = true;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_TRUE(b.raised(kNutationUnresolved));
}

// ---- navigation and configuration at their edges ------------------------------------------------

TEST(ComponentNavigation, GivenABodyRateExactlyAtItsLimitThenUsedAndJustBeyondItIgnored) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.guidance.body_rate_rad_s = Vector3<double>(kSeeker.max_body_rate_rad_s, 0.0, 0.0);  // roll
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_FALSE(b.raised(kNavInvalid));
  b.guidance.body_rate_rad_s(0) = -std::nextafter(kSeeker.max_body_rate_rad_s, 1e3);
  ASSERT_EQ(b.step(), Status::kInputIgnored);
  EXPECT_TRUE(b.raised(kNavInvalid));
}

// The margin's lower bound as check() takes it: the nutation of stopping twice the larger rate
// limit, or the ticks at the rate limit before the shaped torque holds (1 + 2 m, m = 1 for the
// seeker at 2 kHz), whichever is larger.
double margin_floor(const GyroComponentConfig<double>& c) {
  const double h = 2.0 * 3.14159265358979323846 * c.nominal_spin_hz * c.spin_inertia;
  const double rate = std::max(c.max_pitch_rate_rad_s, c.max_yaw_rate_rad_s);
  const double nutation = 2.0 * rate / (std::sqrt(h * h + c.friction * c.friction) / std::sqrt(c.pitch_inertia * c.yaw_inertia));
  return std::max(nutation, 3.0 * rate * c.tick_s);
}

// The cage gain's upper bound for the seeker: a quarter of its nutation frequency, to the
// last bit as check() computes it (H / J for J1 = J2 up to rounding), below 1 / tick.
double cage_ceiling(const GyroComponentConfig<double>& c) {
  const double h = 2.0 * 3.14159265358979323846 * c.nominal_spin_hz * c.spin_inertia;
  const double beta_sq =
      detail::rate_matrix_terms(RotorParameters<double>{c.pitch_inertia, c.yaw_inertia, c.friction, h}).beta_sq;
  return std::min(kCageNutationShare * std::sqrt(beta_sq), 1.0 / c.tick_s);
}

TEST(ComponentConfig, GivenEachLimitExactlyAtItsEdgeThenTheInclusiveOnesAreAcceptedAndTheStrictOnesRefused) {
  using C = GyroComponentConfig<double>;
  struct Case {
    const char* field;
    void (*edge)(C&);
    bool accepted;
  };
  const Case cases[] = {
      {"cage_gain_1_s", [](C& c) { c.cage_gain_1_s = cage_ceiling(c); }, true},  // beta / 4
      {"cage_gain_1_s", [](C& c) { c.cage_gain_1_s = std::nextafter(cage_ceiling(c), 1e9); }, false},
      {"estimator_gain", [](C& c) { c.estimator_gain = 1.0; }, true},
      // At a cone of pi/2 the shaper loses its notch at the protection cone: the bearings damp
      // the nutation there (8.7 1/s after the turn gain), so the cage gain comes within that.
      {"gimbal_cone_limit_rad",
       [](C& c) {
         c.gimbal_cone_limit_rad = c.pickoff_range_rad = kPi<double> / 2;
         c.cage_gain_1_s = 8.0;
       },
       true},
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = c.gimbal_cone_limit_rad; }, false},
      {"min_spin_hz", [](C& c) { c.min_spin_hz = c.nominal_spin_hz; }, false},
      {"min_spin_hz", [](C& c) { c.min_spin_hz = 0.0; }, true},
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = 0.0; }, false},  // < a tick at the rate limit
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = std::nextafter(margin_floor(c), 0.0); }, false},
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = margin_floor(c); }, true},
  };
  for (const Case& k : cases) {
    C c = kSeeker;
    k.edge(c);
    Sil<double> sil;
    const ConfigCheck r = sil.component.configure(c);
    if (k.accepted) {
      EXPECT_TRUE(r.ok()) << k.field << ": " << (r.field ? r.field : "");
    } else {
      EXPECT_EQ(r.status, Status::kOutOfRange) << k.field;
      ASSERT_NE(r.field, nullptr) << k.field;
      EXPECT_STREQ(r.field, k.field);
    }
  }
}

// ---- modes ------------------------------------------------------------------------------------

TEST(ComponentModes, GivenAnUncageRequestWithoutUsableNavigationOrReadingThenItStaysCaged) {
  Bench b;
  ASSERT_TRUE(b.ok);
  b.run(5);
  b.guidance.nav_valid = false;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kCaged) << "no navigation: no attitude to uncage at";
  b.guidance.nav_valid = true;
  b.port.reading.valid = false;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kCaged) << "no reading: no gimbal angles to uncage at";
  b.port.reading.valid = true;
  ASSERT_EQ(b.step(ModeRequest::kUncage), Status::kOk);
  EXPECT_EQ(b.component.mode(), GyroMode::kUncaging);
}

// Leaving safe mode: the estimator, which followed its own prediction while the readings were
// off, restarts at the first good reading: no residual, the prediction the measurement.
TEST(ComponentModes, GivenSafeModeAfterABiasJumpWhenCagedThenTheEstimatorRestartsAtTheMeasurement) {
  SimulatedGyro<double> gyro;
  CorruptingPort<double> wire{gyro};
  GyroComponent<double> component{wire};
  const Matrix3<double> body = Matrix3<double>::Identity();  // at rest
  ASSERT_TRUE(gyro.configure(SeekerGyro<double>::stub()).ok());
  ASSERT_EQ(gyro.start(body, Vector2<double>::Zero()), Status::kOk);
  ASSERT_TRUE(component.configure(kSeeker).ok());
  ASSERT_EQ(component.activate(), Status::kOk);
  GuidanceInput<double> g;
  g.nav_valid = true;
  std::uint64_t tick = 0;
  const auto step = [&](ModeRequest request) {
    ++tick;
    EXPECT_EQ(gyro.advance(tick, body, Vector2<double>::Zero()), Status::kOk);
    g.request = request;
    return component.step(tick, g);
  };
  for (int k = 0; k < 100; ++k) (void)step(ModeRequest::kNone);
  wire.fault = WireFault::kJump;  // every reading 0.1 rad off from now on
  for (int k = 0; k < 15; ++k) (void)step(ModeRequest::kNone);
  ASSERT_EQ(component.mode(), GyroMode::kFault);
  ASSERT_GT(component.telemetry().residual_rad.cwiseAbs().maxCoeff(), 0.05) << "the estimator kept to the gyro";
  ASSERT_EQ(step(ModeRequest::kCage), Status::kOk);
  ASSERT_EQ(component.mode(), GyroMode::kCaged);
  ASSERT_EQ(step(ModeRequest::kNone), Status::kOk);
  const GyroTelemetry<double>& t = component.telemetry();
  EXPECT_EQ(t.residual_rad, Vector2<double>::Zero());
  EXPECT_NEAR(t.gimbal_predicted_rad(0), t.gimbal_measured_rad(0), 1e-12);
  EXPECT_NEAR(t.gimbal_predicted_rad(1), t.gimbal_measured_rad(1), 1e-12);
  for (int k = 0; k < 50; ++k) ASSERT_EQ(step(ModeRequest::kNone), Status::kOk);
  EXPECT_EQ(component.mode(), GyroMode::kCaged) << "no residual fault from the old prediction";
  EXPECT_EQ(t.flags & kResidualFault, 0u);
}

// ---- the torque law ---------------------------------------------------------------------------

TEST(ComponentCaging, GivenAnInvalidReadingWhileCagedThenTheGimbalLoopPausesAndTheYawTermIsOnTheSpinAxis) {
  Bench b;
  ASSERT_TRUE(b.ok);
  const Vector2<double> gimbal(0.04, 0.045);  // the loop's rates within the 1 rad/s limits
  b.port.reading.gimbal_angle_rad = gimbal;
  ASSERT_EQ(b.step(), Status::kOk);
  // th' = -k th; the yaw rate of the spin axis about z_I is ps' cos th = -k ps cos th.
  EXPECT_NEAR(b.tm().rate_cmd_rad_s(0), -kSeeker.cage_gain_1_s * gimbal(0), 1e-9);
  EXPECT_NEAR(b.tm().rate_cmd_rad_s(1), -kSeeker.cage_gain_1_s * gimbal(1) * std::cos(gimbal(0)), 1e-6);
  b.port.reading.valid = false;
  ASSERT_EQ(b.step(), Status::kOk);
  EXPECT_EQ(b.tm().rate_cmd_rad_s, Vector2<double>::Zero()) << "no loop on a reading not taken this tick";
}

// Rates and spin whose torques overflow: the saturated torque keeps the law's direction. With
// H far above f the law is H times the rate turned a quarter: (H w_z, -H w_y cos th).
TEST(ComponentTorqueLaw, GivenRateLimitsOf1e300ThenTheContractRefusesThem) {
  // Rate limits of 1e300 rad/s: the contract refuses them (100 rad/s at most, and one tick's
  // slew within the small-angle limit), so the torque law's overflow path is out of reach.
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 1e300;
  c.max_yaw_rate_rad_s = 1e300;
  const ConfigCheck r = check(c);
  ASSERT_FALSE(r.ok());
  EXPECT_STREQ(r.field, "max_pitch_rate_rad_s");
  EXPECT_EQ(r.value, 1e300);
  EXPECT_EQ(r.bound, 100.0);
}

// The rotor's momentum H + J0 r is negative when the inner gimbal rolls against a slow spin:
// the overflow path scaled its factors by max(f, h) = 0 and wrote a NaN torque.
TEST(ComponentTorqueLaw, GivenRateLimitsOf1e308ThenTheContractRefusesThem) {
  // Rate limits of 1e300 rad/s: the contract refuses them (100 rad/s at most, and one tick's
  // slew within the small-angle limit), so the torque law's overflow path is out of reach.
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 1e308;
  c.max_yaw_rate_rad_s = 1e308;
  const ConfigCheck r = check(c);
  ASSERT_FALSE(r.ok());
  EXPECT_STREQ(r.field, "max_pitch_rate_rad_s");
  EXPECT_EQ(r.value, 1e308);
  EXPECT_EQ(r.bound, 100.0);
}

// Saturation divides by the largest component first: it becomes exactly 1, so the command's
// largest axis sits exactly at max_torque. Scaling by max_torque / largest instead rounds
// that ratio, subnormal when the law's torque nears the largest double (a spin of 1e200 Hz
// and slews of 1e110 rad/s: 1e307 N m), and lands off the limit. Each slew is held for three
// ticks, so that the shaper's taps agree and give it back exactly.
TEST(ComponentTorqueLaw, GivenRateLimitsNearTheLargestDoubleThenRefused) {
  // Rate limits of 1e300 rad/s: the contract refuses them (100 rad/s at most, and one tick's
  // slew within the small-angle limit), so the torque law's overflow path is out of reach.
  GyroComponentConfig<double> c = kSeeker;
  c.max_pitch_rate_rad_s = 1.7e308;
  c.max_yaw_rate_rad_s = 1.7e308;
  const ConfigCheck r = check(c);
  ASSERT_FALSE(r.ok());
  EXPECT_STREQ(r.field, "max_pitch_rate_rad_s");
  EXPECT_EQ(r.value, 1.7e308);
  EXPECT_EQ(r.bound, 100.0);
}

// ---- the model's gimbal-limit flag after a correction -----------------------------------------

TEST(GyroModelCorrection, GivenASpinAxisOutsideTheConeWhenCorrectedBackInsideThenTheGimbalLimitFlagClears) {
  const GyroModelConfig<double> c = ReportSample<double>::config();  // cone 0.436 rad
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  const Matrix3<double> r = Matrix3<double>::Identity();
  ASSERT_EQ(g.uncage(r, Vector2<double>::Zero(), Vector2<double>(0.5, 0.0)), Status::kOk);
  ASSERT_TRUE(g.gimbal_limit_exceeded());
  ASSERT_EQ(g.correct_attitude(Vector2<double>(-0.2, 0.0), r), Status::kOk);
  EXPECT_FALSE(g.gimbal_limit_exceeded()) << "cone " << g.gimbal_cone_rad();
  EXPECT_EQ(g.flags() & kFlagGimbalLimit, 0u);
  ASSERT_EQ(g.correct_attitude(Vector2<double>(0.0, 0.5), r), Status::kOk);
  EXPECT_TRUE(g.gimbal_limit_exceeded()) << "cone " << g.gimbal_cone_rad();
}

// A correction of the gimbal angles moves them by itself: the yaw part turns the spin axis
// about the outer axis (body z), by yaw cos(pitch) on the gyro's own axes. Off the pitch
// zero, a yaw not so resolved would move the yaw angle by yaw / cos(pitch) (4.7 % more at
// 0.3 rad). First order in the correction: 1e-5 rad leaves terms of 1e-10.
TEST(GyroModelCorrection, GivenAGimbalCorrectionOffThePitchZeroThenEachAngleMovesByItsOwnCorrection) {
  const GyroModelConfig<double> c = ReportSample<double>::config();
  GyroModel<double> g;
  ASSERT_TRUE(g.configure(c).ok());
  const Matrix3<double> body = (Eigen::AngleAxisd(0.4, Vector3<double>::UnitZ()) *
                                Eigen::AngleAxisd(-0.2, Vector3<double>::UnitY()))
                                   .toRotationMatrix();
  for (const double pitch : {0.0, 0.3, -0.35}) {
    SCOPED_TRACE(pitch);
    ASSERT_EQ(g.uncage_on_gimbal(body, Vector3<double>::Zero(), Vector2<double>(pitch, 0.1)), Status::kOk);
    ASSERT_NEAR(g.gimbal_pitch_rad(), pitch, 1e-15);
    ASSERT_NEAR(g.gimbal_yaw_rad(), 0.1, 1e-15);
    const Vector2<double> d(-0.7e-5, 1e-5);
    ASSERT_EQ(g.correct_gimbal_angles(d, body), Status::kOk);
    EXPECT_NEAR(g.gimbal_pitch_rad(), pitch + d(0), 1e-9);
    EXPECT_NEAR(g.gimbal_yaw_rad(), 0.1 + d(1), 1e-9);
  }
}

// A correction followed by a new uncaging: the angles read are those of the new uncaging, as
// if the correction had never been made (it turned an attitude that uncaging replaced, against
// the body of its own time).
TEST(GyroModelCorrection, GivenACorrectionThenAnUncagingOnAnotherBodyThenTheAnglesAreTheUncagingsOwn) {
  const GyroModelConfig<double> c = ReportSample<double>::config();
  const Matrix3<double> first = Eigen::AngleAxisd(0.3, Vector3<double>(1, -2, 0.5).normalized()).toRotationMatrix();
  const Matrix3<double> second = Eigen::AngleAxisd(-0.8, Vector3<double>(0.2, 1, -1).normalized()).toRotationMatrix();
  GyroModel<double> corrected, fresh;
  ASSERT_TRUE(corrected.configure(c).ok() && fresh.configure(c).ok());
  ASSERT_EQ(corrected.uncage(first, Vector2<double>::Zero(), Vector2<double>(0.1, -0.2)), Status::kOk);
  ASSERT_EQ(corrected.correct_attitude(Vector2<double>(0.05, 0.02), first), Status::kOk);
  ASSERT_EQ(corrected.uncage(second, Vector2<double>::Zero(), Vector2<double>(-0.1, 0.15)), Status::kOk);
  ASSERT_EQ(fresh.uncage(second, Vector2<double>::Zero(), Vector2<double>(-0.1, 0.15)), Status::kOk);
  EXPECT_EQ(corrected.gimbal_pitch_rad(), fresh.gimbal_pitch_rad());
  EXPECT_EQ(corrected.gimbal_yaw_rad(), fresh.gimbal_yaw_rad());
  ASSERT_EQ(corrected.uncage_on_gimbal(first, Vector3<double>::Zero(), Vector2<double>(0.2, 0.1)), Status::kOk);
  ASSERT_EQ(corrected.correct_attitude(Vector2<double>(0.05, 0.02), first), Status::kOk);
  ASSERT_EQ(corrected.uncage_on_gimbal(second, Vector3<double>::Zero(), Vector2<double>(0.3, -0.2)), Status::kOk);
  EXPECT_NEAR(corrected.gimbal_pitch_rad(), 0.3, 1e-12);
  EXPECT_NEAR(corrected.gimbal_yaw_rad(), -0.2, 1e-12);
}

// A correction taken at the next step is the same turn as one taken now followed by the
// step: R(c) R(a) = R(c + a + (c x a) / 2 + third order). The reference is the product of the
// two exact rotations; the roll term (c x a) / 2 is what makes them agree: without it the
// attitudes differ by |c| |a| / 2 (1e-5 rad here), with it by less than the third-order
// bound |a| |c| (|a| + |c|) / 12 = 2e-8 rad.
TEST(GyroModelCorrection, GivenACorrectionAtTheNextStepThenTheStepEndsWhereTheCorrectionAndThenTheStepLeaveIt) {
  const GyroModelConfig<double> c = ReportSample<double>::config();
  const Matrix3<double> body = Eigen::AngleAxisd(0.3, Vector3<double>(1, -2, 0.5).normalized()).toRotationMatrix();
  const auto uncaged = [&](GyroModel<double>& g) {
    return g.configure(c).ok() && g.uncage(body, Vector2<double>(1.0, -0.5), Vector2<double>(0.1, -0.2)) == Status::kOk;
  };
  GyroModel<double> now, next, probe;
  ASSERT_TRUE(uncaged(now) && uncaged(next) && uncaged(probe));
  EXPECT_EQ(GyroModel<double>().correct_gimbal_angles_at_next_step(Vector2<double>(1e-3, 0.0)),
            Status::kNotConfigured);
  EXPECT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(std::nan(""), 0.0)), Status::kNonFiniteInput);
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "a refused call changes nothing";

  const Vector2<double> d(-0.7e-3, 0.5e-3);
  ASSERT_EQ(now.correct_gimbal_angles(d, body), Status::kOk);
  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(0.5 * d)), Status::kOk);
  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(Vector2<double>(0.5 * d)), Status::kOk);  // the two add
  const Vector2<double> corr = next.pending_correction_rad();
  EXPECT_EQ(next.attitude_gyro_to_earth().coeffs(), probe.attitude_gyro_to_earth().coeffs()) << "not turned yet";

  GyroStepInput<double> in;
  in.dt_s = 0.02;
  in.spin_hz = ReportSample<double>::kSpinHz;
  in.R_earth_to_body = body;
  const Vector2<double> torque(1500.0, -800.0);  // a precession near 1 rad/s against H = 1885
  const Quaternion<double> start = next.attitude_gyro_to_earth();
  ASSERT_EQ(now.step_torque(in, torque), Status::kOk);
  ASSERT_EQ(next.step_torque(in, torque), Status::kOk);
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "taken by the step";
  const Vector2<double> a = next.isaf_angle_rad();
  ASSERT_GT(a.norm(), 1e-2) << "a step long enough for the roll term to matter";
  const double third_order = a.norm() * corr.norm() * (a.norm() + corr.norm()) / 12;
  EXPECT_LT(now.attitude_gyro_to_earth().angularDistance(next.attitude_gyro_to_earth()), third_order + 1e-14);
  const Quaternion<double> without_roll = start * step_rotation(Vector2<double>(a + corr));
  EXPECT_GT(now.attitude_gyro_to_earth().angularDistance(without_roll), 0.3 * a.norm() * corr.norm())
      << "the roll term is needed";
  EXPECT_NEAR(now.gimbal_pitch_rad(), next.gimbal_pitch_rad(), third_order);
  EXPECT_NEAR(now.gimbal_yaw_rad(), next.gimbal_yaw_rad(), third_order);

  ASSERT_EQ(next.correct_gimbal_angles_at_next_step(d), Status::kOk);
  ASSERT_TRUE(uncaged(next));
  EXPECT_EQ(next.pending_correction_rad(), Vector2<double>::Zero()) << "uncaging drops a pending correction";
}

}  // namespace
}  // namespace gyro
