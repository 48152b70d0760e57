// GyroModel refuses bad configuration and bad step inputs with a status and leaves its state
// bit-identical; identical inputs give bit-identical outputs.
#include "support/gyro_model_support.hpp"  // gtest, Eigen, GyroModel and the standard headers
#include "support/requirements.hpp"

namespace gyro {
namespace {

using namespace model_test;  // NOLINT(google-build-using-namespace): the shared fixtures

// ---------------------------------------------------------------------------------------
// Bad input.

template <typename T>
class GyroBadInput : public ::testing::Test {};
TYPED_TEST_SUITE(GyroBadInput, Scalars);

template <typename T>
struct ConfigCase {
  std::function<void(GyroModelConfig<T>&)> spoil;
  Status status;
  const char* field;
};

template <typename T>
std::vector<ConfigCase<T>> config_cases() {
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  std::vector<ConfigCase<T>> v;
  const auto add = [&](T GyroModelConfig<T>::*m, T value, Status st, const char* field) {
    v.push_back({[m, value](GyroModelConfig<T>& c) { c.*m = value; }, st, field});
  };
  using C = GyroModelConfig<T>;
  const std::pair<T C::*, const char*> inertias[] = {
      {&C::pitch_inertia, "pitch_inertia"}, {&C::yaw_inertia, "yaw_inertia"}, {&C::spin_inertia, "spin_inertia"}};
  for (const auto& [m, name] : inertias) {
    for (const T bad : {T(0), -T(0), T(-1)}) add(m, bad, Status::kNonPositiveInertia, name);
    for (const T bad : {nan, inf, -inf}) add(m, bad, Status::kNonFiniteInput, name);
  }
  for (const T bad : {T(-1e-9), T(-5)}) add(&C::friction, bad, Status::kNegativeFriction, "friction");
  for (const T bad : {nan, inf, -inf}) add(&C::friction, bad, Status::kNonFiniteInput, "friction");
  for (const T bad : {T(0), T(-0.1), kPi<T>, T(4)}) add(&C::gimbal_cone_limit_rad, bad, Status::kOutOfRange, "gimbal_cone_limit_rad");
  for (const T bad : {nan, inf}) add(&C::gimbal_cone_limit_rad, bad, Status::kNonFiniteInput, "gimbal_cone_limit_rad");
  const std::pair<T C::*, const char*> axis_limits[] = {{&C::pitch_gimbal_limit_rad, "pitch_gimbal_limit_rad"},
                                                        {&C::yaw_gimbal_limit_rad, "yaw_gimbal_limit_rad"}};
  for (const auto& [m, name] : axis_limits) {
    for (const T bad : {T(-1e-6), T(-0.2), kPi<T>, T(10)}) add(m, bad, Status::kOutOfRange, name);
    for (const T bad : {nan, inf, -inf}) add(m, bad, Status::kNonFiniteInput, name);
  }
  const std::pair<T C::*, const char*> positives[] = {{&C::max_pitch_rate_rad_s, "max_pitch_rate_rad_s"},
                                                      {&C::max_yaw_rate_rad_s, "max_yaw_rate_rad_s"},
                                                      {&C::small_angle_limit_rad, "small_angle_limit_rad"},
                                                      {&C::gravity, "gravity"}};
  for (const auto& [m, name] : positives) {
    for (const T bad : {T(0), -T(0), T(-1)}) add(m, bad, Status::kOutOfRange, name);
    for (const T bad : {nan, inf, -inf}) add(m, bad, Status::kNonFiniteInput, name);
  }
  using A = AxisErrorSources<T>;
  T A::* const error_fields[] = {&A::static_drift_rad_s,      &A::in_plane_erection_1_s, &A::cross_plane_erection_1_s,
                                &A::g_sensitive_drift_rad_s, &A::torquer_cross_coupling, &A::coulomb_friction_rad_s};
  for (const auto f : error_fields) {
    for (const T bad : {nan, inf}) {
      v.push_back({[f, bad](C& c) { c.errors.pitch.*f = bad; }, Status::kNonFiniteInput, "errors"});
      v.push_back({[f, bad](C& c) { c.errors.yaw.*f = bad; }, Status::kNonFiniteInput, "errors"});
    }
  }
  return v;
}

// A model with some history: uncaged, nutating, slewed, with error sources.
template <typename T>
GyroModel<T> busy_model() {
  GyroModelConfig<T> c = test_config<T>();
  c.friction = T(0.5);
  c.errors.pitch.static_drift_rad_s = T(0.001);
  c.errors.yaw.in_plane_erection_1_s = T(0.1);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.2), T(-0.1)), Vector2<T>(T(0.01), T(0.02)),
                                    some_body_attitude<T>());
  const GyroStepInput<T> in = step_input<T>(T(1e-3), kSpinHz<T>, some_body_attitude<T>());
  for (int n = 0; n < 50; ++n) EXPECT_EQ(g.step_slew(in, Vector2<T>(T(0.1), T(0.05))), Status::kOk);
  return g;
}

TYPED_TEST(GyroBadInput, GivenEachBadConfigFieldThenRefusedWithItsStatusAndNameAndStateUntouched) {
  GYRO_VERIFIES("MODEL-6", "RULE-9");
  using T = TypeParam;
  const std::vector<ConfigCase<T>> cases = config_cases<T>();
  EXPECT_GT(cases.size(), 80u);
  for (const ConfigCase<T>& k : cases) {
    GyroModelConfig<T> bad = test_config<T>();
    k.spoil(bad);
    EXPECT_EQ(check(bad).status, k.status) << k.field;
    GyroModel<T> fresh;
    const ConfigCheck r = fresh.configure(bad);
    EXPECT_EQ(r.status, k.status) << "expected " << k.field << ", got " << (r.field ? r.field : "nullptr");
    ASSERT_NE(r.field, nullptr) << k.field;
    EXPECT_EQ(std::string(r.field), std::string(k.field));
    EXPECT_EQ(fresh.step_slew(step_input<T>(T(1e-3)), Vector2<T>::Zero()), Status::kNotConfigured);
    EXPECT_EQ(fresh.uncage(Matrix3<T>::Identity(), Vector2<T>::Zero()), Status::kNotConfigured);
    // Refused on a running model: everything as it was, still uncaged, still stepping alike.
    GyroModel<T> g = busy_model<T>();
    GyroModel<T> twin = busy_model<T>();
    const Observed<T> before = observe(g);
    const GyroModelConfig<T> config_before = g.config();
    EXPECT_EQ(g.configure(bad).status, k.status);
    EXPECT_TRUE(bit_identical(before, observe(g))) << k.field;
    EXPECT_TRUE(same_config(config_before, g.config())) << k.field;
    const GyroStepInput<T> in = step_input<T>(T(1e-3), kSpinHz<T>, some_body_attitude<T>());
    ASSERT_EQ(g.step_slew(in, Vector2<T>(T(0.1), T(0.05))), Status::kOk) << k.field;
    ASSERT_EQ(twin.step_slew(in, Vector2<T>(T(0.1), T(0.05))), Status::kOk);
    EXPECT_TRUE(bit_identical(observe(twin), observe(g))) << k.field;
  }
  // The edges that are accepted.
  GyroModelConfig<T> edge = test_config<T>();
  edge.friction = T(0);
  edge.pitch_gimbal_limit_rad = T(0);
  edge.yaw_gimbal_limit_rad = T(3.1);
  edge.gimbal_cone_limit_rad = T(3.14);
  GyroModel<T> g;
  const ConfigCheck ok = g.configure(edge);
  EXPECT_TRUE(ok.ok());
  EXPECT_EQ(ok.field, nullptr);
}

TYPED_TEST(GyroBadInput, GivenStepBeforeConfigureOrUncageThenNotConfigured) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  const GyroStepInput<T> in = step_input<T>(T(1e-3));
  GyroModel<T> g;
  EXPECT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kNotConfigured);
  EXPECT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kNotConfigured);
  EXPECT_EQ(g.uncage(Matrix3<T>::Identity(), Vector2<T>::Zero()), Status::kNotConfigured);
  ASSERT_TRUE(g.configure(test_config<T>()).ok());
  const Observed<T> before = observe(g);
  EXPECT_EQ(g.step_slew(in, Vector2<T>::Zero()), Status::kNotConfigured);
  EXPECT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kNotConfigured);
  EXPECT_TRUE(bit_identical(before, observe(g)));
  EXPECT_FALSE(g.uncaged());
  // A new configuration cages an uncaged gyro again.
  ASSERT_EQ(g.uncage(Matrix3<T>::Identity(), Vector2<T>::Zero()), Status::kOk);
  ASSERT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kOk);
  ASSERT_TRUE(g.configure(test_config<T>()).ok());
  EXPECT_FALSE(g.uncaged());
  EXPECT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kNotConfigured);
}

template <typename T>
Matrix3<T> scaled(T s) {
  return (s * some_body_attitude<T>()).eval();
}

TYPED_TEST(GyroBadInput, GivenEachBadStepInputThenItsStatusAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6", "RULE-9");
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  const GyroStepInput<T> good = step_input<T>(T(1e-3), kSpinHz<T>, some_body_attitude<T>());
  const Vector2<T> cmd(T(0.1), T(0.05));
  const Vector2<T> torque(T(10), T(-20));
  struct Case {
    std::string what;
    GyroStepInput<T> in;
    Vector2<T> cmd;     // for step_slew
    Vector2<T> torque;  // for step_torque
    Status status;
  };
  std::vector<Case> cases;
  const auto with = [&](const std::string& what, const std::function<void(GyroStepInput<T>&)>& spoil, Status st) {
    GyroStepInput<T> in = good;
    spoil(in);
    cases.push_back({what, in, cmd, torque, st});
  };
  for (const T bad : {nan, inf, -inf}) {
    with("dt non-finite", [bad](GyroStepInput<T>& in) { in.dt_s = bad; }, Status::kNonFiniteInput);
    with("spin non-finite", [bad](GyroStepInput<T>& in) { in.spin_hz = bad; }, Status::kNonFiniteInput);
    with("lateral accel non-finite", [bad](GyroStepInput<T>& in) { in.body_accel(0) = bad; }, Status::kNonFiniteInput);
    with("normal accel non-finite", [bad](GyroStepInput<T>& in) { in.body_accel(1) = bad; }, Status::kNonFiniteInput);
    for (int i = 0; i < 2; ++i) {
      Vector2<T> v = cmd;
      v(i) = bad;
      Vector2<T> t = torque;
      t(i) = bad;
      cases.push_back({"command/torque non-finite", good, v, t, Status::kNonFiniteInput});
    }
    for (int i = 0; i < 9; i += 4) {
      with("body matrix non-finite", [bad, i](GyroStepInput<T>& in) { in.R_earth_to_body.data()[i] = bad; },
           Status::kInvalidRotation);
    }
  }
  for (const T bad : {T(0), -T(0), T(-1e-3)}) {
    with("dt <= 0", [bad](GyroStepInput<T>& in) { in.dt_s = bad; }, Status::kNonPositiveStep);
  }
  with("negative spin", [](GyroStepInput<T>& in) { in.spin_hz = T(-1); }, Status::kNegativeAngularMomentum);
  with("scaled body matrix", [](GyroStepInput<T>& in) { in.R_earth_to_body = scaled<T>(T(1.001)); },
       Status::kInvalidRotation);
  with("sheared body matrix", [](GyroStepInput<T>& in) { in.R_earth_to_body(0, 1) += T(1e-3); },
       Status::kInvalidRotation);
  with("reflection", [](GyroStepInput<T>& in) { in.R_earth_to_body.row(2) *= T(-1); }, Status::kInvalidRotation);
  with("zero matrix", [](GyroStepInput<T>& in) { in.R_earth_to_body.setZero(); }, Status::kInvalidRotation);

  for (const Case& k : cases) {
    GyroModel<T> g = busy_model<T>();
    GyroModel<T> twin = busy_model<T>();
    const Observed<T> before = observe(g);
    EXPECT_EQ(g.step_slew(k.in, k.cmd), k.status) << "step_slew: " << k.what;
    EXPECT_TRUE(bit_identical(before, observe(g))) << "step_slew: " << k.what;
    EXPECT_EQ(g.step_torque(k.in, k.torque), k.status) << "step_torque: " << k.what;
    EXPECT_TRUE(bit_identical(before, observe(g))) << "step_torque: " << k.what;
    // And the model carries on exactly as if the call had not been made.
    ASSERT_EQ(g.step_slew(good, cmd), Status::kOk) << k.what;
    ASSERT_EQ(twin.step_slew(good, cmd), Status::kOk);
    EXPECT_TRUE(bit_identical(observe(twin), observe(g))) << k.what;
  }
}

// Finite inputs whose torque overflows in the torquer model (cross-coupling adds a share
// of the other axis' torque): a numerical overflow, not a non-finite input, and no change.
TYPED_TEST(GyroBadInput, GivenFiniteTorqueThatOverflowsThroughCrossCouplingThenNumericalOverflowAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6", "EXACT-5");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.errors.yaw.torquer_cross_coupling = T(0.5);
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.2), T(-0.1)), Vector2<T>(T(0.01), T(0.02)),
                                    some_body_attitude<T>());
  const GyroStepInput<T> in = step_input<T>(T(1e-3), kSpinHz<T>, some_body_attitude<T>());
  const T big = std::numeric_limits<T>::max();
  const Observed<T> before = observe(g);
  EXPECT_EQ(g.step_torque(in, Vector2<T>(big, -big)), Status::kNumericalOverflow);
  EXPECT_TRUE(bit_identical(before, observe(g)));
  EXPECT_EQ(g.step_torque(in, Vector2<T>(T(10), T(-20))), Status::kOk);
}

// Rates whose norm is beyond the largest value, each component within it: the exact step's own
// test can pass them while their turn onto the gimbal axes (what rate_on_gimbal_rad_s()
// publishes) is not representable. Over a grid of such rates and starting attitudes, every step
// publishes a finite rate or is refused with its state bit-identical.
TYPED_TEST(GyroBadInput, GivenRatesWhoseTurnOntoTheGimbalOverflowsThenNumericalOverflowAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  const T big = std::numeric_limits<T>::max();
  const GyroStepInput<T> in = step_input<T>(T(1e-4));
  int accepted = 0, refused = 0;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      for (int k = 0; k < 4; ++k) {
        const Vector2<T> rate(T(0.18 * i - 0.99) * big, T(0.18 * j - 0.99) * big);
        const Vector2<T> offset(T(0.07 * k - 0.1), T(0.2 - 0.09 * k));
        GyroModel<T> g = uncaged_model<T>(test_config<T>(), rate, offset);
        const Observed<T> before = observe(g);
        const Status s = g.step_torque(in, Vector2<T>::Zero());
        if (s == Status::kOk) {
          EXPECT_TRUE(all_finite(g.rate_on_gimbal_rad_s())) << i << " " << j << " " << k;
          ++accepted;
        } else {
          EXPECT_EQ(s, Status::kNumericalOverflow);
          EXPECT_TRUE(bit_identical(before, observe(g))) << i << " " << j << " " << k;
          ++refused;
        }
      }
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

// Without spin a finite torque accelerates the gimbals freely (w' = T/J): over 100 s the
// largest torque overflows the rates inside the exact step.
TYPED_TEST(GyroBadInput, GivenNoSpinAndLargestTorqueOver100sThenNumericalOverflowAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6", "EXACT-5");
  using T = TypeParam;
  GyroModel<T> g = uncaged_model<T>(test_config<T>(), Vector2<T>(T(0.2), T(-0.1)), Vector2<T>(T(0.01), T(0.02)),
                                    some_body_attitude<T>());
  const GyroStepInput<T> in = step_input<T>(T(100), T(0), some_body_attitude<T>());
  const T big = std::numeric_limits<T>::max();
  const Observed<T> before = observe(g);
  EXPECT_EQ(g.step_torque(in, Vector2<T>(big, -big)), Status::kNumericalOverflow);
  EXPECT_TRUE(bit_identical(before, observe(g)));
  EXPECT_EQ(g.step_torque(in, Vector2<T>(T(1e-3), T(-2e-3))), Status::kOk);
}

TYPED_TEST(GyroBadInput, GivenBadUncageInputThenRefusedAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T inf = std::numeric_limits<T>::infinity();
  GyroModel<T> g = busy_model<T>();
  const Observed<T> before = observe(g);
  const Matrix3<T> body = some_body_attitude<T>();
  for (const T bad : {nan, inf}) {
    EXPECT_EQ(g.uncage(body, Vector2<T>(bad, T(0))), Status::kNonFiniteInput);
    EXPECT_EQ(g.uncage(body, Vector2<T>(T(0), bad)), Status::kNonFiniteInput);
    EXPECT_EQ(g.uncage(body, Vector2<T>::Zero(), Vector2<T>(bad, T(0))), Status::kNonFiniteInput);
    Matrix3<T> m = body;
    m(1, 1) = bad;
    EXPECT_EQ(g.uncage(m, Vector2<T>::Zero()), Status::kInvalidRotation);
  }
  EXPECT_EQ(g.uncage(scaled<T>(T(0.999)), Vector2<T>::Zero()), Status::kInvalidRotation);
  EXPECT_EQ(g.uncage(Matrix3<T>(-body), Vector2<T>::Zero()), Status::kInvalidRotation);  // det -1
  EXPECT_TRUE(bit_identical(before, observe(g)));
}

TYPED_TEST(GyroBadInput, GivenTorquerAxesOutsideTheirEnumThenRefusedByName) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  GyroModelConfig<T> c = test_config<T>();
  c.torquer_axes = static_cast<TorquerAxes>(2);
  GyroModel<T> g;
  const ConfigCheck r = g.configure(c);
  EXPECT_EQ(r.status, Status::kOutOfRange);
  EXPECT_STREQ(r.field, "torquer_axes");
  c.torquer_axes = TorquerAxes::kGimbal;
  EXPECT_TRUE(g.configure(c).ok());
}

TYPED_TEST(GyroBadInput, GivenBadUncageOnGimbalInputThenRefused) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  GyroModel<T> g;
  const Matrix3<T> body = some_body_attitude<T>();
  EXPECT_EQ(g.uncage_on_gimbal(body, Vector3<T>::Zero(), Vector2<T>::Zero()), Status::kNotConfigured);
  ASSERT_TRUE(g.configure(test_config<T>()).ok());
  EXPECT_EQ(g.uncage_on_gimbal(scaled<T>(T(0.999)), Vector3<T>::Zero(), Vector2<T>::Zero()), Status::kInvalidRotation);
  EXPECT_FALSE(g.uncaged());
  EXPECT_EQ(g.uncage_on_gimbal(body, Vector3<T>::Zero(), Vector2<T>(T(0.1), T(-0.2))), Status::kOk);
  EXPECT_TRUE(g.uncaged());
}

// A finite spin whose angular momentum 2 pi spin J0 is not: refused as the step's input.
TYPED_TEST(GyroBadInput, GivenASpinWhoseMomentumOverflowsThenRefusedAndStateBitIdentical) {
  GYRO_VERIFIES("MODEL-6");
  using T = TypeParam;
  GyroModel<T> g = busy_model<T>();
  const Observed<T> before = observe(g);
  const GyroStepInput<T> in = step_input<T>(T(1e-3), std::numeric_limits<T>::max() / T(2));
  EXPECT_EQ(g.step_torque(in, Vector2<T>::Zero()), Status::kNonFiniteInput);
  EXPECT_TRUE(bit_identical(before, observe(g)));
}

// ---------------------------------------------------------------------------------------
// Determinism.

template <typename T>
class GyroDeterminism : public ::testing::Test {};
TYPED_TEST_SUITE(GyroDeterminism, Scalars);

template <typename T>
std::vector<Observed<T>> busy_run() {
  GyroModelConfig<T> c = test_config<T>();
  c.friction = T(0.3);
  c.max_pitch_rate_rad_s = T(0.2);
  c.max_yaw_rate_rad_s = T(0.25);
  c.gimbal_cone_limit_rad = T(0.5);
  c.pitch_gimbal_limit_rad = T(0.3);
  c.errors.pitch = {T(1e-3), T(0.2), T(0.05), T(2e-3), T(0.02), T(1e-3)};
  c.errors.yaw = {T(-2e-3), T(0.3), T(-0.04), T(3e-3), T(-0.03), T(2e-3)};
  GyroModel<T> g = uncaged_model<T>(c, Vector2<T>(T(0.3), T(-0.1)), Vector2<T>(T(0.02), T(-0.01)));
  std::vector<Observed<T>> out;
  GyroStepInput<T> in = step_input<T>(T(2e-3));
  for (int n = 1; n <= 5000; ++n) {
    const T t = static_cast<T>(n) * in.dt_s;
    in.spin_hz = T(100) - T(0.01) * static_cast<T>(n);  // spin-down: a new transition each step
    in.body_accel = Vector2<T>(T(30) * std::sin(t), T(20) * std::cos(T(1.3) * t));
    in.R_earth_to_body = frame_rotation_z<T>(T(0.2) * std::sin(t)) * frame_rotation_y<T>(T(0.3) * t);
    const Vector2<T> cmd(T(0.4) * std::sin(T(2) * t), T(-0.3) * std::cos(T(0.7) * t));
    EXPECT_EQ(g.step_slew(in, cmd), Status::kOk);
    out.push_back(observe(g));
  }
  return out;
}

TYPED_TEST(GyroDeterminism, GivenTwoIdenticalRunsThenEveryStepIsBitIdentical) {
  GYRO_VERIFIES("MODEL-6", "RULE-6");
  using T = TypeParam;
  const std::vector<Observed<T>> a = busy_run<T>();
  const std::vector<Observed<T>> b = busy_run<T>();
  ASSERT_EQ(a.size(), b.size());
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differing += bit_identical(a[k], b[k]) ? 0u : 1u;
  EXPECT_EQ(differing, 0u);
}

}  // namespace
}  // namespace gyro
