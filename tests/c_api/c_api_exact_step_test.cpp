// The C API's exact step (gyro_make_transition_*, gyro_advance_*): the same numbers as the C++
// calls, bit for bit, in every damping regime and precision; the batch as the single step row
// by row; refused rows left as they were.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "c_api/c_api_scalar.hpp"
#include "gyro/gyro.h"
#include "gyro/rotor_transition.hpp"

namespace gyro {
namespace {

using c_api_test::C;

template <typename T>
class CApiExactStep : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(CApiExactStep, Scalars);

// Underdamped (the report's gyro), critically damped, overdamped, and without spin or friction.
template <typename T>
std::array<RotorParameters<T>, 4> regimes() {
  return {RotorParameters<T>{T(2.25), T(2), T(5), angular_momentum(T(100), T(3))},
          RotorParameters<T>{T(1), T(1), T(2), T(0)},
          RotorParameters<T>{T(2.25), T(2), T(40), T(3)},
          RotorParameters<T>{T(2.25), T(2), T(0), T(0)}};
}

TYPED_TEST(CApiExactStep, GivenEveryRegimeThenStepsAreTheCppStepsBitForBit) {
  using T = TypeParam;
  for (const RotorParameters<T>& p : regimes<T>()) {
    const typename C<T>::Params cp{p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum};
    RotorTransition<T> tr;
    typename C<T>::Transition ctr{};
    ASSERT_EQ(make_transition(p, T(1e-3), tr), Status::kOk);
    ASSERT_EQ(C<T>::make(&cp, T(1e-3), &ctr), GYRO_OK);
    RotorState<T> s;
    s.angle_rad = Vector2<T>(T(0.01), T(-0.02));
    s.rate_rad_s = Vector2<T>(T(0.3), T(-0.4));
    T cs[4] = {s.angle_rad(0), s.angle_rad(1), s.rate_rad_s(0), s.rate_rad_s(1)};
    const T torque[2] = {T(1.5), T(-0.5)};
    for (int k = 0; k < 100; ++k) {
      ASSERT_EQ(advance(tr, Vector2<T>(torque[0], torque[1]), s), Status::kOk);
      ASSERT_EQ(C<T>::advance(&ctr, torque, cs), GYRO_OK);
    }
    EXPECT_EQ(cs[0], s.angle_rad(0));
    EXPECT_EQ(cs[1], s.angle_rad(1));
    EXPECT_EQ(cs[2], s.rate_rad_s(0));
    EXPECT_EQ(cs[3], s.rate_rad_s(1));
  }
}

TYPED_TEST(CApiExactStep, GivenABatchThenEachRowIsTheSingleStep) {
  using T = TypeParam;
  const RotorParameters<T> p = regimes<T>()[0];
  const typename C<T>::Params cp{p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum};
  typename C<T>::Transition ctr{};
  ASSERT_EQ(C<T>::make(&cp, T(2e-3), &ctr), GYRO_OK);
  constexpr std::size_t kRows = 7;
  std::array<T, 4 * kRows> batch{}, one_torque{};
  std::array<T, 2 * kRows> torques{};
  for (std::size_t i = 0; i < batch.size(); ++i) batch[i] = T(0.01) * static_cast<T>(i % 5) - T(0.02);
  for (std::size_t i = 0; i < torques.size(); ++i) torques[i] = T(3) - static_cast<T>(i);
  one_torque = batch;
  std::array<std::uint8_t, kRows> statuses{};
  ASSERT_EQ(C<T>::batch(&ctr, batch.data(), kRows, torques.data(), 2, statuses.data()), GYRO_OK);
  ASSERT_EQ(C<T>::batch(&ctr, one_torque.data(), kRows, torques.data(), 0, nullptr), GYRO_OK);
  for (std::size_t i = 0; i < kRows; ++i) {
    T s[4];
    for (int j = 0; j < 4; ++j) s[j] = T(0.01) * static_cast<T>((4 * i + static_cast<std::size_t>(j)) % 5) - T(0.02);
    T s0[4];
    std::memcpy(s0, s, sizeof s);
    ASSERT_EQ(C<T>::advance(&ctr, torques.data() + 2 * i, s), GYRO_OK);
    ASSERT_EQ(C<T>::advance(&ctr, torques.data(), s0), GYRO_OK);
    EXPECT_EQ(std::memcmp(s, batch.data() + 4 * i, sizeof s), 0) << "row " << i;
    EXPECT_EQ(std::memcmp(s0, one_torque.data() + 4 * i, sizeof s0), 0) << "row " << i;
    EXPECT_EQ(statuses[i], GYRO_OK);
  }
}

TYPED_TEST(CApiExactStep, GivenANonFiniteRowThenOnlyItIsRefusedAndKept) {
  using T = TypeParam;
  const RotorParameters<T> p = regimes<T>()[0];
  const typename C<T>::Params cp{p.pitch_inertia, p.yaw_inertia, p.friction, p.angular_momentum};
  typename C<T>::Transition ctr{};
  ASSERT_EQ(C<T>::make(&cp, T(1e-3), &ctr), GYRO_OK);
  std::array<T, 12> batch{T(0), T(0), T(1), T(1), T(0), std::numeric_limits<T>::quiet_NaN(), T(1), T(1),
                          T(0), T(0), T(1), T(1)};
  const std::array<T, 12> before = batch;
  const T torque[2] = {T(1), T(1)};
  std::array<std::uint8_t, 3> st{};
  EXPECT_EQ(C<T>::batch(&ctr, batch.data(), 3, torque, 0, st.data()), GYRO_NON_FINITE_INPUT);
  EXPECT_EQ(st[0], GYRO_OK);
  EXPECT_EQ(st[1], GYRO_NON_FINITE_INPUT);
  EXPECT_EQ(st[2], GYRO_OK);
  EXPECT_EQ(std::memcmp(batch.data() + 4, before.data() + 4, 4 * sizeof(T)), 0);
  EXPECT_NE(batch[0], before[0]);
  EXPECT_EQ(C<T>::batch(&ctr, nullptr, 0, nullptr, 0, nullptr), GYRO_OK);  // an empty batch
  EXPECT_EQ(C<T>::batch(&ctr, nullptr, 1, torque, 0, nullptr), GYRO_NULL_ARGUMENT);
}

TEST(CApiExactStep, GivenBadParametersThenTheCppStatusAndTheTransitionKept) {
  gyro_transition_d tr{};
  tr.coefficients[16] = 42.0;
  const gyro_rotor_parameters_d neg_inertia{-1.0, 2.0, 5.0, 1.0};
  const gyro_rotor_parameters_d nan_h{1.0, 2.0, 5.0, std::nan("")};
  EXPECT_EQ(gyro_make_transition_d(&neg_inertia, 1e-3, &tr), GYRO_NON_POSITIVE_INERTIA);
  EXPECT_EQ(gyro_make_transition_d(&nan_h, 1e-3, &tr), GYRO_NON_FINITE_INPUT);
  EXPECT_EQ(tr.coefficients[16], 42.0);
}

}  // namespace
}  // namespace gyro
