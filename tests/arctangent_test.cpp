// fixed_cost_atan2 (gyro/arctangent.hpp) against the C library's atan2, whose results are
// correctly rounded or within an ulp: over every octant, near the reduction's break points,
// at the axes and on special values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "gyro/arctangent.hpp"
#include "support/requirements.hpp"

namespace {

template <typename T>
class ArctangentTest : public ::testing::Test {};
using Scalars = ::testing::Types<double, float>;
TYPED_TEST_SUITE(ArctangentTest, Scalars);

// Two ulps of the result, and never finer than two ulps of pi/4 for the results that pass
// through pi/4 + atan(...).
template <typename T>
T tolerance(T expected) {
  const T eps = std::numeric_limits<T>::epsilon();
  return T(2) * eps * std::max(std::abs(expected), T(0.7853981633974483));
}

TYPED_TEST(ArctangentTest, GivenPointsOnTheCircle_WhenTheAngleIsComputed_ThenItIsWithinTwoUlpsOfAtan2) {
  GYRO_VERIFIES("EXACT-6");
  using T = TypeParam;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-3.14159265358979, 3.14159265358979);
  std::uniform_real_distribution<double> log_radius(-20.0, 20.0);
  T worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double a = angle(rng), r = std::exp(log_radius(rng));
    const T y = static_cast<T>(r * std::sin(a)), x = static_cast<T>(r * std::cos(a));
    const T expected = std::atan2(y, x);
    const T error = std::abs(gyro::fixed_cost_atan2(y, x) - expected);
    worst = std::max(worst, error / tolerance(expected));
  }
  EXPECT_LE(worst, T(1));
}

TYPED_TEST(ArctangentTest, GivenRatiosAtTheReductionBreakPoints_WhenTheAngleIsComputed_ThenItIsContinuous) {
  GYRO_VERIFIES("EXACT-6");
  using T = TypeParam;
  // tan(pi/8), where the reduction starts, and 1, where the octants meet.
  for (const double t : {0.41421356237309504880, 1.0}) {
    for (int k = -50; k <= 50; ++k) {
      const T y = static_cast<T>(t * (1.0 + k * 1e-7));
      const T expected = std::atan2(y, T(1));
      EXPECT_NEAR(gyro::fixed_cost_atan2(y, T(1)), expected, tolerance(expected)) << "y " << y;
    }
  }
}

TYPED_TEST(ArctangentTest, GivenTheAxesAndSignedZeros_WhenTheAngleIsComputed_ThenItIsExactAndKeepsTheSign) {
  GYRO_VERIFIES("EXACT-6");
  using T = TypeParam;
  const T pi = T(3.14159265358979323846), half = pi / T(2);
  EXPECT_EQ(gyro::fixed_cost_atan2(T(0), T(1)), T(0));
  EXPECT_EQ(gyro::fixed_cost_atan2(T(1), T(0)), half);
  EXPECT_EQ(gyro::fixed_cost_atan2(T(-1), T(0)), -half);
  EXPECT_EQ(gyro::fixed_cost_atan2(T(0), T(-1)), pi);
  EXPECT_EQ(gyro::fixed_cost_atan2(T(-0.0), T(-1)), -pi);
  EXPECT_EQ(gyro::fixed_cost_atan2(T(1), T(1)), pi / T(4));
  EXPECT_TRUE(std::signbit(gyro::fixed_cost_atan2(T(-0.0), T(1))));
  EXPECT_EQ(gyro::fixed_cost_atan2(T(0), T(0)), T(0));
}

TYPED_TEST(ArctangentTest, GivenNonFiniteArguments_WhenTheAngleIsComputed_ThenNaNIsNotHiddenAndInfinityIsAnAxis) {
  GYRO_VERIFIES("EXACT-6");
  using T = TypeParam;
  const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
  EXPECT_TRUE(std::isnan(gyro::fixed_cost_atan2(nan, T(1))));
  EXPECT_TRUE(std::isnan(gyro::fixed_cost_atan2(T(1), nan)));
  EXPECT_TRUE(std::isnan(gyro::fixed_cost_atan2(inf, inf)));
  EXPECT_EQ(gyro::fixed_cost_atan2(inf, T(1)), std::atan2(inf, T(1)));
  EXPECT_EQ(gyro::fixed_cost_atan2(T(1), inf), T(0));
}

}  // namespace
