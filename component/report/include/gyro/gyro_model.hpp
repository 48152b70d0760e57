// The report's subroutine GYRO as a class: what a 6-DOF simulation embeds to carry a
// two-axis gimballed gyro (and what the SIL stub wraps to emulate one).
//
// Per step: start the inertial small-angle frame (ISAF) at the gyro's attitude with the
// angles at zero, advance the exact rotor dynamics over dt with the torques held, rotate the
// attitude by the step's angles exactly, and read the gimbal angles off the spin axis in the
// body axes of the END of the step. Every error of the listing is fixed; each is recorded in
// docs/seed-errata.md. Allocation-free, exception-free; float or double.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "gyro/attitude.hpp"
#include "gyro/config_check.hpp"
#include "gyro/error_sources.hpp"
#include "gyro/gimbal_geometry.hpp"
#include "gyro/nutation.hpp"
#include "gyro/rotor_transition.hpp"
#include "gyro/saturate.hpp"
#include "gyro/torquer_axes.hpp"

namespace gyro {

template <typename T>
struct GyroModelConfig {
  T pitch_inertia{};       // J1
  T yaw_inertia{};         // J2
  T spin_inertia{};        // J0
  T friction{};            // f
  T gimbal_cone_limit_rad{};        // limit on the total angle of spin axis to body x
  T pitch_gimbal_limit_rad{};       // optional per-axis limits; 0 means "no per-axis limit"
  T yaw_gimbal_limit_rad{};
  T max_pitch_rate_rad_s{};         // slew-rate limits (the implied torquer limit)
  T max_yaw_rate_rad_s{};
  T small_angle_limit_rad{T(0.01)}; // the report's .01: at least 4 digits
  T gravity{T(9.80665)};            // in the units of the accelerations passed to step()
  GyroErrorSources<T> errors{};
  TorquerAxes torquer_axes{TorquerAxes::kGyro};  // kGimbal: the torque resolved on the gyro axes is held over a step
};

// The fields (gyro/config_fields.hpp); a scenario gives them in its "rotor" and "limits".
template <typename T>
struct FieldTable<GyroModelConfig<T>> {
  static constexpr bool kDefined = true;
  template <class Visit, class... C>
  static constexpr void visit(Visit&& v, C&... c) {
    constexpr Rule kPos = Rule::kPositive, kNonNeg = Rule::kNonNegative;
    constexpr Status kRange = Status::kOutOfRange, kInertia = Status::kNonPositiveInertia;
    constexpr Presence kReq = Presence::kRequired, kOpt = Presence::kOptional;
    constexpr const char* kUnits = "consistent units: products with rates and spins stay within float's range";
    v(Field{"pitch_inertia", kPos, kInertia, kReq, "rotor", 1e-12, 1e12, "inertia", kUnits}, c.pitch_inertia...);
    v(Field{"yaw_inertia", kPos, kInertia, kReq, "rotor", 1e-12, 1e12, "inertia", kUnits}, c.yaw_inertia...);
    v(Field{"spin_inertia", kPos, kInertia, kReq, "rotor", 1e-12, 1e12, "inertia", kUnits}, c.spin_inertia...);
    v(Field{"friction", kNonNeg, Status::kNegativeFriction, kReq, "rotor", 0.0, 1e12, "torque/(rad/s)", kUnits}, c.friction...);
    v(Field{"gimbal_cone_limit_rad", kPos, kRange, kReq, "limits", 1e-3, 3.141592653589793, "rad", "a cone of a milliradian to below pi"}, c.gimbal_cone_limit_rad...);
    v(Field{"pitch_gimbal_limit_rad", kNonNeg, kRange, kOpt, "limits", 0.0, 3.141592653589793, "rad", "0 (none) or below pi"}, c.pitch_gimbal_limit_rad...);
    v(Field{"yaw_gimbal_limit_rad", kNonNeg, kRange, kOpt, "limits", 0.0, 3.141592653589793, "rad", "0 (none) or below pi"}, c.yaw_gimbal_limit_rad...);
    v(Field{"max_pitch_rate_rad_s", kPos, kRange, kReq, "limits", 1e-6, 1e4, "rad/s", "the model's slew limit"}, c.max_pitch_rate_rad_s...);
    v(Field{"max_yaw_rate_rad_s", kPos, kRange, kReq, "limits", 1e-6, 1e4, "rad/s", "the model's slew limit"}, c.max_yaw_rate_rad_s...);
    v(Field{"small_angle_limit_rad", kPos, kRange, kOpt, "limits", 1e-6, 1.0, "rad", "the report's 0.01; the flag means nothing beyond a radian"}, c.small_angle_limit_rad...);
    v(Field{"gravity", kPos, kRange, kReq, nullptr, 1e-3, 1e4, "accel", "g in the units of the accelerations: 9.80665 m/s^2, 32.17 ft/s^2"}, c.gravity...);
    v(Field{"errors", Rule::kFinite, kRange, kOpt}, c.errors...);
    v(Field{"torquer_axes", Rule::kNone, kRange, Presence::kImplied}, c.torquer_axes...);
  }
};

template <typename T>
[[nodiscard]] ConfigCheck check(const GyroModelConfig<T>& c) noexcept {
  const FieldRefusal r = first_refusal<RealFields>(c);
  if (r.status != Status::kOk) return r.check;
  const ConfigCheck e = check(c.errors);
  if (!e.ok()) return e;
  if (!(c.gimbal_cone_limit_rad < kPi<T>)) return {Status::kOutOfRange, "gimbal_cone_limit_rad"};
  if (!(c.pitch_gimbal_limit_rad < kPi<T>)) return {Status::kOutOfRange, "pitch_gimbal_limit_rad"};
  if (!(c.yaw_gimbal_limit_rad < kPi<T>)) return {Status::kOutOfRange, "yaw_gimbal_limit_rad"};
  if (c.torquer_axes != TorquerAxes::kGyro && c.torquer_axes != TorquerAxes::kGimbal) {
    return {Status::kOutOfRange, "torquer_axes"};
  }
  return {};
}

// Inputs of one step.
template <typename T>
struct GyroStepInput {
  T dt_s{};
  Matrix3<T> R_earth_to_body{Matrix3<T>::Identity()};  // body attitude at the END of the step
  Vector2<T> body_accel{Vector2<T>::Zero()};  // (lateral y, normal z), units of config.gravity
  T spin_hz{};                                // may vary step to step (spin-down)
  Vector3<T> body_rate_rad_s{Vector3<T>::Zero()};  // body (p, q, r) over the step (kGimbal only)
};

// Flag bits (a word, not a union of bools, so telemetry can carry it as is).
enum GyroModelFlag : std::uint32_t {
  kFlagGimbalLimit = 1u << 0,  // the spin axis is outside the gimbal cone or a per-axis limit
  kFlagSmallAngle = 1u << 1,   // the step's angles or nutation amplitude exceed the limit
};

template <typename T>
class GyroModel;

// A body attitude found to be a rotation by GyroModel::check_body_attitude: the model's step
// and correction take it without checking it again (a copy of a checked matrix is as good).
template <typename T>
class CheckedRotation {
 public:
  CheckedRotation() noexcept = default;  // the identity
  [[nodiscard]] const Matrix3<T>& matrix() const noexcept { return R_; }

 private:
  friend class GyroModel<T>;
  explicit CheckedRotation(const Matrix3<T>& R) noexcept : R_(R) {}
  Matrix3<T> R_{Matrix3<T>::Identity()};
};

template <typename T>
class GyroModel {
 public:
  // Validates and stores the configuration; refuses with the field's name. Leaves the gyro
  // caged (call uncage() before step()).
  [[nodiscard]] ConfigCheck configure(const GyroModelConfig<T>& config) noexcept {
    const ConfigCheck c = check(config);
    if (!c.ok()) return c;
    config_ = config;
    cos_cone_limit_ = std::cos(config.gimbal_cone_limit_rad);
    drift_needs_angles_ = drift_depends_on_gimbal(config.errors);
    has_error_sources_ = any_error_source(config.errors);
    configured_ = true;
    uncaged_ = false;
    cache_valid_ = false;
    pending_correction_.setZero();
    return c;
  }

  // Uncaging (the report's initialisation): rates from the body's pitch and yaw rates, the
  // gyro attitude from the body's plus a small (pitch, yaw) offset.
  [[nodiscard]] Status uncage(const Matrix3<T>& R_earth_to_body, const Vector2<T>& body_rate_rad_s,
                              const Vector2<T>& offset_rad = Vector2<T>::Zero()) noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (!all_finite(body_rate_rad_s, offset_rad)) return Status::kNonFiniteInput;
    if (!is_rotation(R_earth_to_body)) return Status::kInvalidRotation;
    Quaternion<T> q_body(Matrix3<T>(R_earth_to_body.transpose()));  // body to earth
    Quaternion<T> q = q_body * step_rotation(offset_rad);
    q.normalize();
    q_gyro_to_earth_ = q;
    rate_rad_s_ = body_rate_rad_s;
    isaf_angle_rad_.setZero();
    pending_correction_.setZero();
    nutation_amplitude_rad_.setZero();
    gimbal_frame(R_earth_to_body, q_gyro_to_earth_, frames_[frame_index_]);
    gimbal_ = gimbal_angles(frame().spin_axis_body);
    angles_stale_ = false;  // read just now (a correction before uncaging is gone)
    flags_ = gimbal_flag(gimbal_);
    uncaged_ = true;
    have_frame_roll_ = false;
    return Status::kOk;
  }

  // Uncaging at the gimbal angles (pitch, yaw): the gyro axes put on the inner gimbal frame
  // exactly (the joint rotations, not a rotation vector), the rates those of the body across
  // the spin axis (gimbals at rest relative to the body).
  [[nodiscard]] Status uncage_on_gimbal(const Matrix3<T>& R_earth_to_body, const Vector3<T>& body_rate_rad_s,
                                        const Vector2<T>& gimbal_rad) noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (!all_finite(body_rate_rad_s, gimbal_rad)) return Status::kNonFiniteInput;
    if (!is_rotation(R_earth_to_body)) return Status::kInvalidRotation;
    Quaternion<T> q_body(Matrix3<T>(R_earth_to_body.transpose()));  // body to earth
    const Quaternion<T> yaw(Eigen::AngleAxis<T>(gimbal_rad(1), Vector3<T>::UnitZ()));
    const Quaternion<T> pitch(Eigen::AngleAxis<T>(gimbal_rad(0), Vector3<T>::UnitY()));
    Quaternion<T> q = q_body * yaw * pitch;
    q.normalize();
    q_gyro_to_earth_ = q;
    gimbal_frame(R_earth_to_body, q_gyro_to_earth_, frames_[frame_index_]);
    rate_rad_s_ = times(frame().gimbal_to_gyro, body_rate_on_gimbal(frame(), body_rate_rad_s));
    isaf_angle_rad_.setZero();
    pending_correction_.setZero();
    nutation_amplitude_rad_.setZero();
    gimbal_ = gimbal_angles(frame().spin_axis_body);
    angles_stale_ = false;  // read just now (a correction before uncaging is gone)
    flags_ = gimbal_flag(gimbal_);
    uncaged_ = true;
    have_frame_roll_ = false;
    return Status::kOk;
  }

  // One step with the report's command: slew rates, limited per axis (pitch by the pitch
  // limit), turned into torque for a frictionless gyro as the report's torquer does.
  [[nodiscard]] Status step_slew(const GyroStepInput<T>& in, const Vector2<T>& slew_rate_cmd_rad_s) noexcept {
    if (!all_finite(slew_rate_cmd_rad_s, in.spin_hz)) return Status::kNonFiniteInput;
    const Vector2<T> limited(saturate(slew_rate_cmd_rad_s(0), config_.max_pitch_rate_rad_s),
                             saturate(slew_rate_cmd_rad_s(1), config_.max_yaw_rate_rad_s));
    const T h = angular_momentum(in.spin_hz, config_.spin_inertia);
    if (config_.torquer_axes == TorquerAxes::kGimbal) {
      return step_torque(in, torquers_for_rate(frame(), h, T(0), limited, Vector2<T>(Vector2<T>::Zero())));
    }
    return step_torque(in, torque_for_rate_frictionless(h, limited));
  }

  // One step with the torquer torques held over dt: (T1 pitch axis, T2 yaw axis) of the gyro
  // (kGyro), or (inner, outer) about the gimbal axes (kGimbal).
  [[nodiscard]] Status step_torque(const GyroStepInput<T>& in, const Vector2<T>& torque_cmd) noexcept {
    const Status st = check_step(in, torque_cmd);
    if (st != Status::kOk) return st;
    if (!is_rotation(in.R_earth_to_body)) return Status::kInvalidRotation;
    return step_checked(in, in.R_earth_to_body, torque_cmd);
  }

  // The same with an attitude already checked (check_body_attitude) in place of
  // in.R_earth_to_body, which is not read: one check per tick for a caller that also corrects.
  [[nodiscard]] Status step_torque(const GyroStepInput<T>& in, const CheckedRotation<T>& attitude,
                                   const Vector2<T>& torque_cmd) noexcept {
    const Status st = check_step(in, torque_cmd);
    if (st != Status::kOk) return st;
    return step_checked(in, attitude.matrix(), torque_cmd);
  }

 private:
  [[nodiscard]] Status check_step(const GyroStepInput<T>& in, const Vector2<T>& torque_cmd) const noexcept {
    if (!configured_) return Status::kNotConfigured;
    if (!uncaged_) return Status::kNotConfigured;
    if (!all_finite(in.dt_s, in.spin_hz, in.body_accel, torque_cmd, in.body_rate_rad_s)) {
      return Status::kNonFiniteInput;
    }
    if (!(in.dt_s > T(0))) return Status::kNonPositiveStep;
    if (in.spin_hz < T(0)) return Status::kNegativeAngularMomentum;
    return Status::kOk;
  }

  // step_torque() once its inputs are checked; R_earth_to_body is the end-of-step attitude.
  [[nodiscard]] Status step_checked(const GyroStepInput<T>& in, const Matrix3<T>& R_earth_to_body,
                                    const Vector2<T>& torque_cmd) noexcept {
    const RotorParameters<T> prm{config_.pitch_inertia, config_.yaw_inertia, config_.friction,
                                 angular_momentum(in.spin_hz, config_.spin_inertia)};
    if (!cache_valid_ || !(prm.angular_momentum == cached_h_) || !(in.dt_s == transition_.dt_s)) {
      // One validation and one set of rate-matrix terms for the transition and the map.
      const Status valid = validate(prm);
      if (valid != Status::kOk) return valid;
      const detail::RateMatrixTerms<T> terms = detail::rate_matrix_terms(prm);
      // Written in place: a refused transition leaves transition_ (and the cache) as it was.
      const Status st = detail::make_transition_from_terms(prm, terms, in.dt_s, transition_);
      if (st != Status::kOk) return st;
      nutation_map_ = detail::nutation_map_from_terms(prm, terms);
      cached_h_ = prm.angular_momentum;
      cache_valid_ = true;
    }

    const bool on_gimbal = config_.torquer_axes == TorquerAxes::kGimbal;
    T frame_roll{};
    const Vector2<T> rotor_torque = on_gimbal ? torque_on_gyro_axes(in, torque_cmd, frame_roll) : torque_cmd;
    // The error sources as torques (none configured: the torquers' alone, as the sums below
    // would give with every coefficient zero).
    const Vector2<T> torque = has_error_sources_ ? with_error_sources(in, rotor_torque, prm.angular_momentum)
                                                 : rotor_torque;

    // Finite inputs can still overflow here (cross-coupling, drift torques of huge spins).
    if (!all_finite(torque)) return Status::kNumericalOverflow;

    RotorState<T> s;  // the ISAF starts at the gyro's attitude: angles zero (listing kept them)
    s.rate_rad_s = rate_rad_s_;
    const Status adv = advance(transition_, torque, s);
    if (adv != Status::kOk) return adv;

    const Vector2<T> amplitude = nutation_amplitude(nutation_map_, rate_rad_s_, torque);

    Quaternion<T> q = q_gyro_to_earth_ * step_rotation(s.angle_rad, pending_correction_);
    renormalize(q);
    // The frame at the step's end (the next one's start, and what the accessors and a gimbal
    // correction read, whichever the torquers' axes) goes to the spare buffer, taken on
    // success; the angles come from its spin axis.
    GimbalFrame<T>& end = frames_[frame_index_ ^ 1u];
    gimbal_frame(R_earth_to_body, q, end);
    const GimbalAngles<T> g = gimbal_angles(end.spin_axis_body);
    // The rate the accessors derive must be representable too: near gimbal lock the inner
    // gimbal's roll feeds the rates until their turn onto the gimbal axes overflows.
    if (!all_finite(g.pitch_rad, g.yaw_rad, transpose_times(end.gimbal_to_gyro, s.rate_rad_s))) {
      return Status::kNumericalOverflow;
    }

    std::uint32_t step_flags = gimbal_flag(g);
    const T lim = config_.small_angle_limit_rad;
    if (amplitude.maxCoeff() > lim || s.angle_rad.cwiseAbs().maxCoeff() > lim) step_flags |= kFlagSmallAngle;

    q_gyro_to_earth_ = q;
    rate_rad_s_ = s.rate_rad_s;
    isaf_angle_rad_ = s.angle_rad;
    pending_correction_.setZero();
    nutation_amplitude_rad_ = amplitude;
    gimbal_ = g;
    angles_stale_ = false;
    flags_ = step_flags;
    applied_torque_ = torque;
    frame_index_ ^= 1u;
    frame_roll_ = frame_roll;
    have_frame_roll_ = true;
    return Status::kOk;
  }

 public:
  // Turns the gyro by small (pitch, yaw) angles about its own axes and re-reads the gimbal
  // angles with `R_earth_to_body`: the correction step of an estimator built on the model.
  [[nodiscard]] Status correct_attitude(const Vector2<T>& angle_rad, const Matrix3<T>& R_earth_to_body) noexcept {
    if (!uncaged_) return Status::kNotConfigured;
    if (!all_finite(angle_rad)) return Status::kNonFiniteInput;
    if (!is_rotation(R_earth_to_body)) return Status::kInvalidRotation;
    apply_correction(angle_rad, R_earth_to_body);
    return Status::kOk;
  }
  [[nodiscard]] Status correct_attitude(const Vector2<T>& angle_rad, const CheckedRotation<T>& attitude) noexcept {
    if (!uncaged_) return Status::kNotConfigured;
    if (!all_finite(angle_rad)) return Status::kNonFiniteInput;
    apply_correction(angle_rad, attitude.matrix());
    return Status::kOk;
  }

 private:
  void apply_correction(const Vector2<T>& angle_rad, const Matrix3<T>& R_earth_to_body) noexcept {
    Quaternion<T> q = q_gyro_to_earth_ * step_rotation(angle_rad);
    renormalize(q);
    q_gyro_to_earth_ = q;
    R_earth_to_body_ = R_earth_to_body;
    angles_stale_ = true;  // read afresh when asked for (or by the next step)
  }

 public:

  // The same for a change of the gimbal angles (pitch, yaw): the gyro turns by pitch about the
  // inner gimbal axis and by yaw about body z (a spin-axis turn of yaw * cos th about z_I),
  // resolved on its own axes with the gimbal frame of the last step.
  template <typename Attitude>  // Matrix3<T> or CheckedRotation<T>
  [[nodiscard]] Status correct_gimbal_angles(const Vector2<T>& gimbal_rad, const Attitude& R_earth_to_body) noexcept {
    if (!all_finite(gimbal_rad)) return Status::kNonFiniteInput;
    return correct_attitude(gyro_turn_for_gimbal(gimbal_rad), R_earth_to_body);
  }

  // The same turn taken at the start of the next step instead of now, composed with that
  // step's rotation: one rotation a step where an estimator correcting every step would make
  // two. Until that step the attitude, the angles and the frame read do not include it; a
  // second call before it adds to the first.
  [[nodiscard]] Status correct_gimbal_angles_at_next_step(const Vector2<T>& gimbal_rad) noexcept {
    if (!uncaged_) return Status::kNotConfigured;
    if (!all_finite(gimbal_rad)) return Status::kNonFiniteInput;
    pending_correction_ += gyro_turn_for_gimbal(gimbal_rad);
    return Status::kOk;
  }
  // Gyro-axis (pitch, yaw) angles taken at the start of the next step (0 when none).
  [[nodiscard]] const Vector2<T>& pending_correction_rad() const noexcept { return pending_correction_; }

  [[nodiscard]] const Quaternion<T>& attitude_gyro_to_earth() const noexcept { return q_gyro_to_earth_; }
  [[nodiscard]] Matrix3<T> R_earth_to_gyro() const noexcept {
    return q_gyro_to_earth_.toRotationMatrix().transpose();
  }
  [[nodiscard]] const Vector2<T>& rate_rad_s() const noexcept { return rate_rad_s_; }  // (theta', psi')
  // The spin axis's inertial rate on the inner gimbal axes (pitch about y_I, yaw about z_I).
  [[nodiscard]] Vector2<T> rate_on_gimbal_rad_s() const noexcept { return transpose_times(frame().gimbal_to_gyro, rate_rad_s_); }
  [[nodiscard]] const GimbalFrame<T>& gimbal_frame_now() const noexcept { return frame(); }
  // kGimbal: the inner gimbal's roll rate about the spin axis over the last step (0 before
  // one): J0 times it is the rotor's momentum beyond the motor-held spin's.
  [[nodiscard]] T inner_gimbal_roll_rad_s() const noexcept { return have_frame_roll_ ? frame_roll_ : T(0); }
  [[nodiscard]] const Vector2<T>& isaf_angle_rad() const noexcept { return isaf_angle_rad_; }  // last step
  [[nodiscard]] const Vector2<T>& nutation_amplitude_rad() const noexcept { return nutation_amplitude_rad_; }
  [[nodiscard]] const Vector2<T>& applied_torque() const noexcept { return applied_torque_; }
  [[nodiscard]] T gimbal_pitch_rad() const noexcept { return refresh_angles().pitch_rad; }
  [[nodiscard]] T gimbal_yaw_rad() const noexcept { return refresh_angles().yaw_rad; }
  [[nodiscard]] Vector2<T> gimbal_rad() const noexcept {  // (pitch, yaw)
    const GimbalAngles<T>& g = refresh_angles();
    return Vector2<T>(g.pitch_rad, g.yaw_rad);
  }
  [[nodiscard]] T gimbal_cosine_of_cone() const noexcept { return refresh_angles().cosine_of_cone; }
  [[nodiscard]] T gimbal_cone_rad() const noexcept {
    return std::acos(saturate(refresh_angles().cosine_of_cone, T(1)));
  }
  [[nodiscard]] std::uint32_t flags() const noexcept {
    (void)refresh_angles();
    return flags_;
  }
  [[nodiscard]] bool gimbal_limit_exceeded() const noexcept { return (flags() & kFlagGimbalLimit) != 0u; }
  [[nodiscard]] bool small_angle_exceeded() const noexcept { return (flags_ & kFlagSmallAngle) != 0u; }
  [[nodiscard]] const GyroModelConfig<T>& config() const noexcept { return config_; }
  [[nodiscard]] bool uncaged() const noexcept { return uncaged_; }

  // Whether R is a rotation (gyro/attitude.hpp's is_rotation); if so, `out` receives it, for
  // the step and correction of the same tick to take without checking it again.
  [[nodiscard]] static bool check_body_attitude(const Matrix3<T>& R, CheckedRotation<T>& out) noexcept {
    if (!is_rotation(R)) return false;
    out = CheckedRotation<T>(R);
    return true;
  }

 private:
  // The turn of the gyro's axes (pitch, yaw) that changes the gimbal angles by `gimbal_rad`:
  // pitch about y_I, yaw times cos th about z_I, resolved with the last step's frame.
  [[nodiscard]] Vector2<T> gyro_turn_for_gimbal(const Vector2<T>& gimbal_rad) const noexcept {
    const Vector2<T> on_gimbal(gimbal_rad(0), gimbal_rad(1) * frame().cos_pitch);
    return times(frame().gimbal_to_gyro, on_gimbal);
  }

  // The gimbal angles and their flag, read again after a correction (lazily: a correction
  // followed by a step never reads them twice).
  const GimbalAngles<T>& refresh_angles() const noexcept {
    if (angles_stale_) read_angles();  // the reading apart: the test alone is inlined
    return gimbal_;
  }
  void read_angles() const noexcept {
    gimbal_ = gimbal_angles(R_earth_to_body_, spin_axis_in_earth(q_gyro_to_earth_));
    flags_ = (flags_ & ~static_cast<std::uint32_t>(kFlagGimbalLimit)) | gimbal_flag(gimbal_);
    angles_stale_ = false;
  }

  // kGimbal: the torquers' and bearings' torque on the rotor, on the gyro's axes. The torquer
  // axes turn over the step (the body rolls them about the spin axis, the gimbal pitch
  // changes the outer torquer's lever): the torque is held at the frame of the step's middle,
  // moved from its start by the gimbal rates there (second order in the step). The friction
  // correction moves the model's f w onto the gimbal rates. The spin motor holds the spin
  // relative to the inner gimbal, which rolls about the spin axis at `frame_roll`: the rotor's
  // momentum is H + J0 frame_roll. The motor's reaction as it follows frame_roll is not
  // carried: it is a derivative of estimated rates, and with real pickoff noise it cost more
  // than it gave (docs/gimbal-geometry.md, "Spin motor").
  [[nodiscard]] Vector2<T> torque_on_gyro_axes(const GyroStepInput<T>& in, const Vector2<T>& torquer,
                                               T& frame_roll) const noexcept {
    const GimbalFrame<T>& start = frame();  // the last step's end
    const Vector2<T> rate_on_gimbal = transpose_times(start.gimbal_to_gyro, rate_rad_s_);
    const Vector2<T> body_on_gimbal = body_rate_on_gimbal(start, in.body_rate_rad_s);
    frame_roll = inner_gimbal_roll(start, in.body_rate_rad_s, rate_on_gimbal, body_on_gimbal);
    const T half_dt = T(0.5) * in.dt_s;
    const T pitch_rate = rate_on_gimbal(0) - body_on_gimbal(0);  // th'
    Vector2<T> t = rotor_torque_on_gyro_axes_moved(start, torquer, pitch_rate * half_dt, frame_roll * half_dt);
    t += times(start.gimbal_to_gyro, friction_correction(start, config_.friction, rate_on_gimbal, body_on_gimbal));
    // The exact step precesses with the readback's H: the rest of the momentum, J0 frame_roll,
    // needs (J0 frame_roll) (w_z, -w_y) more, taken off the torque (a quarter turn of w).
    t += config_.spin_inertia * frame_roll * Vector2<T>(-rate_rad_s_(1), rate_rad_s_(0));
    return t;
  }

  // The torque that carries the error sources' drifts and the torquer's cross-coupling.
  [[nodiscard]] Vector2<T> with_error_sources(const GyroStepInput<T>& in, const Vector2<T>& rotor_torque,
                                              T h) const noexcept {
    if (drift_needs_angles_) (void)refresh_angles();  // otherwise they enter multiplied by zero
    const Vector2<T> gimbal(gimbal_.pitch_rad, gimbal_.yaw_rad);
    const Vector2<T> drift = error_drift(config_.errors, gimbal, in.body_accel, config_.gravity);
    Vector2<T> torque = cross_coupled_torque(config_.errors, rotor_torque) + torque_for_rate_frictionless(h, drift);
    // Coulomb friction against the steady precession of all the other torques (none when
    // f = H = 0: then there is no precession, and a drift would be no torque anyway).
    if (nutation_map_.has_steady) {
      Vector2<T> precession;
      precession.noalias() = nutation_map_.steady_from_torque * torque;
      torque += torque_for_rate_frictionless(h, coulomb_drift(config_.errors, precession));
    }
    return torque;
  }

  // Total cone (the listing's GP(1) > COS(GIMBAL) test) and, if set, each axis against its
  // own limit (the listing compared an angle with a cosine).
  [[nodiscard]] std::uint32_t gimbal_flag(const GimbalAngles<T>& g) const noexcept {
    bool out = g.cosine_of_cone < cos_cone_limit_;
    if (config_.pitch_gimbal_limit_rad > T(0)) out = out || std::abs(g.pitch_rad) > config_.pitch_gimbal_limit_rad;
    if (config_.yaw_gimbal_limit_rad > T(0)) out = out || std::abs(g.yaw_rad) > config_.yaw_gimbal_limit_rad;
    return out ? static_cast<std::uint32_t>(kFlagGimbalLimit) : 0u;
  }

  GyroModelConfig<T> config_{};
  T cos_cone_limit_{T(1)};
  bool configured_{false};
  bool uncaged_{false};
  Quaternion<T> q_gyro_to_earth_{Quaternion<T>::Identity()};
  Vector2<T> rate_rad_s_{Vector2<T>::Zero()};
  Vector2<T> isaf_angle_rad_{Vector2<T>::Zero()};
  Vector2<T> pending_correction_{Vector2<T>::Zero()};  // turned at the next step's start
  Vector2<T> nutation_amplitude_rad_{Vector2<T>::Zero()};
  Vector2<T> applied_torque_{Vector2<T>::Zero()};
  mutable GimbalAngles<T> gimbal_{};  // read lazily after a correction (refresh_angles)
  mutable std::uint32_t flags_{0};
  mutable bool angles_stale_{false};
  bool drift_needs_angles_{false};
  bool has_error_sources_{false};
  Matrix3<T> R_earth_to_body_{Matrix3<T>::Identity()};  // the last correction's body (refresh_angles)
  // The gimbal frame at the end of the last step, and a spare the next step writes its end
  // frame into (kept only if the step succeeds: no copy of the frame per step).
  std::array<GimbalFrame<T>, 2> frames_{};
  std::uint32_t frame_index_{0};
  [[nodiscard]] const GimbalFrame<T>& frame() const noexcept { return frames_[frame_index_]; }
  RotorTransition<T> transition_{};  // cached while H and dt stay the same
  NutationMap<T> nutation_map_{};    // cached with it (depends on H only)
  T cached_h_{};
  bool cache_valid_{false};
  T frame_roll_{};               // the inner gimbal's roll rate about the spin axis, last step
  bool have_frame_roll_{false};  // none yet since uncaging
};

}  // namespace gyro
