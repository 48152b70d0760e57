// The configuration contract (docs/component.md, "Configuration contract"): every field of
// the component's configuration has both bounds, rules between fields refuse what cannot work
// together, a refusal names the field, the value, the bound and the rule, and check_all()
// gives every violated rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "gyro/component_config.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_contract.hpp"
#include "gyro/torque_shaper.hpp"

namespace gyro {
namespace {

using Seeker = SeekerExample<double>;

std::string message(const ConfigCheck& c) {
  char buf[400];
  (void)format_refusal(c, "component.", buf, sizeof buf);
  return buf;
}

ConfigCheckList<32> all_of(const GyroComponentConfig<double>& c) {
  ConfigCheckList<32> all;
  check_all(c, all);
  return all;
}

TEST(ComponentConfig, GivenTheSeekerExampleWHENCheckedTHENNoRuleIsBroken) {
  EXPECT_TRUE(all_of(Seeker::component()).empty());
  GyroComponentConfig<float> f;
  cast_fields(Seeker::component(), f);
  ConfigCheckList<32> all;
  check_all(f, all);
  EXPECT_TRUE(all.empty());
  ConfigCheckList<8> pair;
  check_against_hardware(Seeker::stub(), Seeker::component(), pair);
  EXPECT_TRUE(pair.empty());
}

TEST(ComponentConfig, GivenEveryNumberFieldWHENListedTHENItHasBothBounds) {
  const GyroComponentConfig<double> c{};
  visit_fields(
      [](const Field& f, const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, bool>) {
          EXPECT_EQ(f.rule, Rule::kNone) << f.name;
        } else {
          EXPECT_NE(f.rule, Rule::kNone) << f.name;
          EXPECT_TRUE(std::isfinite(f.lower) && std::isfinite(f.upper)) << f.name;
          EXPECT_LE(f.lower, f.upper) << f.name;
          EXPECT_NE(f.why, nullptr) << f.name;
        }
      },
      c);
}

TEST(ComponentConfig, GivenASettleOf2To32TicksTHENRefusedAgainstLongestTime) {
  GyroComponentConfig<double> c = Seeker::component();
  c.uncage_settle_ticks = 4294967295u;
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "uncage_settle_ticks");
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_EQ(r.value, 4294967295.0);
  EXPECT_EQ(r.bound, 20000.0);  // 10 s at 2 kHz
  EXPECT_EQ(r.relation, Relation::kAbove);
  EXPECT_EQ(message(r),
            "component.uncage_settle_ticks = 4.29497e+09 is above 10 s of ticks (the longest configured time) "
            "(20000): the torquers would stay off longer than the contract's longest time");
}

TEST(ComponentConfig, GivenASubnormalBodyRateLimitTHENRefusedAsALockOut) {
  GyroComponentConfig<double> c = Seeker::component();
  c.max_body_rate_rad_s = 5e-324;
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "max_body_rate_rad_s");
  EXPECT_EQ(r.value, 5e-324);
  EXPECT_EQ(r.bound, 1e-4);
  EXPECT_EQ(r.relation, Relation::kBelow);
  // Within its own range but below the rates flown: the rule between fields says why.
  c.max_body_rate_rad_s = 0.5;
  const ConfigCheck flown = check(c);
  ASSERT_STREQ(flown.field, "max_body_rate_rad_s");
  EXPECT_EQ(flown.bound, 1.0);
  EXPECT_EQ(message(flown),
            "component.max_body_rate_rad_s = 0.5 is below the larger rate limit (1): a body turning as the gyro "
            "slews would be refused: a lock-out");
}

TEST(ComponentConfig, GivenAResidualLimitBelowTwoLsbsTHENRefusedNamingTheRule) {
  GyroComponentConfig<double> c = Seeker::component();
  c.pickoff_lsb_rad = 6.103515625e-05;
  EXPECT_TRUE(check(c).ok());
  c.residual_limit_rad = 1e-5;
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "residual_limit_rad");
  EXPECT_EQ(r.bound, 2 * 6.103515625e-05);
  EXPECT_EQ(message(r),
            "component.residual_limit_rad = 1e-05 is below 2 pickoff LSBs (0.00012207): a healthy gyro would latch "
            "a fault");
  // The noise the board promises, 9 sigma.
  c.pickoff_lsb_rad = 0;
  c.pickoff_noise_rad = 5e-5;
  c.residual_limit_rad = 2e-4;
  const ConfigCheck n = check(c);
  ASSERT_STREQ(n.field, "residual_limit_rad");
  EXPECT_NEAR(n.bound, 4.5e-4, 1e-18);
}

TEST(ComponentConfig, GivenTheHardwarePickoffWHENResidualBelowItTHENRefused) {
  SimulatedGyroConfig<double> g = Seeker::stub();
  g.pickoff.lsb_rad = 6.103515625e-05;
  GyroComponentConfig<double> c = Seeker::component();
  c.residual_limit_rad = 1e-5;  // the component states no LSB: the hardware's is known here
  ConfigCheckList<8> pair;
  check_against_hardware(g, c, pair);
  ASSERT_FALSE(pair.empty());
  EXPECT_STREQ(pair[0].field, "residual_limit_rad");
  EXPECT_EQ(message(pair[0]),
            "component.residual_limit_rad = 1e-05 is below 2 pickoff LSBs (0.00012207): a healthy gyro would latch "
            "a fault");
}

TEST(ComponentConfig, GivenAPickoffStepBeyondTheRangeTHENRefused) {
  GyroComponentConfig<double> c = Seeker::component();
  c.max_pickoff_step_rad = 1.0;  // range 0.6
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "max_pickoff_step_rad");
  EXPECT_EQ(r.bound, 0.6);
  EXPECT_EQ(r.relation, Relation::kAbove);
  EXPECT_EQ(message(r),
            "component.max_pickoff_step_rad = 1 is above pickoff_range_rad (0.6): a step larger than the range "
            "believes any reading");
}

TEST(ComponentConfig, GivenAPickoffRangeOf5RadTHENRefusedOnBothSides) {
  GyroComponentConfig<double> c = Seeker::component();
  c.pickoff_range_rad = 5.0;
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "pickoff_range_rad");
  EXPECT_NEAR(r.bound, 1.5707963267948966, 0);
  SimulatedGyroConfig<double> g = Seeker::stub();
  g.pickoff.range_rad = 5.0;
  const ConfigCheck s = check(g);
  ASSERT_STREQ(s.field, "pickoff.range_rad");
  EXPECT_EQ(s.relation, Relation::kAbove);
}

TEST(ComponentConfig, GivenATorqueLimit100TimesTheTorquersTHENRefused) {
  SimulatedGyroConfig<double> g = Seeker::stub();
  g.torquer.max_torque = 0.1;
  GyroComponentConfig<double> c = Seeker::component();
  ConfigCheckList<8> ok_pair;
  check_against_hardware(g, c, ok_pair);
  EXPECT_TRUE(ok_pair.empty());
  c.max_torque = 10.0;  // 100 times what the electronics drive
  ConfigCheckList<8> pair;
  check_against_hardware(g, c, pair);
  const ConfigCheck* r = pair.find("max_torque");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->bound, 0.1);
  EXPECT_EQ(r->relation, Relation::kAbove);
  // On its own the component refuses it too: a full-torque step's nutation.
  const ConfigCheck own = check(c);
  ASSERT_STREQ(own.field, "max_torque");
  EXPECT_NEAR(own.bound, 0.1 * 0.01 * std::pow(2 * kPi<double> * 400 * 3e-5, 2) / 2e-5, 1e-12);
}

TEST(ComponentConfig, GivenAZeroCageGainTHENRefusedForTheStopProtection) {
  GyroComponentConfig<double> c = Seeker::component();
  c.cage_gain_1_s = 0;
  EXPECT_STREQ(check(c).field, "cage_gain_1_s");
  c.cage_gain_1_s = 2001;  // gain * tick > 1 at 2 kHz
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "cage_gain_1_s");
  EXPECT_EQ(r.bound, 2000);
}

// A loop commanding the spin axis's rate from the gimbal angles drives the nutation it reads:
// the cage gain stays below a quarter of the nutation frequency, and where no torque shaper
// can be designed (a tick of under pi/30 of nutation phase), below the bearings' damping.
TEST(ComponentConfig, GivenACageGainThatDrivesTheNutationTHENRefused) {
  GyroComponentConfig<double> c = Seeker::component();
  const double beta = 2 * kPi<double> * c.nominal_spin_hz * c.spin_inertia / c.pitch_inertia;  // J1 = J2
  c.cage_gain_1_s = 1000;  // within 1 / tick (2000)
  ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "cage_gain_1_s");
  EXPECT_NEAR(r.bound, beta / 4, 1e-9 * beta);
  EXPECT_NE(message(r).find("the nutation frequency / 4"), std::string::npos) << message(r);

  c = Seeker::component();
  c.tick_s = kPi<double> / 32 / beta;  // no shaper: m would be 16
  c.cage_gain_1_s = 25;
  r = check(c);
  ASSERT_STREQ(r.field, "cage_gain_1_s");
  // alpha = f / J, less the stop protection's turn gain: the torquer's authority T / H (below
  // the navigation's limit) over the sine of the protection cone.
  const double h = 2 * kPi<double> * c.nominal_spin_hz * c.spin_inertia;
  const double turn_gain = (c.max_torque / h) / std::sin(c.gimbal_cone_limit_rad - c.gimbal_stop_margin_rad);
  EXPECT_NEAR(r.bound, c.friction / c.pitch_inertia - turn_gain, 1e-9);
  EXPECT_NE(message(r).find("no torque shaper"), std::string::npos) << message(r);
  c.cage_gain_1_s = 0.99 * r.bound;
  EXPECT_TRUE(check(c).ok()) << message(check(c));
  // A protection cone of 0.05 rad: the turn gain alone (1.33 rad/s / sin 0.05 = 27 1/s)
  // exceeds the bearings' damping (20 1/s), and no cage gain will do.
  c.gimbal_stop_margin_rad = c.gimbal_cone_limit_rad - 0.05;
  r = check(c);
  ASSERT_STREQ(r.field, "cage_gain_1_s") << message(r);
  EXPECT_LT(r.bound, 0.0);
  c.tick_s = kPi<double> / 28 / beta;  // m = 14: shaped, the bearings need not damp
  c.cage_gain_1_s = 25;
  EXPECT_TRUE(check(c).ok()) << message(check(c));
}

// Held at the protection cone c_p in pitch, the motor-held spin adds C tan^2 c_p to the yaw
// inertia: the nutation there is slower than the one the torque shaper notches. The seeker's
// rotor (C = 1.5 J) at a cone limit of 1.3 rad (protection from 1.25 rad): 3.8 times slower,
// and the shaper passes 91 % of it, no better than none; without bearing damping the stop
// protection's turn gain pumps it. At the seeker's own (0.45 rad) 1.16 times, 20 % passed.
TEST(ComponentConfig, GivenAProtectionConeWhereTheShaperLosesItsNotchTHENTheBearingsMustDampIt) {
  GyroComponentConfig<double> c = Seeker::component();
  const double h = 2 * kPi<double> * c.nominal_spin_hz * c.spin_inertia;
  // The three taps' gain at a nutation of `phase` rad a tick, summed here as complex numbers.
  const ShaperDesign<double> shaper = design_shaper(h / c.pitch_inertia * c.tick_s);
  ASSERT_GT(shaper.spacing, 0u);
  const auto passed = [&](double protect_cone) {
    const double tan_p = std::tan(protect_cone);
    const double beta = h / std::sqrt(c.pitch_inertia * (c.yaw_inertia + c.spin_inertia * tan_p * tan_p));
    const std::complex<double> z = std::polar(1.0, -beta * c.tick_s * shaper.spacing);
    return std::abs(shaper.edge + (1 - 2 * shaper.edge) * z + shaper.edge * z * z);
  };
  EXPECT_LT(passed(c.gimbal_cone_limit_rad - c.gimbal_stop_margin_rad), 0.5);
  EXPECT_TRUE(check(c).ok()) << message(check(c));

  c.gimbal_cone_limit_rad = 1.3;
  c.pickoff_range_rad = 1.5;
  c.friction = 0;
  const double protect_cone = c.gimbal_cone_limit_rad - c.gimbal_stop_margin_rad;
  ASSERT_GT(passed(protect_cone), 0.5);
  const ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "cage_gain_1_s") << message(r);
  EXPECT_NEAR(r.bound, -(c.max_torque / h) / std::sin(protect_cone), 1e-9);
  EXPECT_NE(message(r).find("at the protection cone"), std::string::npos) << message(r);
  // The rule is the shaper's: without one (a tick of pi/32 of nutation) the unshaped rule
  // refuses the same cone, by its own words.
  c.tick_s = kPi<double> / 32 / (h / c.pitch_inertia);
  EXPECT_NE(message(check(c)).find("no torque shaper"), std::string::npos) << message(check(c));
}

// The estimator corrects a fraction of the residual a tick: what its model misses of a tick's
// motion (a hundredth) settles at that over the gain, within the residual limit. Without
// correction (gain 0) the prediction drifts from the gimbal without bound.
TEST(ComponentConfig, GivenAnEstimatorGainTooSmallForTheResidualLimitTHENRefused) {
  GyroComponentConfig<double> c = Seeker::component();
  const double rate = std::max(c.max_pitch_rate_rad_s, c.max_yaw_rate_rad_s);
  const double floor = 0.01 * rate * c.tick_s / c.residual_limit_rad;
  c.estimator_gain = 0;
  ConfigCheck r = check(c);
  ASSERT_STREQ(r.field, "estimator_gain");
  EXPECT_NEAR(r.bound, floor, 1e-12 * floor);
  EXPECT_NE(message(r).find("build up beyond the residual limit"), std::string::npos) << message(r);
  c.estimator_gain = 0.99 * floor;
  EXPECT_STREQ(check(c).field, "estimator_gain");
  c.estimator_gain = floor;
  EXPECT_TRUE(check(c).ok()) << message(check(c));
  // The floor scales as 1 / residual_limit_rad: a tenfold looser limit takes a tenfold smaller gain.
  c.residual_limit_rad *= 10;
  c.estimator_gain = 0.11 * floor;
  EXPECT_TRUE(check(c).ok()) << message(check(c));
}

TEST(ComponentConfig, GivenSeveralBadFieldsWHENCheckAllTHENEveryRuleIsListed) {
  GyroComponentConfig<double> c = Seeker::component();
  c.max_pickoff_step_rad = 1.0;           // above the range
  c.gimbal_stop_margin_rad = 1e-6;        // less than a tick at the rate limit, and than the
                                          // nutation of stopping twice it: two rules
  c.max_body_rate_rad_s = 0.5;            // below the rate limits
  c.uncage_settle_ticks = 4294967295u;    // beyond the longest time
  c.residual_persistence_ticks = 100000;  // beyond the longest time
  const ConfigCheckList<32> all = all_of(c);
  EXPECT_EQ(all.total(), 6u);
  for (const char* f : {"max_pickoff_step_rad", "gimbal_stop_margin_rad", "max_body_rate_rad_s", "uncage_settle_ticks",
                        "residual_persistence_ticks"}) {
    EXPECT_NE(all.find(f), nullptr) << f;
  }
  // check() keeps returning the first of them.
  EXPECT_STREQ(check(c).field, all[0].field);
}

TEST(ComponentConfig, GivenOwnRangesBrokenWHENCheckAllTHENEachFieldNamedOnce) {
  GyroComponentConfig<double> c = Seeker::component();
  c.tick_s = 1.0;  // beyond 0.1 s
  c.estimator_gain = 1.5;
  c.friction = std::numeric_limits<double>::quiet_NaN();
  const ConfigCheckList<32> all = all_of(c);
  ASSERT_EQ(all.total(), 3u);
  EXPECT_EQ(all.find("friction")->status, Status::kNonFiniteInput);
  EXPECT_EQ(all.find("friction")->relation, Relation::kNotFinite);
  EXPECT_EQ(all.find("tick_s")->bound, 0.1);
  EXPECT_EQ(all.find("estimator_gain")->bound, 1.0);
}

TEST(ComponentConfig, GivenAConeBeyondTheStopTHENRefusedAgainstTheHardware) {
  GyroComponentConfig<double> c = Seeker::component();
  SimulatedGyroConfig<double> g = Seeker::stub();
  g.gimbal.stop_cone_rad = 0.45;  // inside the component's 0.5 rad cone
  ConfigCheckList<8> pair;
  check_against_hardware(g, c, pair);
  const ConfigCheck* r = pair.find("gimbal_cone_limit_rad");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->bound, 0.45);
}

TEST(ComponentConfig, GivenASmallBufferWHENFormattedTHENTruncatedAndTerminated) {
  GyroComponentConfig<double> c = Seeker::component();
  c.estimator_gain = 1.5;
  char buf[16];
  const int n = format_refusal(check(c), nullptr, buf, sizeof buf);
  EXPECT_GT(n, 15);
  EXPECT_EQ(std::string(buf), "estimator_gain ");
}

}  // namespace
}  // namespace gyro
