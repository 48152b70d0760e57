#include "sil_runner.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <type_traits>
#include <string>
#include <vector>

#include "body_motion.hpp"
#include "flight_computer.hpp"
#include "gyro/gyro_component.hpp"
#include "gyro/sil_loop.hpp"
#include "gyro/sil_contract.hpp"
#include "gyro/simulated_gyro.hpp"
#include "los_tracking.hpp"
#include "pil_flight.hpp"
#include "scenario_limits.hpp"

namespace gyro::sil {

namespace {

// What a column holds, for the bound of a row's length (csv_size_bound).
enum class Kind : std::uint8_t {
  kReal,        // a number, %.9e
  kTick,        // k, at most run.ticks
  kFlags,       // the component's flag word
  kTruthFlags,  // bits 0..2
  kFaultBits,   // one bit per FaultKind
  kStatus,      // a gyro::Status
  kMode,        // a mode's name
  kRequest,     // a mode request's name
};

struct Column {
  std::string_view name;
  Kind kind;
};

// The CSV's columns, in order, each with what it holds and its value: f(column, value) where
// value is a double, an unsigned integer or a name. The one list the header, the rows, the
// bound of a row's length and the finiteness count are made from. The required columns
// (kRequiredColumns) come first.
template <typename F>
void for_each_column(const TickRecord& r, F&& f) {
  const auto u = [](std::uint32_t v) { return static_cast<std::uint64_t>(v); };
  f(Column{"t", Kind::kReal}, r.t_s);
  f(Column{"mode", Kind::kMode}, enum_name_or(r.mode, "unknown"));
  f(Column{"gimbal_pitch", Kind::kReal}, r.gimbal_true_rad(0));
  f(Column{"gimbal_yaw", Kind::kReal}, r.gimbal_true_rad(1));
  f(Column{"gimbal_pitch_meas", Kind::kReal}, r.gimbal_measured_rad(0));
  f(Column{"gimbal_yaw_meas", Kind::kReal}, r.gimbal_measured_rad(1));
  f(Column{"theta_rate", Kind::kReal}, r.rate_est_rad_s(0));
  f(Column{"psi_rate", Kind::kReal}, r.rate_est_rad_s(1));
  f(Column{"torque_pitch", Kind::kReal}, r.torque_cmd(0));
  f(Column{"torque_yaw", Kind::kReal}, r.torque_cmd(1));
  f(Column{"flags", Kind::kFlags}, u(r.flags));
  // extras
  f(Column{"tick", Kind::kTick}, r.tick);
  f(Column{"gimbal_pitch_pred", Kind::kReal}, r.gimbal_predicted_rad(0));
  f(Column{"gimbal_yaw_pred", Kind::kReal}, r.gimbal_predicted_rad(1));
  f(Column{"residual_pitch", Kind::kReal}, r.residual_rad(0));
  f(Column{"residual_yaw", Kind::kReal}, r.residual_rad(1));
  f(Column{"theta_rate_true", Kind::kReal}, r.rate_true_rad_s(0));
  f(Column{"psi_rate_true", Kind::kReal}, r.rate_true_rad_s(1));
  f(Column{"rate_cmd_pitch", Kind::kReal}, r.rate_cmd_rad_s(0));
  f(Column{"rate_cmd_yaw", Kind::kReal}, r.rate_cmd_rad_s(1));
  f(Column{"slew_cmd_pitch", Kind::kReal}, r.slew_cmd_rad_s(0));
  f(Column{"slew_cmd_yaw", Kind::kReal}, r.slew_cmd_rad_s(1));
  f(Column{"request", Kind::kRequest}, request_name(r.request));
  f(Column{"nutation_pitch", Kind::kReal}, r.nutation_est_rad(0));
  f(Column{"nutation_yaw", Kind::kReal}, r.nutation_est_rad(1));
  f(Column{"nutation_pitch_true", Kind::kReal}, r.nutation_true_rad(0));
  f(Column{"nutation_yaw_true", Kind::kReal}, r.nutation_true_rad(1));
  f(Column{"cone_true", Kind::kReal}, r.cone_true_rad);
  f(Column{"spin_hz", Kind::kReal}, r.spin_hz);
  f(Column{"spin_hz_true", Kind::kReal}, r.spin_hz_true);
  f(Column{"torque_applied_pitch", Kind::kReal}, r.torque_applied(0));
  f(Column{"torque_applied_yaw", Kind::kReal}, r.torque_applied(1));
  f(Column{"body_pitch_rate", Kind::kReal}, r.body_rate_rad_s(1));
  f(Column{"body_yaw_rate", Kind::kReal}, r.body_rate_rad_s(2));
  f(Column{"truth_flags", Kind::kTruthFlags}, u(r.truth_flags));
  f(Column{"active_faults", Kind::kFaultBits}, u(r.active_faults));
  f(Column{"step_status", Kind::kStatus}, static_cast<std::uint64_t>(r.step_status));
  if (r.tracking) {
    f(Column{"pointing_error_true", Kind::kReal}, r.pointing_error_true_rad);
    f(Column{"los_rate_error", Kind::kReal}, r.los_rate_error_rad_s);
  }
}

// The columns of a run without and with tracking, once (sil_app_test checks the required ones
// lead, in order).
std::vector<Column> make_column_table(bool tracking) {
  TickRecord r;
  r.tracking = tracking;
  std::vector<Column> t;
  for_each_column(r, [&](const Column& c, const auto&) { t.push_back(c); });
  return t;
}

const std::vector<Column>& column_table(bool tracking) {
  static const std::vector<Column> plain = make_column_table(false), tracked = make_column_table(true);
  return tracking ? tracked : plain;
}

std::vector<std::string_view> make_names(bool tracking) {
  std::vector<std::string_view> n;
  for (const Column& c : column_table(tracking)) n.push_back(c.name);
  return n;
}

const std::vector<std::string_view>& columns(bool tracking) {
  static const std::vector<std::string_view> plain = make_names(false), tracked = make_names(true);
  return tracking ? tracked : plain;
}

std::uint64_t nonfinite_count(const TickRecord& r) {
  std::uint64_t n = 0;
  for_each_column(r, [&](const Column&, const auto& v) {
    if constexpr (std::is_same_v<std::decay_t<decltype(v)>, double>) {
      if (!std::isfinite(v)) ++n;
    }
  });
  return n;
}

// A configuration read in double, in the run's scalar type (field by field, through its table).
template <typename T, template <class> class Config>
Config<T> cast_config(const Config<double>& d) {
  Config<T> out;
  cast_fields(d, out);
  return out;
}

// The refusal's rule as format_refusal words it ("residual_limit_rad = 1e-05 is below ...").
std::string rule_text(const ConfigCheck& c) {
  std::array<char, 512> buf{};
  (void)format_refusal(c, nullptr, buf.data(), buf.size());
  return std::string(buf.data());
}

std::string refusal(const Scenario& s, const std::string& path, const char* who, const ConfigCheck& c) {
  std::string r = to_string(c.status);
  if (c.status == Status::kNumericalOverflow) r += ": the rotor's exact step over one tick overflows";
  const std::map<std::string, std::string> values = written_values(s);
  const auto v = values.find(path);
  if (v != values.end()) r += " (value " + v->second + ")";
  r += "; refused by ";
  r += who;
  r += "::configure";
  if (s.run.precision == Precision::kFloat) r += " in float";
  if (c.relation != Relation::kNone || c.rule != nullptr) r += ": " + rule_text(c);
  return r;
}

// Every further rule of `all` after the first, as "; also component.x = ... : why".
template <std::size_t N>
std::string also(const Scenario& s, const ConfigCheckList<N>& all) {
  std::string r;
  for (std::size_t i = 1; i < all.size(); ++i) {
    r += "; also " + component_field_path(s, all[i].field ? all[i].field : "(unnamed)") + ": " + rule_text(all[i]);
  }
  if (all.total() > all.size()) r += "; and " + std::to_string(all.total() - all.size()) + " more";
  return r;
}

// Configures both sides; a refusal names the scenario's JSON field, its value, the bound and
// the rule, and lists every other rule the component's configuration breaks.
template <typename T>
void configure_both(const Scenario& s, SimulatedGyro<T>& stub, FlightComputer<T>& comp) {
  const SimulatedGyroConfig<T> gyro = cast_config<T>(s.gyro);
  const ConfigCheck g = stub.configure(gyro);
  if (!g.ok()) {
    const std::string path = gyro_field_path(s, g.field ? g.field : "(unnamed)");
    throw ScenarioError(s.file, path, refusal(s, path, "SimulatedGyro", g));
  }
  const GyroComponentConfig<T> component = cast_config<T>(s.component);
  const ConfigCheck c = comp.configure(component);
  if (!c.ok()) {
    ConfigCheckList<32> all;
    check_all(component, all);
    const std::string path = component_field_path(s, c.field ? c.field : "(unnamed)");
    throw ScenarioError(s.file, path, refusal(s, path, "GyroComponent", c) + also(s, all));
  }
  ConfigCheckList<32> pair;
  check_against_hardware(gyro, component, pair);
  if (!pair.empty()) {
    const std::string path = component_field_path(s, pair[0].field);
    throw ScenarioError(s.file, path,
                        to_string(pair[0].status) + std::string(" against the gyro's hardware: ") + rule_text(pair[0]) +
                            also(s, pair));
  }
}

// The guidance schedule, replayed tick by tick: requests fire once, commands are held.
class GuidancePlayer {
 public:
  explicit GuidancePlayer(const std::vector<GuidanceEvent>& events) : events_(events) {}

  // Applies every event due at `tick`; returns the request of this tick (the last one due).
  ModeRequest at(std::uint64_t tick) {
    ModeRequest request = ModeRequest::kNone;
    while (next_ < events_.size() && events_[next_].tick <= tick) {
      const GuidanceEvent& e = events_[next_++];
      if (e.request != ModeRequest::kNone) request = e.request;
      if (e.slew_rate_rad_s) slew_ = *e.slew_rate_rad_s;
      if (e.nav_valid) nav_valid_ = *e.nav_valid;
    }
    return request;
  }
  [[nodiscard]] const Eigen::Vector2d& slew() const { return slew_; }
  [[nodiscard]] bool nav_valid() const { return nav_valid_; }

 private:
  const std::vector<GuidanceEvent>& events_;
  std::size_t next_{0};
  Eigen::Vector2d slew_{Eigen::Vector2d::Zero()};
  bool nav_valid_{true};
};

class Progress {
 public:
  Progress(const RunOptions& o, std::uint64_t ticks) : o_(o), ticks_(ticks) {}
  void tick(std::uint64_t k, double t) {
    if (!o_.progress || o_.progress_out == nullptr) return;
    const std::uint64_t decile = ticks_ == 0 ? 10 : (k * 10) / ticks_;
    if (decile == last_decile_) return;
    last_decile_ = decile;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < 1.0 && !printed_) return;  // short runs stay quiet
    printed_ = true;
    std::fprintf(o_.progress_out, "%s: %3llu%% (tick %llu of %llu, t = %.4f s, %.1f s elapsed)\n", o_.label.c_str(),
                 static_cast<unsigned long long>(decile * 10), static_cast<unsigned long long>(k),
                 static_cast<unsigned long long>(ticks_), t, elapsed);
    std::fflush(o_.progress_out);
  }
  [[nodiscard]] double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  const RunOptions& o_;
  std::uint64_t ticks_;
  std::uint64_t last_decile_{0};
  bool printed_{false};
  std::chrono::steady_clock::time_point start_{std::chrono::steady_clock::now()};
};

template <typename T>
RunSummary run_in(const Scenario& s, TickObserver& observer, const RunOptions& options) {
  RunSummary sum;
  SimulatedGyro<T> stub;
  std::unique_ptr<FlightComputer<T>> flight;
  if (options.pil) {
    sum.pil.emplace();
    flight = make_pil_flight(stub, *options.pil, *sum.pil);
  } else {
    flight = std::make_unique<LocalFlightComputer<T>>(stub);
  }
  FlightComputer<T>& comp = *flight;
  configure_both<T>(s, stub, comp);

  sum.precision = s.run.precision;
  sum.ticks = s.run.ticks;

  try {
    check_trajectory_covers_run(s);  // the curve is never extrapolated
  } catch (const ScenarioError& e) {
    throw RunError(e.what());
  }
  BodyMotion body(s.body, s.run.tick_s);
  GuidancePlayer guidance(s.guidance);
  Progress progress(options, s.run.ticks);

  // The body's truth at the current tick, in the run's scalar.
  const auto sample = [&body] {
    BodySample<T> b;
    b.R_earth_to_body = body.R_earth_to_body().cast<T>();
    b.rate_rad_s = body.rate_rad_s().cast<T>();
    b.specific_force = body.specific_force().cast<T>();
    return b;
  };
  SilLoop<T, FlightComputer<T>> loop(stub, comp);
  const SilStatus<Status> started = loop.start(sample());
  if (started.stub != Status::kOk) {
    throw RunError(std::string("SimulatedGyro::start refused: ") + to_string(started.stub));
  }
  if (started.component != Status::kOk) {
    throw RunError(std::string("GyroComponent::activate refused: ") + to_string(started.component));
  }
  Status last_step = Status::kOk;  // held over the ticks a processor in the loop skipped

  observer.set_extra_columns(comp.extra_columns(), [&comp](CsvWriter& w) { comp.write_extras(w); });
  observer.on_start(s);
  TickRecord rec;
  rec.tracking = s.track.has_value();
  const Eigen::Vector2d rate_limits(s.component.max_pitch_rate_rad_s, s.component.max_yaw_rate_rad_s);
  // The body's attitude at the tick of the component's last estimate (a tracker sees the
  // estimate published last tick).
  Eigen::Matrix3d R_at_estimate = body.R_earth_to_body();
  for (std::uint64_t k = 0; k <= s.run.ticks; ++k) {
    if (k > 0) body.advance();
    GuidanceCommand<T> command;
    command.request = guidance.at(k);
    Eigen::Vector2d slew = guidance.slew();
    if (s.track && k >= s.track->start_tick) {
      const double t_estimate = static_cast<double>(k == 0 ? 0 : k - 1) * s.run.tick_s;
      const Eigen::Vector2d estimate = comp.telemetry().gimbal_predicted_rad.template cast<double>();
      slew = track_command(line_of_sight_at(s.track->los, t_estimate), spin_axis_earth(estimate, R_at_estimate),
                           body.R_earth_to_body(), s.track->gain_1_s, rate_limits);
    }
    command.slew_rate_cmd_rad_s = slew.template cast<T>();
    command.nav_valid = guidance.nav_valid();
    const SilStatus<std::optional<Status>> ran = loop.tick(k, sample(), command);
    if (ran.stub != Status::kOk) {
      throw RunError("tick " + std::to_string(k) + ": SimulatedGyro::advance refused: " + to_string(ran.stub));
    }
    if (ran.component && *ran.component != Status::kOk && *ran.component != Status::kInputIgnored) {
      ++sum.refused_steps;
    }
    const Status step = ran.component.value_or(last_step);
    last_step = step;

    const GyroTelemetry<T>& tm = comp.telemetry();
    const Vector2<T> truth_angle = stub.gimbal_angle_rad();
    const Vector2<T> truth_rate = stub.spin_axis_rate_rad_s();
    const GyroModel<T>* report = stub.report_model();
    const Vector2<T> truth_nutation = report != nullptr ? report->nutation_amplitude_rad() : Vector2<T>(Vector2<T>::Zero());
    const std::uint32_t truth_flags = report != nullptr ? report->flags() : 0u;
    sum.flags_seen |= tm.flags;
    if (stub.at_gimbal_stop()) ++sum.gimbal_stop_hits;
    sum.max_abs_gimbal_rad = std::max({sum.max_abs_gimbal_rad, std::abs(static_cast<double>(truth_angle(0))),
                                       std::abs(static_cast<double>(truth_angle(1)))});

    rec.tick = k;
    rec.t_s = body.time_s();
    rec.mode = tm.mode;
    rec.request = command.request;
    rec.flags = tm.flags;
    rec.gimbal_true_rad = truth_angle.template cast<double>();
    rec.gimbal_measured_rad = tm.gimbal_measured_rad.template cast<double>();
    rec.gimbal_predicted_rad = tm.gimbal_predicted_rad.template cast<double>();
    rec.residual_rad = tm.residual_rad.template cast<double>();
    rec.rate_est_rad_s = tm.precession_rate_rad_s.template cast<double>();
    rec.rate_true_rad_s = truth_rate.template cast<double>();
    rec.rate_cmd_rad_s = tm.rate_cmd_rad_s.template cast<double>();
    // What guidance and the body sent, in double (the component received them in T). Read
    // back from the input in a float run, GCC 12.2's SLP vectoriser at -O2 drops the float
    // rounding.
    rec.slew_cmd_rad_s = slew;
    rec.torque_cmd = tm.torque_cmd.template cast<double>();
    rec.nutation_est_rad = tm.nutation_amplitude_rad.template cast<double>();
    rec.nutation_true_rad = truth_nutation.template cast<double>();
    rec.cone_true_rad = static_cast<double>(stub.cone_rad());
    rec.spin_hz = static_cast<double>(tm.spin_hz);
    rec.spin_hz_true = static_cast<double>(stub.spin_hz());
    rec.torque_applied = stub.applied_torque().template cast<double>();
    rec.body_rate_rad_s = body.rate_rad_s();
    rec.at_gimbal_stop = stub.at_gimbal_stop();
    rec.truth_flags = truth_flags | (rec.at_gimbal_stop ? 4u : 0u);
    rec.active_faults = stub.active_faults();
    rec.step_status = step;
    if (s.track) {
      const LineOfSight los = line_of_sight_at(s.track->los, rec.t_s);
      rec.pointing_error_true_rad = angle_between(spin_axis_earth(rec.gimbal_true_rad, body.R_earth_to_body()), los.direction);
      rec.los_rate_error_rad_s = (spin_axis_rate_body(rec.gimbal_predicted_rad, rec.rate_est_rad_s) -
                                  spin_axis_rate_body(rec.gimbal_true_rad, rec.rate_true_rad_s))
                                     .norm();
    }
    R_at_estimate = body.R_earth_to_body();
    sum.nonfinite_values += nonfinite_count(rec);
    observer.on_tick(rec);
    ++sum.rows;

    progress.tick(k, rec.t_s);
  }

  comp.finish();
  sum.final_mode = comp.mode();
  sum.counters = comp.telemetry().counters;
  sum.wall_s = progress.elapsed_s();
  return sum;
}

}  // namespace

std::span<const std::string_view> csv_columns(bool tracking) noexcept { return columns(tracking); }

void row_cells(const TickRecord& r, std::span<CellValue> out) {
  if (out.size() != columns(r.tracking).size()) throw std::invalid_argument("row_cells: one cell per CSV column");
  std::size_t i = 0;
  for_each_column(r, [&](const Column&, const auto& v) { out[i++] = CellValue(v); });
}

namespace {

std::uint64_t decimal_digits(std::uint64_t v) {
  std::uint64_t n = 1;
  while (v >= 10) {
    v /= 10;
    ++n;
  }
  return n;
}

// The longest name a name function gives over every value of its 8-bit enum (undefined
// values included: they print as "unknown").
template <typename Enum, typename NameOf>
std::uint64_t longest_name(NameOf name_of) {
  std::size_t n = 0;
  for (unsigned v = 0; v < 256; ++v) n = std::max(n, std::string_view(name_of(static_cast<Enum>(v))).size());
  return n;
}

std::uint64_t max_chars(Kind k, std::uint64_t ticks) {
  switch (k) {
    case Kind::kReal: return kMaxScientificChars;
    case Kind::kTick: return decimal_digits(ticks);
    case Kind::kFlags: return decimal_digits((std::uint64_t{1} << kComponentFlagCount) - 1u);
    case Kind::kTruthFlags: return decimal_digits(7);
    case Kind::kFaultBits: return decimal_digits((std::uint64_t{1} << kFaultKindCount) - 1u);
    case Kind::kStatus: return decimal_digits(255);
    case Kind::kMode: return longest_name<GyroMode>([](GyroMode m) { return gyro::enum_name_or(m, "unknown"); });
    case Kind::kRequest: return longest_name<ModeRequest>([](ModeRequest r) { return request_name(r); });
  }
  return 0;
}

}  // namespace

std::uint64_t csv_row_bytes_bound(std::uint64_t ticks, bool tracking) {
  std::uint64_t n = column_table(tracking).size();  // the commas and the newline
  for (const Column& c : column_table(tracking)) n += max_chars(c.kind, ticks);
  return n;
}

std::uint64_t csv_size_bound(const Scenario& s) {
  const bool tracking = s.track.has_value();
  std::uint64_t header = column_table(tracking).size();
  for (const Column& c : column_table(tracking)) header += c.name.size();
  const std::uint64_t rows = s.run.ticks + 1;
  const std::uint64_t row = csv_row_bytes_bound(s.run.ticks, tracking);
  if (rows > (std::numeric_limits<std::uint64_t>::max() - header) / row) return std::numeric_limits<std::uint64_t>::max();
  return header + rows * row;
}

int csv_column(std::string_view name, bool tracking) noexcept {
  const std::vector<std::string_view>& c = columns(tracking);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i] == name) return static_cast<int>(i) + 1;
  }
  return 0;
}

void CsvObserver::set_extra_columns(std::span<const std::string_view> names, std::function<void(CsvWriter&)> write) {
  extra_names_ = names;
  write_extras_ = std::move(write);
}

void CsvObserver::on_start(const Scenario& s) {
  const std::span<const std::string_view> standard = csv_columns(s.track.has_value());
  std::vector<std::string_view> names(standard.begin(), standard.end());
  names.insert(names.end(), extra_names_.begin(), extra_names_.end());
  csv_.header(names);
}

void CsvObserver::on_tick(const TickRecord& r) {
  for_each_column(r, [&](const Column&, const auto& v) {
    using V = std::decay_t<decltype(v)>;
    if constexpr (std::is_same_v<V, double>) {
      csv_.number(v);
    } else if constexpr (std::is_same_v<V, std::uint64_t>) {
      csv_.integer(v);
    } else {
      csv_.text(v);
    }
  });
  if (write_extras_) write_extras_(csv_);
  csv_.end_row();
  if (!csv_.ok()) throw RunError("writing the CSV failed at tick " + std::to_string(r.tick));
  if (csv_.bytes() > max_bytes_) {
    throw RunError("the CSV passed its limit of " + std::to_string(max_bytes_) + " bytes at tick " +
                   std::to_string(r.tick));
  }
}

void check_configs(const Scenario& s) {
  check_precision_range(s);
  if (s.run.precision == Precision::kFloat) {
    SimulatedGyro<float> stub;
    LocalFlightComputer<float> comp(stub);
    configure_both<float>(s, stub, comp);
  } else {
    SimulatedGyro<double> stub;
    LocalFlightComputer<double> comp(stub);
    configure_both<double>(s, stub, comp);
  }
  check_run_limits(s);
}

Scenario load_scenario(const std::filesystem::path& path, std::optional<Precision> precision) {
  Scenario s = read_scenario(path);
  if (precision) s.run.precision = *precision;
  check_configs(s);
  return s;
}

RunSummary run_scenario(const Scenario& s, TickObserver& observer, const RunOptions& options) {
  if (s.run.precision == Precision::kFloat) return run_in<float>(s, observer, options);
  return run_in<double>(s, observer, options);
}

RunSummary run_scenario(const Scenario& s, CsvWriter& csv, const RunOptions& options) {
  CsvObserver observer(csv, options.max_csv_bytes);
  return run_scenario(s, observer, options);
}

std::string flag_names(std::uint32_t flags) {
  std::string out;
  for (int i = 0; i < kComponentFlagCount; ++i) {
    if ((flags & (1u << static_cast<unsigned>(i))) == 0u) continue;
    if (!out.empty()) out += '|';
    out += flag_name(i);
  }
  return out;
}

}  // namespace gyro::sil
