// The SIL loop (gyro/sil_loop.hpp): its order of operations, its refusals, and two loops with
// the same inputs bit for bit alike. (That it never touches the heap: no_heap_test.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "support/requirements.hpp"
#include "support/sil_fixture.hpp"

namespace gyro {
namespace {

using testing::identical;
using testing::same_bits;

template <typename T>
class SilLoopTest : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SilLoopTest, Scalars);

// A run with everything that draws numbers or changes course: pickoff noise and lag, a
// torquer scale error, a rolling body with specific force, uncaging, slewing.
template <typename T>
struct LoopRun {
  SimulatedGyro<T> stub;
  GyroComponent<T> component{stub};
  SilLoop<T, GyroComponent<T>> loop;

  explicit LoopRun(StubBodyFeed feed) : loop(stub, component, feed) {
    SimulatedGyroConfig<T> s = SeekerExample<T>::stub();
    s.pickoff.noise_rad = T(2e-5);
    s.pickoff.lag_s = T(2e-4);
    s.torquer.scale_factor = Vector2<T>(T(1.01), T(0.99));
    s.seed = 11;
    EXPECT_TRUE(stub.configure(s).ok());
    EXPECT_TRUE(component.configure(SeekerExample<T>::component()).ok());
  }

  // The body at tick k: turning at constant rates (p, q, r) = (1, 0.2, -0.1) rad/s from level,
  // with a lateral and a normal specific force.
  static BodySample<T> body_at(std::uint64_t k) {
    const Eigen::Vector3d w(1.0, 0.2, -0.1);
    const double t = static_cast<double>(k) * 5e-4;
    BodySample<T> b;
    b.R_earth_to_body = Eigen::AngleAxisd(-w.norm() * t, w.normalized()).toRotationMatrix().cast<T>();
    b.rate_rad_s = w.cast<T>();
    b.specific_force = Vector3<T>(T(0), T(5), T(-30));
    return b;
  }
  static GuidanceCommand<T> command_at(std::uint64_t k) {
    GuidanceCommand<T> c;
    c.request = k == 100 ? ModeRequest::kUncage : ModeRequest::kNone;
    if (k > 700) c.slew_rate_cmd_rad_s = Vector2<T>(T(0.3), T(-0.2));
    return c;
  }
};

TYPED_TEST(SilLoopTest, GivenTwoLoopsWithIdenticalInputsThenEveryTickIsBitIdentical) {
  GYRO_VERIFIES("STUB-2");
  using T = TypeParam;
  for (const StubBodyFeed feed : {StubBodyFeed::kFull, StubBodyFeed::kAttitude}) {
    LoopRun<T> a(feed), b(feed);
    ASSERT_EQ(a.loop.start(LoopRun<T>::body_at(0)).component, Status::kOk);
    ASSERT_EQ(b.loop.start(LoopRun<T>::body_at(0)).component, Status::kOk);
    for (std::uint64_t k = 0; k <= 1500; ++k) {
      const SilStatus<Status> sa = a.loop.tick(k, LoopRun<T>::body_at(k), LoopRun<T>::command_at(k));
      const SilStatus<Status> sb = b.loop.tick(k, LoopRun<T>::body_at(k), LoopRun<T>::command_at(k));
      ASSERT_EQ(sa.stub, Status::kOk) << k;
      ASSERT_EQ(sa.component, sb.component) << k;
      ASSERT_TRUE(identical(a.component.telemetry(), b.component.telemetry())) << "tick " << k;
      ASSERT_TRUE(same_bits(a.stub.gimbal_angle_rad(), b.stub.gimbal_angle_rad())) << "tick " << k;
      ASSERT_TRUE(same_bits(a.stub.spin_axis_rate_rad_s(), b.stub.spin_axis_rate_rad_s())) << "tick " << k;
      ASSERT_TRUE(same_bits(a.stub.applied_torque(), b.stub.applied_torque())) << "tick " << k;
    }
    EXPECT_EQ(a.component.mode(), GyroMode::kFree);
    EXPECT_GT(a.component.telemetry().torque_cmd.cwiseAbs().maxCoeff(), T(0)) << "the run slewed";
  }
}

TYPED_TEST(SilLoopTest, GivenATickThenTheStubAdvancesFirstAndHoldsTheTorqueTheComponentWrote) {
  GYRO_VERIFIES("STUB-2");
  using T = TypeParam;
  LoopRun<T> r(StubBodyFeed::kFull);
  ASSERT_EQ(r.loop.start(LoopRun<T>::body_at(0)).component, Status::kOk);
  // Tick 0 is the power-up conversion: the component steps, the stub stays at tick 0.
  ASSERT_EQ(r.loop.tick(0, LoopRun<T>::body_at(0), LoopRun<T>::command_at(0)).component, Status::kOk);
  EXPECT_EQ(r.stub.tick(), 0u);
  EXPECT_EQ(r.component.telemetry().tick, 0u);
  for (std::uint64_t k = 1; k <= 800; ++k) {
    const BodySample<T> body = LoopRun<T>::body_at(k);
    ASSERT_EQ(r.loop.tick(k, body, LoopRun<T>::command_at(k)).component, Status::kOk);
    ASSERT_EQ(r.stub.tick(), k);
    ASSERT_EQ(r.component.telemetry().tick, k);
    // What the component wrote this tick is what the stub holds for the next interval.
    ASSERT_EQ(r.stub.torque_command(), r.component.telemetry().torque_cmd) << k;
    // The component was given this tick's body and the command.
    ASSERT_TRUE(same_bits(r.loop.input().R_earth_to_body, body.R_earth_to_body)) << k;
    ASSERT_TRUE(same_bits(r.loop.input().body_rate_rad_s, body.rate_rad_s)) << k;
    ASSERT_EQ(r.loop.input().request, LoopRun<T>::command_at(k).request);
    ASSERT_TRUE(same_bits(r.stub.body().rate_rad_s, body.rate_rad_s)) << "the full body reached the stub";
  }
}

TYPED_TEST(SilLoopTest, GivenTheAttitudeFeedThenTheStubTakesTheRateFromTheAttitudesAndTheForceAcross) {
  GYRO_VERIFIES("STUB-2");
  using T = TypeParam;
  LoopRun<T> r(StubBodyFeed::kAttitude);
  BodySample<T> body = turning_body(Matrix3<T>(Matrix3<T>::Identity()), Vector2<T>(T(0.4), T(-0.3)));
  body.rate_rad_s(0) = T(5);  // told to the component only
  body.specific_force = Vector3<T>(T(7), T(5), T(-30));
  ASSERT_EQ(r.loop.start(body).component, Status::kOk);
  EXPECT_EQ(r.stub.body().rate_rad_s(0), T(0)) << "power-up from the pitch and yaw rates";
  EXPECT_EQ(r.stub.body().specific_force, Vector3<T>::Zero());
  body.R_earth_to_body = pitch_then_yaw_turn(Vector2<T>(T(0.4), T(-0.3)), SeekerExample<T>::kTick);
  ASSERT_EQ(r.loop.tick(1, body, GuidanceCommand<T>{}).component, Status::kOk);
  EXPECT_NEAR(static_cast<double>(r.stub.body().rate_rad_s(0)), 0.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(r.stub.body().rate_rad_s(1)), 0.4, 1e-3);
  EXPECT_NEAR(static_cast<double>(r.stub.body().rate_rad_s(2)), -0.3, 1e-3);
  EXPECT_EQ(r.stub.body().specific_force, Vector3<T>(T(0), T(5), T(-30)));
  EXPECT_EQ(r.loop.input().body_rate_rad_s(0), T(5));
}

TYPED_TEST(SilLoopTest, GivenARefusedStubThenTheComponentIsNotCalled) {
  using T = TypeParam;
  SimulatedGyro<T> stub;  // never configured
  GyroComponent<T> component(stub);
  ASSERT_TRUE(component.configure(SeekerExample<T>::component()).ok());
  SilLoop<T, GyroComponent<T>> loop(stub, component);
  EXPECT_EQ(loop.start(LoopRun<T>::body_at(0)).stub, Status::kNotConfigured);
  EXPECT_EQ(component.mode(), GyroMode::kIdle) << "not activated";

  LoopRun<T> r(StubBodyFeed::kFull);
  ASSERT_EQ(r.loop.start(LoopRun<T>::body_at(0)).component, Status::kOk);
  ASSERT_EQ(r.loop.tick(1, LoopRun<T>::body_at(1), LoopRun<T>::command_at(1)).component, Status::kOk);
  BodySample<T> bad = LoopRun<T>::body_at(2);
  bad.rate_rad_s(1) = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(r.loop.tick(2, bad, LoopRun<T>::command_at(2)).stub, Status::kNonFiniteInput);
  EXPECT_EQ(r.component.telemetry().tick, 1u) << "not stepped";
  EXPECT_EQ(r.loop.tick(3, LoopRun<T>::body_at(3), LoopRun<T>::command_at(3)).stub, Status::kOutOfRange)
      << "the stub is still at tick 1";
  EXPECT_EQ(r.loop.tick(2, LoopRun<T>::body_at(2), LoopRun<T>::command_at(2)).component, Status::kOk);
}

// A flight computer that skips ticks (a processor in the loop that overran): its result
// passes through as it is.
struct SkippingComputer {
  GyroComponent<double>& component;
  [[nodiscard]] Status activate() { return component.activate(); }
  [[nodiscard]] std::optional<Status> step(std::uint64_t k, const GuidanceInput<double>& in) {
    if (k % 3 == 2) return std::nullopt;
    return component.step(k, in);
  }
};

TEST(SilLoop, GivenAComputerThatSkipsTicksThenTheStubStillAdvancesAndTheSkipIsReported) {
  GYRO_VERIFIES("STUB-2", "TICK-2");
  LoopRun<double> r(StubBodyFeed::kFull);
  SkippingComputer computer{r.component};
  SilLoop<double, SkippingComputer> loop(r.stub, computer);
  ASSERT_EQ(loop.start(LoopRun<double>::body_at(0)).component, Status::kOk);
  for (std::uint64_t k = 1; k <= 30; ++k) {
    const SilStatus<std::optional<Status>> s = loop.tick(k, LoopRun<double>::body_at(k), LoopRun<double>::command_at(k));
    ASSERT_EQ(s.stub, Status::kOk);
    ASSERT_EQ(r.stub.tick(), k);
    EXPECT_EQ(s.component.has_value(), k % 3 != 2) << k;
  }
}

}  // namespace
}  // namespace gyro
