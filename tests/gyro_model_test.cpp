// GyroModel against physics worked out here, independently of the model's own formulas.
//
// The expectations come from the gyro's behaviour, not from the implementation:
//   - a frictionless gyro (f = 0) under a constant torque precesses at w_ss = (-T2/H, T1/H)
//     plus a pure sinusoid at beta = H/sqrt(J1 J2), so the mean of the rates over whole
//     nutation periods, sampled 20 times a period, is w_ss exactly;
//   - a rotation about a fixed axis moves the spin axis along a cone (Rodrigues' formula);
//   - with J1 = J2 and no torque or friction the rate vector keeps its length and turns at
//     H/J (whatever H(t) does), and without spin the axes decouple into exponentials.
// And its transition cache: a step of a new dt is bit for bit a fresh model's step of that dt.
#include "gyro/report_sample.hpp"
#include "support/gyro_model_support.hpp"  // gtest, Eigen, GyroModel and the standard headers
#include "support/requirements.hpp"

namespace gyro {
namespace {

using namespace model_test;  // NOLINT(google-build-using-namespace): the shared fixtures

// ---------------------------------------------------------------------------------------
// Orthonormality of the attitude over long runs.

// A gyro that nutates without end (f = 0, uncaged at rates far from its command), slewed by
// a command that reverses every 5 s, under a body turning about two axes. Returns the
// orthonormality error of R_earth_to_gyro() at the checkpoints and its largest sample.
template <typename T>
std::vector<double> orthonormality_run(long steps, const std::vector<long>& checkpoints, double& worst) {
  GyroModelConfig<T> c = test_config<T>();
  c.max_pitch_rate_rad_s = T(0.3);
  c.max_yaw_rate_rad_s = T(0.3);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.5), T(0.4)));
  const double dt = 1e-3;
  GyroStepInput<T> in = step_input<T>(static_cast<T>(dt));
  const Vector2<T> cmd_a(T(0.2), T(-0.1)), cmd_b(T(-0.15), T(0.25));
  // The body turns at constant body rates (0.17 pitch, 0.31 yaw rad/s), R <- turn * R as the
  // report's driver does, set exactly to turn^k = (axis, k * angle) every 64 steps.
  const Matrix3<T> turn = frame_rotation_z<T>(static_cast<T>(0.31 * dt)) * frame_rotation_y<T>(static_cast<T>(0.17 * dt));
  const Eigen::AngleAxis<double> turn_aa(
      Matrix3<double>(frame_rotation_z<double>(0.31 * dt) * frame_rotation_y<double>(0.17 * dt)));
  std::vector<double> out;
  std::size_t next = 0;
  worst = 0;
  for (long k = 1; k <= steps; ++k) {
    if (k % 64 == 1) {
      const double angle = std::fmod(static_cast<double>(k) * turn_aa.angle(), 2.0 * kPi<double>);
      in.R_earth_to_body = Eigen::AngleAxis<double>(angle, turn_aa.axis()).toRotationMatrix().template cast<T>();
    } else {
      in.R_earth_to_body = (turn * in.R_earth_to_body).eval();
    }
    const Status st = g.step_slew(in, ((k / 5000) % 2 == 0) ? cmd_a : cmd_b);
    if (st != Status::kOk) {
      ADD_FAILURE() << "step " << k << ": " << to_string(st);
      break;
    }
    if (k % 97 == 0) worst = std::max(worst, D(orthonormality_error(g.R_earth_to_gyro())));
    if (next < checkpoints.size() && k == checkpoints[next]) {
      out.push_back(D(orthonormality_error(g.R_earth_to_gyro())));
      ++next;
    }
  }
  EXPECT_GT(D(g.nutation_amplitude_rad().maxCoeff()), 1e-5) << "the gyro still nutates at the end";
  return out;
}

TEST(GyroModelOrthonormality, GivenNutatingSlewingGyroUnderTurningBodyWhen1e7DoubleStepsThenAttitudeStaysOrthonormalTo1e12) {
  GYRO_VERIFIES("MODEL-3");
#if defined(GYRO_TEST_UNDER_EMULATION)
  // Under qemu-user 1e7 steps take minutes; the host runs the full 1e7.
  const std::vector<long> at = {1000, 100000, 1000000};
#else
  const std::vector<long> at = {1000, 100000, 1000000, 10000000};
#endif
  double worst = 0;
  const std::vector<double> err = orthonormality_run<double>(at.back(), at, worst);
  ASSERT_EQ(err.size(), at.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    std::printf("double: orthonormality error of R_earth_to_gyro after %8ld steps: %.3g\n", at[i], err[i]);
    EXPECT_LT(err[i], 1e-12) << "after " << at[i] << " steps";
  }
  std::printf("double: largest sampled orthonormality error over 1e7 steps: %.3g\n", worst);
  EXPECT_LT(worst, 1e-12);
  RecordProperty("orthonormality_error_1e7_steps", std::to_string(err.back()));
}

TEST(GyroModelOrthonormality, GivenSameRunInFloatWhen1e6StepsThenAttitudeStaysOrthonormalTo1e5) {
  GYRO_VERIFIES("MODEL-3", "RULE-8");
  const std::vector<long> at = {1000, 100000, 1000000};
  double worst = 0;
  const std::vector<double> err = orthonormality_run<float>(1000000, at, worst);
  ASSERT_EQ(err.size(), at.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    std::printf("float:  orthonormality error of R_earth_to_gyro after %8ld steps: %.3g\n", at[i], err[i]);
    EXPECT_LT(err[i], 1e-5) << "after " << at[i] << " steps";
  }
  std::printf("float:  largest sampled orthonormality error over 1e6 steps: %.3g\n", worst);
  EXPECT_LT(worst, 1e-5);
}

// ---------------------------------------------------------------------------------------
// Slew-rate limits, each on its own axis.

template <typename T>
class GyroSlewLimits : public ::testing::Test {};
TYPED_TEST_SUITE(GyroSlewLimits, Scalars);

TYPED_TEST(GyroSlewLimits, GivenDifferentPitchAndYawLimitsWhenCommandedThenSteadyPrecessionIsTheCommandLimitedPerAxis) {
  GYRO_VERIFIES("EXACT-3");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.max_pitch_rate_rad_s = T(0.1);
  c.max_yaw_rate_rad_s = T(0.3);
  struct Case {
    Vector2<T> cmd;
    Vector2<double> expected;
  };
  const Case cases[] = {
      {Vector2<T>(T(1.0), T(-1.0)), Vector2<double>(0.1, -0.3)},
      {Vector2<T>(T(-0.5), T(0.5)), Vector2<double>(-0.1, 0.3)},
      {Vector2<T>(T(0.05), T(-0.2)), Vector2<double>(0.05, -0.2)},  // within both: unchanged
      // Pitch over its limit, yaw under its own but over the pitch limit: paired crosswise
      // (the listing) this would give (0.2, 0.1).
      {Vector2<T>(T(0.2), T(0.2)), Vector2<double>(0.1, 0.2)},
      {Vector2<T>(T(0.05), T(0.25)), Vector2<double>(0.05, 0.25)},
  };
  for (const Case& k : cases) {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
    const Vector2<double> mean = mean_rate_over_nutation_periods<T>(g, step_input<T>(T(0)), 50, slewing<T>(k.cmd));
    EXPECT_NEAR(mean(0), k.expected(0), Tol<T>::kRate) << "cmd " << k.cmd.transpose();
    EXPECT_NEAR(mean(1), k.expected(1), Tol<T>::kRate) << "cmd " << k.cmd.transpose();
  }
}

// Uncaged at the limited command, the gyro has nothing to nutate about: it turns about the
// fixed axis (0, w1, w2) of its own frame at |w|, and the spin axis follows Rodrigues' cone.
TYPED_TEST(GyroSlewLimits, GivenGyroUncagedAtLimitedCommandWhenSlewedThenRatesStayAndSpinAxisTurnsAboutFixedAxis) {
  GYRO_VERIFIES("MODEL-3");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.max_pitch_rate_rad_s = T(0.1);
  c.max_yaw_rate_rad_s = T(0.3);
  const Vector2<T> limited(T(0.1), T(-0.3));
  GyroModel<T> g = uncaged_model<T>(c, limited);
  const GyroStepInput<T> in = step_input<T>(T(1e-3));
  const int n = 200;
  double worst_rate = 0;
  for (int k = 0; k < n; ++k) {
    ASSERT_EQ(g.step_slew(in, Vector2<T>(T(2), T(-2))), Status::kOk);
    worst_rate = std::max(worst_rate, (g.rate_rad_s() - limited).cwiseAbs().template cast<double>().maxCoeff());
  }
  EXPECT_LT(worst_rate, Tol<T>::kRate);
  const double w = std::hypot(0.1, 0.3);
  const Vector2<double> expected = gimbal_of(spin_after_rotation(0.1 / w, -0.3 / w, w * 1e-3 * n));
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), expected(0), Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), expected(1), Tol<T>::kAngle);
  EXPECT_GT(D(g.gimbal_pitch_rad()), 0.019);  // nose-up and to the left, as commanded
  EXPECT_LT(D(g.gimbal_yaw_rad()), -0.059);
}

// The gyroscope law itself: a torque about the pitch axis precesses the spin axis in yaw,
// to the right for a positive torque (dH/dt = T with H along +x), at T1/H; a torque about
// the yaw axis precesses it in pitch at -T2/H.
TYPED_TEST(GyroSlewLimits, GivenTorqueAboutOneAxisThenSpinAxisPrecessesAboutTheOtherAtTorqueOverH) {
  GYRO_VERIFIES("PORT-3", "EXACT-3");
  using T = TypeParam;
  const GyroModelConfig<T> c = test_config<T>();
  const double h = D(momentum(c, kSpinHz<T>));
  {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
    const Vector2<double> mean =
        mean_rate_over_nutation_periods<T>(g, step_input<T>(T(0)), 50, torquing<T>(Vector2<T>(T(100), T(0))));
    EXPECT_NEAR(mean(0), 0.0, Tol<T>::kRate);
    EXPECT_NEAR(mean(1), 100.0 / h, Tol<T>::kRate);
    EXPECT_GT(D(g.gimbal_yaw_rad()), 0.0) << "to the right";
  }
  {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
    const Vector2<double> mean =
        mean_rate_over_nutation_periods<T>(g, step_input<T>(T(0)), 50, torquing<T>(Vector2<T>(T(0), T(-100))));
    EXPECT_NEAR(mean(0), 100.0 / h, Tol<T>::kRate);
    EXPECT_NEAR(mean(1), 0.0, Tol<T>::kRate);
    EXPECT_GT(D(g.gimbal_pitch_rad()), 0.0) << "nose-up";
  }
}

// ---------------------------------------------------------------------------------------
// Uncaging.

template <typename T>
class GyroUncage : public ::testing::Test {};
TYPED_TEST_SUITE(GyroUncage, Scalars);

TYPED_TEST(GyroUncage, GivenOffsetThenGimbalAnglesEqualItWithPositivePitchNoseUpAndPositiveYawRight) {
  GYRO_VERIFIES("MODEL-3", "PORT-3");
  using T = TypeParam;
  const GyroModelConfig<T> c = test_config<T>();
  const Matrix3<T> body = some_body_attitude<T>();
  const Vector2<T> rates(T(0.3), T(-0.2));
  struct Case {
    Vector2<T> offset;
    double tol;
  };
  const Case cases[] = {
      {Vector2<T>(T(0.1), T(0)), Tol<T>::kAngle},  {Vector2<T>(T(-0.2), T(0)), Tol<T>::kAngle},
      {Vector2<T>(T(0), T(0.1)), Tol<T>::kAngle},  {Vector2<T>(T(0), T(-0.25)), Tol<T>::kAngle},
      {Vector2<T>(T(0), T(0)), Tol<T>::kAngle},
      // Both axes: equal to third order, |offset|^3/3 = 4e-13 here.
      {Vector2<T>(T(1e-4), T(-5e-5)), kIsFloat<T> ? Tol<T>::kAngle : 1e-12},
  };
  for (const Case& k : cases) {
    GyroModel<T> g = uncaged_model<T>(c, rates, k.offset, body);
    EXPECT_NEAR(D(g.gimbal_pitch_rad()), D(k.offset(0)), k.tol) << "offset " << k.offset.transpose();
    EXPECT_NEAR(D(g.gimbal_yaw_rad()), D(k.offset(1)), k.tol) << "offset " << k.offset.transpose();
    EXPECT_EQ(g.rate_rad_s(), rates);
    EXPECT_EQ(g.isaf_angle_rad(), Vector2<T>::Zero());
    // The sign convention, straight from the spin axis in body axes (x fwd, y right, z down).
    const Vector3<T> s = body * (g.attitude_gyro_to_earth() * Vector3<T>::UnitX());
    if (k.offset(0) > T(0)) {
      EXPECT_LT(D(s(2)), 0.0) << "nose-up is -z";
    }
    if (k.offset(0) < T(0)) {
      EXPECT_GT(D(s(2)), 0.0);
    }
    if (k.offset(1) > T(0)) {
      EXPECT_GT(D(s(1)), 0.0) << "right is +y";
    }
    if (k.offset(1) < T(0)) {
      EXPECT_LT(D(s(1)), 0.0);
    }
    EXPECT_GT(D(s(0)), 0.9);
  }
}

// A large two-axis offset is the rotation vector (0, pitch, yaw) applied to the body's axes.
TYPED_TEST(GyroUncage, GivenLargeTwoAxisOffsetThenSpinAxisIsTheOffsetRotationVectorApplied) {
  GYRO_VERIFIES("MODEL-3");
  using T = TypeParam;
  const double p = 0.2, y = 0.3, n = std::hypot(p, y);
  GyroModel<T> g = uncaged_model<T>(test_config<T>(), Vector2<T>::Zero(), Vector2<T>(T(p), T(y)),
                                    some_body_attitude<T>());
  const Vector2<double> expected = gimbal_of(spin_after_rotation(p / n, y / n, n));
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), expected(0), Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), expected(1), Tol<T>::kAngle);
  EXPECT_GT(std::abs(expected(1) - y), 1e-3) << "and not the offset itself";
}

TYPED_TEST(GyroUncage, GivenNoTorqueNoFrictionAndBodyAtRestThenGyroKeepsItsAttitude) {
  GYRO_VERIFIES("MODEL-3");
  using T = TypeParam;
  const Matrix3<T> body = some_body_attitude<T>();
  GyroModel<T> g = uncaged_model<T>(test_config<T>(), Vector2<T>::Zero(), Vector2<T>(T(0.05), T(-0.03)), body);
  const Quaternion<T> q0 = g.attitude_gyro_to_earth();
  const T pitch0 = g.gimbal_pitch_rad(), yaw0 = g.gimbal_yaw_rad();
  const GyroStepInput<T> in = step_input<T>(T(1e-3), kSpinHz<T>, body);
  for (int n = 0; n < 10000; ++n) ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
  const double eps = D(std::numeric_limits<T>::epsilon());
  EXPECT_LT(D((g.attitude_gyro_to_earth().coeffs() - q0.coeffs()).cwiseAbs().maxCoeff()), 4 * eps);
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), D(pitch0), 8 * eps);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), D(yaw0), 8 * eps);
  EXPECT_EQ(g.rate_rad_s(), Vector2<T>::Zero());
  EXPECT_EQ(g.flags(), 0u);
}

// The same gyro under a body that turns: it stays put in inertial space.
TYPED_TEST(GyroUncage, GivenNoTorqueNoFrictionAndTurningBodyThenSpinAxisStaysFixedInEarthAxes) {
  GYRO_VERIFIES("MODEL-3");
  using T = TypeParam;
  const Matrix3<T> body0 = some_body_attitude<T>();
  GyroModel<T> g = uncaged_model<T>(test_config<T>(), Vector2<T>::Zero(), Vector2<T>(T(0.05), T(-0.03)), body0);
  const Vector3<T> s0 = g.attitude_gyro_to_earth() * Vector3<T>::UnitX();
  GyroStepInput<T> in = step_input<T>(T(1e-3));
  for (int n = 1; n <= 1000; ++n) {
    in.R_earth_to_body = frame_rotation_y<T>(static_cast<T>(1e-4 * n)) * frame_rotation_z<T>(static_cast<T>(-2e-4 * n)) * body0;
    ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
  }
  const Vector3<T> s = g.attitude_gyro_to_earth() * Vector3<T>::UnitX();
  EXPECT_LT(D((s - s0).cwiseAbs().maxCoeff()), 8 * D(std::numeric_limits<T>::epsilon()));
  // Read in the turned body: the body pitched up 0.1 rad and yawed left 0.2 rad, so the
  // gyro is now lower and further right by about as much.
  const Vector2<double> expected = gimbal_of((in.R_earth_to_body * s).template cast<double>());
  EXPECT_NEAR(D(g.gimbal_pitch_rad()), expected(0), Tol<T>::kAngle);
  EXPECT_NEAR(D(g.gimbal_yaw_rad()), expected(1), Tol<T>::kAngle);
  EXPECT_LT(D(g.gimbal_pitch_rad()), -0.02);
  EXPECT_GT(D(g.gimbal_yaw_rad()), 0.12);
}

// ---------------------------------------------------------------------------------------
// Spin-down.

template <typename T>
class GyroSpinDown : public ::testing::Test {};
TYPED_TEST_SUITE(GyroSpinDown, Scalars);

// J1 = J2 = J, f = 0, no torque: J w' = H(t) (-w2, w1), so the rate vector keeps its length
// and turns with phase Phi(t) = (2 pi J0/J) * integral of spin_hz. Spin from 100 Hz down to
// 20 Hz linearly over 2 s; the zero crossings of w1 in each window follow Phi.
TYPED_TEST(GyroSpinDown, GivenSpinVaryingEveryStepThenNutationFrequencyFollowsH) {
  GYRO_VERIFIES("EXACT-3");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.pitch_inertia = T(2);
  c.yaw_inertia = T(2);
  const double j = 2.0, j0 = 3.0, s0 = 100.0, s1 = 20.0, duration = 2.0, dt = 1e-4;
  const int steps = static_cast<int>(duration / dt + 0.5);
  const double w0 = 0.05;
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(static_cast<T>(w0), T(0)));
  const auto spin_at = [&](double t) { return s0 + (s1 - s0) * t / duration; };
  const auto phase_at = [&](double t) {
    return 2.0 * kPi<double> * j0 / j * (s0 * t + (s1 - s0) * t * t / (2.0 * duration));
  };
  GyroStepInput<T> in = step_input<T>(static_cast<T>(dt));
  const int window = 2000;  // 0.2 s
  int crossings = 0;
  double prev = w0, worst_norm = 0;
  std::vector<double> crossing_times;
  for (int n = 1; n <= steps; ++n) {
    in.spin_hz = static_cast<T>(spin_at((n - 0.5) * dt));  // the step's mean spin
    ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
    const double w1 = D(g.rate_rad_s()(0));
    worst_norm = std::max(worst_norm, std::abs(D(g.rate_rad_s().norm()) - w0));
    if ((w1 < 0) != (prev < 0)) {
      ++crossings;
      crossing_times.push_back((n - 1) * dt + dt * prev / (prev - w1));
    }
    prev = w1;
    if (n % window == 0) {
      const double t_b = n * dt, t_a = t_b - window * dt;
      const double expected = (phase_at(t_b) - phase_at(t_a)) / kPi<double>;
      EXPECT_NEAR(crossings, expected, 1.0) << "window ending at " << t_b << " s, spin " << spin_at(t_b);
      // The frequency from the crossing times, against H(t_mid)/(2 pi J).
      if (crossing_times.size() > 4) {
        const double hz = static_cast<double>(crossing_times.size() - 1) /
                          (2.0 * (crossing_times.back() - crossing_times.front()));
        const double expected_hz = spin_at(0.5 * (t_a + t_b)) * j0 / j;
        EXPECT_NEAR(hz, expected_hz, 0.02 * expected_hz) << "window ending at " << t_b << " s";
      }
      crossings = 0;
      crossing_times.clear();
    }
  }
  EXPECT_LT(worst_norm, kIsFloat<T> ? 1e-5 : 1e-12) << "|w| is conserved (float: 2e4 steps of rounding)";
}

// No spin: the axes decouple, J_i w_i' = -f w_i + T_i, pure exponentials toward T_i/f.
TYPED_TEST(GyroSpinDown, GivenZeroSpinWithFrictionThenEachAxisJustDamps) {
  GYRO_VERIFIES("EXACT-1");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.friction = T(5);
  const double f = 5.0, j1 = 2.25, j2 = 2.0;
  {
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.1), T(-0.2)));
    const GyroStepInput<T> in = step_input<T>(T(1e-2), T(0));
    for (int n = 1; n <= 300; ++n) {
      ASSERT_EQ(g.step_slew(in, Vector2<T>(T(0.5), T(0.5))), Status::kOk) << "no spin: the torquer has no effect";
      const double t = n * 1e-2;
      EXPECT_NEAR(D(g.rate_rad_s()(0)), 0.1 * std::exp(-f * t / j1), Tol<T>::kRel * 0.1);
      EXPECT_NEAR(D(g.rate_rad_s()(1)), -0.2 * std::exp(-f * t / j2), Tol<T>::kRel * 0.2);
      EXPECT_EQ(g.applied_torque()(0), T(0));
      EXPECT_EQ(g.applied_torque()(1), T(0));
    }
  }
  {  // one axis only: the gyro turns about its pitch axis by w0 J1/f (1 - exp(-f t/J1))
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.1), T(0)));
    const GyroStepInput<T> in = step_input<T>(T(1e-2), T(0));
    for (int n = 1; n <= 100; ++n) ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
    EXPECT_NEAR(D(g.gimbal_pitch_rad()), 0.1 * j1 / f * (1.0 - std::exp(-f * 1.0 / j1)), Tol<T>::kAngle);
    EXPECT_NEAR(D(g.gimbal_yaw_rad()), 0.0, Tol<T>::kAngle);
  }
  {  // a torque drives the rate to T/f, exponentially
    GyroModel<T> g = uncaged_model<T>(c, Vector2<T>::Zero());
    const GyroStepInput<T> in = step_input<T>(T(1e-2), T(0));
    for (int n = 1; n <= 100; ++n) ASSERT_EQ(g.step_torque(in, Vector2<T>(T(0.5), T(-1))), Status::kOk);
    EXPECT_NEAR(D(g.rate_rad_s()(0)), 0.1 * (1.0 - std::exp(-f / j1)), Tol<T>::kRel * 0.1);
    EXPECT_NEAR(D(g.rate_rad_s()(1)), -0.2 * (1.0 - std::exp(-f / j2)), Tol<T>::kRel * 0.2);
  }
}

// No spin and no friction: free gimbals, w' = T/J.
TYPED_TEST(GyroSpinDown, GivenZeroSpinWithoutFrictionThenTorqueAcceleratesTheGimbalsFreely) {
  GYRO_VERIFIES("EXACT-1");
  using T = TypeParam;
  GyroModel<T> g = uncaged_model<T>(test_config<T>(), Vector2<T>(T(0.01), T(0)));
  const GyroStepInput<T> in = step_input<T>(T(1e-2), T(0));
  for (int n = 1; n <= 100; ++n) ASSERT_EQ(g.step_torque(in, Vector2<T>(T(0.0225), T(-0.02))), Status::kOk);
  EXPECT_NEAR(D(g.rate_rad_s()(0)), 0.01 + 0.01 * 1.0, Tol<T>::kRate);
  EXPECT_NEAR(D(g.rate_rad_s()(1)), -0.01 * 1.0, Tol<T>::kRate);
  EXPECT_EQ(g.nutation_amplitude_rad()(0), T(0)) << "without spin or friction nothing nutates";
  EXPECT_EQ(g.nutation_amplitude_rad()(1), T(0));
}

// Spinning down to a stop through critical damping (J1 != J2, heavy friction): every step
// is finite and, with no torque, the gimbal energy J1 w1^2 + J2 w2^2 never grows
// (its derivative is -2 f |w|^2 whatever H does).
TYPED_TEST(GyroSpinDown, GivenSpinDownToZeroThroughCriticalDampingThenRatesStayFiniteAndEnergyDecays) {
  GYRO_VERIFIES("EXACT-1", "EXACT-4");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.friction = T(50);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(2), T(-3)));
  GyroStepInput<T> in = step_input<T>(T(1e-3));
  const auto energy = [&] {
    const Vector2<double> w = g.rate_rad_s().template cast<double>();
    return 2.25 * w(0) * w(0) + 2.0 * w(1) * w(1);
  };
  double e_prev = energy();
  RotorModes<T> modes;
  int overdamped = 0;
  for (int n = 1; n <= 2500; ++n) {
    const T spin = (n <= 2000) ? static_cast<T>(10.0 * (1.0 - n / 2000.0)) : T(0);
    in.spin_hz = spin;
    ASSERT_EQ(compute_modes(RotorParameters<T>{c.pitch_inertia, c.yaw_inertia, c.friction, momentum(c, spin)}, modes),
              Status::kOk);
    overdamped += (modes.regime == DampingRegime::kOverdamped) ? 1 : 0;
    ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk) << "step " << n << " spin " << D(spin);
    ASSERT_TRUE(all_finite(g.rate_rad_s(), g.nutation_amplitude_rad(), g.gimbal_pitch_rad(), g.gimbal_yaw_rad()));
    const double e = energy();
    EXPECT_LE(e, e_prev * (1.0 + 8 * D(std::numeric_limits<T>::epsilon()))) << "step " << n;
    e_prev = e;
  }
  EXPECT_GT(overdamped, 500) << "the run does cross into the overdamped regime";
  EXPECT_LT(e_prev, 1e-12);
}

// ---------------------------------------------------------------------------------------
// The transition cache.

// A step of a new dt with the spin unchanged is the step of that dt, bit for bit what a model
// uncaged at the same rates does in one step.
TEST(GyroModelCache, ANewStepUsesItsOwnTransition) {
  GYRO_VERIFIES("MODEL-6");
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

}  // namespace
}  // namespace gyro
