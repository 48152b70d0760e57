// GyroModel's error sources, gimbal limits and small-angle flag, each against the behaviour
// it must produce (drift rates, exponential erection, cones, flag thresholds), worked out
// here rather than from the model's formulas; a step whose drift torque is beyond the scalar
// type is refused.
#include "gyro/report_sample.hpp"
#include "support/gyro_model_support.hpp"  // gtest, Eigen, GyroModel and the standard headers
#include "support/requirements.hpp"
#include "support/same_bits.hpp"

namespace gyro {
namespace {

using namespace model_test;  // NOLINT(google-build-using-namespace): the shared fixtures

// ---------------------------------------------------------------------------------------
// Error sources, one at a time.

template <typename T>
class GyroErrorSources : public ::testing::Test {};
TYPED_TEST_SUITE(GyroErrorSources, Scalars);

template <typename T>
Vector2<double> steady_rate_with(const GyroModelConfig<T>& c, const Vector2<T>& start_rate,
                                 const std::function<Status(GyroModel<T>&, const GyroStepInput<T>&)>& step,
                                 const Vector2<T>& accel = Vector2<T>::Zero(), T spin_hz = kSpinHz<T>) {
  GyroModel<T> g = uncaged_model<T>(c, start_rate);
  GyroStepInput<T> in = step_input<T>(T(0), spin_hz);
  in.body_accel = accel;
  return mean_rate_over_nutation_periods<T>(g, in, 50, step);
}

TYPED_TEST(GyroErrorSources, GivenStaticDriftThenSteadyRateShiftsByExactlyTheDrift) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  const Vector2<T> cmd(T(0.05), T(-0.1));
  {
    GyroModelConfig<T> c = test_config<T>();
    c.errors.pitch.static_drift_rad_s = T(0.02);
    const Vector2<double> w = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(cmd));
    EXPECT_NEAR(w(0), 0.07, Tol<T>::kRate);
    EXPECT_NEAR(w(1), -0.1, Tol<T>::kRate);
    const Vector2<double> w0 = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(Vector2<T>::Zero()));
    EXPECT_NEAR(w0(0), 0.02, Tol<T>::kRate);
    EXPECT_NEAR(w0(1), 0.0, Tol<T>::kRate);
  }
  {
    GyroModelConfig<T> c = test_config<T>();
    c.errors.yaw.static_drift_rad_s = T(-0.03);
    const Vector2<double> w = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(cmd));
    EXPECT_NEAR(w(0), 0.05, Tol<T>::kRate);
    EXPECT_NEAR(w(1), -0.13, Tol<T>::kRate);
  }
  {  // the drift is not subject to the slew limit: it is not part of the command
    GyroModelConfig<T> c = test_config<T>();
    c.max_pitch_rate_rad_s = T(0.1);
    c.errors.pitch.static_drift_rad_s = T(0.02);
    const Vector2<double> w = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(Vector2<T>(T(0.5), T(0))));
    EXPECT_NEAR(w(0), 0.12, Tol<T>::kRate);
  }
}

// With friction the drift, being a torque like the command's, is cross-coupled by f through
// the dynamics (eq 11's k5, k6) and by nothing else: friction is not counted twice.
TYPED_TEST(GyroErrorSources, GivenStaticDriftWithFrictionThenSteadyRateIsTheDynamicsOwnCouplingOnly) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.friction = T(5);
  c.errors.pitch.static_drift_rad_s = T(0.2);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
  const GyroStepInput<T> in = step_input<T>(T(0.01));
  for (int k = 0; k < 2000; ++k) ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);  // 20 s, alpha t = 47
  // The drift's torque is T = (0, -H d); eq 11: w1 = -H T2/(f^2+H^2), w2 = f T2/(f^2+H^2).
  const double f = 5.0, h = D(momentum(c, kSpinHz<T>)), d = 0.2;
  const double w1 = h * h * d / (f * f + h * h), w2 = -f * h * d / (f * f + h * h);
  const double tol = kIsFloat<T> ? 2e-7 : 1e-13;
  EXPECT_NEAR(D(g.rate_rad_s()(0)), w1, tol);
  EXPECT_NEAR(D(g.rate_rad_s()(1)), w2, tol);
  EXPECT_GT(std::abs(w2), 20 * tol) << "the coupling is resolved by the test";
}

// The model holds each step's drift, so the angle follows (1 - k dt)^n rather than exp(-k t):
// at most k dt/(2e) relative (4e-5 for k dt = 2e-4). Float steps longer, to keep its rounding
// of 15000 attitude compositions from swamping the decay.
template <typename T>
struct Erection;
template <>
struct Erection<double> {
  static constexpr double kDt = 1e-4;
  static constexpr double kRel = 1e-4;
};
template <>
struct Erection<float> {
  static constexpr double kDt = 1e-3;
  static constexpr double kRel = 1.5e-3;
};

// In-plane erection: drift = -k (own gimbal angle), so with the body at rest the angle obeys
// a' = -k a and decays as exp(-k t). The decaying torque also leaves the gyroscopic lag
// J1 w1'/H on the other axis: w2 = -J1 w1'/H, whose integral is -J1 k a0/H (1 - exp(-k t)).
TYPED_TEST(GyroErrorSources, GivenInPlaneErectionOnPitchThenPitchGimbalDecaysExponentiallyAtRateK) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  const Matrix3<T> body = some_body_attitude<T>();
  for (const double a0 : {0.01, -0.01}) {
    GyroModelConfig<T> c = test_config<T>();
    const double k = 2.0;
    c.errors.pitch.in_plane_erection_1_s = T(k);
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(static_cast<T>(-k * a0), T(0)),
                                      Vector2<T>(static_cast<T>(a0), T(0)), body);
    const GyroStepInput<T> in = step_input<T>(static_cast<T>(Erection<T>::kDt), kSpinHz<T>, body);
    const int steps = static_cast<int>(1.5 / Erection<T>::kDt + 0.5);
    double worst = 0, a_025 = 0, a_125 = 0;
    for (int n = 1; n <= steps; ++n) {
      ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);
      const double t = n * Erection<T>::kDt, a = D(g.gimbal_pitch_rad());
      worst = std::max(worst, std::abs(a - a0 * std::exp(-k * t)));
      if (n == steps / 6) a_025 = a;
      if (n == 5 * steps / 6) a_125 = a;
    }
    EXPECT_LT(worst, Erection<T>::kRel * std::abs(a0)) << "a0 " << a0;
    EXPECT_NEAR(std::log(a_125 / a_025) / 1.0, -k, 2e-3 * k);
    const double h = D(momentum(c, kSpinHz<T>));
    const double lag = -2.25 * k * a0 / h * (1.0 - std::exp(-k * 1.5));
    EXPECT_NEAR(D(g.gimbal_yaw_rad()), lag, 0.05 * std::abs(lag) + Tol<T>::kAngle);
  }
}

TYPED_TEST(GyroErrorSources, GivenInPlaneErectionOnYawThenYawGimbalDecaysExponentiallyAtRateK) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  const Matrix3<T> body = some_body_attitude<T>();
  GyroModelConfig<T> c = test_config<T>();
  const double k = 3.0, a0 = 0.01;
  c.errors.yaw.in_plane_erection_1_s = T(k);
  GyroModel<T> g =
      uncaged_model<T>(c, Vector2<T>(T(0), static_cast<T>(-k * a0)), Vector2<T>(T(0), static_cast<T>(a0)), body);
  const double dt = Erection<T>::kDt;
  const GyroStepInput<T> in = step_input<T>(static_cast<T>(dt), kSpinHz<T>, body);
  const int steps = static_cast<int>(1.0 / dt + 0.5);
  double worst = 0;
  for (int n = 1; n <= steps; ++n) {
    ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);
    worst = std::max(worst, std::abs(D(g.gimbal_yaw_rad()) - a0 * std::exp(-k * n * dt)));
  }
  EXPECT_LT(worst, 1.5 * Erection<T>::kRel * a0);
  // The lag on pitch: J2 w2' - H w1 = 0 gives w1 = J2 w2'/H, integral +J2 k a0/H (1 - e^-kt).
  const double h = D(momentum(c, kSpinHz<T>));
  const double lag = 2.0 * k * a0 / h * (1.0 - std::exp(-k * 1.0));
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), lag, 0.05 * lag + Tol<T>::kAngle);
}

// Cross-plane erection: drift = -k (other axis' gimbal angle). A gyro yawed by y0 and turned
// about its own pitch axis keeps its azimuth y0 exactly and rises at -k y0: linear in t.
TYPED_TEST(GyroErrorSources, GivenCrossPlaneErectionOnPitchThenYawGimbalAngleDrivesPitchAtMinusKTimesIt) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  const double k = 0.5, y0 = 0.02;
  c.errors.pitch.cross_plane_erection_1_s = T(k);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(static_cast<T>(-k * y0), T(0)), Vector2<T>(T(0), T(y0)));
  const GyroStepInput<T> in = step_input<T>(T(1e-3));
  for (int n = 1; n <= 1000; ++n) ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), -k * y0 * 1.0, Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), y0, Tol<T>::kAngle);
}

// The same on yaw: a gyro pitched by p0 turned about its own yaw axis by psi has azimuth
// atan(tan(psi)/cos(p0)) and elevation asin(sin(p0) cos(psi)) ~ p0, so psi ~ -k p0 t.
TYPED_TEST(GyroErrorSources, GivenCrossPlaneErectionOnYawThenPitchGimbalAngleDrivesYawAtMinusKTimesIt) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  const double k = 0.5, p0 = 0.02;
  c.errors.yaw.cross_plane_erection_1_s = T(k);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0), static_cast<T>(-k * p0)), Vector2<T>(T(p0), T(0)));
  const GyroStepInput<T> in = step_input<T>(T(1e-3));
  for (int n = 1; n <= 1000; ++n) ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);
  const double psi = -k * p0 * 1.0;
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), std::atan(std::tan(psi) / std::cos(p0)), 1e-6 + Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), p0, 1e-5 + Tol<T>::kAngle);
}

// g-sensitive drift: the report's s * (a/g - sign(a)) beyond 1 g, zero below; lateral
// acceleration drifts pitch, normal acceleration drifts yaw. Gravity in ft/s^2 here.
TYPED_TEST(GyroErrorSources, GivenGSensitiveDriftThenDriftIsProportionalToAccelerationBeyondOneG) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  const double g0 = 32.1725, sp = 0.004, sy = 0.006;
  c.gravity = T(g0);
  c.errors.pitch.g_sensitive_drift_rad_s = T(sp);
  c.errors.yaw.g_sensitive_drift_rad_s = T(sy);
  struct Case {
    double lateral_g, normal_g;  // in g
    Vector2<double> expected;
  };
  const Case cases[] = {
      {0.0, 0.0, {0.0, 0.0}},
      {0.5, 0.0, {0.0, 0.0}},
      {-0.99, 0.9, {0.0, 0.0}},
      {1.0, -1.0, {0.0, 0.0}},
      {3.0, 0.0, {2.0 * sp, 0.0}},   // lateral: pitch only
      {-3.0, 0.0, {-2.0 * sp, 0.0}},
      {5.0, 0.0, {4.0 * sp, 0.0}},   // twice the excess of 3 g: twice the drift
      {0.0, 2.5, {0.0, 1.5 * sy}},   // normal: yaw only
      {0.0, -4.0, {0.0, -3.0 * sy}},
      {2.0, 2.0, {sp, sy}},
  };
  for (const Case& k : cases) {
    const Vector2<T> accel(static_cast<T>(k.lateral_g * g0), static_cast<T>(k.normal_g * g0));
    const Vector2<T> start = k.expected.template cast<T>();
    const Vector2<double> w = steady_rate_with<T>(c, start, slewing<T>(Vector2<T>::Zero()), accel);
    EXPECT_NEAR(w(0), k.expected(0), Tol<T>::kRate) << k.lateral_g << " g, " << k.normal_g << " g";
    EXPECT_NEAR(w(1), k.expected(1), Tol<T>::kRate) << k.lateral_g << " g, " << k.normal_g << " g";
  }
}

// Torquer cross-coupling: c_p of the yaw torquer command leaks into pitch, whatever the spin.
TYPED_TEST(GyroErrorSources, GivenTorquerCrossCouplingThenPureYawCommandDriftsPitchByCpTimesIt) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  for (const T spin : {kSpinHz<T>, T(40)}) {
    GyroModelConfig<T> c = test_config<T>();
    c.max_yaw_rate_rad_s = T(0.3);
    c.errors.pitch.torquer_cross_coupling = T(0.05);
    c.errors.yaw.torquer_cross_coupling = T(-0.04);
    struct Case {
      Vector2<T> cmd;
      Vector2<double> expected;
    };
    const Case cases[] = {
        {Vector2<T>(T(0), T(0.2)), {0.05 * 0.2, 0.2}},
        {Vector2<T>(T(0), T(-0.2)), {-0.05 * 0.2, -0.2}},
        {Vector2<T>(T(0), T(5.0)), {0.05 * 0.3, 0.3}},  // the limited command leaks
        {Vector2<T>(T(0.25), T(0)), {0.25, -0.04 * 0.25}},
    };
    for (const Case& k : cases) {
      const Vector2<double> w = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(k.cmd), Vector2<T>::Zero(), spin);
      EXPECT_NEAR(w(0), k.expected(0), Tol<T>::kRate) << "cmd " << k.cmd.transpose() << " spin " << D(spin);
      EXPECT_NEAR(w(1), k.expected(1), Tol<T>::kRate) << "cmd " << k.cmd.transpose() << " spin " << D(spin);
    }
    // In torque form: a pitch-axis torque T1 precesses yaw at T1/H and leaks c_p T1/H into pitch.
    const double h = D(momentum(c, spin));
    const Vector2<double> w =
        steady_rate_with<T>(c, Vector2<T>::Zero(), torquing<T>(Vector2<T>(T(50), T(0))), Vector2<T>::Zero(), spin);
    EXPECT_NEAR(w(0), 0.05 * 50.0 / h, Tol<T>::kRate);
    EXPECT_NEAR(w(1), 50.0 / h, Tol<T>::kRate);
  }
}

// Coulomb friction: a drift of constant size against the rate, none at rest, and a gimbal
// whose command is below the friction stays put (it is not pushed backwards).
TYPED_TEST(GyroErrorSources, GivenCoulombFrictionThenDriftOpposesTheRate) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.errors.pitch.coulomb_friction_rad_s = T(0.02);
  c.errors.yaw.coulomb_friction_rad_s = T(0.03);
  struct Case {
    Vector2<T> cmd;
    Vector2<double> expected;
  };
  const Case cases[] = {
      {Vector2<T>(T(0.1), T(0)), {0.08, 0.0}},
      {Vector2<T>(T(-0.1), T(0)), {-0.08, 0.0}},
      {Vector2<T>(T(0), T(0.2)), {0.0, 0.17}},
      {Vector2<T>(T(0), T(-0.2)), {0.0, -0.17}},
      {Vector2<T>(T(0.1), T(-0.2)), {0.08, -0.17}},
  };
  for (const Case& k : cases) {
    // Uncaged at the expected rate (a still axis exactly still) and from rest (nutating).
    for (const Vector2<T>& start : {Vector2<T>(k.expected.template cast<T>()), Vector2<T>(Vector2<T>::Zero())}) {
      const Vector2<double> w = steady_rate_with<T>(c, start, slewing<T>(k.cmd));
      EXPECT_NEAR(w(0), k.expected(0), Tol<T>::kRate) << "cmd " << k.cmd.transpose() << " from " << start.transpose();
      EXPECT_NEAR(w(1), k.expected(1), Tol<T>::kRate) << "cmd " << k.cmd.transpose() << " from " << start.transpose();
    }
  }
  // Commands within the friction: stuck.
  for (const Vector2<T>& cmd : {Vector2<T>(T(0.015), T(0)), Vector2<T>(T(-0.01), T(0.025)), Vector2<T>(T(0), T(-0.02))}) {
    const Vector2<double> w = steady_rate_with<T>(c, Vector2<T>::Zero(), slewing<T>(cmd));
    EXPECT_NEAR(w(0), 0.0, Tol<T>::kRate) << "cmd " << cmd.transpose();
    EXPECT_NEAR(w(1), 0.0, Tol<T>::kRate) << "cmd " << cmd.transpose();
  }
}

// Coulomb friction must not feed the nutation. A gyro slewed on one axis with the other
// axis still but for a rounding-level rate, or one that nutates, behaves exactly as the
// linear gyro under the same constant torque: its nutation is kept (f = 0) or damped (f > 0)
// as it would be without Coulomb friction. (Evaluated as -c sign(rate) at each step's start,
// as the listing does, the friction flips late on every swing: the frictionless gyro's
// nutation grows without bound and the report's gyro, f = 5, settles into a 2 rad/s limit
// cycle.)
TYPED_TEST(GyroErrorSources, GivenCoulombFrictionOnANutatingGyroThenTheNutationIsNotFed) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  const Vector2<T> cmd(T(0.1), T(0));
  for (const T f : {T(0), T(5)}) {
    GyroModelConfig<T> c = test_config<T>();
    c.friction = f;
    c.errors.pitch.coulomb_friction_rad_s = T(0.02);
    c.errors.yaw.coulomb_friction_rad_s = T(0.03);
    GyroModelConfig<T> without = c;
    without.errors = {};
    for (const Vector2<T>& start : {Vector2<T>(T(0.08), T(1e-9)), Vector2<T>(T(0.08), T(0.15))}) {
      GyroModel<T> g = uncaged_model<T>(c, start);
      GyroModel<T> twin = uncaged_model<T>(without, start);  // torqued with g's torque
      const GyroStepInput<T> in = step_input<T>(T(3.5e-4));  // 20 steps a nutation period
      double largest_rate = 0;
      bool same = true;
      for (int n = 0; n < 20000; ++n) {
        ASSERT_EQ(g.step_slew(in, cmd), Status::kOk);
        ASSERT_EQ(twin.step_torque(in, g.applied_torque()), Status::kOk);
        same = same && g.rate_rad_s() == twin.rate_rad_s() && g.applied_torque() == twin.applied_torque();
        largest_rate = std::max(largest_rate, D(g.rate_rad_s().norm()));
      }
      EXPECT_TRUE(same) << "f " << D(f) << " start " << start.transpose();
      // 0.08 of precession plus at most the initial 0.15 of nutation (the J1/J2 ellipse).
      EXPECT_LT(largest_rate, 0.08 + 0.15 * 1.07) << "f " << D(f) << " start " << start.transpose();
      if (f > T(0)) {  // 7 s, alpha t = 16: the nutation is gone, as it is without Coulomb
        EXPECT_LT(D(g.nutation_amplitude_rad().maxCoeff()), 1e-9);
      }
    }
  }
}

TYPED_TEST(GyroErrorSources, GivenCoulombFrictionAndGyroAtRestThenItDoesNotMove) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.errors.pitch.coulomb_friction_rad_s = T(0.02);
  c.errors.yaw.coulomb_friction_rad_s = T(0.03);
  const Matrix3<T> body = some_body_attitude<T>();
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero(), Vector2<T>(T(0.05), T(-0.02)), body);
  const double pitch0 = D(g.gimbal_pitch_rad()), yaw0 = D(g.gimbal_yaw_rad());
  const GyroStepInput<T> in = step_input<T>(T(1e-3), kSpinHz<T>, body);
  for (int n = 0; n < 1000; ++n) ASSERT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kOk);
  EXPECT_EQ(g.rate_rad_s()(0), T(0));
  EXPECT_EQ(g.rate_rad_s()(1), T(0));
  EXPECT_EQ(g.applied_torque()(0), T(0));
  EXPECT_EQ(g.applied_torque()(1), T(0));
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), pitch0, Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), yaw0, Tol<T>::kAngle);
}

// ---------------------------------------------------------------------------------------
// Gimbal limits.

template <typename T>
class GyroGimbalLimits : public ::testing::Test {};
TYPED_TEST_SUITE(GyroGimbalLimits, Scalars);

// The body turns about its own axis u = (0, cos phi, sin phi), away from a gyro held
// inertially: after angle a the spin axis in body axes is (cos a, -sin a sin phi,
// sin a cos phi), a from body x. The flag is raised exactly while a exceeds the cone, the
// step completes all the same, and it clears when the body comes back.
TYPED_TEST(GyroGimbalLimits, GivenBodyTurningAwayFromInertiallyHeldGyroThenConeFlagRaisedOnlyOutsideTheCone) {
  GYRO_VERIFIES("MODEL-4", "EST-5");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.gimbal_cone_limit_rad = T(0.3);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
  const double phi = 0.6, rate = 0.5, dt = 0.01, cone = 0.3;
  const Vector3<T> u(T(0), static_cast<T>(std::cos(phi)), static_cast<T>(std::sin(phi)));
  GyroStepInput<T> in = step_input<T>(static_cast<T>(dt));
  int flagged = 0;
  for (int n = 1; n <= 200; ++n) {
    const double a = rate * dt * (n <= 100 ? n : 200 - n);  // out to 0.5 rad and back
    in.R_earth_to_body = Eigen::AngleAxis<T>(static_cast<T>(a), u).toRotationMatrix().transpose();
    ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk) << "flagged steps complete";
    const Vector2<double> expected =
        gimbal_of(Vector3<double>(std::cos(a), -std::sin(a) * std::sin(phi), std::sin(a) * std::cos(phi)));
    EXPECT_NEAR(D(g.gimbal_pitch_rad()), expected(0), 20 * Tol<T>::kAngle) << "a " << a;
    EXPECT_NEAR(D(g.gimbal_yaw_rad()), expected(1), 20 * Tol<T>::kAngle) << "a " << a;
    EXPECT_NEAR(D(g.gimbal_cone_rad()), a, kIsFloat<T> ? 1e-3 : 1e-7) << "a " << a;
    if (std::abs(a - cone) > 1e-6) {
      EXPECT_EQ(g.gimbal_limit_exceeded(), a > cone) << "a " << a;
      flagged += g.gimbal_limit_exceeded() ? 1 : 0;
    }
  }
  EXPECT_EQ(flagged, 2 * 40 - 1);  // a = 0.305 .. 0.5 out and 0.495 .. 0.305 back
  EXPECT_FALSE(g.gimbal_limit_exceeded());
  EXPECT_LT(D(g.gimbal_cone_rad()), 1e-3);
}

// Per-axis limits compared as angles with |angle| (the listing compared an angle with a
// cosine, and only positive angles), pitch against the pitch limit, yaw against the yaw limit.
TYPED_TEST(GyroGimbalLimits, GivenPerAxisLimitsThenEachAxisIsComparedAsAnAngleWithItsOwnLimit) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.gimbal_cone_limit_rad = T(1.2);
  c.pitch_gimbal_limit_rad = T(0.1);
  c.yaw_gimbal_limit_rad = T(0.3);
  const Matrix3<T> body = some_body_attitude<T>();
  struct Case {
    Vector2<T> offset;
    bool flag;
  };
  const Case cases[] = {
      {Vector2<T>(T(0.08), T(0)), false},  {Vector2<T>(T(0.12), T(0)), true},
      {Vector2<T>(T(-0.12), T(0)), true},  {Vector2<T>(T(-0.08), T(0)), false},
      {Vector2<T>(T(0), T(0.2)), false},   {Vector2<T>(T(0), T(-0.28)), false},
      {Vector2<T>(T(0), T(0.32)), true},   {Vector2<T>(T(0), T(-0.32)), true},
      {Vector2<T>(T(0.09), T(0.29)), false}, {Vector2<T>(T(0.11), T(0.29)), true},
  };
  for (const Case& k : cases) {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero(), k.offset, body);
    EXPECT_EQ(g.gimbal_limit_exceeded(), k.flag) << "at uncaging, offset " << k.offset.transpose();
    ASSERT_EQ(g.step_torque(step_input<T>(T(1e-3), kSpinHz<T>, body), Vector2<T>::Zero()), Status::kOk);
    EXPECT_EQ(g.gimbal_limit_exceeded(), k.flag) << "after a step, offset " << k.offset.transpose();
  }
}

TYPED_TEST(GyroGimbalLimits, GivenPerAxisLimitsZeroThenOnlyTheConeCounts) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.gimbal_cone_limit_rad = T(1.2);
  struct Case {
    Vector2<T> offset;
    bool flag;
  };
  // An offset is a rotation vector (0, pitch, yaw): the cone angle is its length.
  const Case cases[] = {
      {Vector2<T>(T(0.9), T(0)), false},   {Vector2<T>(T(0), T(-1.1)), false},
      {Vector2<T>(T(0.8), T(0.8)), false}, {Vector2<T>(T(0), T(1.25)), true},
      {Vector2<T>(T(-1.22), T(0)), true},  {Vector2<T>(T(0.85), T(-0.85)), true},
  };
  for (const Case& k : cases) {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero(), k.offset);
    ASSERT_EQ(g.step_torque(step_input<T>(T(1e-3)), Vector2<T>::Zero()), Status::kOk);
    EXPECT_EQ(g.gimbal_limit_exceeded(), k.flag) << "offset " << k.offset.transpose();
    EXPECT_NEAR(D(g.gimbal_cone_rad()), D(k.offset.norm()), 1e-4);
  }
}

// ---------------------------------------------------------------------------------------
// Small-angle flag.

template <typename T>
class GyroSmallAngle : public ::testing::Test {};
TYPED_TEST_SUITE(GyroSmallAngle, Scalars);

// No nutation (uncaged at the commanded rate): the step's angle is rate * dt, and the flag
// follows |theta| or |psi| against the limit, each axis on its own.
TYPED_TEST(GyroSmallAngle, GivenStepTooLongForTheRatesThenFlagRaised) {
  GYRO_VERIFIES("MODEL-4", "EST-5");
  using T = TypeParam;
  const GyroModelConfig<T> c = test_config<T>();
  struct Case {
    Vector2<T> rate;
    T dt;
    bool flag;
  };
  const Case cases[] = {
      {Vector2<T>(T(0.1), T(0)), T(0.09), false},     {Vector2<T>(T(0.1), T(0)), T(0.11), true},
      {Vector2<T>(T(0), T(-0.1)), T(0.09), false},    {Vector2<T>(T(0), T(-0.1)), T(0.11), true},
      {Vector2<T>(T(-0.08), T(0.08)), T(0.1), false},  // |(theta, psi)| = 0.0113, each 0.008
      {Vector2<T>(T(0.5), T(0.5)), T(1e-3), false},
  };
  for (const Case& k : cases) {
    GyroModel<T> g = uncaged_model<T>(c, k.rate);
    ASSERT_EQ(g.step_slew(step_input<T>(k.dt), k.rate), Status::kOk);
    EXPECT_NEAR(D(g.isaf_angle_rad()(0)), D(k.rate(0) * k.dt), 10 * Tol<T>::kAngle);
    EXPECT_NEAR(D(g.isaf_angle_rad()(1)), D(k.rate(1) * k.dt), 10 * Tol<T>::kAngle);
    EXPECT_LT(D(g.nutation_amplitude_rad().maxCoeff()), 1e-9);
    EXPECT_EQ(g.small_angle_exceeded(), k.flag) << "rate " << k.rate.transpose() << " dt " << D(k.dt);
    EXPECT_FALSE(g.gimbal_limit_exceeded());
  }
  // The limit is the configured one.
  GyroModelConfig<T> loose = c;
  loose.small_angle_limit_rad = T(0.05);
  GyroModel<T> g = uncaged_model<T>(loose, Vector2<T>(T(0.1), T(0)));
  ASSERT_EQ(g.step_slew(step_input<T>(T(0.2)), Vector2<T>(T(0.1), T(0))), Status::kOk);
  EXPECT_FALSE(g.small_angle_exceeded());
}

// J1 = J2 = J, f = 0, no torque: the rate vector turns at beta = H/J, and the angles swing
// on a circle of radius |w0|/beta. Flag when that exceeds the limit, with tiny steps.
TYPED_TEST(GyroSmallAngle, GivenNutationAmplitudeAboveTheLimitThenFlagRaised) {
  GYRO_VERIFIES("MODEL-4", "EST-5");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.pitch_inertia = T(2);
  c.yaw_inertia = T(2);
  const double beta = 10.0;                           // rad/s
  const double spin_hz = beta * 2.0 / (2.0 * kPi<double> * 3.0);  // H = beta J
  for (const double w0 : {0.15, 0.05}) {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(static_cast<T>(w0), T(0)));
    const GyroStepInput<T> in = step_input<T>(T(1e-4), static_cast<T>(spin_hz));
    double lo = 0, hi = 0;
    const int per_period = static_cast<int>(2.0 * kPi<double> / beta / 1e-4) + 1;
    for (int n = 0; n < per_period; ++n) {
      ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
      EXPECT_NEAR(D(g.nutation_amplitude_rad()(0)), w0 / beta, 20 * Tol<T>::kRel * w0 / beta);
      EXPECT_NEAR(D(g.nutation_amplitude_rad()(1)), w0 / beta, 20 * Tol<T>::kRel * w0 / beta);
      EXPECT_EQ(g.small_angle_exceeded(), w0 / beta > 0.01) << "w0 " << w0 << " step " << n;
      lo = std::min(lo, D(g.gimbal_pitch_rad()));
      hi = std::max(hi, D(g.gimbal_pitch_rad()));
    }
    // The pitch gimbal swings +-|w0|/beta (the simulated excursion, not the formula).
    EXPECT_NEAR(hi, w0 / beta, 2e-3 * w0 / beta);
    EXPECT_NEAR(lo, -w0 / beta, 2e-3 * w0 / beta);
  }
}

TEST(GyroSmallAngleReportSample, GivenReportSampleThenNoStepRaisesTheFlag) {
  GYRO_VERIFIES("MODEL-1");
  using Report = ReportSample<double>;
  int steps = 0, raised = 0;
  double largest_amplitude = 0, largest_angle = 0;
  const SampleRunSummary sum = run_report_sample<double>(
      Report::initg_step(), Report::kSteps, [&](int, double, const GyroModel<double>& g, const Matrix3<double>&) {
        ++steps;
        raised += g.small_angle_exceeded() ? 1 : 0;
        largest_amplitude = std::max(largest_amplitude, g.nutation_amplitude_rad().maxCoeff());
        largest_angle = std::max(largest_angle, g.isaf_angle_rad().cwiseAbs().maxCoeff());
      });
  EXPECT_EQ(sum.status, Status::kOk);
  EXPECT_EQ(steps, 801);
  EXPECT_EQ(raised, 0);
  EXPECT_LT(largest_amplitude, 0.01);
  EXPECT_LT(largest_angle, 0.01);
  EXPECT_GT(largest_amplitude, 1e-4) << "the sample does nutate";
}

// ---------------------------------------------------------------------------------------
// An error source's torque beyond the scalar type.

// A drift torque (H times the drift) that is not representable: the step is refused and the
// model keeps its state, rather than carrying an infinite torque into it. configure() bounds
// the drifts; the g-sensitive one still grows with the step's acceleration.
TEST(GyroModelErrorSources, ADriftTorqueBeyondDoubleIsRefused) {
  GYRO_VERIFIES("MODEL-6");
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

// Without spin and friction there is no steady precession for the Coulomb friction to oppose:
// the step takes none (no 0/0) and the rotor keeps its rate.
TYPED_TEST(GyroErrorSources, GivenCoulombFrictionWithoutSpinOrFrictionThenNoDrift) {
  GYRO_VERIFIES("MODEL-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();  // f = 0
  c.errors.pitch.coulomb_friction_rad_s = T(0.02);
  c.errors.yaw.coulomb_friction_rad_s = T(0.03);
  GyroModel<T> g;
  ASSERT_TRUE(g.configure(c).ok());
  ASSERT_EQ(g.uncage(Matrix3<T>::Identity(), Vector2<T>(T(0.01), T(-0.02))), Status::kOk);
  const Vector2<T> rate0 = g.rate_rad_s();
  ASSERT_EQ(g.step_torque(step_input<T>(T(1e-2), T(0)), Vector2<T>::Zero()), Status::kOk);
  EXPECT_NEAR(g.rate_rad_s()(0), rate0(0), 1e-6);
  EXPECT_NEAR(g.rate_rad_s()(1), rate0(1), 1e-6);
  EXPECT_GT(rate0.norm(), T(0.01));
}

}  // namespace
}  // namespace gyro
