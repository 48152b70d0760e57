#include "scenario_limits.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gyro/error_sources.hpp"
#include "gyro/rotor_transition.hpp"

namespace gyro::sil {

namespace {

// A value and the scenario field it comes from.
struct Factor {
  double value;
  std::string field;
};

// How far from 1 in magnitude (0 for 0): of the factors of a quantity that overflows, the one
// furthest from 1 is the one to name.
double extremeness(double v) {
  const double a = std::abs(v);
  return a > 0 ? std::abs(std::log(a)) : 0.0;
}

// A non-negative part of a bound: the product of its factors (a constant factor has no field).
struct Term {
  double value;
  std::vector<Factor> factors;
};

// A zero factor makes the term 0 whatever the others (it contributes nothing), so a term is
// never NaN.
Term product(std::vector<Factor> factors) {
  double v = 1.0;
  for (const Factor& f : factors) v *= std::abs(f.value);
  for (const Factor& f : factors) {
    if (f.value == 0) v = 0;
  }
  return Term{v, std::move(factors)};
}

std::string format(double v) {
  std::array<char, 32> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, 6);
  return std::string(buf.data(), r.ptr);
}

[[noreturn]] void refuse(const Scenario& s, const std::vector<Term>& terms, const std::string& reason) {
  const Term* largest = &terms.front();
  for (const Term& t : terms) {
    if (t.value > largest->value) largest = &t;
  }
  const Factor* culprit = nullptr;
  for (const Factor& f : largest->factors) {
    if (f.field.empty()) continue;
    if (culprit == nullptr || extremeness(f.value) > extremeness(culprit->value)) culprit = &f;
  }
  throw ScenarioError(s.file, culprit != nullptr ? culprit->field : s.run.tick_field, reason);
}

const char* precision_name(const Scenario& s) { return to_string(s.run.precision); }

// ---------------------------------------------------------------------------------------
// Every number within float's range, for a float run.

void float_range(const Scenario& s) {
  constexpr auto kMax = static_cast<double>(std::numeric_limits<float>::max());
  for (const auto& [path, text] : written_values(s)) {
    double v = 0;
    const std::from_chars_result r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size()) continue;  // not a number
    if (std::abs(v) > kMax) {
      throw ScenarioError(s.file, path,
                          text + " is beyond float's range (largest 3.4028235e+38): not representable in float");
    }
  }
}

// ---------------------------------------------------------------------------------------
// The body's motion.

// A recorded trajectory's largest rate |(p, q, r)| or specific force |(x, y, z)| (offset 0),
// or its largest |f| on one axis (offset 1 + axis), with the field of that row's largest part.
struct TrajectoryPeak {
  double value{0};
  std::string field;  // body.trajectory.file for a file, "p_rad_s[12]" for arrays
  std::string where;  // "FILE: p_rad_s (line 14): " for a file, "" for arrays
};

TrajectoryPeak trajectory_peak(const BodyTrajectory& tr, const std::string& file_field, bool force, int axis) {
  TrajectoryPeak peak;
  std::size_t at = 0;
  for (std::size_t i = 0; i < tr.samples.size(); ++i) {
    const Eigen::Vector3d& v = force ? tr.samples[i].specific_force : tr.samples[i].rate_rad_s;
    const double m = axis < 0 ? v.norm() : std::abs(v(axis));
    if (i == 0 || m > peak.value) {
      peak.value = m;
      at = i;
    }
  }
  const Eigen::Vector3d& v = force ? tr.samples[at].specific_force : tr.samples[at].rate_rad_s;
  Eigen::Index largest = axis;
  if (axis < 0) v.cwiseAbs().maxCoeff(&largest);
  const std::size_t first = tr.columns.size() - 6 + (force ? 3 : 0);
  const std::string row = trajectory_field(tr, at, tr.columns[first + static_cast<std::size_t>(largest)]);
  peak.field = tr.from_file ? file_field : row;
  peak.where = tr.from_file ? tr.source + ": " + row + ": " : "";
  return peak;
}

// The body's specific force on `axis` (its largest over a trajectory) and its field.
Factor body_force(const Scenario& s, int axis) {
  if (s.body.trajectory) {
    const TrajectoryPeak p = trajectory_peak(*s.body.trajectory, s.body.trajectory_spec->file_field, true, axis);
    return {p.value, p.field};
  }
  return {s.body.specific_force[static_cast<std::size_t>(axis)], body_force_field(s, axis)};
}

// The fields the body's rates come from: q, r, their weave amplitudes, p.
std::vector<Factor> body_rate_factors(const Scenario& s) {
  const BodyProfile& b = s.body;
  return {
      {b.rate_rad_s[1], body_rate_field(s, 1)},
      {b.rate_rad_s[2], body_rate_field(s, 2)},
      {b.weave.pitch_amplitude_rad_s, "body.weave.pitch_amplitude_rad_s"},
      {b.weave.yaw_amplitude_rad_s, "body.weave.yaw_amplitude_rad_s"},
      {b.rate_rad_s[0], body_rate_field(s, 0)},
  };
}

// The largest |(p, q, r)| the body reaches (constant rates plus the weave at its crest).
double peak_body_rate(const std::vector<Factor>& f) {
  const double q = std::abs(f[0].value) + std::abs(f[2].value);
  const double r = std::abs(f[1].value) + std::abs(f[3].value);
  return std::hypot(std::abs(f[4].value), std::hypot(q, r));
}

const std::string& largest_field(const std::vector<Factor>& factors) {
  const Factor* largest = &factors.front();
  for (const Factor& f : factors) {
    if (std::abs(f.value) > std::abs(largest->value)) largest = &f;
  }
  return largest->field;
}

void check_trajectory_body(const Scenario& s) {
  const BodyProfile& b = s.body;
  if (!b.trajectory) {
    throw ScenarioError(s.file, b.trajectory_spec->file_field,
                        "missing required field (or give the trajectory's columns from Python)");
  }
  const TrajectoryPeak rate = trajectory_peak(*b.trajectory, b.trajectory_spec->file_field, false, -1);
  const double turn = rate.value * s.run.tick_s;
  if (!(turn <= kTwoPi / 2)) {
    throw ScenarioError(s.file, rate.field,
                        rate.where + "the body would turn by " + format(turn) + " rad in one tick at this row's rates (" +
                            format(rate.value) + " rad/s), more than pi: give a shorter tick or lower rates");
  }
  check_trajectory_covers_run(s);
}

void check_body(const Scenario& s) {
  const BodyProfile& b = s.body;
  if (b.trajectory_spec) {
    check_trajectory_body(s);
    return;
  }
  const double tick = s.run.tick_s;
  const std::vector<Factor> peaks = body_rate_factors(s);
  const double turn = peak_body_rate(peaks) * tick;
  if (!(turn <= kTwoPi / 2)) {
    throw ScenarioError(s.file, largest_field(peaks),
                        "the body would turn by " + format(turn) +
                            " rad in one tick at its peak rates, more than pi: the tick cannot represent it "
                            "(aliased), give a shorter tick or lower rates");
  }
  if (b.weave.frequency_hz > 0.5 / tick) {
    throw ScenarioError(s.file, "body.weave.frequency_hz",
                        "above the tick's Nyquist rate (" + format(0.5 / tick) +
                            " Hz): the rates sampled at the ticks would not show the weave");
  }
}

// ---------------------------------------------------------------------------------------
// The torque on the emulated rotor (SimulatedGyro::torque_on_rotor, then
// GyroModel::step_torque: cross-coupling, error-source drifts as H * drift, Coulomb).

std::string axis_errors(int axis) { return axis == 0 ? "gyro.errors.pitch." : "gyro.errors.yaw."; }

// Bound of the torquer's torque on one axis, as terms (any one of them may be the largest).
std::vector<Term> torquer_terms(const Scenario& s, int axis) {
  const auto i = static_cast<Eigen::Index>(axis);
  const std::string idx = "[" + std::to_string(axis) + "]";
  std::vector<Term> terms;
  const double stub_limit = s.gyro.torquer.max_torque;
  Term command = product({{s.gyro.torquer.scale_factor(i), "gyro.torquer.scale_factor" + idx},
                          {s.component.max_torque, "component.max_torque"}});
  if (stub_limit > 0 && !(command.value <= stub_limit)) command = product({{stub_limit, "gyro.torquer.max_torque"}});
  terms.push_back(command);
  for (std::size_t k = 0; k < s.fault_count; ++k) {
    const FaultEvent<double>& f = s.gyro.faults[k];
    if (f.kind != FaultKind::kSaturatedTorquer || !(f.axis < 0 || f.axis == axis)) continue;
    terms.push_back(product({{f.magnitude, "gyro.faults[" + std::to_string(k) + "].magnitude"}}));
  }
  return terms;
}

// The terms of the bound of the torque on `axis` in the model's step.
std::vector<Term> rotor_torque_terms(const Scenario& s, int axis) {
  const GyroModelConfig<double>& m = s.gyro.gyro;
  // Axis 0 (T1) carries the yaw drift (T1 = H psi'), axis 1 the pitch drift; cross-coupling
  // leaks the other axis' torquer torque in with the coupling of the drifted axis.
  const int drifted = 1 - axis;
  const AxisErrorSources<double>& e = drifted == 0 ? m.errors.pitch : m.errors.yaw;
  const std::string err = axis_errors(drifted);

  std::vector<Term> terms = torquer_terms(s, axis);
  const std::vector<Term> other = torquer_terms(s, 1 - axis);
  for (const Term& t : other) {
    std::vector<Factor> f = t.factors;
    f.push_back({e.torquer_cross_coupling, err + "torquer_cross_coupling"});
    terms.push_back(product(std::move(f)));
  }

  const std::string spin_field = extremeness(s.gyro.spin_hz) >= extremeness(m.spin_inertia) ? "gyro.rotor.spin_hz"
                                                                                             : "gyro.rotor.spin_inertia";
  const Factor h{kTwoPi * s.gyro.spin_hz * m.spin_inertia, spin_field};
  const Factor largest_angle{kTwoPi / 2, ""};
  const Factor force = body_force(s, drifted + 1);
  const double accel = force.value;
  const double g_excess = std::abs(accel) > m.gravity ? std::abs(accel) / m.gravity - 1.0 : 0.0;
  const std::string accel_field = extremeness(accel) >= extremeness(m.gravity) ? force.field
                                                                               : std::string("gyro.gravity");
  terms.push_back(product({h, {e.static_drift_rad_s, err + "static_drift_rad_s"}}));
  terms.push_back(product({h, {e.in_plane_erection_1_s, err + "in_plane_erection_1_s"}, largest_angle}));
  terms.push_back(product({h, {e.cross_plane_erection_1_s, err + "cross_plane_erection_1_s"}, largest_angle}));
  terms.push_back(product({h, {e.g_sensitive_drift_rad_s, err + "g_sensitive_drift_rad_s"}, {g_excess, accel_field}}));
  terms.push_back(product({h, {e.coulomb_friction_rad_s, err + "coulomb_friction_rad_s"}}));
  return terms;
}

template <typename T>
void check_rotor_torque(const Scenario& s) {
  // The g-sensitive drift's factor accel / gravity is computed on its own first.
  const GyroModelConfig<double>& m = s.gyro.gyro;
  for (std::size_t i = 0; i < 2; ++i) {
    const Factor force = body_force(s, static_cast<int>(i) + 1);
    const double accel = force.value;
    if (!(std::abs(accel) / m.gravity <= static_cast<double>(std::numeric_limits<T>::max()))) {
      const std::string& accel_field = force.field;
      throw ScenarioError(s.file, extremeness(accel) >= extremeness(m.gravity) ? accel_field : "gyro.gravity",
                          "the acceleration in units of gyro.gravity is not representable in " +
                              std::string(precision_name(s)));
    }
  }

  std::vector<Term> all;
  Vector2<T> bound = Vector2<T>::Zero();
  bool representable = true;
  for (int axis = 0; axis < 2; ++axis) {
    const std::vector<Term> terms = rotor_torque_terms(s, axis);
    double sum = 0;
    for (const Term& t : terms) sum += t.value;
    representable = representable && sum <= static_cast<double>(std::numeric_limits<T>::max());
    if (representable) bound(axis) = static_cast<T>(sum);
    all.insert(all.end(), terms.begin(), terms.end());
  }
  const std::string reason = std::string("the largest torque that can act on the emulated rotor ") +
                             "(torquer, faults, cross-coupling, error-source drifts) is not representable in " +
                             precision_name(s) + " over one tick";
  if (!representable) refuse(s, all, reason);

  // The stub's rotor at its start spin: its transition was checked by configure().
  const RotorParameters<T> rotor{static_cast<T>(m.pitch_inertia), static_cast<T>(m.yaw_inertia),
                                 static_cast<T>(m.friction),
                                 angular_momentum(static_cast<T>(s.gyro.spin_hz), static_cast<T>(m.spin_inertia))};
  RotorTransition<T> tr;
  if (make_transition(rotor, static_cast<T>(s.run.tick_s), tr) != Status::kOk) return;  // configure() refuses it
  RotorState<T> from_rest;
  if (advance(tr, bound, from_rest) != Status::kOk) refuse(s, all, reason);
  // From the steady precession the torque drives (the nutation can overshoot it twice).
  Vector2<T> steady = Vector2<T>::Zero();
  const Status st = steady_precession_rate(rotor, bound, steady);
  RotorState<T> precessing;
  precessing.rate_rad_s = T(2) * steady.cwiseAbs();
  if ((st != Status::kOk && st != Status::kNoSteadyState) || !all_finite(precessing.rate_rad_s) ||
      advance(tr, bound, precessing) != Status::kOk) {
    refuse(s, all, reason);
  }
}

// The gimbal plant's envelope (GimbalPlantConfig's max_*): outside it the plant refuses a
// step, and the run would stop on a tick.
void check_gimbal_envelope(const Scenario& s) {
  if (s.gyro.plant != PlantKind::kGimbal) return;
  const GimbalPlantConfig<double>& g = s.gyro.gimbal;
  std::vector<Factor> rates;
  double peak_rate = 0;
  std::string where;
  if (s.body.trajectory) {
    const TrajectoryPeak p = trajectory_peak(*s.body.trajectory, s.body.trajectory_spec->file_field, false, -1);
    rates = {{p.value, p.field}};
    peak_rate = p.value;
    where = p.where;
  } else {
    rates = body_rate_factors(s);
    peak_rate = peak_body_rate(rates);
  }
  if (!(peak_rate <= g.max_body_rate_rad_s)) {
    throw ScenarioError(s.file, largest_field(rates),
                        where + "the body's peak rate |(p, q, r)| of " + format(peak_rate) +
                            " rad/s is more than gyro.gimbal.max_body_rate_rad_s (" +
                            format(g.max_body_rate_rad_s) + ")");
  }
  std::vector<Factor> force = {body_force(s, 0), body_force(s, 1), body_force(s, 2)};
  double f = std::hypot(force[0].value, std::hypot(force[1].value, force[2].value));
  if (s.body.trajectory) {
    const TrajectoryPeak p = trajectory_peak(*s.body.trajectory, s.body.trajectory_spec->file_field, true, -1);
    force = {{p.value, p.field}};
    f = p.value;
    where = p.where;
  }
  if (!(f <= g.max_specific_force)) {
    throw ScenarioError(s.file, largest_field(force),
                        where + "the body's specific force of " + format(f) + " is more than "
                            "gyro.gimbal.max_specific_force (" + format(g.max_specific_force) + ")");
  }
  const Term unbalance = product({{g.mass_unbalance, "gyro.gimbal.mass_unbalance"}, {f, largest_field(force)}});
  if (!(unbalance.value <= g.max_torque)) {
    refuse(s, {unbalance}, "the mass unbalance's torque at the body's specific force, " + format(unbalance.value) +
                               ", is more than gyro.gimbal.max_torque (" + format(g.max_torque) + ")");
  }
  for (int axis = 0; axis < 2; ++axis) {
    const std::vector<Term> terms = torquer_terms(s, axis);
    for (const Term& t : terms) {
      if (!(t.value <= g.max_torque)) {
        refuse(s, terms, "the torquer can put " + format(t.value) + " on a gimbal axis, more than "
                             "gyro.gimbal.max_torque (" + format(g.max_torque) + ")");
      }
    }
  }
}

}  // namespace

void check_trajectory_covers_run(const Scenario& s) {
  if (!s.body.trajectory) return;
  const double run_s = static_cast<double>(s.run.ticks) * s.run.tick_s;
  const double end_s = s.body.trajectory->end_s();
  // A last tick within a millionth of a tick of the end (rounding) takes the last row.
  if (!(run_s <= end_s + 1e-6 * s.run.tick_s)) {
    throw ScenarioError(s.file, s.run.length_field,
                        "the run lasts " + format(run_s) + " s, past the end of the body's trajectory at " +
                            format(end_s) + " s (" + s.body.trajectory->source + ")");
  }
}

void check_precision_range(const Scenario& s) {
  if (s.run.precision == Precision::kFloat) float_range(s);
}

void check_run_limits(const Scenario& s) {
  check_body(s);
  check_gimbal_envelope(s);
  if (s.run.precision == Precision::kFloat) {
    check_rotor_torque<float>(s);
  } else {
    check_rotor_torque<double>(s);
  }
}

}  // namespace gyro::sil
