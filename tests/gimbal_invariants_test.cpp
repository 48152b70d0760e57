// The gimbal plant (gyro/gimbal_plant.hpp) checked as a dynamicist would, on the seeker's
// device over 1 s of large nutation (30 deg cone, 5 rad/s on each gimbal), double:
//   - no friction, no torque, free rotor, body at rest: kinetic energy and the angular
//     momentum about the outer (body z) axis are constant;
//   - constant body rates: the Jacobi integral p.u - T is constant;
//   - friction, torques, spin motor, drag and unbalance: the kinetic energy changes by the
//     work the plant reports;
//   - steady precession at 0 and 40 deg: T/(H cos theta) (with friction, the report's k5/k6
//     with H cos theta for H);
//   - the sub-step rule: the error of the default against a run 8x finer.
// The figures are printed ("figure:") for docs/gimbal-plant.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "support/gimbal_support.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

using namespace gimbal_test;
using V2 = Vector2<double>;
using V3 = Vector3<double>;

// Kinetic energy of everything but the rotor's spin about its axis (J0 w_x^2 / 2).
double non_spin_energy(const GimbalPlant<double>& p) {
  const double w = p.spin_inertial_rad_s();
  return p.kinetic_energy() - p.config().spin_inertia * w * w / 2.0;
}

TEST(GimbalInvariants, GivenNoFrictionNoTorqueBodyAtRestWhenOneSecondOfLargeNutationThenEnergyAndYawMomentumConserved) {
  GYRO_VERIFIES("STUB-1");
  GimbalPlant<double> p = started(ideal_seeker<double>(), large_nutation<double>());
  const double e0 = p.kinetic_energy(), l0 = p.angular_momentum_body()(2), w0 = p.spin_inertial_rad_s();
  const double e_gimbal = non_spin_energy(p);
  double de = 0.0, dl = 0.0, dw = 0.0, cone_min = 1.0, cone_max = 0.0;
  run(p, kTicksPerSecond, V2::Zero().eval(), BodyState<double>{}, [&](int, const GimbalPlant<double>& g) {
    de = std::max(de, std::abs(g.kinetic_energy() - e0));
    dl = std::max(dl, std::abs(g.angular_momentum_body()(2) - l0));
    dw = std::max(dw, std::abs(g.spin_inertial_rad_s() - w0));
    cone_min = std::min(cone_min, g.cone_rad());
    cone_max = std::max(cone_max, g.cone_rad());
    EXPECT_FALSE(g.in_contact());
  });
  std::printf("figure: energy %.2e of T (%.2e of the non-spin part), yaw momentum %.2e of Lz, inertial spin %.2e "
              "rel; cone %.4f..%.4f rad; %d sub-steps per tick\n",
              de / e0, de / e_gimbal, dl / std::abs(l0), dw / w0, cone_min, cone_max, p.substeps());
  EXPECT_LT(de / e0, 1e-10);
  EXPECT_LT(dl / std::abs(l0), 1e-10);
  // The part that nutates, not only the spin's: what is left is the rounding of phi' (one ulp
  // of 2513 rad/s is 3e-14 J of spin energy, 7e-11 of the non-spin part).
  EXPECT_LT(de / e_gimbal, 1e-8);
  EXPECT_LT(dw / w0, 1e-12);       // free rotor: no torque about its axis
  EXPECT_GT(cone_max - cone_min, 1e-3);  // it did nutate
}

TEST(GimbalInvariants, GivenConstantBodyRatesWhenOneSecondOfLargeNutationThenJacobiIntegralConserved) {
  GYRO_VERIFIES("STUB-1");
  BodyState<double> body;
  body.rate_rad_s = V3(8.0, 0.2, -0.15);  // rolling at 8 rad/s, turning slowly in pitch and yaw
  GimbalPlant<double> p = started(ideal_seeker<double>(), large_nutation<double>(), body);
  auto jacobi = [](const GimbalPlant<double>& g) {
    const GimbalJointState<double>& s = g.joint_state();
    return g.generalised_momentum().dot(V3(s.pitch_rate_rad_s, s.yaw_rate_rad_s, s.spin_rate_rad_s)) -
           g.kinetic_energy();
  };
  const double h0 = jacobi(p), e0 = p.kinetic_energy(), e_gimbal = non_spin_energy(p);
  double dh = 0.0, de = 0.0, yaw_travel = 0.0;
  const double yaw0 = p.gimbal_angle_rad()(1);
  run(p, kTicksPerSecond, V2::Zero().eval(), body, [&](int, const GimbalPlant<double>& g) {
    dh = std::max(dh, std::abs(jacobi(g) - h0));
    de = std::max(de, std::abs(g.kinetic_energy() - e0));
    yaw_travel = std::max(yaw_travel, std::abs(g.gimbal_angle_rad()(1) - yaw0));
  });
  std::printf("figure: Jacobi integral %.2e of |h| (%.2e of the non-spin energy); kinetic energy itself moves %.2e "
              "of T; yaw travel %.3f rad\n",
              dh / std::abs(h0), dh / e_gimbal, de / e0, yaw_travel);
  EXPECT_LT(dh / std::abs(h0), 1e-10);
  EXPECT_LT(dh / e_gimbal, 1e-8);
  EXPECT_GT(de / e0, 1e3 * dh / std::abs(h0));  // the body does work: energy alone is not the invariant
  EXPECT_GT(yaw_travel, 0.05);                  // the body turned under the gyro
}

// Kinetic energy change minus the work reported, worst over 1 s of large nutation with the
// torques reversed every 0.125 s, body at rest under gravity; and the work that flowed.
struct Balance {
  double worst = 0.0;
  double flow = 0.0;
  GimbalWork<double> work;
  int saturated_ticks = 0;
};
Balance energy_balance(const GimbalPlantConfig<double>& c) {
  BodyState<double> body;
  body.specific_force = V3(0.0, 0.0, -9.80665);
  GimbalPlant<double> p = started(c, large_nutation<double>(), body);
  const double e0 = p.kinetic_energy();
  Balance b;
  for (int k = 0; k < kTicksPerSecond; ++k) {
    const double sign = ((k / 250) % 2 == 0) ? 1.0 : -1.0;
    EXPECT_EQ(p.step(V2(4e-3, -3e-3) * sign, body, body), Status::kOk);
    EXPECT_FALSE(p.in_contact());
    const GimbalWork<double>& w = p.work();
    b.worst = std::max(b.worst, std::abs(p.kinetic_energy() - e0 - (w.torquer + w.friction + w.spin + w.unbalance)));
    b.flow = std::abs(w.torquer) + std::abs(w.friction) + std::abs(w.spin) + std::abs(w.unbalance);
    b.saturated_ticks += static_cast<int>(p.motor_saturated());
  }
  b.work = p.work();
  std::printf("figure: energy balance closes to %.2e J against %.2e J of work (%.1e); torquer %.3e, friction %.3e, "
              "spin %.3e, unbalance %.3e J; motor at its limit in %d ticks\n",
              b.worst, b.flow, b.worst / b.flow, b.work.torquer, b.work.friction, b.work.spin, b.work.unbalance,
              b.saturated_ticks);
  return b;
}

// Viscous friction, torquers, a spin motor that holds (limit raised), spin drag, unbalance.
TEST(GimbalInvariants, GivenFrictionTorquesMotorAndUnbalanceBodyAtRestWhenOneSecondThenEnergyBalanceCloses) {
  GimbalPlantConfig<double> c = seeker_gimbal_config<double>();
  c.stop_cone_rad = 1.0;
  c.motor_torque_limit = 1.0;
  c.mass_unbalance = 2e-4;
  const Balance b = energy_balance(c);
  EXPECT_EQ(b.saturated_ticks, 0);
  EXPECT_LT(b.worst, 1e-10 * b.flow);
  EXPECT_LT(b.work.friction, 0.0);
  EXPECT_GT(std::abs(b.work.spin), 1e-3 * b.flow);       // the motor and the drag did work
  EXPECT_GT(std::abs(b.work.unbalance), 1e-6 * b.flow);  // and so did gravity on the unbalance
  EXPECT_GT(std::abs(b.work.torquer), 1e-6 * b.flow);
}

// The non-smooth parts on: Coulomb friction (its sign flips within a sub-step as the gimbal
// rates nutate through zero) and the seeker's spin motor at its torque limit for part of the
// run. The balance still closes, to the integration error these leave (docs/gimbal-plant.md).
TEST(GimbalInvariants, GivenCoulombFrictionAndASaturatingMotorWhenOneSecondThenEnergyBalanceClosesToTheStatedTolerance) {
  GimbalPlantConfig<double> c = seeker_gimbal_config<double>();
  c.stop_cone_rad = 1.0;
  c.inner_coulomb_torque = 2e-4;
  c.outer_coulomb_torque = 3e-4;
  c.mass_unbalance = 2e-4;
  const Balance b = energy_balance(c);
  EXPECT_GT(b.saturated_ticks, 0);
  EXPECT_LT(b.worst, 1e-6 * b.flow);
}

// The quasi-steady precession of the friction-coupled gyro at pitch theta: the report's k5/k6
// with H cos(theta) for H (docs/gimbal-plant.md).
V2 steady_precession(double h_cos, double f_in, double f_out, const V2& torque) {
  const double den = h_cos * h_cos + f_in * f_out;
  return V2((f_out * torque(0) - h_cos * torque(1)) / den, (h_cos * torque(0) + f_in * torque(1)) / den);
}

struct PrecessionCase {
  const char* name;
  double pitch_deg;
  V2 torque;
};

class GimbalPrecession : public ::testing::TestWithParam<PrecessionCase> {};

TEST_P(GimbalPrecession, GivenAHeldTorqueWhenTheNutationHasDiedThenTheRatesAreTOverHCosTheta) {
  const PrecessionCase pc = GetParam();
  const GimbalPlantConfig<double> c = [] {
    GimbalPlantConfig<double> k = seeker_gimbal_config<double>();
    k.stop_cone_rad = 1.0;
    return k;
  }();
  GimbalStart<double> s;
  s.spin_hz = 400.0;
  // Start 1/4 s of precession before the cone is reached, so that it is crossed when the
  // nutation has decayed (alpha = 20 1/s: e^-5).
  const double h0 = c.spin_inertia * 2.0 * kPiD * s.spin_hz;
  const V2 guess = steady_precession(h0 * std::cos(pc.pitch_deg * kDeg), c.inner_friction, c.outer_friction, pc.torque);
  s.gimbal_angle_rad = V2(pc.pitch_deg * kDeg - 0.25 * guess(0), 0.0);
  s.gimbal_rate_rad_s = guess;
  GimbalPlant<double> p = started(c, s);
  const int ticks = kTicksPerSecond / 4;
  run(p, ticks, pc.torque, BodyState<double>{}, [](int, const GimbalPlant<double>&) {});
  const double pitch = p.gimbal_angle_rad()(0);
  const double h = c.spin_inertia * p.spin_inertial_rad_s();
  const V2 expected = steady_precession(h * std::cos(pitch), c.inner_friction, c.outer_friction, pc.torque);
  const V2 frictionless(-pc.torque(1) / (h * std::cos(pitch)), pc.torque(0) / (h * std::cos(pitch)));
  const V2 rate = p.gimbal_rate_rad_s();
  const double scale = expected.cwiseAbs().maxCoeff();
  std::printf("figure: %s at pitch %.3f deg: rates (%.6e, %.6e) rad/s, expected (%.6e, %.6e): %.1e of the rate; "
              "T/(H cos theta) alone %.1e\n",
              pc.name, pitch / kDeg, rate(0), rate(1), expected(0), expected(1),
              (rate - expected).cwiseAbs().maxCoeff() / scale, (rate - frictionless).cwiseAbs().maxCoeff() / scale);
  EXPECT_NEAR(pitch / kDeg, pc.pitch_deg, 0.05);
  EXPECT_LT((rate - expected).cwiseAbs().maxCoeff(), 2e-4 * scale);
  // Sign and size of the headline: the torqued axis precesses at T/(H cos theta) to 1 %.
  EXPECT_LT((rate - frictionless).cwiseAbs().maxCoeff(), 1e-2 * scale);
}

INSTANTIATE_TEST_SUITE_P(
    Seeker, GimbalPrecession,
    ::testing::Values(PrecessionCase{"outer torque", 40.0, V2(0.0, 2e-3)},
                      PrecessionCase{"inner torque", 40.0, V2(2e-3, 0.0)},
                      PrecessionCase{"outer torque, zero angles", 0.0, V2(0.0, 2e-3)},
                      PrecessionCase{"inner torque, zero angles", 0.0, V2(-2e-3, 0.0)}),
    [](const ::testing::TestParamInfo<PrecessionCase>& i) { return std::to_string(i.index); });

// The sub-step rule: runs at 1, 0.5 (the default) and 0.25 rad of phase per sub-step against
// a run at 1/8 rad (eighth order: its own error is 2^-8 of the 0.25 run's, below rounding),
// over 1 s of large nutation with the body rolling at 10 rad/s and turning, viscous friction,
// a held spin and a torque. Worst gimbal-angle errors.
std::array<double, 3> substep_errors(void (*adjust)(GimbalPlantConfig<double>&)) {
  auto config = [adjust](double phase) {
    GimbalPlantConfig<double> c = seeker_gimbal_config<double>();
    c.stop_cone_rad = 1.0;
    adjust(c);
    c.max_substep_phase_rad = phase;
    return c;
  };
  BodyState<double> body;
  body.rate_rad_s = V3(10.0, 0.3, -0.2);
  const V2 torque(3e-3, -2e-3);
  GimbalPlant<double> ref = started(config(1.0 / 8.0), large_nutation<double>(), body);
  const double phases[] = {1.0, 0.5, 0.25};
  GimbalPlant<double> runs[] = {started(config(phases[0]), large_nutation<double>(), body),
                                started(config(phases[1]), large_nutation<double>(), body),
                                started(config(phases[2]), large_nutation<double>(), body)};
  std::array<double, 3> worst = {0.0, 0.0, 0.0};
  int saturated = 0;
  for (int k = 0; k < kTicksPerSecond; ++k) {
    EXPECT_EQ(ref.step(torque, body, body), Status::kOk);
    saturated += static_cast<int>(ref.motor_saturated());
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(runs[i].step(torque, body, body), Status::kOk);
      const V2 d = runs[i].gimbal_angle_rad() - ref.gimbal_angle_rad();
      worst[i] = std::max(worst[i], d.cwiseAbs().maxCoeff());
    }
  }
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("figure: phase %.2f rad per sub-step (%d sub-steps per tick): worst gimbal-angle error %.2e rad over "
                "1 s (reference: %d sub-steps per tick; motor at its limit in %d ticks)\n",
                phases[i], runs[i].substeps(), worst[i], ref.substeps(), saturated);
  }
  return worst;
}

TEST(GimbalSubsteps, GivenSmoothDynamicsWhenTheDefaultRuleIsComparedWithAFinerRunThenWithinTheDocumentedError) {
  const std::array<double, 3> e = substep_errors([](GimbalPlantConfig<double>& c) { c.motor_torque_limit = 1.0; });
  EXPECT_LT(e[1], 1e-10);  // docs/gimbal-plant.md: the default's error
  EXPECT_GT(e[0], 64.0 * e[1]);  // eighth order: halving the step gains up to 2^8
}

// With the non-smooth parts: Coulomb friction flipping within a sub-step and the spin motor
// switching in and out of its limit. The method loses its order there; the error stays small
// next to the model differences the plant is for (1e-4 rad and up).
TEST(GimbalSubsteps, GivenCoulombFrictionAndASaturatingMotorWhenTheDefaultRuleIsUsedThenWithinTheDocumentedError) {
  const std::array<double, 3> e = substep_errors([](GimbalPlantConfig<double>& c) {
    c.inner_coulomb_torque = 3e-4;
    c.outer_coulomb_torque = 3e-4;
  });
  EXPECT_LT(e[1], 1e-4);
  EXPECT_LT(e[2], e[0]);
}

}  // namespace
}  // namespace gyro
