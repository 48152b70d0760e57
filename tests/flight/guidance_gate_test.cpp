// The guidance gate (gyro/guidance_gate.hpp): unknown requests dropped, non-finite slews ignored
// with the last one held, navigation used only when marked valid and usable.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gyro/guidance_gate.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace guidance_gate_test {

constexpr double kMaxBodyRate = 4.0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

GuidanceInput<double> with_nav(const Vector3<double>& rate) {
  GuidanceInput<double> in;
  in.nav_valid = true;
  in.body_rate_rad_s = rate;
  in.R_earth_to_body = Eigen::AngleAxisd(0.3, Vector3<double>(0, 0.6, 0.8)).toRotationMatrix();
  return in;
}

TEST(GuidanceGate, AUsableInputIsTakenAsSent) {
  GYRO_VERIFIES("INPUT-1", "INPUT-4");
  GuidanceGate<double> g;
  GuidanceInput<double> in = with_nav(Vector3<double>(1, -2, 3));
  in.request = ModeRequest::kUncage;
  in.slew_rate_cmd_rad_s = Vector2<double>(0.2, -0.1);
  const GuidanceVerdict v = g.accept(in, kMaxBodyRate);
  EXPECT_EQ(v.request, ModeRequest::kUncage);
  EXPECT_TRUE(v.nav_ok);
  EXPECT_EQ(v.flags, 0u);
  EXPECT_EQ(g.slew_cmd_rad_s(), Vector2<double>(0.2, -0.1));
  EXPECT_EQ(g.navigation().body_rate_rad_s(), Vector3<double>(1, -2, 3));
  EXPECT_TRUE(g.navigation().attitude().matrix().isApprox(in.R_earth_to_body, 0.0));
}

TEST(GuidanceGate, AnUnknownRequestIsDroppedAndRejected) {
  GYRO_VERIFIES("INPUT-2");
  GuidanceGate<double> g;
  GuidanceInput<double> in;
  in.request = static_cast<ModeRequest>(7);
  const GuidanceVerdict v = g.accept(in, kMaxBodyRate);
  EXPECT_EQ(v.request, ModeRequest::kNone);
  EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kCommandRejected | kNavInvalid));
}

TEST(GuidanceGate, ANonFiniteSlewIsIgnoredAndTheLastOneHeld) {
  GYRO_VERIFIES("INPUT-1");
  GuidanceGate<double> g;
  GuidanceInput<double> in = with_nav(Vector3<double>::Zero());
  in.slew_rate_cmd_rad_s = Vector2<double>(0.3, 0.4);
  (void)g.accept(in, kMaxBodyRate);
  in.slew_rate_cmd_rad_s = Vector2<double>(0.5, kNaN);
  const GuidanceVerdict v = g.accept(in, kMaxBodyRate);
  EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kCommandRejected));
  EXPECT_TRUE(v.nav_ok) << "a bad command field does not cost the navigation";
  EXPECT_EQ(g.slew_cmd_rad_s(), Vector2<double>(0.3, 0.4));
}

TEST(GuidanceGate, NavigationMarkedInvalidIsNoRejectedCommand) {
  GYRO_VERIFIES("INPUT-3");
  GuidanceGate<double> g;
  (void)g.accept(with_nav(Vector3<double>(0.1, 0.2, 0.3)), kMaxBodyRate);
  GuidanceInput<double> in = with_nav(Vector3<double>(9, 9, 9));
  in.nav_valid = false;
  const GuidanceVerdict v = g.accept(in, kMaxBodyRate);
  EXPECT_FALSE(v.nav_ok);
  EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kNavInvalid));
  EXPECT_EQ(g.navigation().body_rate_rad_s(), Vector3<double>(0.1, 0.2, 0.3)) << "the last good one is kept";
}

TEST(GuidanceGate, NavigationMarkedValidButUnusableIsRejected) {
  GYRO_VERIFIES("INPUT-4");
  GuidanceInput<double> not_rotation = with_nav(Vector3<double>::Zero());
  not_rotation.R_earth_to_body(0, 0) = 1.5;
  const double just_beyond = std::nextafter(kMaxBodyRate, 1e3);
  for (const GuidanceInput<double>& in :
       {with_nav(Vector3<double>(0, kNaN, 0)), with_nav(Vector3<double>(0, 0, 4.0000001)),
        with_nav(Vector3<double>(-just_beyond, 0, 0)), not_rotation}) {
    GuidanceGate<double> g;
    const GuidanceVerdict v = g.accept(in, kMaxBodyRate);
    EXPECT_FALSE(v.nav_ok);
    EXPECT_EQ(v.flags, static_cast<std::uint32_t>(kNavInvalid | kCommandRejected));
    EXPECT_EQ(g.navigation().body_rate_rad_s(), Vector3<double>::Zero());
  }
}

TEST(GuidanceGate, ABodyRateAtItsLimitIsBelieved) {
  GYRO_VERIFIES("INPUT-4");
  GuidanceGate<double> g;
  const GuidanceVerdict v = g.accept(with_nav(Vector3<double>(-kMaxBodyRate, 0, kMaxBodyRate)), kMaxBodyRate);
  EXPECT_TRUE(v.nav_ok);
  EXPECT_EQ(v.flags, 0u);
}

TEST(GuidanceGate, TheMeanRateIsOfTheLastTwoUsableRates) {
  GYRO_VERIFIES("EST-2");
  GuidanceGate<double> g;
  (void)g.accept(with_nav(Vector3<double>(1, 2, 3)), kMaxBodyRate);
  GuidanceInput<double> lost = with_nav(Vector3<double>(-3, -3, -3));
  lost.nav_valid = false;
  (void)g.accept(lost, kMaxBodyRate);
  (void)g.accept(with_nav(Vector3<double>(3, 2, 1)), kMaxBodyRate);
  EXPECT_EQ(g.navigation().mean_body_rate_rad_s(), Vector3<double>(2, 2, 2));
}

}  // namespace guidance_gate_test
}  // namespace gyro
