// What the configuration contract accepts, flies (docs/component.md, "Configuration
// contract"): configurations drawn across the accepted space, corners included (a fixed seed),
// each flown against the SIL stub: caged, uncaged, slewing, holding, caged again, with the body
// turning. No lock-out (every cage and uncage request honoured), no fault latched, no contact
// with the stop (the stub reports the truth at its stop).
//
// The stub's plant is the gimbal (the device, not the estimator's model: the report's plant
// would differ from the component's model by the friction on inertial rather than relative
// rates, which no configuration rule is about), at its coarsest sub-step (2 rad of the fastest
// mode's phase), the seeker example's construction scaled to the drawn rotor.
// GYRO_CONTRACT_CONFIGS sets how many accepted configurations are flown (default 100: the
// normal suite; docs/component.md records a run of 10,000); GYRO_CONTRACT_FIRST_SEED the first
// seed drawn (default 1), so that a campaign can be split and one failure flown again alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "gyro/component_config.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/sil_contract.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "gyro/torque_shaper.hpp"
#include "support/requirements.hpp"

namespace gyro {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Uniform draws in [0, 1); a corner draw gives 0 or 1 only, putting every derived quantity at
// an end of the range it is drawn from.
class Draw {
 public:
  Draw(std::uint64_t seed, bool corner) : rng_(seed), corner_(corner) {}
  double u() {
    const double x = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
    return corner_ ? (x < 0.5 ? 0.0 : 1.0) : x;
  }
  double lu(double lo, double hi) { return hi > lo ? lo * std::pow(hi / lo, u()) : lo; }  // log-uniform
  std::uint32_t count(double lo, double hi) {
    return static_cast<std::uint32_t>(std::clamp(std::floor(lu(lo, hi)), lo, hi));
  }
  bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }

 private:
  std::mt19937_64 rng_;
  bool corner_;
};

struct Drawn {
  GyroComponentConfig<double> component;
  SimulatedGyroConfig<double> stub;
  double body_rate_rad_s{};  // the body's pitch rate while flown
};

Drawn draw(std::uint64_t seed, bool corner) {
  Draw d(seed, corner);
  Drawn out;
  GyroComponentConfig<double>& c = out.component;
  c.tick_s = d.lu(1e-5, 0.1);
  c.pitch_inertia = d.lu(1e-10, 1e2);
  c.yaw_inertia = c.pitch_inertia * d.lu(0.7, 1.4);
  c.spin_inertia = c.pitch_inertia * d.lu(0.5, 1.8);
  c.friction = d.chance(0.1) ? 0.0 : c.pitch_inertia * d.lu(0.1, 200.0);
  c.nominal_spin_hz = d.lu(10.0, 2000.0);
  c.min_spin_hz = c.nominal_spin_hz * 0.9 * d.u();
  c.use_spin_readback = d.chance(0.5);
  c.friction_compensation = !d.chance(0.2);
  c.small_angle_limit_rad = d.chance(0.5) ? 0.01 : d.lu(1e-3, 0.1);
  const double max_rate = std::min(100.0, c.small_angle_limit_rad / c.tick_s);
  c.max_pitch_rate_rad_s = d.lu(1e-3, max_rate);
  c.max_yaw_rate_rad_s = d.lu(1e-3, max_rate);
  const double rate = std::max(c.max_pitch_rate_rad_s, c.max_yaw_rate_rad_s);
  const double h = kTwoPi * c.nominal_spin_hz * c.spin_inertia;
  c.max_torque = d.lu(kAuthorityFraction * h * rate,
                      kNutationShare * c.small_angle_limit_rad * h * h / std::max(c.pitch_inertia, c.yaw_inertia));
  // (The nutation frequency of the flown rotor: the yaw inertia is set to the pitch's below.)
  c.cage_gain_1_s = d.lu(0.1, std::min({1e5, 1.0 / c.tick_s, kCageNutationShare * h / c.pitch_inertia}));
  c.gimbal_cone_limit_rad = d.lu(1e-2, 1.3);  // the gimbal plant's stop is at most 80 deg
  c.pickoff_range_rad = c.gimbal_cone_limit_rad * d.lu(1.0, 1.5707963267948966 / c.gimbal_cone_limit_rad);
  const double shaper_ticks = 1.0 + 2.0 * design_shaper(h / c.pitch_inertia * c.tick_s).spacing;
  c.gimbal_stop_margin_rad = d.lu(shaper_ticks * rate * c.tick_s, 0.9 * c.gimbal_cone_limit_rad);
  const double lsb = d.chance(0.3) ? 0.0 : d.lu(1e-7, 1e-3);
  const double noise = d.chance(0.3) ? 0.0 : d.lu(1e-7, 1e-3);
  const double floor = std::max({2 * lsb + 9 * noise, 1e-6, 64 * 2.3e-16 * c.pickoff_range_rad});
  c.residual_limit_rad = d.lu(std::max(floor, rate * c.tick_s), 0.9 * c.gimbal_cone_limit_rad);
  const double nutation = c.max_torque * std::max(c.pitch_inertia, c.yaw_inertia) / (h * h);
  c.max_pickoff_step_rad = d.lu(std::max(2 * (rate * c.tick_s + nutation), 2 * lsb + 9 * noise), c.pickoff_range_rad);
  c.estimator_gain = d.u();
  const double longest = std::floor(kLongestConfiguredTime_s / c.tick_s);
  c.residual_persistence_ticks = d.count(1, longest);
  c.invalid_persistence_ticks = d.count(1, longest);
  c.spin_low_persistence_ticks = d.count(1, longest);
  c.torquer_fail_persistence_ticks = d.count(1, longest);
  c.uncage_settle_ticks = d.chance(0.1) ? 0u : d.count(1, longest);
  c.max_tick_gap = d.count(1, longest);
  c.input_persistence_ticks = d.count(1, longest);
  c.max_body_rate_rad_s = d.lu(rate, std::min(1e4, kPi<double> / c.tick_s));
  if (d.chance(0.5)) {
    c.pickoff_lsb_rad = lsb;
    c.pickoff_noise_rad = noise;
  }

  SimulatedGyroConfig<double>& s = out.stub;
  s.plant = PlantKind::kGimbal;
  // The seeker example's construction (gyro/seeker_example.hpp), scaled: effective inertias at
  // zero gimbal angles J1 = Iy + A and J2 = Oz + Iz + A both the component's pitch inertia.
  c.yaw_inertia = c.pitch_inertia;
  const double j = c.pitch_inertia, a = 0.9 * j, ring = (j - a) / 2;
  GimbalPlantConfig<double>& g = s.gimbal;
  g.spin_inertia = c.spin_inertia;
  g.rotor_transverse_inertia = a;
  g.inner_gimbal_inertia = Vector3<double>(ring, j - a, ring);
  g.outer_gimbal_inertia = Vector3<double>(2 * ring, ring, ring);
  g.inner_friction = c.friction;
  g.outer_friction = c.friction;
  g.spin_drive = SpinDrive::kMotor;
  g.max_spin_hz = c.nominal_spin_hz;
  g.motor_torque_limit = 100 * c.max_torque;
  g.spin_servo_bandwidth_rad_s = 5;
  g.stop_cone_rad = std::min(1.3962634015954636, c.gimbal_cone_limit_rad * d.lu(1.02, 1.5));
  g.stop_restitution = 0.2;
  g.max_body_rate_rad_s = 1e4;
  g.max_torque = 1e3 * c.max_torque;
  g.max_specific_force = 1e4;
  g.max_substep_phase_rad = 2.0;  // the coarsest the plant accepts: cheap, still a gimbal
  s.gyro.pitch_inertia = c.pitch_inertia;
  s.gyro.yaw_inertia = c.yaw_inertia;
  s.gyro.spin_inertia = c.spin_inertia;
  s.gyro.friction = c.friction;
  s.gyro.gimbal_cone_limit_rad = c.gimbal_cone_limit_rad;
  s.gyro.max_pitch_rate_rad_s = 1e4;
  s.gyro.max_yaw_rate_rad_s = 1e4;
  s.gyro.small_angle_limit_rad = c.small_angle_limit_rad;
  s.gimbal_stop_rad = g.stop_cone_rad;
  s.tick_s = c.tick_s;
  s.spin_hz = c.nominal_spin_hz;
  s.has_spin_readback = true;
  s.pickoff.lsb_rad = lsb;
  s.pickoff.noise_rad = noise;
  s.pickoff.range_rad = c.pickoff_range_rad;
  s.torquer.max_torque = c.max_torque * d.lu(1.0, 3.0);
  s.seed = seed;
  // The body turns at a fraction of what the torquer can follow and the gyro slews.
  out.body_rate_rad_s = 0.3 * std::min({c.max_pitch_rate_rad_s, c.max_yaw_rate_rad_s, c.max_torque / h});
  return out;
}

// What went wrong in one flight ("" when it flew).
struct Flight {
  std::string failure;
  std::uint64_t ticks{0};
};

Flight fly(const Drawn& dr) {
  const GyroComponentConfig<double>& c = dr.component;
  SimulatedGyro<double> gyro;
  GyroComponent<double> component{gyro};
  SilLoop<double, GyroComponent<double>> loop{gyro, component, StubBodyFeed::kAttitude};
  Flight f;
  if (!gyro.configure(dr.stub).ok()) return {"stub refused", 0};
  if (!component.configure(c).ok()) return {"component refused", 0};
  Matrix3<double> R = Matrix3<double>::Identity();
  const Vector2<double> body(dr.body_rate_rad_s, 0.0);
  if (loop.start(turning_body(R, body)).component != Status::kOk) return {"start refused", 0};
  const auto phase = [&](double seconds) {
    return static_cast<std::uint64_t>(std::clamp(std::ceil(seconds / c.tick_s), 20.0, 500.0));
  };
  std::ostringstream why;
  const auto run = [&](std::uint64_t n, ModeRequest first, const Vector2<double>& slew) {
    for (std::uint64_t k = 0; k < n; ++k) {
      R = pitch_then_yaw_turn(body, c.tick_s) * R;
      GuidanceCommand<double> cmd;
      cmd.request = k == 0 ? first : ModeRequest::kNone;
      cmd.slew_rate_cmd_rad_s = slew;
      cmd.nav_valid = true;
      ++f.ticks;
      const auto ran = loop.tick(f.ticks, turning_body(R, body), cmd);
      if (ran.stub != Status::kOk) {
        why << "stub step " << to_string(ran.stub) << " at tick " << f.ticks;
        return false;
      }
      const GyroTelemetry<double>& tm = component.telemetry();
      if (component.mode() == GyroMode::kFault || (tm.flags & kFaultLatched) != 0u) {
        why << "fault latched at tick " << f.ticks << " (flags 0x" << std::hex << tm.flags << std::dec << ")";
        return false;
      }
      if (gyro.at_gimbal_stop()) {
        why << "stop contact at tick " << f.ticks;
        return false;
      }
    }
    return true;
  };
  const Vector2<double> zero = Vector2<double>::Zero();
  const Vector2<double> slew(0.5 * c.max_pitch_rate_rad_s, -0.5 * c.max_yaw_rate_rad_s);
  const double slew_s = std::min(0.2, 0.3 * c.gimbal_cone_limit_rad / (slew.norm() + dr.body_rate_rad_s));
  if (!run(phase(0.05), ModeRequest::kNone, zero)) return {why.str(), f.ticks};
  if (component.mode() != GyroMode::kCaged) return {"not caged after activation", f.ticks};
  if (!run(1, ModeRequest::kUncage, zero)) return {why.str(), f.ticks};
  if (component.mode() != GyroMode::kUncaging && component.mode() != GyroMode::kFree) {
    return {"uncage refused: a lock-out (flags 0x" + [&] {
              std::ostringstream h;
              h << std::hex << component.telemetry().flags;
              return h.str();
            }() + ")", f.ticks};
  }
  if (!run(std::uint64_t{c.uncage_settle_ticks} + 1u, ModeRequest::kNone, zero)) return {why.str(), f.ticks};
  if (component.mode() != GyroMode::kFree) return {"not free after the settle time", f.ticks};
  if (!run(phase(slew_s), ModeRequest::kNone, slew)) return {why.str(), f.ticks};
  if (!run(phase(0.2), ModeRequest::kNone, zero)) return {why.str(), f.ticks};
  if (!run(1, ModeRequest::kCage, zero)) return {why.str(), f.ticks};
  if (component.mode() != GyroMode::kCaged) return {"cage refused: a lock-out", f.ticks};
  if (!run(phase(0.05), ModeRequest::kNone, zero)) return {why.str(), f.ticks};
  return f;
}

std::uint64_t wanted() {
  const char* env = std::getenv("GYRO_CONTRACT_CONFIGS");
#if defined(GYRO_TEST_UNDER_EMULATION)
  constexpr std::uint64_t kSuiteCount = 10;  // under qemu-user 100 flights take minutes; the host flies 100
#else
  constexpr std::uint64_t kSuiteCount = 100;
#endif
  return env != nullptr ? std::strtoull(env, nullptr, 10) : kSuiteCount;
}

std::uint64_t first_seed() {
  const char* env = std::getenv("GYRO_CONTRACT_FIRST_SEED");
  return env != nullptr ? std::max<std::uint64_t>(1, std::strtoull(env, nullptr, 10)) : 1;
}

TEST(ConfigContractProperty, GivenAcceptedConfigsWHENFlownTHENNoLockOutFaultOrStop) {
  GYRO_VERIFIES("CONF-7");
  const std::uint64_t n = wanted();
  std::uint64_t accepted = 0, drawn = 0, failed = 0, ticks = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::uint64_t seed = first_seed(); accepted < n && drawn < 100 * n + 1000; ++seed) {
    ++drawn;
    const Drawn dr = draw(seed, seed % 4 == 0);
    ConfigCheckList<8> refused;
    check_all(dr.component, refused);
    check_against_hardware(dr.stub, dr.component, refused);
    if (!refused.empty() || !check(dr.stub).ok()) continue;
    ++accepted;
    const Flight f = fly(dr);
    ticks += f.ticks;
    if (!f.failure.empty()) {
      ++failed;
      if (failed <= 10) {
        ADD_FAILURE() << "seed " << seed << (seed % 4 == 0 ? " (corner)" : "") << ": " << f.failure
                      << "\n  tick " << dr.component.tick_s << " J " << dr.component.pitch_inertia << " spin "
                      << dr.component.nominal_spin_hz << " rates " << dr.component.max_pitch_rate_rad_s << ", "
                      << dr.component.max_yaw_rate_rad_s << " torque " << dr.component.max_torque << " gain "
                      << dr.component.cage_gain_1_s << " est " << dr.component.estimator_gain << " resid "
                      << dr.component.residual_limit_rad << " cone " << dr.component.gimbal_cone_limit_rad
                      << " margin " << dr.component.gimbal_stop_margin_rad << " settle "
                      << dr.component.uncage_settle_ticks << " body " << dr.body_rate_rad_s;
      } else {
        std::printf("seed %llu%s: %s\n", static_cast<unsigned long long>(seed), seed % 4 == 0 ? " (corner)" : "",
                    f.failure.c_str());
      }
    }
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("flew %llu accepted configurations (%llu drawn), %llu ticks in %.1f s; %llu failed\n",
              static_cast<unsigned long long>(accepted), static_cast<unsigned long long>(drawn),
              static_cast<unsigned long long>(ticks), s, static_cast<unsigned long long>(failed));
  EXPECT_EQ(accepted, n) << "too few draws accepted";
  EXPECT_EQ(failed, 0u);
}

}  // namespace
}  // namespace gyro
