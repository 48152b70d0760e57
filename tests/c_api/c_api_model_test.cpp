// The C API's GyroModel (gyro_model_d_*, gyro_model_f_*): the same model as the C++ class, bit
// for bit, over the report's sample with error sources and on the gimbal torquer axes; every
// reading; a refused step leaves it as it was; any storage alignment.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

#include "c_api/c_api_scalar.hpp"
#include "gyro/gyro.h"
#include "gyro/gyro_model.hpp"
#include "gyro/report_sample.hpp"

namespace gyro {
namespace {

using c_api_test::C;

template <typename T>
class CApiModel : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(CApiModel, Scalars);

// The report's sample gyro with an error source of each kind, through the C struct.
gyro_model_config sample_config_with_errors(bool on_gimbal) {
  gyro_report_sample s{};
  gyro_model_config c{};
  EXPECT_EQ(gyro_report_sample_get(&s, &c), GYRO_OK);
  c.errors.pitch.static_drift_rad_s = 1e-3;
  c.errors.yaw.in_plane_erection_1_s = 0.2;
  c.errors.pitch.cross_plane_erection_1_s = -0.1;
  c.errors.yaw.g_sensitive_drift_rad_s = 2e-3;
  c.errors.pitch.torquer_cross_coupling = 0.05;
  c.errors.yaw.coulomb_friction_rad_s = 1e-3;
  if (on_gimbal) {
    EXPECT_EQ(gyro_config_set_choice(GYRO_MODEL_CONFIG, &c, "torquer_axes", "gimbal"), GYRO_OK);
  }
  return c;
}

// The same configuration as the C++ struct, field by field (the binding under test is not used).
template <typename T>
GyroModelConfig<T> cpp_config(bool on_gimbal) {
  GyroModelConfig<T> c = ReportSample<T>::config();
  c.errors.pitch.static_drift_rad_s = T(1e-3);
  c.errors.yaw.in_plane_erection_1_s = T(0.2);
  c.errors.pitch.cross_plane_erection_1_s = T(-0.1);
  c.errors.yaw.g_sensitive_drift_rad_s = T(2e-3);
  c.errors.pitch.torquer_cross_coupling = T(0.05);
  c.errors.yaw.coulomb_friction_rad_s = T(1e-3);
  if (on_gimbal) c.torquer_axes = TorquerAxes::kGimbal;
  return c;
}

template <typename T>
void expect_same(const GyroModel<T>& g, const typename C<T>::Model* m, int k) {
  T v[2];
  C<T>::gimbal(m, v);
  EXPECT_EQ(v[0], g.gimbal_pitch_rad()) << k;
  EXPECT_EQ(v[1], g.gimbal_yaw_rad()) << k;
  C<T>::rate(m, v);
  EXPECT_EQ(v[0], g.rate_rad_s()(0)) << k;
  EXPECT_EQ(v[1], g.rate_rad_s()(1)) << k;
  C<T>::isaf(m, v);
  EXPECT_EQ(v[1], g.isaf_angle_rad()(1)) << k;
  C<T>::nutation(m, v);
  EXPECT_EQ(v[0], g.nutation_amplitude_rad()(0)) << k;
  C<T>::applied(m, v);
  EXPECT_EQ(v[1], g.applied_torque()(1)) << k;
  T r[9];
  C<T>::roteg(m, r);
  const Matrix3<T> roteg = g.R_earth_to_gyro();
  for (int i = 0; i < 9; ++i) EXPECT_EQ(r[i], roteg(i / 3, i % 3)) << k;
  T q[4];
  C<T>::attitude(m, q);
  EXPECT_EQ(q[0], g.attitude_gyro_to_earth().w()) << k;
  EXPECT_EQ(q[3], g.attitude_gyro_to_earth().z()) << k;
  EXPECT_EQ(C<T>::cone(m), g.gimbal_cone_rad()) << k;
  EXPECT_EQ(C<T>::flags(m), g.flags()) << k;
}

TYPED_TEST(CApiModel, GivenTheReportSampleWithErrorsThenEveryReadingIsTheCppModels) {
  using T = TypeParam;
  for (const bool on_gimbal : {false, true}) {
    SCOPED_TRACE(on_gimbal ? "gimbal torquer axes" : "gyro torquer axes");
    std::vector<double> storage(C<T>::size() / sizeof(double) + 1);
    typename C<T>::Model* m = C<T>::init(storage.data(), storage.size() * sizeof(double));
    ASSERT_NE(m, nullptr);
    const gyro_model_config cc = sample_config_with_errors(on_gimbal);
    ASSERT_EQ(C<T>::configure(m, &cc), GYRO_OK);
    GyroModel<T> g;
    ASSERT_TRUE(g.configure(cpp_config<T>(on_gimbal)).ok());
    using S = ReportSample<T>;
    const T dt = S::initg_step();
    const T rates[2] = {S::kBodyPitchRate, S::kBodyYawRate};
    Matrix3<T> r_eb = Matrix3<T>::Identity();
    typename C<T>::Input in{};
    for (int i = 0; i < 9; ++i) in.R_earth_to_body[i] = r_eb(i / 3, i % 3);
    ASSERT_EQ(C<T>::uncage(m, in.R_earth_to_body, rates), GYRO_OK);
    ASSERT_EQ(g.uncage(r_eb, Vector2<T>(rates[0], rates[1])), Status::kOk);
    expect_same(g, m, -1);
    const Matrix3<T> turn = frame_rotation_z(S::kBodyYawRate * dt) * frame_rotation_y(S::kBodyPitchRate * dt);
    GyroStepInput<T> cpp_in;
    cpp_in.dt_s = in.dt_s = dt;
    cpp_in.spin_hz = in.spin_hz = S::kSpinHz;
    for (int k = 0; k < S::kSteps; ++k) {
      r_eb = turn * r_eb;
      cpp_in.R_earth_to_body = r_eb;
      cpp_in.body_accel = Vector2<T>(T(40) * std::sin(T(0.01) * T(k)), T(-20));
      cpp_in.body_rate_rad_s = Vector3<T>(T(3), rates[0], rates[1]);
      for (int i = 0; i < 9; ++i) in.R_earth_to_body[i] = r_eb(i / 3, i % 3);
      for (int i = 0; i < 2; ++i) in.body_accel[i] = cpp_in.body_accel(i);
      for (int i = 0; i < 3; ++i) in.body_rate_rad_s[i] = cpp_in.body_rate_rad_s(i);
      if (k % 2 == 0) {
        const Vector2<T> slew = S::slew_command();
        const T w[2] = {slew(0), slew(1)};
        ASSERT_EQ(C<T>::slew(m, &in, w), static_cast<int>(g.step_slew(cpp_in, slew))) << k;
      } else {
        const T t[2] = {T(30), T(-45)};
        ASSERT_EQ(C<T>::torque(m, &in, t), static_cast<int>(g.step_torque(cpp_in, Vector2<T>(t[0], t[1])))) << k;
      }
      if (k % 100 == 0 || k == S::kSteps - 1) expect_same(g, m, k);
    }
  }
}

TYPED_TEST(CApiModel, GivenARefusedStepThenTheModelIsAsItWas) {
  using T = TypeParam;
  std::vector<double> storage(C<T>::size() / sizeof(double) + 1);
  typename C<T>::Model* m = C<T>::init(storage.data(), storage.size() * sizeof(double));
  gyro_report_sample s{};
  gyro_model_config config{};
  ASSERT_EQ(gyro_report_sample_get(&s, &config), GYRO_OK);
  typename C<T>::Input in{};
  const T w[2] = {T(0.1), T(0.2)};
  in.dt_s = T(1e-3);
  in.spin_hz = T(100);
  for (int i = 0; i < 9; i += 4) in.R_earth_to_body[i] = T(1);
  EXPECT_EQ(C<T>::slew(m, &in, w), GYRO_NOT_CONFIGURED);
  ASSERT_EQ(C<T>::configure(m, &config), GYRO_OK);
  EXPECT_EQ(C<T>::slew(m, &in, w), GYRO_NOT_CONFIGURED);  // caged
  ASSERT_EQ(C<T>::uncage(m, in.R_earth_to_body, w), GYRO_OK);
  ASSERT_EQ(C<T>::slew(m, &in, w), GYRO_OK);
  const std::vector<double> before = storage;
  in.dt_s = T(-1);
  EXPECT_EQ(C<T>::slew(m, &in, w), GYRO_NON_POSITIVE_STEP);
  in.dt_s = T(1e-3);
  in.R_earth_to_body[0] = T(2);
  EXPECT_EQ(C<T>::slew(m, &in, w), GYRO_INVALID_ROTATION);
  EXPECT_EQ(C<T>::slew(m, nullptr, w), GYRO_NULL_ARGUMENT);
  EXPECT_EQ(std::memcmp(before.data(), storage.data(), storage.size() * sizeof(double)), 0);
}

TYPED_TEST(CApiModel, GivenStorageAtAnyOffsetThenItHoldsAModel) {
  using T = TypeParam;
  std::vector<unsigned char> bytes(C<T>::size() + 64);
  for (std::size_t offset = 0; offset < 33; ++offset) {
    typename C<T>::Model* m = C<T>::init(bytes.data() + offset, C<T>::size());
    ASSERT_NE(m, nullptr) << offset;
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(m) % alignof(GyroModel<T>), 0u) << offset;
    EXPECT_EQ(C<T>::init(bytes.data() + offset, C<T>::size() - 1), nullptr) << offset;
  }
  EXPECT_EQ(C<T>::init(nullptr, 1u << 20), nullptr);
}

TEST(CApiModel, GivenAFloatOverflowingConfigurationThenTheFieldIsNamedAsGiven) {
  gyro_report_sample s{};
  gyro_model_config config{};
  ASSERT_EQ(gyro_report_sample_get(&s, &config), GYRO_OK);
  config.gravity = 1e300;
  gyro_refusal r{};
  gyro_model_f_storage storage;
  gyro_model_f* m = gyro_model_f_init(&storage, sizeof storage);
  EXPECT_EQ(gyro_model_f_configure(m, &config, &r), GYRO_OUT_OF_RANGE);
  EXPECT_STREQ(r.field, "gravity");
  EXPECT_EQ(r.value, 1e300);
  EXPECT_EQ(r.relation, 2);  // above
  EXPECT_EQ(gyro_model_f_uncaged(m), 0);
}

TEST(CApiModel, GivenModelsOnTheHeapThenTheyWorkAsInStorage) {
  gyro_model_d* m = gyro_model_d_create();
  ASSERT_NE(m, nullptr);
  gyro_report_sample s{};
  gyro_model_config config{};
  ASSERT_EQ(gyro_report_sample_get(&s, &config), GYRO_OK);
  EXPECT_EQ(gyro_model_d_configure(m, &config, nullptr), GYRO_OK);
  gyro_model_d_destroy(m);
  gyro_model_f_destroy(nullptr);
}

}  // namespace
}  // namespace gyro
