// The runs behind docs/model-validity.md (tools/model_validity.cpp) and its ctest
// (tests/model_validity_test.cpp): the seeker example over its envelope of gimbal cone, body
// turn rate and roll, open loop (GyroModel against the gimbal plant, the same torques held per
// tick) and closed loop (GyroComponent against the SIL stub with the gimbal plant and ideal
// pickoffs). docs/model-validity.md says how the motion is chosen; this is the code of it.
//
// The motion of a case (cone c, turn b, roll p, scan s):
//   body      constant rates (p, b/sqrt2, b/sqrt2), attitude exp(t [w]x) from identity: exact;
//   spin axis at the cone c from body x, at the clock angle phi(t) = (s/sin c - p) t about it:
//             its inertial angular velocity across itself is that of
//               w_path = (0, q, r) + (s/sin c) x_B
//             so it turns with the body's pitch and yaw, not with its roll (the body rolls
//             round it, as round a seeker's line of sight), and scans round body x at s rad/s.
// Open loop the torques are the corrected law's feed-forward along that path (no feedback);
// closed loop guidance commands w_path plus a pull back onto the cone, from the telemetry.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "gyro/gimbal_geometry.hpp"
#include "gyro/gimbal_plant.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/seeker_example.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro::validity {

using V2 = Vector2<double>;
using V3 = Vector3<double>;
using M3 = Matrix3<double>;
using Seeker = SeekerExample<double>;

inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr double kDeg = kPiD / 180.0;

struct Case {
  double cone_rad{};    // c: spin axis to body x
  double turn_rad_s{};  // b: body rate across x, split equally on pitch q and yaw r
  double roll_rad_s{};  // p
  double scan_rad_s{};  // s: spin-axis speed round body x at the cone (0 when c = 0)
};

// A figure in a test's name: "0.5" -> "0p5", no trailing zeros.
inline std::string name_number(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  for (char& ch : s) {
    if (ch == '.') ch = 'p';
  }
  return s;
}

// The body turning at constant rates from the identity attitude: a rotation about a fixed
// axis, exact at any time.
struct BodyTurn {
  V3 rate_rad_s{V3::Zero()};

  explicit BodyTurn(const Case& c) : rate_rad_s(c.roll_rad_s, c.turn_rad_s / std::sqrt(2.0), c.turn_rad_s / std::sqrt(2.0)) {}

  [[nodiscard]] M3 R_earth_to_body(double t) const {
    const double n = rate_rad_s.norm();
    if (!(n > 0.0)) return M3::Identity();
    return Eigen::AngleAxisd(n * t, rate_rad_s / n).toRotationMatrix().transpose();
  }
};

// The spin axis's path in body axes and the angular velocity that keeps it there.
struct Path {
  Case c;

  [[nodiscard]] double scan_rate_1_s() const {
    return c.cone_rad > 0.0 ? c.scan_rad_s / std::sin(c.cone_rad) : 0.0;
  }
  // Clock angle about body x at time t.
  [[nodiscard]] double clock_rad(double t) const { return (scan_rate_1_s() - c.roll_rad_s) * t; }
  // (pitch, yaw) gimbal angles of the path at time t: x_s = (cos c, sin c cos phi, sin c sin phi).
  [[nodiscard]] V2 gimbal_rad(double t) const { return gimbal_on_cone(c.cone_rad, clock_rad(t)); }
  // The inertial angular velocity of the spin axis along the path, body axes.
  [[nodiscard]] V3 angular_velocity(const BodyTurn& body) const {
    return V3(scan_rate_1_s(), body.rate_rad_s(1), body.rate_rad_s(2));
  }

  [[nodiscard]] static V2 gimbal_on_cone(double cone, double clock) {
    const V3 x(std::cos(cone), std::sin(cone) * std::cos(clock), std::sin(cone) * std::sin(clock));
    return gimbal_of_axis(x);
  }
  [[nodiscard]] static V2 gimbal_of_axis(const V3& x) {
    return V2(-std::asin(std::clamp(x(2), -1.0, 1.0)), std::atan2(x(1), x(0)));
  }
  [[nodiscard]] static V3 axis_of_gimbal(const V2& g) {
    return V3(std::cos(g(0)) * std::cos(g(1)), std::cos(g(0)) * std::sin(g(1)), -std::sin(g(0)));
  }
};

// ---------------------------------------------------------------------------------------
// Open loop: the report's model (kGyro: the torques as T1, T2 on its own axes, friction on
// its inertial rates) and the corrected model (kGimbal: torquer commands), both started on
// the plant's state, against the gimbal plant, the same torques held per tick for 1 s.

struct OpenLoopResult {
  bool ok{false};                 // every call accepted
  double report_error_rad{};      // worst |gimbal angle, plant - model| (either axis), kGyro
  double corrected_error_rad{};   // the same, kGimbal
  double report_error_end_rad{};  // at the end of the run
  double corrected_error_end_rad{};
  double max_torque{};            // largest torquer command of the history
  double max_cone_rad{};          // largest cone of the plant
  bool plant_contact{false};      // the plant touched its stop
};

inline GyroModelConfig<double> model_config(TorquerAxes axes, bool frictionless = false) {
  GyroModelConfig<double> m = estimator_config(Seeker::component());
  m.torquer_axes = axes;
  if (frictionless) m.friction = 0.0;
  return m;
}

inline constexpr double kOpenLoopSeconds = 1.0;

// Variants that take one uncorrected effect out, to size it.
struct OpenLoopVariant {
  bool massless_gimbals{false};     // the plant's gimbal rings without inertia (rotor A = J)
  bool models_inertial_spin{false}; // the models given the rotor's inertial spin, not the readback
  bool frictionless{false};         // no bearing friction, in the plant and the models
  bool free_rotor{false};           // the plant's rotor free-running (no spin motor, no drag)
};

inline GimbalPlantConfig<double> plant_config(const OpenLoopVariant& v) {
  GimbalPlantConfig<double> c = Seeker::gimbal();
  if (v.massless_gimbals) {
    c.inner_gimbal_inertia.setZero();
    c.outer_gimbal_inertia.setZero();
    c.rotor_transverse_inertia = Seeker::kJ;
  }
  if (v.free_rotor) {
    c.spin_drive = SpinDrive::kFree;
    c.spin_down_time_s = 0.0;
    c.spin_servo_bandwidth_rad_s = 0.0;
  }
  if (v.frictionless) {
    c.inner_friction = 0.0;
    c.outer_friction = 0.0;
  }
  return c;
}

inline OpenLoopResult run_open_loop(const Case& k, const OpenLoopVariant& variant = {},
                                    double seconds = kOpenLoopSeconds) {
  OpenLoopResult out;
  const double dt = Seeker::kTick;
  const int ticks = static_cast<int>(std::lround(seconds / dt));
  const BodyTurn body(k);
  const Path path{k};
  const double h = angular_momentum(Seeker::kSpinHz, Seeker::kJ0);
  const double f = variant.frictionless ? 0.0 : Seeker::kFriction;

  // Start on the path, moving along it (no nutation to begin with).
  const V2 g0 = path.gimbal_rad(0.0);
  const GimbalFrame<double> f0 = gimbal_frame_at(g0);
  const V2 w0 = body_rate_on_gimbal(f0, path.angular_velocity(body));
  const V2 wb0 = body_rate_on_gimbal(f0, body.rate_rad_s);
  GimbalPlant<double> plant;
  if (!plant.configure(plant_config(variant), dt).ok()) return out;
  GimbalStart<double> start;
  start.gimbal_angle_rad = g0;
  start.gimbal_rate_rad_s = V2(w0(0) - wb0(0), (w0(1) - wb0(1)) / std::cos(g0(0)));
  start.spin_hz = Seeker::kSpinHz;
  const BodyState<double> body_state{body.rate_rad_s, V3::Zero()};
  if (plant.start(start, body_state) != Status::kOk) return out;
  // uncage_on_gimbal takes the gyro's rates from the body rate it is given: hand it the
  // vector whose components on (y_I, z_I) are the path's rates.
  const V3 rate_vector = w0(0) * f0.y_inner_body + w0(1) * f0.z_inner_body;
  GyroModel<double> report, corrected;
  if (!report.configure(model_config(TorquerAxes::kGyro, variant.frictionless)).ok() ||
      !corrected.configure(model_config(TorquerAxes::kGimbal, variant.frictionless)).ok() ||
      report.uncage_on_gimbal(body.R_earth_to_body(0.0), rate_vector, g0) != Status::kOk ||
      corrected.uncage_on_gimbal(body.R_earth_to_body(0.0), rate_vector, g0) != Status::kOk) {
    return out;
  }

  GyroStepInput<double> in;
  in.dt_s = dt;
  in.body_rate_rad_s = body.rate_rad_s;
  for (int i = 0; i < ticks; ++i) {
    // The feed-forward torque of the path at the middle of the tick.
    const double t_mid = (i + 0.5) * dt;
    const GimbalFrame<double> fm = gimbal_frame_at(path.gimbal_rad(t_mid));
    const V2 torque = torquers_for_rate(fm, h, f, body_rate_on_gimbal(fm, path.angular_velocity(body)),
                                        body_rate_on_gimbal(fm, body.rate_rad_s));
    out.max_torque = std::max(out.max_torque, torque.cwiseAbs().maxCoeff());
    // The readback (the spin relative to the inner gimbal), or the rotor's inertial spin.
    in.spin_hz = (variant.models_inertial_spin ? plant.spin_inertial_rad_s() : plant.spin_rate_rad_s()) / (2.0 * kPiD);
    in.R_earth_to_body = body.R_earth_to_body((i + 1) * dt);
    if (plant.step(torque, body_state, body_state) != Status::kOk) return out;
    if (report.step_torque(in, torque) != Status::kOk || corrected.step_torque(in, torque) != Status::kOk) return out;
    const V2 truth = plant.gimbal_angle_rad();
    const double e_report = (truth - V2(report.gimbal_pitch_rad(), report.gimbal_yaw_rad())).cwiseAbs().maxCoeff();
    const double e_corr = (truth - V2(corrected.gimbal_pitch_rad(), corrected.gimbal_yaw_rad())).cwiseAbs().maxCoeff();
    out.report_error_rad = std::max(out.report_error_rad, e_report);
    out.corrected_error_rad = std::max(out.corrected_error_rad, e_corr);
    out.report_error_end_rad = e_report;
    out.corrected_error_end_rad = e_corr;
    out.max_cone_rad = std::max(out.max_cone_rad, plant.cone_rad());
    out.plant_contact = out.plant_contact || plant.in_contact();
  }
  out.ok = true;
  return out;
}

// ---------------------------------------------------------------------------------------
// Closed loop: GyroComponent (SeekerExample::component()) against the SIL stub with the
// gimbal plant (SeekerExample::stub(): ideal pickoffs and torquers). The stub powers up with
// the gimbal at rest relative to the body; the component cages, uncages at kUncageTick
// (torquers off while it settles: the gimbal drifts with the body), and once free, guidance
// commands the path:
//   w_cmd = w_path + pull onto the cone, on (y_I, z_I) at the last measured gimbal angles.
// Measured: the residual from uncaging on; the slew-rate error (the stub's spin-axis rate at
// tick k+1 against the rate the component flew from tick k, telemetry rate_cmd_rad_s) in a 1 s
// window that opens kSettleSeconds after the component goes free.

// Released with the body turning, the rotor nutates (|wb| / beta: 2.7e-4 rad at 1 rad/s) and
// the estimator, started a tick later from the body's rate, misses it by up to 6.3e-4 rad
// until it decays (alpha = 20 1/s): uncaging waits 0.2 s for that.
inline constexpr std::uint64_t kUncageTick = 400;
inline constexpr double kSettleSeconds = 0.8;  // the cone acquired, nutation (alpha = 20 1/s) gone
inline constexpr double kWindowSeconds = 1.0;
inline constexpr double kConeGain_1_s = 4.0;   // pull onto the cone
inline constexpr double kMaxPull_rad_s = 0.5;
inline constexpr double kMinCommand_rad_s = 0.05;  // below this the slew error is absolute only

struct ClosedLoopResult {
  bool ok{false};                      // every call accepted and the component went free
  double worst_residual_caged_rad{};   // before uncaging (the power-up transient)
  double worst_residual_rad{};         // from uncaging on (either axis)
  double worst_residual_uncaging_rad{};  // while uncaging (torquers off)
  std::uint64_t worst_residual_tick{};   // where worst_residual_rad was
  double worst_residual_window_rad{};  // in the window
  bool residual_fault{false};          // a residual fault was raised
  bool fault{false};                   // the component was in safe mode at some tick
  double slew_error_rel{};             // worst |w_true - w_cmd| / |w_cmd| in the window (2-norms)
  double slew_error_rad_s{};           // worst |w_true - w_cmd| in the window
  double min_command_rad_s{1e300};     // smallest |w_cmd| in the window
  double max_command_rad_s{};          // largest per-axis |w_cmd| asked by guidance in the window
  std::uint32_t flags_seen{};          // OR of the component's flags from uncaging on
  std::uint32_t flags_window{};        // OR in the window
  std::uint64_t clipped_ticks{};       // window ticks whose command the rate limit cut
  std::uint64_t saturated_ticks{};     // ticks (from uncaging on) with kTorquerSaturated
  std::uint64_t contact_ticks{};       // ticks the plant was on its stop
  double max_cone_rad{};               // largest true cone after going free
  double cone_min_window_rad{1e300};   // true cone range in the window
  double cone_max_window_rad{};
  double free_at_s{};
  // The first tick (from uncaging on) of: kGimbalLimit, kTorquerSaturated, the plant on its
  // stop, safe mode. 0: never.
  std::uint64_t first_limit_tick{};
  std::uint64_t first_saturated_tick{};
  std::uint64_t first_contact_tick{};
  std::uint64_t first_fault_tick{};
  std::uint32_t flags_before_fault{};  // OR of the flags up to the tick before safe mode
};

// Guidance: the path's angular velocity plus a pull of the spin axis onto the cone at its
// measured clock angle, on (y_I, z_I) at the measured gimbal angles.
inline V2 guidance_command(const Path& path, const BodyTurn& body, const V2& measured) {
  const V3 x = Path::axis_of_gimbal(measured);
  const double radial = std::hypot(x(1), x(2));
  const V3 target = radial > 1e-9 ? Path::axis_of_gimbal(Path::gimbal_on_cone(path.c.cone_rad, std::atan2(x(2), x(1))))
                                  : Path::axis_of_gimbal(Path::gimbal_on_cone(path.c.cone_rad, 0.0));
  V3 pull = kConeGain_1_s * x.cross(target);  // turns x toward target at gain * angle
  const double n = pull.norm();
  if (n > kMaxPull_rad_s) pull *= kMaxPull_rad_s / n;
  return body_rate_on_gimbal(gimbal_frame_at(measured), V3(path.angular_velocity(body) + pull));
}

// The component closed around the stub on a case's turning body, configured and started (the
// body at its t = 0 attitude); `started` false when either side refused.
struct ClosedLoopRig {
  SimulatedGyro<double> stub;
  GyroComponent<double> comp{stub};
  SilLoop<double, GyroComponent<double>> loop{stub, comp};
  BodySample<double> sample;
  bool started{false};

  ClosedLoopRig(const BodyTurn& body, const SimulatedGyroConfig<double>& stub_config,
                const GyroComponentConfig<double>& cc) {
    sample.rate_rad_s = body.rate_rad_s;
    sample.R_earth_to_body = body.R_earth_to_body(0.0);
    if (!stub.configure(stub_config).ok() || !comp.configure(cc).ok()) return;
    const SilStatus<Status> s = loop.start(sample);
    started = s.stub == Status::kOk && s.component == Status::kOk;
  }
  ClosedLoopRig(const ClosedLoopRig&) = delete;
  ClosedLoopRig& operator=(const ClosedLoopRig&) = delete;
};

inline ClosedLoopResult run_closed_loop(const Case& k, double window_s = kWindowSeconds,
                                        const SimulatedGyroConfig<double>& stub_config = Seeker::stub(),
                                        const GyroComponentConfig<double>& cc = Seeker::component()) {
  ClosedLoopResult out;
  const double dt = Seeker::kTick;
  const BodyTurn body(k);
  const Path path{k};
  ClosedLoopRig rig(body, stub_config, cc);
  if (!rig.started) return out;
  SimulatedGyro<double>& stub = rig.stub;
  GyroComponent<double>& comp = rig.comp;
  SilLoop<double, GyroComponent<double>>& loop = rig.loop;
  BodySample<double>& sample = rig.sample;
  const std::uint64_t settle = static_cast<std::uint64_t>(std::lround(kSettleSeconds / dt));
  const std::uint64_t window = static_cast<std::uint64_t>(std::lround(window_s / dt));
  std::uint64_t free_tick = 0;
  V2 flown = V2::Zero();  // the rate the component flew from the last tick
  GuidanceCommand<double> command;
  const std::uint64_t last = kUncageTick + cc.uncage_settle_ticks + 2 + settle + window;
  for (std::uint64_t tick = 1; tick <= last; ++tick) {
    const double t = static_cast<double>(tick) * dt;
    sample.R_earth_to_body = body.R_earth_to_body(t);
    // Guidance from the last tick's telemetry.
    const bool free_before = comp.mode() == GyroMode::kFree;
    command.request = tick == kUncageTick ? ModeRequest::kUncage : ModeRequest::kNone;
    command.slew_rate_cmd_rad_s =
        free_before ? guidance_command(path, body, comp.telemetry().gimbal_measured_rad) : V2(V2::Zero());
    const SilStatus<Status> ran = loop.tick(tick, sample, command);
    if (ran.stub != Status::kOk || ran.component != Status::kOk) return out;
    // The window, from the tick the component went free before this one (the stub's truth is
    // what the torque written this tick has not moved yet).
    const bool window_tick = free_tick > 0 && tick > free_tick + settle && tick <= free_tick + settle + window;
    const GyroTelemetry<double>& now = comp.telemetry();
    if (window_tick) {
      const V2 truth = stub.spin_axis_rate_rad_s();
      const double err = (truth - flown).norm();
      out.slew_error_rad_s = std::max(out.slew_error_rad_s, err);
      const double cmd = flown.norm();
      out.min_command_rad_s = std::min(out.min_command_rad_s, cmd);
      if (cmd >= kMinCommand_rad_s) out.slew_error_rel = std::max(out.slew_error_rel, err / cmd);
      out.cone_min_window_rad = std::min(out.cone_min_window_rad, stub.cone_rad());
      out.cone_max_window_rad = std::max(out.cone_max_window_rad, stub.cone_rad());
    }
    flown = now.rate_cmd_rad_s;
    if (free_tick == 0 && comp.mode() == GyroMode::kFree) {
      free_tick = tick;
      out.free_at_s = t;
    }
    const double residual = now.residual_rad.cwiseAbs().maxCoeff();
    if (tick < kUncageTick) out.worst_residual_caged_rad = std::max(out.worst_residual_caged_rad, residual);
    if (tick >= kUncageTick) {
      const bool fault_now = comp.mode() == GyroMode::kFault;
      if (residual > out.worst_residual_rad) {
        out.worst_residual_rad = residual;
        out.worst_residual_tick = tick;
      }
      if (comp.mode() == GyroMode::kUncaging) {
        out.worst_residual_uncaging_rad = std::max(out.worst_residual_uncaging_rad, residual);
      }
      out.flags_seen |= now.flags;
      if ((now.flags & kTorquerSaturated) != 0u) ++out.saturated_ticks;
      if (out.first_limit_tick == 0 && (now.flags & kGimbalLimit) != 0u) out.first_limit_tick = tick;
      if (out.first_saturated_tick == 0 && (now.flags & kTorquerSaturated) != 0u) out.first_saturated_tick = tick;
      if (out.first_fault_tick == 0 && fault_now) out.first_fault_tick = tick;
      if (out.first_fault_tick == 0) out.flags_before_fault |= now.flags;
      out.fault = out.fault || fault_now;
    }
    if (stub.at_gimbal_stop()) {
      ++out.contact_ticks;
      if (out.first_contact_tick == 0) out.first_contact_tick = tick;
    }
    if (free_tick > 0) out.max_cone_rad = std::max(out.max_cone_rad, stub.cone_rad());
    if (window_tick) {
      out.worst_residual_window_rad = std::max(out.worst_residual_window_rad, now.residual_rad.cwiseAbs().maxCoeff());
      out.flags_window |= now.flags;
      out.max_command_rad_s = std::max(out.max_command_rad_s, command.slew_rate_cmd_rad_s.cwiseAbs().maxCoeff());
      if ((command.slew_rate_cmd_rad_s - now.rate_cmd_rad_s).cwiseAbs().maxCoeff() > 1e-12) ++out.clipped_ticks;
    }
  }
  out.residual_fault = comp.telemetry().counters[6] > 0u;  // kResidualFault is bit 6
  out.ok = free_tick > 0;
  return out;
}

// ---------------------------------------------------------------------------------------
// A change of command: the closed loop above, and kChangeAfterSeconds after the component
// goes free (the cone acquired) guidance adds kChange to its command, as a step, as a ramp
// over kRampSeconds, or as a chirp (a sine of amplitude kChange swept 0 -> kChirpTopHz over
// kChirpSeconds, ending at zero). Measured against the plant's true spin-axis rate (the stub's
// truth at tick k against the rate the component flew from tick k-1): the rate error
// relative to the commanded rate, or to |kChange| where the command is smaller (a chirp
// passes through zero); the peak from the change on, and the settling time: from the end of
// the change to the last tick the error is beyond 1 %, within kAfterChangeSeconds.

enum class CommandShape { kStep, kRamp, kChirp };

inline const char* shape_name(CommandShape s) {
  return s == CommandShape::kStep ? "step" : s == CommandShape::kRamp ? "ramp" : "chirp";
}

inline constexpr double kChangeAfterSeconds = kSettleSeconds;
inline constexpr double kRampSeconds = 0.01;
inline constexpr double kChirpSeconds = 0.1;
inline constexpr double kChirpTopHz = 40.0;
inline constexpr double kAfterChangeSeconds = 0.15;
inline constexpr double kSettleBand = 0.01;
inline const V2 kChange(0.25, -0.25);  // rad/s on (y_I, z_I): with the path, up to the slew limit

// How long the change itself lasts, and its share of kChange tau s after it begins.
inline double change_seconds(CommandShape s) {
  return s == CommandShape::kStep ? 0.0 : s == CommandShape::kRamp ? kRampSeconds : kChirpSeconds;
}
inline double change_share(CommandShape s, double tau) {
  if (tau < 0.0) return 0.0;
  if (s == CommandShape::kStep) return 1.0;
  if (s == CommandShape::kRamp) return std::min(1.0, tau / kRampSeconds);
  if (tau >= kChirpSeconds) return 0.0;
  // phase 2 pi (f1 / (2 T)) tau^2: 2 pi f1 T / 2 = 4 pi at the end, sin = 0 there.
  return std::sin(kPiD * kChirpTopHz / kChirpSeconds * tau * tau);
}

// The plant's nutation frequency at pitch angle theta (docs/gimbal-plant.md, the mass matrix
// with the spin held): pitch J1 = Iy + A; yaw, for the spin axis's rate on z_I (psi' cos th),
// J2 = (Oz + (Ix + J0) s^2 + (Iz + A) c^2) / c^2; beta = H / sqrt(J1 J2).
inline double plant_nutation_rad_s(const GimbalPlantConfig<double>& g, double theta, double spin_inertial_rad_s) {
  const double s = std::sin(theta), c = std::cos(theta);
  const double a = g.rotor_transverse_inertia;
  const double j1 = g.inner_gimbal_inertia(1) + a;
  const double j2 =
      (g.outer_gimbal_inertia(2) + (g.inner_gimbal_inertia(0) + g.spin_inertia) * s * s + (g.inner_gimbal_inertia(2) + a) * c * c) /
      (c * c);
  return std::abs(g.spin_inertia * spin_inertial_rad_s) / std::sqrt(j1 * j2);
}

struct SettlingResult {
  bool ok{false};                // every call accepted, free before the change, no safe mode
  double settle_s{};             // from the end of the change; kAfterChangeSeconds: not settled
  bool settled{false};           // within the band before the measurement ended
  double peak_error_rel{};       // from the change on
  double error_50ms_rel{};       // worst from 50 ms after the end of the change on
  double nutation_period_s{};    // the plant's, at the change
  double pitch_at_change_rad{};  // the plant's pitch gimbal angle then
  std::uint32_t flags_seen{};    // OR of the component's flags from the change on
};

inline SettlingResult run_command_change(const Case& k, CommandShape shape,
                                         const SimulatedGyroConfig<double>& stub_config = Seeker::stub(),
                                         const GyroComponentConfig<double>& cc = Seeker::component()) {
  SettlingResult out;
  const double dt = Seeker::kTick;
  const BodyTurn body(k);
  const Path path{k};
  ClosedLoopRig rig(body, stub_config, cc);
  if (!rig.started) return out;
  SimulatedGyro<double>& stub = rig.stub;
  GyroComponent<double>& comp = rig.comp;
  SilLoop<double, GyroComponent<double>>& loop = rig.loop;
  BodySample<double>& sample = rig.sample;
  const auto ticks_of = [dt](double s) { return static_cast<std::uint64_t>(std::lround(s / dt)); };
  const std::uint64_t change_after = ticks_of(kChangeAfterSeconds);
  const std::uint64_t change_ticks = ticks_of(change_seconds(shape));
  const std::uint64_t after = ticks_of(kAfterChangeSeconds);
  const std::uint64_t after_50ms = ticks_of(0.05);
  std::uint64_t free_tick = 0, change_tick = 0, last_out = 0;
  V2 flown = V2::Zero();
  GuidanceCommand<double> command;
  const std::uint64_t last = kUncageTick + cc.uncage_settle_ticks + 2 + change_after + change_ticks + after;
  for (std::uint64_t tick = 1; tick <= last; ++tick) {
    sample.R_earth_to_body = body.R_earth_to_body(static_cast<double>(tick) * dt);
    const bool free_before = comp.mode() == GyroMode::kFree;
    if (free_tick > 0 && change_tick == 0 && tick > free_tick + change_after) {
      const GimbalPlant<double>* plant = stub.gimbal_plant();
      if (plant == nullptr) return out;  // the report's plant: no gimbal geometry
      change_tick = tick;
      out.pitch_at_change_rad = plant->gimbal_angle_rad()(0);
      out.nutation_period_s =
          2.0 * kPiD / plant_nutation_rad_s(stub_config.gimbal, out.pitch_at_change_rad, plant->spin_inertial_rad_s());
    }
    const double tau = change_tick > 0 ? static_cast<double>(tick - change_tick) * dt : -1.0;
    command.request = tick == kUncageTick ? ModeRequest::kUncage : ModeRequest::kNone;
    command.slew_rate_cmd_rad_s = free_before ? V2(guidance_command(path, body, comp.telemetry().gimbal_measured_rad) +
                                                   change_share(shape, tau) * kChange)
                                              : V2(V2::Zero());
    const SilStatus<Status> ran = loop.tick(tick, sample, command);
    if (ran.stub != Status::kOk || ran.component != Status::kOk || comp.mode() == GyroMode::kFault) return out;
    // From the tick after the first changed command was flown.
    if (change_tick > 0 && tick > change_tick) {
      const double err = (stub.spin_axis_rate_rad_s() - flown).norm() / std::max(flown.norm(), kChange.norm());
      out.peak_error_rel = std::max(out.peak_error_rel, err);
      const std::uint64_t since_end = tick - change_tick - 1;  // ticks since the change ended, once >= change_ticks
      if (since_end >= change_ticks + after_50ms) out.error_50ms_rel = std::max(out.error_50ms_rel, err);
      if (err > kSettleBand) last_out = tick;
      out.flags_seen |= comp.telemetry().flags;
    }
    flown = comp.telemetry().rate_cmd_rad_s;
    if (free_tick == 0 && comp.mode() == GyroMode::kFree) free_tick = tick;
  }
  if (change_tick == 0) return out;
  const std::uint64_t end = change_tick + change_ticks;  // the last tick whose error the change drives
  out.settle_s = last_out > end ? static_cast<double>(last_out - end) * dt : 0.0;
  out.settled = last_out < last;
  out.ok = true;
  return out;
}

// The seeker with heavier gimbal rings at the same effective inertias at zero gimbal angles
// (J1 = Iy + A = J, J2 = Oz + Iz + A = J) and the same momentum H: the rings (thin, as the
// seeker's) take `ring_share` of J, the rotor the rest (A = (1 - share) J); where that leaves
// J0 > 2A (no rigid rotor), J0 = 2A (a flat disc) spinning faster for the same H.
struct Rig {
  SimulatedGyroConfig<double> stub;
  GyroComponentConfig<double> component;
};

inline Rig heavy_ring_rig(double ring_share) {
  Rig r{Seeker::stub(), Seeker::component()};
  const double j = Seeker::kJ;
  const double ring = ring_share * j;
  GimbalPlantConfig<double>& g = r.stub.gimbal;
  g.rotor_transverse_inertia = j - ring;
  g.inner_gimbal_inertia = V3(ring / 2, ring, ring / 2);
  g.outer_gimbal_inertia = V3(ring, ring / 2, ring / 2);
  const double j0 = std::min(Seeker::kJ0, 2.0 * g.rotor_transverse_inertia);
  const double spin_hz = Seeker::kSpinHz * Seeker::kJ0 / j0;
  g.spin_inertia = j0;
  g.max_spin_hz = spin_hz;
  r.stub.gyro.spin_inertia = j0;
  r.stub.spin_hz = spin_hz;
  r.component.spin_inertia = j0;
  r.component.min_spin_hz *= spin_hz / r.component.nominal_spin_hz;
  r.component.nominal_spin_hz = spin_hz;
  return r;
}

}  // namespace gyro::validity
