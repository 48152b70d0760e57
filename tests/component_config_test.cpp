// The configuration contract (docs/component.md, "Configuration contract"): every field of
// the component's configuration has both bounds, each edge exactly where it is stated, rules
// between fields refuse what cannot work together, a refusal names the field, the value, the
// bound and the rule, check_all() gives every violated rule, and the component keeps the last
// configuration it accepted.
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
#include "support/requirements.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace component_config_test {

using testing::Sil;
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

TEST(ComponentConfig, TheSeekerExampleBreaksNoRule) {
  GYRO_VERIFIES("CONF-8");
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

TEST(ComponentConfig, EveryNumberFieldHasBothBounds) {
  GYRO_VERIFIES("CONF-1");
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

TEST(ComponentConfig, EachBadFieldIsRefusedByName) {
  GYRO_VERIFIES("CONF-1");
  using C = GyroComponentConfig<double>;
  struct Case {
    const char* field;
    void (*spoil)(C&);
    Status status;
  };
  const Case cases[] = {
      {"tick_s", [](C& c) { c.tick_s = 0; }, Status::kNonPositiveStep},
      {"tick_s", [](C& c) { c.tick_s = std::nan(""); }, Status::kNonFiniteInput},
      {"pitch_inertia", [](C& c) { c.pitch_inertia = -1; }, Status::kNonPositiveInertia},
      {"yaw_inertia", [](C& c) { c.yaw_inertia = 0; }, Status::kNonPositiveInertia},
      {"spin_inertia", [](C& c) { c.spin_inertia = 0; }, Status::kNonPositiveInertia},
      {"friction", [](C& c) { c.friction = -1e-6; }, Status::kNegativeFriction},
      {"friction", [](C& c) { c.friction = HUGE_VAL; }, Status::kNonFiniteInput},
      {"nominal_spin_hz", [](C& c) { c.nominal_spin_hz = 0; }, Status::kOutOfRange},
      {"min_spin_hz", [](C& c) { c.min_spin_hz = 500; }, Status::kOutOfRange},
      {"max_pitch_rate_rad_s", [](C& c) { c.max_pitch_rate_rad_s = 0; }, Status::kOutOfRange},
      {"max_yaw_rate_rad_s", [](C& c) { c.max_yaw_rate_rad_s = -1; }, Status::kOutOfRange},
      {"max_torque", [](C& c) { c.max_torque = 0; }, Status::kOutOfRange},
      {"cage_gain_1_s", [](C& c) { c.cage_gain_1_s = 1e4; }, Status::kOutOfRange},
      {"gimbal_cone_limit_rad", [](C& c) { c.gimbal_cone_limit_rad = 2; }, Status::kOutOfRange},
      {"gimbal_stop_margin_rad", [](C& c) { c.gimbal_stop_margin_rad = 0.6; }, Status::kOutOfRange},
      {"small_angle_limit_rad", [](C& c) { c.small_angle_limit_rad = 0; }, Status::kOutOfRange},
      {"pickoff_range_rad", [](C& c) { c.pickoff_range_rad = 0; }, Status::kOutOfRange},
      {"max_pickoff_step_rad", [](C& c) { c.max_pickoff_step_rad = -1; }, Status::kOutOfRange},
      {"estimator_gain", [](C& c) { c.estimator_gain = 1.5; }, Status::kOutOfRange},
      {"residual_limit_rad", [](C& c) { c.residual_limit_rad = 0; }, Status::kOutOfRange},
      {"residual_persistence_ticks", [](C& c) { c.residual_persistence_ticks = 0; }, Status::kOutOfRange},
      {"invalid_persistence_ticks", [](C& c) { c.invalid_persistence_ticks = 0; }, Status::kOutOfRange},
      {"spin_low_persistence_ticks", [](C& c) { c.spin_low_persistence_ticks = 0; }, Status::kOutOfRange},
      {"torquer_fail_persistence_ticks", [](C& c) { c.torquer_fail_persistence_ticks = 0; },
       Status::kOutOfRange},
  };
  for (const Case& k : cases) {
    Sil<double> sil;
    C c = Seeker::component();
    k.spoil(c);
    const ConfigCheck r = sil.component.configure(c);
    EXPECT_EQ(r.status, k.status) << k.field;
    ASSERT_NE(r.field, nullptr) << k.field;
    EXPECT_STREQ(r.field, k.field);
    EXPECT_EQ(sil.component.activate(), Status::kNotConfigured) << "a refused config is not kept";
  }
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

// Each limit exactly at its edge: the inclusive ones are accepted, the strict ones refused.
TEST(ComponentConfig, InclusiveEdgesAcceptedStrictOnesRefused) {
  GYRO_VERIFIES("CONF-1");
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
    C c = Seeker::component();
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

// The configured nominal rotor must have a finite transition over a tick: a nominal spin so
// high that H^2 overflows is refused at configure, not discovered in flight. Since the
// contract bounds the spin (100 kHz), such a spin is refused by its own range first.
TEST(ComponentConfig, ANominalSpinOf1e200IsRefusedByItsRange) {
  GYRO_VERIFIES("CONF-1", "CONF-2");
  Sil<double> sil;
  GyroComponentConfig<double> c = Seeker::component();
  c.nominal_spin_hz = 1e200;  // finite and above min_spin_hz
  const ConfigCheck r = sil.component.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_EQ(r.bound, 1e5);
  ASSERT_NE(r.field, nullptr);
  EXPECT_STREQ(r.field, "nominal_spin_hz");  // the field responsible, not the tick
  EXPECT_EQ(sil.component.activate(), Status::kNotConfigured) << "a refused config is not kept";
}

// Rate limits far beyond the contract's 100 rad/s (one tick's slew must stay within the
// small-angle limit too), up to the largest double: refused, naming the first rate limit.
TEST(ComponentConfig, RateLimitsBeyond100RadPerSecondAreRefused) {
  GYRO_VERIFIES("CONF-1");
  for (const double limit : {1e300, 1e308, 1.7e308}) {
    GyroComponentConfig<double> c = Seeker::component();
    c.max_pitch_rate_rad_s = limit;
    c.max_yaw_rate_rad_s = limit;
    const ConfigCheck r = check(c);
    ASSERT_FALSE(r.ok()) << limit;
    EXPECT_STREQ(r.field, "max_pitch_rate_rad_s");
    EXPECT_EQ(r.value, limit);
    EXPECT_EQ(r.bound, 100.0);
  }
}

// A torque limit so small that max_torque / |torque| is subnormal (found by
// fuzz_component_tick: scaling by that ratio overshot the limit by 5e-15 relative) cannot
// precess the spin axis at all: the configuration contract refuses it, naming the rule.
TEST(ComponentConfig, ATinyTorqueLimitIsRefused) {
  GYRO_VERIFIES("CONF-3");
  GyroComponentConfig<double> c = Seeker::component();
  c.max_torque = 1.8816602877266144e-306;
  const ConfigCheck r = check(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  ASSERT_NE(r.field, nullptr);
  EXPECT_STREQ(r.field, "max_torque");
  EXPECT_EQ(r.value, c.max_torque);
  Sil<double> sil;
  EXPECT_FALSE(sil.start(c));
}

TEST(ComponentConfig, ASettleBeyondTheLongestTimeIsRefused) {
  GYRO_VERIFIES("CONF-5");
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

TEST(ComponentConfig, ATinyBodyRateLimitIsRefusedAsALockOut) {
  GYRO_VERIFIES("CONF-3");
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

TEST(ComponentConfig, AResidualLimitBelowTwoLsbsIsRefused) {
  GYRO_VERIFIES("CONF-5");
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

TEST(ComponentConfig, AResidualBelowTheHardwaresLsbIsRefused) {
  GYRO_VERIFIES("CONF-5", "STUB-4");
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

TEST(ComponentConfig, APickoffStepBeyondTheRangeIsRefused) {
  GYRO_VERIFIES("CONF-5");
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

TEST(ComponentConfig, APickoffRangeOf5RadIsRefusedOnBothSides) {
  GYRO_VERIFIES("CONF-1", "STUB-4");
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

TEST(ComponentConfig, ATorqueLimitBeyondTheTorquersIsRefused) {
  GYRO_VERIFIES("STUB-4");
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

TEST(ComponentConfig, ACageGainOfZeroOrOverATickIsRefused) {
  GYRO_VERIFIES("CONF-4");
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
TEST(ComponentConfig, ACageGainDrivingTheNutationIsRefused) {
  GYRO_VERIFIES("CONF-4");
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
TEST(ComponentConfig, BeyondTheShapersNotchTheBearingsMustDamp) {
  GYRO_VERIFIES("CONF-4");
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
TEST(ComponentConfig, AnEstimatorGainTooSmallIsRefused) {
  GYRO_VERIFIES("CONF-4");
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

TEST(ComponentConfig, CheckAllListsEveryBrokenRule) {
  GYRO_VERIFIES("CONF-6");
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

TEST(ComponentConfig, CheckAllNamesEachFieldOnce) {
  GYRO_VERIFIES("CONF-6");
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

TEST(ComponentConfig, AConeBeyondTheHardwaresStopIsRefused) {
  GYRO_VERIFIES("CONF-5", "STUB-4");
  GyroComponentConfig<double> c = Seeker::component();
  SimulatedGyroConfig<double> g = Seeker::stub();
  g.gimbal.stop_cone_rad = 0.45;  // inside the component's 0.5 rad cone
  ConfigCheckList<8> pair;
  check_against_hardware(g, c, pair);
  const ConfigCheck* r = pair.find("gimbal_cone_limit_rad");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->bound, 0.45);
}

TEST(ComponentConfig, ARefusalIsTruncatedToASmallBuffer) {
  GYRO_VERIFIES("CONF-6");
  GyroComponentConfig<double> c = Seeker::component();
  c.estimator_gain = 1.5;
  char buf[16];
  const int n = format_refusal(check(c), nullptr, buf, sizeof buf);
  EXPECT_GT(n, 15);
  EXPECT_EQ(std::string(buf), "estimator_gain ");
}

// A refused configure() leaves the component with the configuration it accepted before.
TEST(ComponentConfig, ARefusedConfigureKeepsTheAcceptedOne) {
  GYRO_VERIFIES("LIFE-1");
  Sil<double> sil;
  GyroComponentConfig<double> c = Seeker::component();
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

// A rotor the bearings overdamp has no nutation: the rules that keep the caging loop off it
// have nothing to keep it off. The gain the underdamped rotor refuses passes them.
TEST(ComponentConfig, AnOverdampedRotorHasNoNutationRuleToBreak) {
  GYRO_VERIFIES("CONF-4");
  GyroComponentConfig<double> c = Seeker::component();
  c.cage_gain_1_s = 1000;  // above a quarter of the seeker's nutation frequency
  ASSERT_NE(all_of(c).find("cage_gain_1_s"), nullptr);
  // Overdamped where f^2 (1/J1 - 1/J2)^2 > 4 H^2 / (J1 J2): with J2 = 2 J1, f > 2.9 H (J1 = J2
  // nutates at H / J whatever the friction).
  c.yaw_inertia = 2 * c.pitch_inertia;
  c.friction = 1e12;  // the largest the field takes
  const ConfigCheckList<32> all = all_of(c);
  EXPECT_EQ(all.size(), all.total());
  for (const ConfigCheck& r : all) {
    const std::string why = message(r);
    EXPECT_EQ(why.find("nutation frequency"), std::string::npos) << why;
    EXPECT_EQ(why.find("nutation damping"), std::string::npos) << why;
  }
}

// Every field within its own range, the float rotor's exact step may still not be
// representable: the step check, last, refuses it.
TEST(ComponentConfig, AFloatRotorWhoseStepOverflowsIsRefusedLast) {
  GYRO_VERIFIES("CONF-3");
  GyroComponentConfig<float> c = SeekerExample<float>::component();
  c.pitch_inertia = 2e-12F;  // as a double above the field's 1e-12
  c.yaw_inertia = 2e-12F;
  c.spin_inertia = 1e12F;
  c.nominal_spin_hz = 1e5F;  // H^2 / (J1 J2) ~ 1e59: beyond float
  ConfigCheckList<64> all;
  check_all(c, all);
  ASSERT_GT(all.size(), 0U);
  ASSERT_EQ(all.size(), all.total());
  const ConfigCheck& last = all[all.size() - 1];
  EXPECT_EQ(last.status, Status::kNumericalOverflow);
  EXPECT_STREQ(last.field, "spin_inertia");
  for (std::size_t i = 0; i + 1 < all.size(); ++i) EXPECT_NE(all[i].relation, Relation::kNone) << all[i].field;
}

TEST(ComponentFlags, ABitOutsideTheFlagsHasNoName) {
  GYRO_VERIFIES("TLM-5");
  EXPECT_STREQ(flag_name(0), "gimbal_limit");
  EXPECT_STREQ(flag_name(kComponentFlagCount - 1), "request_refused");
  EXPECT_STREQ(flag_name(-1), "");
  EXPECT_STREQ(flag_name(kComponentFlagCount), "");
}

}  // namespace component_config_test
}  // namespace gyro
