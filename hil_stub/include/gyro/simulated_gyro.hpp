// The software-in-the-loop gyro: the other side of the hardware port. It emulates the gyro
// hardware with the report's exact model (GyroModel) plus what the real electronics add:
// pickoff lag, bias, noise, range and quantisation; torquer scale factor and saturation; spin
// run-down; a mechanical gimbal stop; and scheduled faults.
//
// One tick, driven by the scenario (host) side:
//   write_torquer(torque)   (flight side, at tick k) latches the command (zero-order hold)
//   advance(k+1, R, accel)  steps the rotor over [k, k+1] with the torque that acts over that
//                           interval (command -> scale factor -> saturation -> torquer faults,
//                           faults as at tick k), the body attitude at k+1; samples the pickoffs
//   read_pickoffs(out)      (flight side, at tick k+1) returns that conversion
//
// Pickoff chain, per axis: truth gimbal angle (gyro/attitude.hpp convention) -> first-order
// lag (exact per tick: y += (1 - exp(-dt/lag)) (x - y)) -> + bias (+ bias-jump faults) ->
// + white Gaussian noise -> saturation at +-range -> rounding to the nearest lsb (and, when
// both are set, clamped to the largest code within the range). Sequence +1 per conversion,
// starting at 1 for the power-up conversion.
//
// Spin: spin(t) = spin_hz exp(-t/tau) (tau = 0: constant) times, for each spin-motor-failure
// fault, exp(-(min(t, t_end) - t_start)/magnitude) once t >= t_start: the run-down stops when
// the fault ends but the lost speed is not regained (no spin-up model). Each step uses the
// spin at the middle of the step (H is constant within a step in the exact model). A spin
// below spin_hz * epsilon is taken as stopped: exactly 0.
//
// Mechanical gimbal stop: if after a step the total cone angle of the spin axis from body x
// exceeds gimbal_stop_rad, the gimbal has hit the stop. The impact is taken as inelastic:
// the model is re-uncaged with the spin axis on the stop, in the direction it was heading,
// and the gimbal rates equal to the body's pitch/yaw rates over the step (from the two body
// attitudes). at_gimbal_stop() says so for that tick. While the body keeps pushing, the gyro
// is put back on the stop every tick and, nutating within each tick, precesses under the
// stop's reaction: the spin axis walks round the rim of the stop (as a real gyro held against
// its stop does) rather than staying where it first struck.
//
// Faults (active for ticks in [start_tick, start_tick + duration_ticks), duration 0 =
// permanent; axis 0 pitch, 1 yaw, -1 both):
//   kStuckPickoff      the converter's output freezes at its last value before the fault
//                      (its value at start_tick - 1; the power-up conversion for a fault
//                      from tick 0);
//                      the sequence keeps counting
//   kInvalidReading    NaN angles: on one axis with valid = true (axis >= 0, tests the
//                      caller's finiteness check), on both with valid = false (axis = -1)
//   kDropout           no new conversion: the whole reading (sequence included) repeats
//   kBiasJump          `magnitude` rad added to the bias of the axis
//   kDeadTorquer       applied torque 0 on the axis
//   kSaturatedTorquer  applied torque pinned at +magnitude on the axis, whatever the command
//   kSpinMotorFailure  spin decays with time constant `magnitude` s (see above)
// Torquer faults act on the interval that starts at their tick: [k, k+1] for a fault active
// at tick k.
//
// No heap, no exceptions, no RTTI; every call returns a status; a refused call changes
// nothing. float or double.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "gyro/attitude.hpp"
#include "gyro/exact_step_check.hpp"
#include "gyro/gyro_model.hpp"
#include "gyro/gyro_port.hpp"
#include "gyro/noise.hpp"
#include "gyro/status.hpp"

namespace gyro {

template <typename T>
struct PickoffModel {
  T lsb_rad{};                              // quantisation step (0 = none)
  Vector2<T> bias_rad{Vector2<T>::Zero()};  // (pitch, yaw)
  T lag_s{};                                // first-order lag time constant (0 = none)
  T noise_rad{};                            // 1-sigma white noise per reading
  T range_rad{};                            // readings saturate at +-range (0 = none)
};

template <typename T>
struct TorquerModel {
  Vector2<T> scale_factor{Vector2<T>::Ones()};  // actual/commanded torque per axis
  T max_torque{};                               // saturation per axis (0 = none)
};

enum class FaultKind : std::uint8_t {
  kNone = 0,
  kStuckPickoff,
  kInvalidReading,
  kDropout,
  kBiasJump,
  kDeadTorquer,
  kSaturatedTorquer,
  kSpinMotorFailure,
};
inline constexpr int kFaultKindCount = 8;

[[nodiscard]] constexpr const char* to_string(FaultKind k) noexcept {
  switch (k) {
    case FaultKind::kNone: return "none";
    case FaultKind::kStuckPickoff: return "stuck pickoff";
    case FaultKind::kInvalidReading: return "invalid reading";
    case FaultKind::kDropout: return "dropout";
    case FaultKind::kBiasJump: return "bias jump";
    case FaultKind::kDeadTorquer: return "dead torquer";
    case FaultKind::kSaturatedTorquer: return "saturated torquer";
    case FaultKind::kSpinMotorFailure: return "spin motor failure";
  }
  return "unknown fault";
}

// The bit of a fault kind in active_faults().
[[nodiscard]] constexpr std::uint32_t fault_bit(FaultKind k) noexcept {
  return 1u << static_cast<std::uint32_t>(k);
}

template <typename T>
struct FaultEvent {
  FaultKind kind{FaultKind::kNone};
  std::uint64_t start_tick{};
  std::uint64_t duration_ticks{};  // 0 = permanent
  int axis{-1};                    // 0 pitch, 1 yaw, -1 both
  T magnitude{};  // bias jump (rad); saturated torquer level (torque); spin failure time constant (s)
};

inline constexpr int kMaxFaultEvents = 8;

// Noise stream ids (one per axis and per random term).
enum class NoiseStreamId : std::uint64_t {
  kPickoffNoisePitch = 1,
  kPickoffNoiseYaw = 2,
};

template <typename T>
struct SimulatedGyroConfig {
  GyroModelConfig<T> gyro{};      // rotor, limits and the report's error sources
  T tick_s{};
  T spin_hz{};                    // spin at start
  T spin_down_time_constant_s{};  // 0 = constant spin; else spin(t) = spin_hz*exp(-t/tau)
  bool has_spin_readback{true};
  PickoffModel<T> pickoff{};
  TorquerModel<T> torquer{};
  T gimbal_stop_rad{};            // mechanical stop on the total cone angle (0 = none)
  std::uint64_t seed{};           // base seed of every noise stream
  std::array<FaultEvent<T>, kMaxFaultEvents> faults{};
};

namespace sim_detail {

static_assert(kMaxFaultEvents == 8, "one name per fault slot below");
inline constexpr const char* kFaultKindNames[kMaxFaultEvents] = {
    "faults[0].kind", "faults[1].kind", "faults[2].kind", "faults[3].kind",
    "faults[4].kind", "faults[5].kind", "faults[6].kind", "faults[7].kind"};
inline constexpr const char* kFaultAxisNames[kMaxFaultEvents] = {
    "faults[0].axis", "faults[1].axis", "faults[2].axis", "faults[3].axis",
    "faults[4].axis", "faults[5].axis", "faults[6].axis", "faults[7].axis"};
inline constexpr const char* kFaultMagnitudeNames[kMaxFaultEvents] = {
    "faults[0].magnitude", "faults[1].magnitude", "faults[2].magnitude", "faults[3].magnitude",
    "faults[4].magnitude", "faults[5].magnitude", "faults[6].magnitude", "faults[7].magnitude"};
inline constexpr const char* kFaultDurationNames[kMaxFaultEvents] = {
    "faults[0].duration_ticks", "faults[1].duration_ticks", "faults[2].duration_ticks",
    "faults[3].duration_ticks", "faults[4].duration_ticks", "faults[5].duration_ticks",
    "faults[6].duration_ticks", "faults[7].duration_ticks"};

template <typename T>
[[nodiscard]] bool non_negative_finite(T v) noexcept {
  return std::isfinite(v) && v >= T(0);
}

}  // namespace sim_detail

// The emulated rotor's exact step over a tick at the spin it starts with (the largest: the
// spin only runs down) must be representable, or advance() would refuse every tick; the
// refusal names the field responsible (gyro/exact_step_check.hpp).
template <typename T>
[[nodiscard]] ConfigCheck check_exact_step_at_start(const SimulatedGyroConfig<T>& c) noexcept {
  constexpr ExactStepFields kFields{"pitch_inertia", "yaw_inertia", "spin_inertia", "friction", "spin_hz", "tick_s"};
  return check_exact_step(c.gyro.pitch_inertia, c.gyro.yaw_inertia, c.gyro.spin_inertia, c.gyro.friction, c.spin_hz,
                          c.tick_s, kFields);
}

template <typename T>
[[nodiscard]] ConfigCheck check(const SimulatedGyroConfig<T>& c) noexcept {
  using sim_detail::non_negative_finite;
  const ConfigCheck g = check(c.gyro);
  if (!g.ok()) return g;
  if (!std::isfinite(c.tick_s)) return {Status::kNonFiniteInput, "tick_s"};
  if (!(c.tick_s > T(0))) return {Status::kNonPositiveStep, "tick_s"};
  if (!std::isfinite(c.spin_hz)) return {Status::kNonFiniteInput, "spin_hz"};
  if (!(c.spin_hz > T(0))) return {Status::kOutOfRange, "spin_hz"};
  if (!std::isfinite(c.spin_down_time_constant_s)) return {Status::kNonFiniteInput, "spin_down_time_constant_s"};
  if (c.spin_down_time_constant_s < T(0)) return {Status::kOutOfRange, "spin_down_time_constant_s"};
  const ConfigCheck step = check_exact_step_at_start(c);
  if (!step.ok()) return step;

  struct NonNegative {
    T value;
    const char* name;
  };
  const NonNegative non_negative[] = {
      {c.pickoff.lsb_rad, "pickoff.lsb_rad"},     {c.pickoff.lag_s, "pickoff.lag_s"},
      {c.pickoff.noise_rad, "pickoff.noise_rad"}, {c.pickoff.range_rad, "pickoff.range_rad"},
      {c.torquer.max_torque, "torquer.max_torque"}, {c.gimbal_stop_rad, "gimbal_stop_rad"},
  };
  for (const NonNegative& n : non_negative) {
    if (!std::isfinite(n.value)) return {Status::kNonFiniteInput, n.name};
    if (n.value < T(0)) return {Status::kOutOfRange, n.name};
  }
  if (!all_finite(c.pickoff.bias_rad)) return {Status::kNonFiniteInput, "pickoff.bias_rad"};
  if (!all_finite(c.torquer.scale_factor)) return {Status::kNonFiniteInput, "torquer.scale_factor"};
  if (!(c.gimbal_stop_rad < kPi<T>)) return {Status::kOutOfRange, "gimbal_stop_rad"};
  if (c.pickoff.range_rad > T(0) && c.pickoff.lsb_rad > c.pickoff.range_rad) {
    return {Status::kOutOfRange, "pickoff.lsb_rad"};
  }

  for (int i = 0; i < kMaxFaultEvents; ++i) {
    const FaultEvent<T>& f = c.faults[static_cast<std::size_t>(i)];
    const auto kind = static_cast<std::uint8_t>(f.kind);
    if (kind >= static_cast<std::uint8_t>(kFaultKindCount)) return {Status::kOutOfRange, sim_detail::kFaultKindNames[i]};
    if (f.kind == FaultKind::kNone) continue;
    if (f.axis < -1 || f.axis > 1) return {Status::kOutOfRange, sim_detail::kFaultAxisNames[i]};
    if (f.duration_ticks > ~std::uint64_t{0} - f.start_tick) {
      return {Status::kOutOfRange, sim_detail::kFaultDurationNames[i]};
    }
    if (!std::isfinite(f.magnitude)) return {Status::kNonFiniteInput, sim_detail::kFaultMagnitudeNames[i]};
    if (f.kind == FaultKind::kSpinMotorFailure && !(f.magnitude > T(0))) {
      return {Status::kOutOfRange, sim_detail::kFaultMagnitudeNames[i]};
    }
  }
  return {};
}

template <typename T>
class SimulatedGyro final : public GyroPort<T> {
 public:
  // Validates and stores the configuration (the field of a refusal is named). Leaves the
  // gyro powered down: start() next.
  [[nodiscard]] ConfigCheck configure(const SimulatedGyroConfig<T>& c) noexcept {
    const ConfigCheck chk = check(c);
    if (!chk.ok()) return chk;
    GyroModel<T> model;
    const ConfigCheck mc = model.configure(c.gyro);
    if (!mc.ok()) return mc;
    config_ = c;
    model_ = model;
    lag_gain_ = (c.pickoff.lag_s > T(0)) ? -std::expm1(-c.tick_s / c.pickoff.lag_s) : T(1);
    noise_[0] = NoiseStream<T>(c.seed, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoisePitch));
    noise_[1] = NoiseStream<T>(c.seed, static_cast<std::uint64_t>(NoiseStreamId::kPickoffNoiseYaw));
    configured_ = true;
    started_ = false;
    return chk;
  }

  // Power-up: the gyro spun up and released aligned with the body (rates = body pitch/yaw
  // rates), tick 0. The power-up conversion is ready for read_pickoffs.
  [[nodiscard]] Status start(const Matrix3<T>& R_earth_to_body, const Vector2<T>& body_rate_rad_s) noexcept {
    if (!configured_) return Status::kNotConfigured;
    GyroModel<T> model;
    const ConfigCheck mc = model.configure(config_.gyro);
    if (!mc.ok()) return mc.status;
    const Status st = model.uncage(R_earth_to_body, body_rate_rad_s);
    if (st != Status::kOk) return st;
    model_ = model;
    tick_ = 0;
    R_earth_to_body_ = R_earth_to_body;
    torque_cmd_.setZero();
    at_stop_ = false;
    spin_hz_ = spin_at(0);
    converter_out_.setZero();
    reading_ = PickoffReading<T>{};
    started_ = true;
    sample(true);
    applied_torque_ = torque_on_rotor(tick_);
    return Status::kOk;
  }

  // Advances the emulated gyro from the previous tick to `tick` (must be previous + 1) with
  // the torque latched by the last write_torquer (zero-order hold, after torquer scale,
  // saturation and faults), the body attitude at `tick` and the body (lateral y, normal z)
  // accelerations; then samples the pickoffs for read_pickoffs.
  [[nodiscard]] Status advance(std::uint64_t tick, const Matrix3<T>& R_earth_to_body,
                               const Vector2<T>& body_accel) noexcept {
    if (!started_) return Status::kNotConfigured;
    if (tick != tick_ + 1u) return Status::kOutOfRange;
    if (!all_finite(body_accel)) return Status::kNonFiniteInput;
    if (!is_rotation(R_earth_to_body)) return Status::kInvalidRotation;

    GyroStepInput<T> in;
    in.dt_s = config_.tick_s;
    in.R_earth_to_body = R_earth_to_body;
    in.body_accel = body_accel;
    in.spin_hz = spin_at_mid_step(tick_);
    const Vector2<T> torque = torque_on_rotor(tick_);
    GyroModel<T> model = model_;
    const Status st = model.step_torque(in, torque);
    if (st != Status::kOk) return st;

    bool hit = false;
    if (config_.gimbal_stop_rad > T(0) && model.gimbal_cone_rad() > config_.gimbal_stop_rad) {
      const Status ss = put_on_stop(model, R_earth_to_body);
      if (ss != Status::kOk) return ss;
      hit = true;
    }

    model_ = model;
    at_stop_ = hit;
    R_earth_to_body_ = R_earth_to_body;
    tick_ = tick;
    spin_hz_ = spin_at(tick_);
    sample(false);
    applied_torque_ = torque_on_rotor(tick_);
    return Status::kOk;
  }

  // The conversion sampled at the current tick. kNotReady before start().
  [[nodiscard]] PortStatus read_pickoffs(PickoffReading<T>& out) noexcept override {
    if (!started_) return PortStatus::kNotReady;
    out = reading_;
    return PortStatus::kOk;
  }

  // Latches the torque command until the next write (zero-order hold). kNotReady before
  // start(); a non-finite command cannot be encoded: kBusError, the previous one stays.
  [[nodiscard]] PortStatus write_torquer(const Vector2<T>& torque) noexcept override {
    if (!started_) return PortStatus::kNotReady;
    if (!all_finite(torque)) return PortStatus::kBusError;
    torque_cmd_ = torque;
    applied_torque_ = torque_on_rotor(tick_);
    return PortStatus::kOk;
  }

  // Truth, for tests and the scenario runner's CSV.
  [[nodiscard]] const GyroModel<T>& truth() const noexcept { return model_; }
  // The torquer torque acting on the rotor from this tick to the next (after scale factor,
  // saturation and faults; the model's error sources come on top, see truth()).
  [[nodiscard]] const Vector2<T>& applied_torque() const noexcept { return applied_torque_; }
  [[nodiscard]] T spin_hz() const noexcept { return spin_hz_; }
  [[nodiscard]] std::uint64_t tick() const noexcept { return tick_; }
  // Bit fault_bit(kind) = 1u << kind for each kind active at the current tick.
  [[nodiscard]] std::uint32_t active_faults() const noexcept {
    std::uint32_t bits = 0;
    for (const FaultEvent<T>& f : config_.faults) {
      if (active(f, tick_)) bits |= fault_bit(f.kind);
    }
    return bits;
  }
  // Extras beyond the port: the last torque command, and whether the gimbal hit its stop in
  // the last advance().
  [[nodiscard]] const Vector2<T>& torque_command() const noexcept { return torque_cmd_; }
  [[nodiscard]] bool at_gimbal_stop() const noexcept { return at_stop_; }
  [[nodiscard]] const SimulatedGyroConfig<T>& config() const noexcept { return config_; }

 private:
  [[nodiscard]] static bool active(const FaultEvent<T>& f, std::uint64_t tick) noexcept {
    if (f.kind == FaultKind::kNone || tick < f.start_tick) return false;
    return f.duration_ticks == 0u || tick - f.start_tick < f.duration_ticks;
  }
  [[nodiscard]] static bool on_axis(const FaultEvent<T>& f, int axis) noexcept {
    return f.axis < 0 || f.axis == axis;
  }

  [[nodiscard]] Vector2<T> truth_gimbal() const noexcept {
    return Vector2<T>(model_.gimbal_pitch_rad(), model_.gimbal_yaw_rad());
  }

  // Spin at time t = ticks * tick_s (ticks may be fractional: the middle of a step).
  [[nodiscard]] T spin_at_time(T ticks) const noexcept {
    const T dt = config_.tick_s;
    T exponent = T(0);
    if (config_.spin_down_time_constant_s > T(0)) exponent += ticks * dt / config_.spin_down_time_constant_s;
    for (const FaultEvent<T>& f : config_.faults) {
      if (f.kind != FaultKind::kSpinMotorFailure) continue;
      const T fault_start = static_cast<T>(f.start_tick);
      if (ticks <= fault_start) continue;
      T fault_end = ticks;
      if (f.duration_ticks != 0u) fault_end = std::min(ticks, static_cast<T>(f.start_tick + f.duration_ticks));
      exponent += (fault_end - fault_start) * dt / f.magnitude;
    }
    const T spin = config_.spin_hz * std::exp(-exponent);
    // Run down below the rounding of the initial spin: stopped. (A vanishing but non-zero H
    // has no use and, squared, underflows inside the exact solution.)
    return (spin < config_.spin_hz * std::numeric_limits<T>::epsilon()) ? T(0) : spin;
  }
  [[nodiscard]] T spin_at(std::uint64_t tick) const noexcept { return spin_at_time(static_cast<T>(tick)); }
  [[nodiscard]] T spin_at_mid_step(std::uint64_t start_tick) const noexcept {
    return spin_at_time(static_cast<T>(start_tick) + T(0.5));
  }

  // The torque acting over [tick, tick + 1]: command -> scale factor -> saturation -> faults.
  [[nodiscard]] Vector2<T> torque_on_rotor(std::uint64_t tick) const noexcept {
    Vector2<T> t = torque_cmd_.cwiseProduct(config_.torquer.scale_factor);
    const T lim = config_.torquer.max_torque;
    if (lim > T(0)) {
      for (int i = 0; i < 2; ++i) t(i) = std::min(lim, std::max(-lim, t(i)));
    }
    for (const FaultEvent<T>& f : config_.faults) {
      if (!active(f, tick)) continue;
      for (int i = 0; i < 2; ++i) {
        if (!on_axis(f, i)) continue;
        if (f.kind == FaultKind::kDeadTorquer) t(i) = T(0);
        if (f.kind == FaultKind::kSaturatedTorquer) t(i) = f.magnitude;
      }
    }
    return t;
  }

  // Body pitch and yaw rates over the last step, from the attitudes at its two ends.
  [[nodiscard]] Vector2<T> body_rate(const Matrix3<T>& R_earth_to_body_now) const noexcept {
    // R_now = dR * R_prev: dR is the passive rotation of the step; its transpose is the
    // active rotation of the body about its own axes.
    Matrix3<T> turn = Matrix3<T>::Zero();
    turn.noalias() = R_earth_to_body_ * R_earth_to_body_now.transpose();
    const Eigen::AngleAxis<T> aa(turn);
    const Vector3<T> w = aa.axis() * (aa.angle() / config_.tick_s);
    if (!all_finite(w)) return Vector2<T>::Zero();
    return Vector2<T>(w(1), w(2));
  }

  // Inelastic impact: spin axis put on the stop in the direction it was heading, gimbal
  // rates those of the body.
  [[nodiscard]] Status put_on_stop(GyroModel<T>& model, const Matrix3<T>& R_earth_to_body_now) const noexcept {
    const T p = model.gimbal_pitch_rad(), y = model.gimbal_yaw_rad();
    // Spin axis in body axes: (cos p cos y, cos p sin y, -sin p); its (y, z) direction.
    const T dy = std::cos(p) * std::sin(y), dz = -std::sin(p);
    const T n = std::hypot(dy, dz);
    if (!(n > T(0))) return Status::kNumericalOverflow;
    // step_rotation((theta, psi)) turns body x by |(theta, psi)| toward (psi, -theta) in (y, z).
    const T s = config_.gimbal_stop_rad / n;
    const Vector2<T> offset(-s * dz, s * dy);
    return model.uncage(R_earth_to_body_now, body_rate(R_earth_to_body_now), offset);
  }

  // One conversion of the pickoff electronics at tick_.
  void sample(bool power_up) noexcept {
    const PickoffModel<T>& pm = config_.pickoff;
    const Vector2<T> truth_rad = truth_gimbal();
    if (power_up || !(pm.lag_s > T(0))) {
      lag_out_ = truth_rad;  // no lag: exactly the truth (x + (y - x) need not round to y)
    } else {
      lag_out_ += lag_gain_ * (truth_rad - lag_out_);
    }

    Vector2<T> bias = pm.bias_rad;
    bool stuck[2] = {false, false};
    bool invalid_axis[2] = {false, false};
    bool invalid_both = false;
    bool dropout = false;
    for (const FaultEvent<T>& f : config_.faults) {
      if (!active(f, tick_)) continue;
      switch (f.kind) {
        case FaultKind::kBiasJump:
          for (int i = 0; i < 2; ++i) {
            if (on_axis(f, i)) bias(i) += f.magnitude;
          }
          break;
        case FaultKind::kStuckPickoff:
          for (int i = 0; i < 2; ++i) stuck[i] = stuck[i] || on_axis(f, i);
          break;
        case FaultKind::kInvalidReading:
          if (f.axis < 0) {
            invalid_both = true;
          } else {
            invalid_axis[f.axis] = true;
          }
          break;
        case FaultKind::kDropout: dropout = true; break;
        default: break;
      }
    }

    Vector2<T> v = lag_out_ + bias;
    if (pm.noise_rad > T(0)) {
      for (std::size_t i = 0; i < 2; ++i) v(static_cast<Eigen::Index>(i)) += pm.noise_rad * noise_[i].gaussian(tick_);
    }
    for (int i = 0; i < 2; ++i) v(i) = quantise(v(i));
    for (int i = 0; i < 2; ++i) {
      if (power_up || !stuck[i]) converter_out_(i) = v(i);  // stuck: the last conversion stays
    }
    if (dropout && !power_up) return;  // stale: nothing new, sequence included

    PickoffReading<T> r;
    r.gimbal_angle_rad = converter_out_;
    r.sequence = reading_.sequence + 1u;
    r.valid = !invalid_both;
    for (int i = 0; i < 2; ++i) {
      if (invalid_both || invalid_axis[i]) r.gimbal_angle_rad(i) = std::numeric_limits<T>::quiet_NaN();
    }
    r.spin_valid = config_.has_spin_readback;
    r.spin_hz = config_.has_spin_readback ? spin_hz_ : T(0);
    reading_ = r;
  }

  [[nodiscard]] T quantise(T v) const noexcept {
    const PickoffModel<T>& pm = config_.pickoff;
    if (pm.range_rad > T(0)) v = std::min(pm.range_rad, std::max(-pm.range_rad, v));
    if (pm.lsb_rad > T(0)) {
      T code = std::round(v / pm.lsb_rad);
      if (pm.range_rad > T(0)) {
        const T max_code = std::floor(pm.range_rad / pm.lsb_rad);
        code = std::min(max_code, std::max(-max_code, code));
      }
      v = code * pm.lsb_rad;
    }
    return v;
  }

  SimulatedGyroConfig<T> config_{};
  GyroModel<T> model_{};
  std::array<NoiseStream<T>, 2> noise_{};
  T lag_gain_{T(1)};
  bool configured_{false};
  bool started_{false};
  bool at_stop_{false};
  std::uint64_t tick_{0};
  Matrix3<T> R_earth_to_body_{Matrix3<T>::Identity()};
  Vector2<T> torque_cmd_{Vector2<T>::Zero()};
  Vector2<T> applied_torque_{Vector2<T>::Zero()};
  T spin_hz_{};
  Vector2<T> lag_out_{Vector2<T>::Zero()};        // state of the pickoff lag
  Vector2<T> converter_out_{Vector2<T>::Zero()};  // last output of the converters
  PickoffReading<T> reading_{};                   // what read_pickoffs returns
};

}  // namespace gyro
