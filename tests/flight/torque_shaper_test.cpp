// The torque shaper's design (gyro/torque_shaper.hpp): the spacing m and first tap a for a
// nutation phase a tick, folded into [0, pi], where no shaper can be designed, and the share
// of another nutation a design lets through; and the filter: a step in three taps m ticks
// apart, no nutation excited at the design phase, the torque limit, a history cleared.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "gyro/torque_shaper.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace torque_shaper_test {

constexpr double kTurn = 2 * kPi<double>;

// a = 1 / (2 (1 - cos(m phi))) for the folded phase phi.
double first_tap(int m, double phi) { return 1 / (2 * (1 - std::cos(m * phi))); }

TEST(TorqueShaperDesign, FewestTicksReachingAQuarterTurn) {
  GYRO_VERIFIES("SHAPE-1");
  const ShaperDesign<double> seeker = design_shaper(1.88);  // the seeker at 2 kHz
  EXPECT_EQ(seeker.spacing, 1u);
  EXPECT_NEAR(seeker.edge, first_tap(1, 1.88), 1e-15);
  const ShaperDesign<double> nyquist = design_shaper(kPi<double>);
  EXPECT_EQ(nyquist.spacing, 1u);
  EXPECT_DOUBLE_EQ(nyquist.edge, 0.25) << "taps 1/4, 1/2, 1/4: a zero at half the tick rate";
  const ShaperDesign<double> quarter = design_shaper(kPi<double> / 2);
  EXPECT_EQ(quarter.spacing, 1u);
  EXPECT_DOUBLE_EQ(quarter.edge, 0.5) << "taps 1/2, 0, 1/2";
  EXPECT_EQ(design_shaper(kPi<double> / 2 * 0.999).spacing, 2u);
}

// A tick aliasing the nutation by less than a turn of m beta dt: the folded phase's design.
TEST(TorqueShaperDesign, AnAliasedPhaseIsFoldedWithinATurn) {
  GYRO_VERIFIES("SHAPE-1");
  // The seeker at 1 kHz: beta dt = 3.77 rad, folded 2 pi - 3.77 = 2.51.
  const double seeker = 3769.964 * 1e-3;
  const ShaperDesign<double> d = design_shaper(seeker);
  EXPECT_EQ(d.spacing, 1u);
  EXPECT_NEAR(d.edge, first_tap(1, kTurn - seeker), 1e-12);
  const ShaperDesign<double> folded = design_shaper(kTurn - seeker);
  EXPECT_EQ(folded.spacing, d.spacing);
  EXPECT_NEAR(folded.edge, d.edge, 1e-12);
  const ShaperDesign<double> two = design_shaper(kTurn - 1.2);  // m = 2: 2 x 5.08 rad, past a turn
  EXPECT_EQ(two.spacing, 0u);
  EXPECT_EQ(design_shaper(kTurn - 3.0).spacing, 1u) << "m beta dt = 3.28";
}

// Past a turn of m beta dt, a few per cent of error in beta puts the notch anywhere: none.
TEST(TorqueShaperDesign, NoShaperWhenAliasedByATurnOrMore) {
  GYRO_VERIFIES("SHAPE-1");
  for (const double phi : {0.3, 1.2, 2.51, 3.0}) {
    SCOPED_TRACE(phi);
    ASSERT_GT(design_shaper(phi).spacing, 0u);
    for (const double aliased : {kTurn + phi, 2 * kTurn - phi, 5 * kTurn - phi, 7 * kTurn + phi}) {
      EXPECT_EQ(design_shaper(aliased).spacing, 0u) << aliased;
    }
  }
}

TEST(TorqueShaperDesign, NoShaperBeyondFifteenTicksOrAtNone) {
  GYRO_VERIFIES("SHAPE-1");
  const ShaperDesign<double> longest = design_shaper(kPi<double> / 29);  // m = ceil(14.5)
  EXPECT_EQ(longest.spacing, kShaperMaxSpacing);
  EXPECT_NEAR(longest.edge, first_tap(15, kPi<double> / 29), 1e-12);
  EXPECT_EQ(design_shaper(kPi<double> / 31).spacing, 0u) << "m would be 16";
  EXPECT_EQ(design_shaper(0.0).spacing, 0u);
  EXPECT_EQ(design_shaper(kTurn).spacing, 0u) << "a whole turn a tick: every torque step excites alike";
  EXPECT_EQ(design_shaper(3 * kTurn + kPi<double> / 31).spacing, 0u);
}

TEST(TorqueShaperDesign, FloatHasTheSpacingOfDouble) {
  GYRO_VERIFIES("SHAPE-1", "RULE-8");
  for (const double phi : {0.2, 1.0, 2.0, 3.1, 10.0, 100.0}) {
    EXPECT_EQ(design_shaper(static_cast<float>(phi)).spacing, design_shaper(phi).spacing) << phi;
  }
}

// The share passed is the three taps' gain, summed here as complex numbers: none at the
// design's own phase (and its aliases), all of a constant torque, all without a shaper.
TEST(TorqueShaperLeakage, IsTheTapsGainAtThePhase) {
  GYRO_VERIFIES("SHAPE-2");
  const auto taps = [](const ShaperDesign<double>& d, double phase) {
    const std::complex<double> z = std::polar(1.0, -phase * d.spacing);
    return std::abs(d.edge + (1 - 2 * d.edge) * z + d.edge * z * z);
  };
  for (const double design : {0.3, 1.2, 1.88, kPi<double>, kTurn - 2.51}) {
    SCOPED_TRACE(design);
    const ShaperDesign<double> d = design_shaper(design);
    ASSERT_GT(d.spacing, 0u);
    EXPECT_NEAR(shaper_leakage(d, design), 0.0, 1e-12);
    EXPECT_NEAR(shaper_leakage(d, kTurn + design), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(shaper_leakage(d, 0.0), 1.0);
    for (const double ratio : {0.26, 0.5, 0.86, 1.1, 2.0}) {
      EXPECT_NEAR(shaper_leakage(d, ratio * design), taps(d, ratio * design), 1e-12) << ratio;
    }
  }
  EXPECT_DOUBLE_EQ(shaper_leakage(ShaperDesign<double>{}, 1.2), 1.0) << "no shaper passes all";
  // The seeker at 2 kHz, its nutation 3.8 times slower (held at 1.25 rad): 91 % passed.
  EXPECT_NEAR(shaper_leakage(design_shaper(1.88), 1.88 / 3.819), 0.909, 1e-3);
}

// ---- the filter ----------------------------------------------------------------------------

using V = Vector2<double>;

TEST(TorqueShaperFilter, WithoutADesignTheTorqueIsWrittenAsAsked) {
  GYRO_VERIFIES("SHAPE-1");
  TorqueShaper<double> s;
  EXPECT_EQ(s.shape(V(0.3, -0.2), 0.1), V(0.3, -0.2)) << "unshaped: not even clamped";
}

TEST(TorqueShaperFilter, AStepComesOutInThreeTapsMTicksApart) {
  GYRO_VERIFIES("SHAPE-2");
  TorqueShaper<double> s;
  const ShaperDesign<double> d = design_shaper(0.5);  // m = 4
  ASSERT_EQ(d.spacing, 4u);
  s.use(d);
  std::vector<double> out;
  for (int k = 0; k < 12; ++k) out.push_back(s.shape(V(1.0, 0.0), 10.0)(0));
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(out[k], d.edge, 1e-15) << k;
  for (std::size_t k = 4; k < 8; ++k) EXPECT_NEAR(out[k], 1 - d.edge, 1e-15) << k;
  for (std::size_t k = 8; k < 12; ++k) EXPECT_EQ(out[k], 1.0) << "equal taps give the input back exactly";
}

TEST(TorqueShaperFilter, AStepExcitesNoNutationAtTheDesignPhase) {
  GYRO_VERIFIES("SHAPE-2");
  // The filtered step's nutation: sum of its increments times e^{-i phi k}.
  const double phi = 0.5;
  TorqueShaper<double> s;
  s.use(design_shaper(phi));
  std::complex<double> excitation{0, 0};
  double last = 0;
  for (int k = 0; k < 40; ++k) {
    const double u = s.shape(V(1.0, 1.0), 10.0)(1);
    excitation += (u - last) * std::polar(1.0, -phi * k);
    last = u;
  }
  EXPECT_LT(std::abs(excitation), 1e-14);
}

TEST(TorqueShaperFilter, TheOutputStaysWithinTheTorqueLimit) {
  GYRO_VERIFIES("SHAPE-2");
  TorqueShaper<double> s;
  s.use(design_shaper(2.9));
  for (int k = 0; k < 20; ++k) {
    const V t = s.shape(V(k % 2 == 0 ? 0.1 : -0.1, 0.1), 0.1);
    EXPECT_LE(t.cwiseAbs().maxCoeff(), 0.1);
  }
}

TEST(TorqueShaperFilter, ClearingStartsTheHistoryFromRest) {
  GYRO_VERIFIES("SHAPE-4");
  TorqueShaper<double> s;
  const ShaperDesign<double> d = design_shaper(0.5);
  s.use(d);
  for (int k = 0; k < 12; ++k) (void)s.shape(V(1.0, 1.0), 10.0);
  s.clear();
  EXPECT_NEAR(s.shape(V(0.0, 0.0), 10.0)(0), 0.0, 0.0);
  s.clear();
  EXPECT_NEAR(s.shape(V(1.0, 0.0), 10.0)(0), d.edge, 1e-15) << "the step starts again from its first tap";
}

}  // namespace torque_shaper_test
}  // namespace gyro
