// The runs behind docs/stop-protection.md (tools/stop_envelope.cpp, scripts/stop-envelope.sh)
// and its ctest (tests/stop_envelope_test.cpp): the flight component against the SIL stub's
// gimbal plant with a body that turns the gimbal toward its stop, per mode, and what the
// plant's truth says about the stop: contact, closest approach, and the component's flags.
//
// A case (gyro, turn b in a direction, roll p, starting cone c, mode):
//   positioning  the stub is powered up with the body at rest and run before the component is
//                activated (torquers off): the body turns across x by c with a half-sine rate
//                (peak kPositioningPeak_rad_s) in the case's turn direction, so the free spin
//                axis is left at the cone c on the side the case's turn drives it toward;
//   flight       the component is activated (caged) and, except in the caged mode, asked to
//                uncage at its first tick; the body's rate (p, b cos a, b sin a) ramps up over
//                kRampSeconds (a smoothstep: no nutation kick); a = 0 pitch, pi/2 yaw, pi/4
//                diagonal, or a = kRotationRate t (the turn rotating round x);
//   guidance     in the free modes, from the last telemetry's measured gimbal angles: zero,
//                or the spin axis slewed toward body x (inward) or away from it (outward) at u.
// Measured from the plant's truth: stop contact, the largest cone (closest approach to the
// stop), and from the telemetry the first tick of each flag and whether a fault latched.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "gyro/gimbal_geometry.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/simulated_gyro.hpp"
#include "scenario.hpp"

namespace gyro::stop_envelope {

using V2 = Vector2<double>;
using V3 = Vector3<double>;
using M3 = Matrix3<double>;

inline constexpr double kPiD = 3.14159265358979323846;
inline constexpr double kDeg = kPiD / 180.0;
inline constexpr double kPositioningPeak_rad_s = 1.5;  // half-sine peak of the positioning turn
inline constexpr double kRampSeconds = 0.05;           // the flight's body rate ramps up in this
inline constexpr double kRotationRate_rad_s = 1.0;     // the rotating turn's direction rate
inline constexpr double kFlightSeconds = 3.0;          // flight after activation
inline constexpr double kNearCentre = 0.01;            // sin of the cone below which "outward" is the turn's way

enum class Mode : std::uint8_t { kFreeZero, kFreeInward, kFreeOutward, kUncaging, kCaged };
inline constexpr Mode kModes[] = {Mode::kFreeZero, Mode::kFreeInward, Mode::kFreeOutward, Mode::kUncaging, Mode::kCaged};
[[nodiscard]] inline const char* mode_name(Mode m) {
  switch (m) {
    case Mode::kFreeZero: return "free, zero command";
    case Mode::kFreeInward: return "free, inward command";
    case Mode::kFreeOutward: return "free, outward command";
    case Mode::kUncaging: return "uncaging";
    case Mode::kCaged: return "caged";
  }
  return "?";
}
[[nodiscard]] inline const char* mode_key(Mode m) {
  switch (m) {
    case Mode::kFreeZero: return "free_zero";
    case Mode::kFreeInward: return "free_inward";
    case Mode::kFreeOutward: return "free_outward";
    case Mode::kUncaging: return "uncaging";
    case Mode::kCaged: return "caged";
  }
  return "?";
}

enum class Direction : std::uint8_t { kPitch, kYaw, kDiagonal, kRotating };
inline constexpr Direction kDirections[] = {Direction::kPitch, Direction::kYaw, Direction::kDiagonal, Direction::kRotating};
[[nodiscard]] inline const char* direction_key(Direction d) {
  switch (d) {
    case Direction::kPitch: return "pitch";
    case Direction::kYaw: return "yaw";
    case Direction::kDiagonal: return "diagonal";
    case Direction::kRotating: return "rotating";
  }
  return "?";
}

// A gyro of the table: the component's and the stub's configurations and the slew command's
// size in the inward/outward modes.
struct Gyro {
  std::string name;
  GyroComponentConfig<double> component{};
  SimulatedGyroConfig<double> stub{};
  double command_rad_s{};  // u
  [[nodiscard]] double tick_s() const { return component.tick_s; }
  [[nodiscard]] double protect_cone_rad() const {
    return component.gimbal_cone_limit_rad - component.gimbal_stop_margin_rad;
  }
  [[nodiscard]] double stop_rad() const { return stub.gimbal.stop_cone_rad; }
};

// The seeker: scenarios/seeker_slew.json's gyro (its gimbal plant, pickoff and torquer
// imperfections) and component, as they are.
inline Gyro seeker_gyro(const std::string& scenario_path) {
  const sil::Scenario s = sil::read_scenario(scenario_path);
  Gyro g;
  g.name = "seeker";
  g.component = s.component;
  g.stub = s.gyro;
  g.command_rad_s = 0.15;
  return g;
}

// The report's gyro: scenarios/report_sample.json's rotor (slug ft^2: J1 = 2.25, J2 = 2.0,
// J0 = 3.0, f = 5, 100 Hz), component, tick (2,828 Hz) and stop (0.5 rad), on the gimbal plant:
// a rotor of transverse inertia A = 1.6 (J0 <= 2A) on thin rings making the effective inertias
// at zero gimbal angles the report's J1 (inner ring Iy + A) and J2 (outer Oz + inner Iz + A),
// the report's friction on each bearing, no dry friction and no unbalance, the spin held by a
// motor (1e4 lbf ft, bandwidth 5 rad/s), dead-ish stop (restitution 0.2, as the seeker's);
// ideal pickoffs and torquers (the report models none).
inline Gyro report_gyro(const std::string& scenario_path) {
  const sil::Scenario s = sil::read_scenario(scenario_path);
  Gyro g;
  g.name = "report";
  g.component = s.component;
  g.stub = s.gyro;
  GimbalPlantConfig<double>& p = g.stub.gimbal;
  const double j0 = s.gyro.gyro.spin_inertia, j1 = s.gyro.gyro.pitch_inertia, j2 = s.gyro.gyro.yaw_inertia;
  const double a = 1.6;
  p.spin_inertia = j0;
  p.rotor_transverse_inertia = a;
  const double inner_y = j1 - a;           // 0.65
  const double inner_z = 0.2;              // the inner ring's x and z: Iy = Ix + Iz
  p.inner_gimbal_inertia = V3(inner_y - inner_z, inner_y, inner_z);
  const double outer_z = j2 - a - inner_z;  // 0.2
  p.outer_gimbal_inertia = V3(2.0 * outer_z, outer_z, outer_z);  // thin ring in its y-z plane
  p.inner_friction = s.gyro.gyro.friction;
  p.outer_friction = s.gyro.gyro.friction;
  p.inner_coulomb_torque = 0.0;
  p.outer_coulomb_torque = 0.0;
  p.spin_drive = SpinDrive::kMotor;
  p.max_spin_hz = s.gyro.spin_hz;
  p.motor_torque_limit = 1e4;
  p.spin_servo_bandwidth_rad_s = 5.0;
  p.spin_down_time_s = 60.0;
  p.mass_unbalance = 0.0;
  p.stop_cone_rad = s.gyro.gimbal_stop_rad;
  p.stop_restitution = 0.2;
  p.torquer_axes = TorquerAxes::kGimbal;
  p.max_body_rate_rad_s = 100.0;
  p.max_torque = 1e4;  // 20x the component's torque limit
  p.max_specific_force = 1e4;
  g.stub.plant = PlantKind::kGimbal;
  g.stub.spin_down_time_constant_s = 0.0;
  g.command_rad_s = 0.05;
  return g;
}

struct Case {
  double turn_rad_s{};
  Direction direction{Direction::kPitch};
  double roll_rad_s{};
  double cone_deg{};
  Mode mode{Mode::kFreeZero};
};

// The body's motion over a run (t from the stub's power-up).
struct BodyMotion {
  Case c;
  std::uint64_t positioning_ticks{};  // the half-sine's length in ticks (0 for a cone of 0)
  double positioning_s{};
  double peak_rad_s{};  // at most kPositioningPeak_rad_s: the half-sine turns the body by c

  BodyMotion(const Case& k, double tick_s) : c(k) {
    const double cone = k.cone_deg * kDeg;
    positioning_ticks = static_cast<std::uint64_t>(std::ceil(cone * kPiD / (2.0 * kPositioningPeak_rad_s) / tick_s));
    positioning_s = static_cast<double>(positioning_ticks) * tick_s;
    peak_rad_s = positioning_ticks > 0 ? cone * kPiD / (2.0 * positioning_s) : 0.0;
  }
  [[nodiscard]] double direction_rad(double t_flight) const {
    switch (c.direction) {
      case Direction::kPitch: return 0.0;
      case Direction::kYaw: return kPiD / 2.0;
      case Direction::kDiagonal: return kPiD / 4.0;
      case Direction::kRotating: return kRotationRate_rad_s * t_flight;
    }
    return 0.0;
  }
  [[nodiscard]] V3 rate_rad_s(double t) const {
    if (t < positioning_s) {
      const double a = direction_rad(0.0);
      const double w = peak_rad_s * std::sin(kPiD * t / positioning_s);
      return V3(0.0, w * std::cos(a), w * std::sin(a));
    }
    const double tf = t - positioning_s;
    const double x = std::min(1.0, tf / kRampSeconds);
    const double ramp = x * x * (3.0 - 2.0 * x);
    const double a = direction_rad(tf);
    return ramp * V3(c.roll_rad_s, c.turn_rad_s * std::cos(a), c.turn_rad_s * std::sin(a));
  }
  // The way the turn drives a free spin axis at body x: d x / dt = -w x x = (0, -r, q).
  [[nodiscard]] V3 drive_tangent(double t_flight) const {
    const double a = direction_rad(t_flight);
    return V3(0.0, -std::sin(a), std::cos(a));
  }
};

// One tick's attitude step: R_earth_to_body turned by the body's rate w held over dt.
[[nodiscard]] inline M3 turn_attitude(const M3& R, const V3& w, double dt) {
  const double n = w.norm();
  if (!(n > 0.0)) return R;
  const M3 step = Eigen::AngleAxisd(n * dt, w / n).toRotationMatrix().transpose();
  return step * R;
}

[[nodiscard]] inline V3 axis_of_gimbal(const V2& g) {
  return V3(std::cos(g(0)) * std::cos(g(1)), std::cos(g(0)) * std::sin(g(1)), -std::sin(g(0)));
}
[[nodiscard]] inline V2 gimbal_of_axis(const V3& x) {
  return V2(-std::asin(std::clamp(x(2), -1.0, 1.0)), std::atan2(x(1), x(0)));
}
// The unit angular velocity (body axes) that moves the spin axis s away from body x, at its
// clock angle (or along `fallback` when s is within kNearCentre of x); zero vector if none.
[[nodiscard]] inline V3 outward_turn(const V3& s, const V3& fallback) {
  const V3 x(1.0, 0.0, 0.0);
  V3 t = s * s.dot(x) - x;  // -(x - (x.s) s): away from x, normal to s
  if (t.norm() < kNearCentre) t = fallback - s * s.dot(fallback);
  const double n = t.norm();
  if (!(n > 0.0)) return V3::Zero();
  return s.cross(t / n);
}

// ---------------------------------------------------------------------------------------
// Authority. Near the stop the protection holds the gimbal where the body's turn pushes it:
// the spin axis must move with the body's outward rate, w = (wb . n) n on the gimbal axes (n
// the outward unit, wb the body's rate there), its tangential part left at the command (zero
// for these commands, which are radial; an outward command is withheld at the hold). The
// torque law (gyro/gimbal_geometry.hpp: T1 = h w_z + f (w - wb)_y, T2 = -h w_y cos th +
// f (w - wb)_z / cos th) gives the torque of that hold, which the torquers must deliver on
// each axis: |T_i| <= min(max_torque * scale_factor_i, the electronics' saturation), with
// h = H + J0 |p| (the inner gimbal's roll adds to the momentum), and |w_i| within that axis's
// slew-rate limit. The worst over every clock angle the case visits at the protection cone c_p
// (the turn's own for a fixed turn without roll, every one otherwise) is the demand; the case
// is within authority when it is at most 1.
struct Authority {
  double demand{};           // worst needed / available, over axes, torque and rate
  double torque_share{};     // of it, the torque's
  double rate_share{};       // of it, the slew-rate limit's
};

[[nodiscard]] inline Authority hold_demand(const Gyro& g, const V3& body_rate, double clock_rad) {
  Authority out;
  const double cp = g.protect_cone_rad();
  const V3 s(std::cos(cp), std::sin(cp) * std::cos(clock_rad), std::sin(cp) * std::sin(clock_rad));
  const V2 angles = gimbal_of_axis(s);
  const GimbalFrame<double> f = gimbal_frame_at(angles);
  const V2 n = body_rate_on_gimbal(f, outward_turn(s, V3(0.0, 1.0, 0.0)));
  const V2 wb = body_rate_on_gimbal(f, body_rate);
  // The gimbal's outward rate relative to the body is (w - wb) . n: a free spin axis (w = 0) is
  // carried outward when wb . n < 0, and held with w = (wb . n) n.
  const double along = wb.dot(n);
  if (!(along < 0.0)) return out;  // the body turns the gimbal inward here: nothing to hold
  const V2 w = along * n;
  const GyroComponentConfig<double>& c = g.component;
  const double h = angular_momentum(c.nominal_spin_hz, c.spin_inertia) + c.spin_inertia * std::abs(body_rate(0));
  const V2 torque = torquers_for_rate(f, h, g.stub.gimbal.inner_friction, w, wb);
  for (int i = 0; i < 2; ++i) {
    double available = c.max_torque * std::abs(g.stub.torquer.scale_factor(i));
    if (g.stub.torquer.max_torque > 0.0) available = std::min(available, g.stub.torquer.max_torque);
    available = std::min(available, g.stub.gimbal.max_torque);
    const double limit = i == 0 ? c.max_pitch_rate_rad_s : c.max_yaw_rate_rad_s;
    out.torque_share = std::max(out.torque_share, std::abs(torque(i)) / available);
    out.rate_share = std::max(out.rate_share, std::abs(w(i)) / limit);
  }
  out.demand = std::max(out.torque_share, out.rate_share);
  return out;
}

[[nodiscard]] inline Authority authority(const Gyro& g, const Case& k) {
  Authority worst;
  const BodyMotion m(k, g.tick_s());
  auto take = [&](const V3& w, double clock) {
    const Authority a = hold_demand(g, w, clock);
    if (a.demand > worst.demand) worst = a;
  };
  if (k.turn_rad_s == 0.0) return worst;
  const bool sweeps = k.roll_rad_s != 0.0 || k.direction == Direction::kRotating;
  if (!sweeps) {
    const V3 w = m.rate_rad_s(m.positioning_s + 1.0);
    const V3 t = m.drive_tangent(0.0);
    const double clock = std::atan2(t(2), t(1));
    for (int i = -5; i <= 5; ++i) take(w, clock + i * kDeg);  // friction drifts it a little sideways
  } else {
    for (int i = 0; i < 72; ++i) {
      for (int j = 0; j < 72; ++j) {
        const double a = j * 5.0 * kDeg;
        take(V3(k.roll_rad_s, k.turn_rad_s * std::cos(a), k.turn_rad_s * std::sin(a)), i * 5.0 * kDeg);
      }
    }
  }
  return worst;
}

// ---------------------------------------------------------------------------------------
// A flag's bit by its telemetry name (gyro::flag_name), or 0 if this build has no such flag:
// the tool measures components with and without the active protection's flags.
[[nodiscard]] inline std::uint32_t flag_bit(const char* name) {
  for (int bit = 0; bit < 32; ++bit) {
    if (std::strcmp(flag_name(bit), name) == 0) return 1u << static_cast<unsigned>(bit);
  }
  return 0u;
}

struct Result {
  bool ok{false};
  std::string error;            // why a call was refused
  double start_cone_rad{};      // the plant's cone at activation
  double max_cone_rad{};        // the plant's largest cone in flight
  double closest_rad{};         // stop - largest cone (0 on contact)
  std::uint64_t contact_ticks{};
  double first_contact_s{-1};   // from activation; -1: never
  double first_protect_s{-1};   // gimbal_stop_protect
  double first_beyond_s{-1};    // stop_beyond_authority
  double first_limit_s{-1};     // gimbal_limit
  double first_fault_s{-1};     // safe mode
  double first_beyond_cp_s{-1}; // the plant's cone past c_p
  std::uint32_t flags_seen{};   // OR over the flight
  std::uint32_t flags_at_contact{};  // OR up to the first contact
  bool fault{false};
  bool reached_mode{false};
  // How the protection flies: the stop_protect flag's switchings (chatter), the ticks the
  // torquer saturated, the component's worst residual (pickoffs against its prediction) and
  // whether its residual fault was raised.
  std::uint64_t protect_toggles{};
  std::uint64_t saturated_ticks{};
  std::uint64_t beyond_ticks{};   // ticks with stop_beyond_authority
  double furthest_out_rad{-1e300};  // largest cone less max(c_p, start cone): how far it went out
  double worst_residual_rad{};
  bool residual_fault{false};     // the case's mode was flown (free, uncaging or caged) at some tick
  GyroMode final_mode{GyroMode::kIdle};
};

inline Result run_case(const Gyro& g, const Case& k) {
  Result out;
  const double dt = g.tick_s();
  const BodyMotion motion(k, dt);
  GyroComponentConfig<double> cc = g.component;
  const std::uint64_t flight_ticks = static_cast<std::uint64_t>(std::lround(kFlightSeconds / dt));
  if (k.mode == Mode::kUncaging) cc.uncage_settle_ticks = static_cast<std::uint32_t>(flight_ticks + 10u);
  SimulatedGyro<double> stub;
  GyroComponent<double> comp(stub);
  const ConfigCheck sc = stub.configure(g.stub);
  if (!sc.ok()) {
    out.error = std::string("stub refused ") + sc.field;
    return out;
  }
  const ConfigCheck ck = comp.configure(cc);
  if (!ck.ok()) {
    out.error = std::string("component refused ") + ck.field;
    return out;
  }
  SilLoop<double, GyroComponent<double>> loop(stub, comp);
  BodySample<double> body;
  body.rate_rad_s = motion.rate_rad_s(0.0);
  if (stub.start(body) != Status::kOk) {
    out.error = "stub start refused";
    return out;
  }
  // Positioning: the stub alone, torquers off; the rate of each tick's end, the attitude
  // turned by the tick's mid rate.
  std::uint64_t tick = 0;
  const std::uint64_t positioning_ticks = motion.positioning_ticks;
  auto advance_body = [&](std::uint64_t kk) {
    const double t0 = static_cast<double>(kk - 1) * dt, t1 = static_cast<double>(kk) * dt;
    body.R_earth_to_body = turn_attitude(body.R_earth_to_body, motion.rate_rad_s(0.5 * (t0 + t1)), dt);
    body.rate_rad_s = motion.rate_rad_s(t1);
  };
  for (tick = 1; tick <= positioning_ticks; ++tick) {
    advance_body(tick);
    if (stub.advance(tick, body) != Status::kOk) {
      out.error = "stub refused a positioning tick";
      return out;
    }
  }
  // Flight: the component from the stub's last positioning tick on (as SilLoop's tick 0).
  const std::uint64_t first = positioning_ticks;
  if (comp.activate() != Status::kOk) {
    out.error = "activate refused";
    return out;
  }
  out.start_cone_rad = stub.cone_rad();
  const double cp = g.protect_cone_rad();
  const std::uint32_t protect_bit = flag_bit("gimbal_stop_protect");
  const std::uint32_t beyond_bit = flag_bit("stop_beyond_authority");
  const std::uint32_t limit_bit = flag_bit("gimbal_limit");
  const GyroMode wanted = k.mode == Mode::kCaged      ? GyroMode::kCaged
                          : k.mode == Mode::kUncaging ? GyroMode::kUncaging
                                                      : GyroMode::kFree;
  const std::uint32_t saturated_bit = flag_bit("torquer_saturated");
  const std::uint32_t residual_bit = flag_bit("residual_fault");
  bool protect_before = false;
  GuidanceCommand<double> command;
  for (std::uint64_t i = 0; i < flight_ticks; ++i) {
    tick = first + i;
    const double at_s = static_cast<double>(i) * dt;  // time from the first flight tick
    command.request = (i == 0 && k.mode != Mode::kCaged) ? ModeRequest::kUncage : ModeRequest::kNone;
    command.slew_rate_cmd_rad_s = V2::Zero();
    if (i > 0 && (k.mode == Mode::kFreeInward || k.mode == Mode::kFreeOutward)) {
      const V2 measured = comp.telemetry().gimbal_measured_rad;
      const V3 s = axis_of_gimbal(measured);
      const bool near_centre = std::hypot(s(1), s(2)) < kNearCentre;
      if (k.mode == Mode::kFreeOutward || !near_centre) {
        const double sign = k.mode == Mode::kFreeOutward ? 1.0 : -1.0;
        const V3 w = outward_turn(s, motion.drive_tangent(at_s));
        command.slew_rate_cmd_rad_s = sign * g.command_rad_s * body_rate_on_gimbal(gimbal_frame_at(measured), w);
      }
    }
    if (i > 0) advance_body(tick);
    // The first flight tick steps the component on the stub's last positioning sample.
    SilStatus<Status> ran;
    if (i == 0) {
      ran.component = comp.step(tick, guidance_input(command, body));
    } else {
      ran = loop.tick(tick, body, command);
    }
    if (ran.stub != Status::kOk) {
      out.error = "stub refused a flight tick";
      return out;
    }
    // (The component's status is not checked: a fail-operational component reports and flies.)
    const GyroTelemetry<double>& tm = comp.telemetry();
    const double cone = stub.cone_rad();
    const bool contact = i > 0 && stub.at_gimbal_stop();
    out.flags_seen |= tm.flags;
    out.max_cone_rad = std::max(out.max_cone_rad, cone);
    if (contact) {
      if (out.contact_ticks == 0) {
        out.first_contact_s = at_s;
        out.flags_at_contact = out.flags_seen;
      }
      ++out.contact_ticks;
    }
    auto first_time = [&](double& slot, bool now) {
      if (slot < 0.0 && now) slot = at_s;
    };
    first_time(out.first_protect_s, (tm.flags & protect_bit) != 0u);
    first_time(out.first_beyond_s, beyond_bit != 0u && (tm.flags & beyond_bit) != 0u);
    first_time(out.first_limit_s, (tm.flags & limit_bit) != 0u);
    first_time(out.first_fault_s, comp.mode() == GyroMode::kFault);
    first_time(out.first_beyond_cp_s, cone > cp);
    out.fault = out.fault || comp.mode() == GyroMode::kFault;
    out.reached_mode = out.reached_mode || comp.mode() == wanted;
    const bool protect_now = (tm.flags & protect_bit) != 0u;
    out.protect_toggles += protect_now != protect_before ? 1u : 0u;
    protect_before = protect_now;
    out.saturated_ticks += (tm.flags & saturated_bit) != 0u ? 1u : 0u;
    out.beyond_ticks += beyond_bit != 0u && (tm.flags & beyond_bit) != 0u ? 1u : 0u;
    out.furthest_out_rad = std::max(out.furthest_out_rad, cone - std::max(cp, out.start_cone_rad));
    out.residual_fault = out.residual_fault || (tm.flags & residual_bit) != 0u;
    if (comp.mode() != GyroMode::kFault) {
      out.worst_residual_rad = std::max(out.worst_residual_rad, tm.residual_rad.cwiseAbs().maxCoeff());
    }
  }
  if (out.contact_ticks == 0) out.flags_at_contact = out.flags_seen;
  out.final_mode = comp.mode();
  out.closest_rad = out.contact_ticks > 0 ? 0.0 : std::max(0.0, g.stop_rad() - out.max_cone_rad);
  out.ok = true;
  return out;
}

// The names of the flags in `flags`, comma-separated.
[[nodiscard]] inline std::string flag_names(std::uint32_t flags, const char* sep = ", ") {
  std::string s;
  for (int bit = 0; bit < 32; ++bit) {
    if ((flags & (1u << static_cast<unsigned>(bit))) == 0u) continue;
    const char* n = flag_name(bit);
    if (!s.empty()) s += sep;
    s += (n != nullptr && n[0] != '\0') ? std::string(n) : "bit" + std::to_string(bit);
  }
  return s;
}

}  // namespace gyro::stop_envelope
