// The rotor dynamics never touch the heap, in float and double: every call runs inside
// gyro::test::measure_heap (tests/support/heap_guard.hpp), which counts operator new/delete
// and malloc/free, and bans Eigen's dynamic allocation (EIGEN_RUNTIME_NO_MALLOC). The canaries
// first show that each check fires.
//
// To prove more code heap-free, add a test with the same pattern:
//   const HeapUse use = measure_heap([&] { st = code_under_test(...); });
//   expect_no_heap(use, "what");
#define EIGEN_RUNTIME_NO_MALLOC          // before any Eigen header
#define GYRO_HEAP_GUARD_IMPLEMENTATION   // this executable's operator new replacement
#include "support/heap_guard.hpp"

#if defined(NDEBUG)
#error "no_heap_test needs assertions: Eigen's EIGEN_RUNTIME_NO_MALLOC check is an eigen_assert"
#endif

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "gyro/gimbal_plant.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/nutation.hpp"
#include "gyro/rotor_transition.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/seeker_gimbal.hpp"
#include "gyro/sil_loop.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

using test::HeapCounter;
using test::HeapUse;
using test::measure_heap;

// Keeps the optimiser from removing an allocation whose result is otherwise unused.
void escape(const void* p) { __asm__ __volatile__("" : : "g"(p) : "memory"); }
// A size the compiler cannot see.
int opaque(int n) {
  volatile int v = n;
  return v;
}

void expect_no_heap(const HeapUse& use, const char* what) {
  EXPECT_EQ(use.allocations, 0U) << what << " allocated";
  EXPECT_EQ(use.releases, 0U) << what << " released heap memory";
}

// ----------------------------------------------------------------------------------------------
// Canaries: each check catches what it is meant to.

TEST(HeapGuardCanary, GivenOperatorNewAndAVectorWhenCountedThenBothSeen) {
  GYRO_VERIFIES("RULE-1");
  const HeapCounter counter;
  {
    std::unique_ptr<int> p = std::make_unique<int>(3);
    escape(p.get());
    std::vector<double> v(static_cast<std::size_t>(opaque(100)), 1.0);
    escape(v.data());
  }
  const HeapUse use = counter.used();
  EXPECT_GE(use.allocations, 2U);
  EXPECT_GE(use.releases, 2U);
}

TEST(HeapGuardCanary, GivenADynamicEigenMatrixWhenCountedThenItsMallocSeen) {
  GYRO_VERIFIES("RULE-1");
  // Eigen allocates with std::malloc, which the counter sees through the linker's --wrap.
  const HeapCounter counter;
  {
    Eigen::MatrixXd m = Eigen::MatrixXd::Constant(opaque(8), opaque(8), 1.0);
    escape(m.data());
  }
  const HeapUse use = counter.used();
  EXPECT_GE(use.allocations, 1U);
  EXPECT_GE(use.releases, 1U);
}

TEST(HeapGuardCanary, GivenFixedSizeEigenWhenCountedThenNothingSeen) {
  GYRO_VERIFIES("RULE-1");
  // The counter does not see the test framework or anything else outside the region.
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  const HeapUse use = measure_heap([&] {
    m = Eigen::Matrix4d::Identity() * opaque(2);
    m = m * m;
    escape(m.data());
  });
  expect_no_heap(use, "fixed-size Eigen");
  EXPECT_EQ(m(0, 0), 4.0);
}

TEST(HeapGuardCanaryDeathTest, GivenEigenMallocBannedWhenDynamicMatrixThenEigenAborts) {
  GYRO_VERIFIES("RULE-1");
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::MatrixXd m(opaque(8), opaque(8));
        escape(m.data());
      },
      "heap allocation is forbidden");
  // measure_heap bans it the same way.
  EXPECT_DEATH(
      {
        const HeapUse use = measure_heap([] {
          Eigen::VectorXf v(opaque(16));
          escape(v.data());
        });
        escape(&use);
      },
      "heap allocation is forbidden");
}

// ----------------------------------------------------------------------------------------------
// The rotor dynamics.

template <typename T>
class NoHeap : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(NoHeap, Scalars);

// One rotor per branch of the transition: series, closed form (under- and near-critically
// damped), separated real eigenvalues (overdamped), H = 0, f = 0, and f = H = 0.
template <typename T>
std::vector<RotorParameters<T>> rotors_in_every_regime() {
  return {
      {T(2.25), T(2), T(5), angular_momentum(T(100), T(3))},  // the report's gyro
      {T(2), T(2), T(3), T(0)},                               // critical (beta^2 = 0 exactly)
      {T(1), T(4), T(4) / T(3), T(1)},                        // near critical, J1 != J2
      {T(1), T(50), T(400), T(3)},                            // overdamped, stiff
      {T(0.5), T(5), T(2), T(0)},                             // no spin
      {T(1), T(2), T(0), T(10)},                              // no friction
      {T(1), T(3), T(0), T(0)},                               // free
  };
}

TYPED_TEST(NoHeap, GivenEveryRegimeAndStepWhenTransitionAdvanceAndPropagateThenNoHeap) {
  GYRO_VERIFIES("RULE-1");
  using T = TypeParam;
  const Vector2<T> torque(T(0.7), T(-1.3));
  for (const RotorParameters<T>& p : rotors_in_every_regime<T>()) {
    for (const T dt : {T(1e-6), T(1e-3), T(0.1), T(10)}) {
      RotorTransition<T> tr;
      RotorState<T> a, b;
      a.rate_rad_s = Vector2<T>(T(0.5), T(0.3));
      b = a;
      Status st_make = Status::kNotConfigured, st_adv = Status::kNotConfigured, st_prop = Status::kNotConfigured;
      const HeapUse use = measure_heap([&] {
        st_make = make_transition(p, dt, tr);
        st_adv = advance(tr, torque, a);
        st_prop = propagate(p, dt, torque, b);
      });
      expect_no_heap(use, "make_transition/advance/propagate");
      EXPECT_EQ(st_make, Status::kOk);
      EXPECT_EQ(st_adv, Status::kOk);
      EXPECT_EQ(st_prop, Status::kOk);
      EXPECT_EQ(a.angle_rad, b.angle_rad);
    }
  }
}

TYPED_TEST(NoHeap, GivenEveryRegimeWhenModesAmplitudeAndPrecessionThenNoHeap) {
  GYRO_VERIFIES("RULE-1");
  using T = TypeParam;
  const Vector2<T> torque(T(0.7), T(-1.3));
  for (const RotorParameters<T>& p : rotors_in_every_regime<T>()) {
    RotorModes<T> modes;
    Vector2<T> amp = Vector2<T>::Zero(), w_ss = Vector2<T>::Zero(), back = Vector2<T>::Zero();
    Status st_modes = Status::kNotConfigured, st_amp = Status::kNotConfigured;
    const HeapUse use = measure_heap([&] {
      st_modes = compute_modes(p, modes);
      st_amp = nutation_amplitude(p, Vector2<T>(T(0.5), T(0.3)), torque, amp);
      if (steady_precession_rate(p, torque, w_ss) == Status::kOk) {
        (void)torque_for_precession_rate(p, w_ss, back);
      }
    });
    expect_no_heap(use, "compute_modes/nutation_amplitude/steady_precession_rate/torque_for_precession_rate");
    EXPECT_EQ(st_modes, Status::kOk);
    EXPECT_EQ(st_amp, Status::kOk);
    EXPECT_TRUE(all_finite(amp));
  }
}

TYPED_TEST(NoHeap, GivenBadInputWhenRejectedThenNoHeap) {
  GYRO_VERIFIES("RULE-1");
  using T = TypeParam;
  const RotorParameters<T> bad{T(-1), T(2), T(5), T(10)};
  const RotorParameters<T> good{T(2.25), T(2), T(5), T(1884)};
  const Vector2<T> nan_torque(std::numeric_limits<T>::quiet_NaN(), T(0));
  RotorTransition<T> tr;
  RotorState<T> s;
  RotorModes<T> modes;
  Vector2<T> out = Vector2<T>::Zero();
  Status st[6] = {};
  const HeapUse use = measure_heap([&] {
    st[0] = make_transition(bad, T(0.01), tr);
    st[1] = make_transition(good, T(-1), tr);
    st[2] = propagate(good, T(0.01), nan_torque, s);
    st[3] = compute_modes(bad, modes);
    st[4] = nutation_amplitude(good, Vector2<T>(T(0), T(0)), nan_torque, out);
    st[5] = steady_precession_rate(RotorParameters<T>{T(1), T(1), T(0), T(0)}, Vector2<T>(T(1), T(0)), out);
  });
  expect_no_heap(use, "rejections");
  EXPECT_EQ(st[0], Status::kNonPositiveInertia);
  EXPECT_EQ(st[1], Status::kNonPositiveStep);
  EXPECT_EQ(st[2], Status::kNonFiniteInput);
  EXPECT_EQ(st[3], Status::kNonPositiveInertia);
  EXPECT_EQ(st[4], Status::kNonFiniteInput);
  EXPECT_EQ(st[5], Status::kNoSteadyState);
}

// ----------------------------------------------------------------------------------------------
// The SIL stub's gimbal plant: configure, start, steps with everything on (contact, motor at
// its limit, Coulomb friction, unbalance, gyro axes), refusals.

TYPED_TEST(NoHeap, GivenTheGimbalPlantWithEverythingOnWhenConfiguredStartedAndSteppedThenNoHeap) {
  GYRO_VERIFIES("RULE-1");
  using T = TypeParam;
  for (const TorquerAxes axes : {TorquerAxes::kGimbal, TorquerAxes::kGyro}) {
    GimbalPlantConfig<T> c = seeker_gimbal_config<T>();
    c.inner_coulomb_torque = T(2e-4);
    c.outer_coulomb_torque = T(2e-4);
    c.mass_unbalance = T(1e-4);
    c.torquer_axes = axes;
    GimbalStart<T> s;
    s.gimbal_angle_rad = Vector2<T>(T(0.3), T(0.2));
    s.gimbal_rate_rad_s = Vector2<T>(T(5), T(-5));
    s.spin_hz = T(400);
    BodyState<T> b0, b1;
    b1.rate_rad_s = Vector3<T>(T(2), T(1), T(-1));
    b1.specific_force = Vector3<T>(T(100), T(0), T(-9.8));
    GimbalPlant<T> p;
    ConfigCheck cc;
    Status st[6] = {};
    bool contact = false, saturated = false;
    const HeapUse use = measure_heap([&] {
      cc = p.configure(c, T(5e-4));
      st[0] = p.start(s, b0);
      for (int k = 0; k < 200; ++k) {
        const Status sk = p.step(Vector2<T>(T(0.3), T(0)), k == 0 ? b0 : b1, b1);  // into the stop
        if (sk != Status::kOk) st[1] = sk;
        contact = contact || p.in_contact();
        saturated = saturated || p.motor_saturated();
      }
      st[2] = p.step(Vector2<T>(std::numeric_limits<T>::quiet_NaN(), T(0)), b1, b1);
      st[3] = p.step(Vector2<T>(T(2), T(0)), b1, b1);
      st[4] = p.set_spin_drive(SpinDrive::kFree, T(0));
      st[5] = p.step(Vector2<T>::Zero(), b1, b1);
    });
    expect_no_heap(use, "GimbalPlant");
    EXPECT_TRUE(cc.ok());
    EXPECT_EQ(st[0], Status::kOk);
    EXPECT_EQ(st[1], Status::kOk);
    EXPECT_EQ(st[2], Status::kNonFiniteInput);
    EXPECT_EQ(st[3], Status::kOutOfRange);
    EXPECT_EQ(st[4], Status::kOk);
    EXPECT_EQ(st[5], Status::kOk);
    EXPECT_TRUE(contact);
    EXPECT_TRUE(saturated);
  }
}

// ----------------------------------------------------------------------------------------------
// The SIL loop (body, stub, component), both plants, both ways of feeding the stub the body:
// configure, power-up, caging, uncaging, slewing, a scheduled torquer fault, a refused tick.

TYPED_TEST(NoHeap, GivenTheSilLoopWithBothPlantsWhenStartedAndTickedThroughEveryModeThenNoHeap) {
  GYRO_VERIFIES("RULE-1");
  using T = TypeParam;
  for (const PlantKind plant : {PlantKind::kGimbal, PlantKind::kReport}) {
    for (const StubBodyFeed feed : {StubBodyFeed::kFull, StubBodyFeed::kAttitude}) {
      SimulatedGyroConfig<T> sc = SeekerExample<T>::stub();
      sc.plant = plant;
      sc.pickoff.noise_rad = T(2e-5);
      sc.faults[0].kind = FaultKind::kDeadTorquer;
      sc.faults[0].start_tick = 900;
      SimulatedGyro<T> stub;
      GyroComponent<T> component(stub);
      SilLoop<T, GyroComponent<T>> loop(stub, component, feed);
      const Vector2<T> pitch_yaw(T(0.1), T(-0.05));
      BodySample<T> body = turning_body(Matrix3<T>(Matrix3<T>::Identity()), pitch_yaw);
      body.specific_force = Vector3<T>(T(0), T(5), T(-30));
      GuidanceCommand<T> command;
      ConfigCheck stub_check, component_check;
      SilStatus<Status> started;
      Status worst = Status::kOk, refused = Status::kOk;
      const HeapUse use = measure_heap([&] {
        stub_check = stub.configure(sc);
        component_check = component.configure(SeekerExample<T>::component());
        started = loop.start(body);
        const Matrix3<T> turn = pitch_then_yaw_turn(pitch_yaw, SeekerExample<T>::kTick);
        for (std::uint64_t k = 0; k <= 1000; ++k) {
          if (k > 0) body.R_earth_to_body = turn * body.R_earth_to_body;
          command.request = k == 100 ? ModeRequest::kUncage : ModeRequest::kNone;
          command.slew_rate_cmd_rad_s = k < 700 ? Vector2<T>(Vector2<T>::Zero()) : Vector2<T>(T(0.3), T(-0.2));
          const SilStatus<Status> s = loop.tick(k, body, command);
          if (s.stub != Status::kOk) worst = s.stub;
          if (s.component != Status::kOk) worst = s.component;
        }
        BodySample<T> bad = body;
        bad.R_earth_to_body(0, 0) = T(2);  // not a rotation: the stub refuses the tick
        refused = loop.tick(1001, bad, command).stub;
      });
      expect_no_heap(use, "SilLoop");
      EXPECT_TRUE(stub_check.ok());
      EXPECT_TRUE(component_check.ok());
      EXPECT_EQ(started.stub, Status::kOk);
      EXPECT_EQ(started.component, Status::kOk);
      EXPECT_EQ(worst, Status::kOk);
      EXPECT_EQ(refused, Status::kInvalidRotation);
      EXPECT_EQ(component.mode(), GyroMode::kFault) << "the dead torquer latched safe mode";
    }
  }
}

}  // namespace
}  // namespace gyro
