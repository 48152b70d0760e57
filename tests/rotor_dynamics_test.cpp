// Analytic invariants of the rotor: eigenvalues, steady precession, nutation frequency.
#include <gtest/gtest.h>

#include "gyro/nutation.hpp"
#include "gyro/rotor_transition.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

// The report's sample gyro: spin 100 Hz, J0 = 3, J1 = 2.25, J2 = 2, f = 5 (slug*ft^2).
RotorParameters<double> report_rotor() {
  return {2.25, 2.0, 5.0, angular_momentum(100.0, 3.0)};
}

TEST(RotorModes, GivenReportGyroThenNutationMatchesInitg) {
  GYRO_VERIFIES("EXACT-3");
  RotorModes<double> m;
  ASSERT_EQ(compute_modes(report_rotor(), m), Status::kOk);
  // INITG: BETA = SQRT((F*F+H*H)/(GJ1*GJ2) - ALPHA**2), GNUTAT = BETA/(2 PI).
  const double h = 2.0 * 3.141592653589793 * 100.0 * 3.0;
  const double alpha = 2.5 * (1.0 / 2.25 + 1.0 / 2.0);
  const double beta = std::sqrt((25.0 + h * h) / 4.5 - alpha * alpha);
  EXPECT_EQ(m.regime, DampingRegime::kUnderdamped);
  EXPECT_NEAR(m.alpha_1_s, alpha, 1e-14);
  EXPECT_NEAR(m.nutation_hz, beta / (2.0 * 3.141592653589793), 1e-9);
  EXPECT_NEAR(m.nutation_hz, 141.4, 0.1);
}

TEST(RotorModes, GivenEqualInertiasThenNutationRateIsHOverJForAnyFriction) {
  GYRO_VERIFIES("EXACT-3");
  for (double f : {0.0, 1.0, 100.0, 1e4}) {
    RotorModes<double> m;
    ASSERT_EQ(compute_modes(RotorParameters<double>{2.0, 2.0, f, 50.0}, m), Status::kOk);
    EXPECT_NEAR(std::sqrt(m.beta_squared_1_s2), 25.0, 1e-12) << "f=" << f;
  }
}

TEST(SteadyPrecession, GivenTorqueThenRateIsReportK5K6AndInverseRoundTrips) {
  GYRO_VERIFIES("EXACT-3");
  const RotorParameters<double> p = report_rotor();
  const Vector2<double> torque(3.0, -7.0);
  Vector2<double> rate = Vector2<double>::Zero();
  ASSERT_EQ(steady_precession_rate(p, torque, rate), Status::kOk);
  const double f = p.friction, h = p.angular_momentum, den = f * f + h * h;
  EXPECT_NEAR(rate(0), (f * torque(0) - h * torque(1)) / den, 1e-15);
  EXPECT_NEAR(rate(1), (h * torque(0) + f * torque(1)) / den, 1e-15);
  Vector2<double> back = Vector2<double>::Zero();
  ASSERT_EQ(torque_for_precession_rate(p, rate, back), Status::kOk);
  EXPECT_NEAR((back - torque).norm(), 0.0, 1e-12);
}

TEST(SteadyPrecession, GivenNoSpinAndNoFrictionThenRefused) {
  GYRO_VERIFIES("EXACT-5");
  Vector2<double> rate(1.0, 2.0);
  EXPECT_EQ(steady_precession_rate(RotorParameters<double>{1.0, 1.0, 0.0, 0.0},
                                   Vector2<double>(1.0, 0.0), rate),
            Status::kNoSteadyState);
  EXPECT_EQ(rate, Vector2<double>(1.0, 2.0));
}

}  // namespace
}  // namespace gyro
