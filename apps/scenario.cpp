// Scenario JSON -> Scenario, with every refusal naming file, JSON path and reason.
#include "scenario.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>
#include <utility>

#include "printable.hpp"

namespace gyro::sil {

namespace {

using json = nlohmann::json;

// Longest run accepted: a sanity bound (the CSV has one row per tick).
constexpr std::uint64_t kMaxTicks = 100'000'000;

struct FaultName {
  FaultKind kind;
  const char* name;
};
constexpr std::array<FaultName, 7> kFaultNames = {{
    {FaultKind::kStuckPickoff, "stuck_pickoff"},
    {FaultKind::kInvalidReading, "invalid_reading"},
    {FaultKind::kDropout, "dropout"},
    {FaultKind::kBiasJump, "bias_jump"},
    {FaultKind::kDeadTorquer, "dead_torquer"},
    {FaultKind::kSaturatedTorquer, "saturated_torquer"},
    {FaultKind::kSpinMotorFailure, "spin_motor_failure"},
}};

// A key that is a plain name joins with a dot; any other (empty, or with dots, brackets,
// spaces, quotes, control characters, non-ASCII) as a JSON string in brackets, so that a path
// always reads back to one field and prints safely.
bool plain_key(std::string_view key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}
std::string join(const std::string& path, std::string_view key) {
  std::string out = path;
  if (plain_key(key)) {
    if (!out.empty()) out += '.';
    out += key;
  } else {
    out += '[';
    out += json(std::string(key)).dump(-1, ' ', true);  // ASCII only: every other character as \uXXXX
    out += ']';
  }
  return out;
}
std::string at_index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string quoted_list(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += '"';
    out += n;
    out += '"';
  }
  return out;
}

// Reads one JSON object: refuses unknown keys up front, then hands out typed fields.
class Reader {
 public:
  Reader(const std::string& file, const json& j, std::string path, std::initializer_list<std::string_view> keys)
      : Reader(file, j, std::move(path), std::span<const std::string_view>(keys.begin(), keys.size())) {}
  Reader(const std::string& file, const json& j, std::string path, std::span<const std::string_view> keys)
      : file_(file), j_(j), path_(std::move(path)) {
    if (!j.is_object()) fail_at(path_, std::string("expected an object, got ") + j.type_name());
    for (const auto& item : j.items()) {
      const std::string& k = item.key();
      if (std::find(keys.begin(), keys.end(), k) != keys.end()) continue;
      std::string reason = "unknown key";
      std::string_view best;
      std::size_t best_d = std::numeric_limits<std::size_t>::max();
      for (std::string_view allowed : keys) {
        const std::size_t d = edit_distance(k, allowed);
        if (d < best_d) {
          best_d = d;
          best = allowed;
        }
      }
      if (!best.empty() && best_d <= std::max<std::size_t>(2, k.size() / 3)) {
        reason += " (did you mean \"" + std::string(best) + "\"?)";
      } else {
        reason += " (allowed: " + quoted_list(keys) + ")";
      }
      fail_at(join(path_, k), reason);
    }
  }

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] std::string path_of(std::string_view key) const { return join(path_, key); }
  [[nodiscard]] bool has(std::string_view key) const { return j_.contains(key); }

  [[noreturn]] void fail(std::string_view key, const std::string& reason) const {
    fail_at(path_of(key), reason);
  }
  [[noreturn]] void fail_at(const std::string& path, const std::string& reason) const {
    throw ScenarioError(file_, path.empty() ? "(root)" : path, reason);
  }

  [[nodiscard]] const json& required(std::string_view key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) fail(key, "missing required field");
    return *it;
  }

  [[nodiscard]] double number(std::string_view key) const { return as_number(required(key), path_of(key)); }
  [[nodiscard]] double number(std::string_view key, double fallback) const {
    return has(key) ? number(key) : fallback;
  }
  [[nodiscard]] double positive(std::string_view key) const {
    const double v = number(key);
    if (!(v > 0)) fail(key, "must be > 0, got " + format(v));
    return v;
  }
  [[nodiscard]] double non_negative(std::string_view key, double fallback) const {
    if (!has(key)) return fallback;
    const double v = number(key);
    if (v < 0) fail(key, "must be >= 0, got " + format(v));
    return v;
  }

  [[nodiscard]] std::uint64_t count(std::string_view key) const {
    const json& v = required(key);
    if (v.is_number_unsigned()) return v.get<std::uint64_t>();
    if (v.is_number_integer()) fail(key, "must be >= 0, got " + v.dump());
    fail(key, std::string("expected a non-negative integer, got ") + describe(v));
  }
  [[nodiscard]] std::uint32_t count32(std::string_view key) const {
    const std::uint64_t v = count(key);
    if (v > std::numeric_limits<std::uint32_t>::max()) fail(key, "must fit in 32 bits, got " + std::to_string(v));
    return static_cast<std::uint32_t>(v);
  }
  // An integer in [lo, hi], compared as written (an unsigned value above 2^63 - 1 must not
  // wrap to a negative one); `range` says which values are allowed.
  [[nodiscard]] std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t lo, std::int64_t hi,
                                     const std::string& range) const {
    if (!has(key)) return fallback;
    const json& v = required(key);
    if (!v.is_number_integer()) fail(key, std::string("expected an integer, got ") + describe(v));
    bool fits = true;
    std::int64_t value = 0;
    if (v.is_number_unsigned()) {
      const std::uint64_t u = v.get<std::uint64_t>();
      fits = u <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
      if (fits) value = static_cast<std::int64_t>(u);
    } else {
      value = v.get<std::int64_t>();
    }
    if (!fits || value < lo || value > hi) fail(key, "must be " + range + ", got " + v.dump());
    return value;
  }

  [[nodiscard]] bool boolean(std::string_view key) const {
    const json& v = required(key);
    if (!v.is_boolean()) fail(key, std::string("expected true or false, got ") + describe(v));
    return v.get<bool>();
  }
  [[nodiscard]] bool boolean(std::string_view key, bool fallback) const { return has(key) ? boolean(key) : fallback; }

  [[nodiscard]] std::string text(std::string_view key, const std::string& fallback) const {
    if (!has(key)) return fallback;
    const json& v = required(key);
    if (!v.is_string()) fail(key, std::string("expected a string, got ") + describe(v));
    return v.get<std::string>();
  }

  template <std::size_t N>
  [[nodiscard]] std::array<double, N> numbers(std::string_view key) const {
    const json& v = required(key);
    const std::string p = path_of(key);
    if (!v.is_array() || v.size() != N) {
      fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + describe(v));
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = as_number(v[i], at_index(p, i));
    return out;
  }
  template <std::size_t N>
  [[nodiscard]] std::array<double, N> numbers(std::string_view key, const std::array<double, N>& fallback) const {
    return has(key) ? numbers<N>(key) : fallback;
  }

  [[nodiscard]] Reader object(std::string_view key, std::initializer_list<std::string_view> keys) const {
    return Reader(file_, required(key), path_of(key), keys);
  }
  [[nodiscard]] Reader object(std::string_view key, std::span<const std::string_view> keys) const {
    return Reader(file_, required(key), path_of(key), keys);
  }

  [[nodiscard]] const json& array(std::string_view key) const {
    const json& v = required(key);
    if (!v.is_array()) fail(key, std::string("expected an array, got ") + describe(v));
    return v;
  }

  [[nodiscard]] static std::string format(double v) {
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os.precision(10);
    os << v;
    return os.str();
  }

  [[nodiscard]] static std::string describe(const json& v) {
    if (v.is_string() || v.is_boolean() || v.is_null()) return std::string(v.type_name()) + " " + v.dump();
    if (v.is_number()) return std::string(v.type_name()) + " " + v.dump();
    return v.type_name();
  }

 private:
  [[nodiscard]] double as_number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail_at(path, std::string("expected a number, got ") + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail_at(path, "not a finite number");
    return d;
  }

  const std::string& file_;
  const json& j_;
  std::string path_;
};

// Times are counted in ticks as integers; beyond 2^53 ticks a double no longer holds every
// count (and llround would be undefined far beyond).
constexpr double kMaxTickCount = 9007199254740992.0;  // 2^53

std::uint64_t ticks_of(double t_s, double tick_s) {
  return static_cast<std::uint64_t>(std::llround(t_s / tick_s));
}

// round(t_s / tick_s) for a time >= 0 read from `key`; refused when it does not fit.
std::uint64_t ticks_at(const Reader& r, std::string_view key, double t_s, double tick_s) {
  if (!(t_s / tick_s <= kMaxTickCount)) {
    r.fail(key, Reader::format(t_s) + " s is more than 2^53 ticks of " + Reader::format(tick_s) +
                    " s: too far to count in ticks");
  }
  return ticks_of(t_s, tick_s);
}

RunSpec parse_run(const Reader& r) {
  RunSpec run;
  const bool has_tick = r.has("tick_s"), has_rate = r.has("rate_hz");
  if (has_tick && has_rate) r.fail("rate_hz", "give either tick_s or rate_hz, not both");
  if (!has_tick && !has_rate) r.fail("tick_s", "missing required field (or give rate_hz)");
  if (has_tick) {
    run.tick_s = r.positive("tick_s");
    run.tick_field = r.path_of("tick_s");
  } else {
    run.tick_s = 1.0 / r.positive("rate_hz");
    run.tick_field = r.path_of("rate_hz");
  }

  const bool has_ticks = r.has("ticks"), has_duration = r.has("duration_s");
  if (has_ticks && has_duration) r.fail("duration_s", "give either ticks or duration_s, not both");
  if (!has_ticks && !has_duration) r.fail("ticks", "missing required field (or give duration_s)");
  const char* length_key = has_ticks ? "ticks" : "duration_s";
  run.length_field = r.path_of(length_key);
  if (has_ticks) {
    run.ticks = r.count("ticks");
  } else {
    const double d = r.positive("duration_s");
    if (d / run.tick_s > static_cast<double>(kMaxTicks)) {
      r.fail("duration_s", "longer than " + std::to_string(kMaxTicks) + " ticks");
    }
    run.ticks = ticks_of(d, run.tick_s);
  }
  if (run.ticks < 1) r.fail(length_key, "the run must have at least one tick");
  if (run.ticks > kMaxTicks) r.fail(length_key, "more than " + std::to_string(kMaxTicks) + " ticks");

  const std::string p = r.text("precision", "double");
  const std::optional<Precision> prec = parse_precision(p);
  if (!prec) r.fail("precision", "expected \"float\" or \"double\", got \"" + p + "\"");
  run.precision = *prec;
  return run;
}

void parse_axis_errors(const Reader& r, AxisErrorSources<double>& e) {
  e.static_drift_rad_s = r.number("static_drift_rad_s", 0);
  e.in_plane_erection_1_s = r.number("in_plane_erection_1_s", 0);
  e.cross_plane_erection_1_s = r.number("cross_plane_erection_1_s", 0);
  e.g_sensitive_drift_rad_s = r.number("g_sensitive_drift_rad_s", 0);
  e.torquer_cross_coupling = r.number("torquer_cross_coupling", 0);
  e.coulomb_friction_rad_s = r.number("coulomb_friction_rad_s", 0);
}

constexpr std::array<std::string_view, 6> kAxisErrorKeys = {
    "static_drift_rad_s",      "in_plane_erection_1_s",  "cross_plane_erection_1_s",
    "g_sensitive_drift_rad_s", "torquer_cross_coupling", "coulomb_friction_rad_s"};

void parse_faults(const Reader& g, const RunSpec& run, Scenario& s) {
  if (!g.has("faults")) return;
  const json& list = g.array("faults");
  const std::string base = g.path_of("faults");
  if (list.size() > static_cast<std::size_t>(kMaxFaultEvents)) {
    g.fail("faults", "at most " + std::to_string(kMaxFaultEvents) + " faults, got " + std::to_string(list.size()));
  }
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Reader f(s.file, list[i], at_index(base, i), {"kind", "start_s", "duration_s", "axis", "magnitude"});
    FaultEvent<double>& ev = s.gyro.faults[i];
    const json& kind = f.required("kind");
    if (!kind.is_string()) f.fail("kind", std::string("expected a string, got ") + kind.type_name());
    const std::optional<FaultKind> k = parse_fault_kind(kind.get<std::string>());
    if (!k) {
      std::string names;
      for (const FaultName& n : kFaultNames) names += (names.empty() ? "" : ", ") + std::string(n.name);
      f.fail("kind", "unknown fault kind \"" + kind.get<std::string>() + "\" (one of: " + names + ")");
    }
    ev.kind = *k;
    const double start = f.number("start_s");
    if (start < 0) f.fail("start_s", "must be >= 0, got " + Reader::format(start));
    ev.start_tick = ticks_at(f, "start_s", start, run.tick_s);
    const double duration = f.non_negative("duration_s", 0);
    ev.duration_ticks = duration > 0 ? std::max<std::uint64_t>(1, ticks_at(f, "duration_s", duration, run.tick_s)) : 0;
    ev.axis = static_cast<int>(f.integer("axis", -1, -1, 1, "0 (pitch), 1 (yaw) or -1 (both)"));
    const bool needs_magnitude = ev.kind == FaultKind::kBiasJump || ev.kind == FaultKind::kSaturatedTorquer ||
                                 ev.kind == FaultKind::kSpinMotorFailure;
    if (needs_magnitude && !f.has("magnitude")) {
      f.fail("magnitude", std::string("missing required field (needed by kind \"") + fault_kind_name(ev.kind) + "\")");
    }
    ev.magnitude = f.number("magnitude", 0);
  }
  s.fault_count = list.size();
}

constexpr std::array<std::string_view, 19> kGimbalKeys = {
    "rotor_transverse_inertia", "inner_gimbal_inertia", "outer_gimbal_inertia", "inner_friction",
    "outer_friction", "inner_coulomb_torque", "outer_coulomb_torque", "coulomb_rate_scale_rad_s",
    "spin_drive", "motor_torque_limit", "spin_servo_bandwidth_rad_s", "spin_down_time_s",
    "mass_unbalance", "stop_restitution", "torque_axes", "max_body_rate_rad_s", "max_torque",
    "max_specific_force", "max_substep_phase_rad"};

// The gimbal plant: the rotor's spin inertia, spin and friction from gyro.rotor, its stop
// from gyro.limits.gimbal_stop_rad, the rest from gyro.gimbal (docs/scenarios.md).
void parse_gimbal(const Reader& r, SimulatedGyroConfig<double>& c) {
  GimbalPlantConfig<double>& g = c.gimbal;
  g.spin_inertia = c.gyro.spin_inertia;
  g.max_spin_hz = c.spin_hz;
  g.stop_cone_rad = c.gimbal_stop_rad;
  g.rotor_transverse_inertia = r.number("rotor_transverse_inertia");
  const std::array<double, 3> inner = r.numbers<3>("inner_gimbal_inertia");
  const std::array<double, 3> outer = r.numbers<3>("outer_gimbal_inertia");
  g.inner_gimbal_inertia = Eigen::Vector3d(inner[0], inner[1], inner[2]);
  g.outer_gimbal_inertia = Eigen::Vector3d(outer[0], outer[1], outer[2]);
  g.inner_friction = r.number("inner_friction", c.gyro.friction);
  g.outer_friction = r.number("outer_friction", c.gyro.friction);
  g.inner_coulomb_torque = r.number("inner_coulomb_torque", 0);
  g.outer_coulomb_torque = r.number("outer_coulomb_torque", 0);
  g.coulomb_rate_scale_rad_s = r.number("coulomb_rate_scale_rad_s", g.coulomb_rate_scale_rad_s);
  const std::string drive = r.text("spin_drive", "motor");
  if (drive == "motor") {
    g.spin_drive = SpinDrive::kMotor;
  } else if (drive == "free") {
    g.spin_drive = SpinDrive::kFree;
  } else {
    r.fail("spin_drive", "expected \"motor\" or \"free\", got \"" + drive + "\"");
  }
  g.motor_torque_limit = r.number("motor_torque_limit", 0);
  g.spin_servo_bandwidth_rad_s = r.number("spin_servo_bandwidth_rad_s", 0);
  g.spin_down_time_s = r.number("spin_down_time_s", 0);
  g.mass_unbalance = r.number("mass_unbalance", 0);
  g.stop_restitution = r.number("stop_restitution", 0);
  const std::string axes = r.text("torque_axes", "gimbal");
  if (axes == "gimbal") {
    g.torque_axes = TorqueAxes::kGimbal;
  } else if (axes == "gyro") {
    g.torque_axes = TorqueAxes::kGyro;
  } else {
    r.fail("torque_axes", "expected \"gimbal\" or \"gyro\", got \"" + axes + "\"");
  }
  g.max_body_rate_rad_s = r.number("max_body_rate_rad_s", 100);
  g.max_torque = r.number("max_torque", 1e3);
  g.max_specific_force = r.number("max_specific_force", 1e4);
  g.max_substep_phase_rad = r.number("max_substep_phase_rad", g.max_substep_phase_rad);
}

void parse_gyro(const Reader& g, const RunSpec& run, Scenario& s) {
  SimulatedGyroConfig<double>& c = s.gyro;
  c.tick_s = run.tick_s;
  {
    const Reader r = g.object("rotor", {"pitch_inertia", "yaw_inertia", "spin_inertia", "friction", "spin_hz",
                                        "spin_down_time_constant_s", "has_spin_readback"});
    c.gyro.pitch_inertia = r.number("pitch_inertia");
    c.gyro.yaw_inertia = r.number("yaw_inertia");
    c.gyro.spin_inertia = r.number("spin_inertia");
    c.gyro.friction = r.number("friction");
    c.spin_hz = r.number("spin_hz");
    c.spin_down_time_constant_s = r.number("spin_down_time_constant_s", 0);
    c.has_spin_readback = r.boolean("has_spin_readback");
  }
  {
    const Reader r = g.object("limits", {"gimbal_cone_limit_rad", "pitch_gimbal_limit_rad", "yaw_gimbal_limit_rad",
                                         "gimbal_stop_rad", "max_pitch_rate_rad_s", "max_yaw_rate_rad_s",
                                         "small_angle_limit_rad"});
    c.gyro.gimbal_cone_limit_rad = r.number("gimbal_cone_limit_rad");
    c.gyro.pitch_gimbal_limit_rad = r.number("pitch_gimbal_limit_rad", 0);
    c.gyro.yaw_gimbal_limit_rad = r.number("yaw_gimbal_limit_rad", 0);
    c.gimbal_stop_rad = r.number("gimbal_stop_rad", 0);
    c.gyro.max_pitch_rate_rad_s = r.number("max_pitch_rate_rad_s");
    c.gyro.max_yaw_rate_rad_s = r.number("max_yaw_rate_rad_s");
    c.gyro.small_angle_limit_rad = r.number("small_angle_limit_rad", 0.01);
  }
  c.gyro.gravity = g.number("gravity");
  const std::string plant = g.text("plant", "gimbal");
  if (plant == "gimbal") {
    c.plant = PlantKind::kGimbal;
    if (!g.has("gimbal")) {
      g.fail("gimbal", "missing required field for plant \"gimbal\" (the default): the device's inertias and "
                       "bearings; or set gyro.plant to \"report\" for the report's linear model");
    }
    parse_gimbal(g.object("gimbal", kGimbalKeys), c);
    if (g.has("errors")) {
      g.fail("errors", "the report's error sources belong to plant \"report\"; the gimbal plant has its own "
                       "(gimbal.mass_unbalance, gimbal.inner_coulomb_torque, ...)");
    }
    if (c.spin_down_time_constant_s != 0) {
      g.fail("rotor", "spin_down_time_constant_s belongs to plant \"report\"; the gimbal plant runs down with "
                      "gimbal.spin_drive \"free\" and gimbal.spin_down_time_s");
    }
  } else if (plant == "report") {
    c.plant = PlantKind::kReport;
    if (g.has("gimbal")) g.fail("gimbal", "only for plant \"gimbal\" (this scenario's plant is \"report\")");
  } else {
    g.fail("plant", "expected \"gimbal\" or \"report\", got \"" + plant + "\"");
  }
  if (g.has("errors")) {
    const Reader e = g.object("errors", {"pitch", "yaw"});
    if (e.has("pitch")) parse_axis_errors(e.object("pitch", kAxisErrorKeys), c.gyro.errors.pitch);
    if (e.has("yaw")) parse_axis_errors(e.object("yaw", kAxisErrorKeys), c.gyro.errors.yaw);
  }
  if (g.has("pickoff")) {
    const Reader r = g.object("pickoff", {"lsb_rad", "bias_rad", "lag_s", "noise_rad", "range_rad"});
    c.pickoff.lsb_rad = r.number("lsb_rad", 0);
    const std::array<double, 2> bias = r.numbers<2>("bias_rad", {0, 0});
    c.pickoff.bias_rad = Eigen::Vector2d(bias[0], bias[1]);
    c.pickoff.lag_s = r.number("lag_s", 0);
    c.pickoff.noise_rad = r.number("noise_rad", 0);
    c.pickoff.range_rad = r.number("range_rad", 0);
  }
  if (g.has("torquer")) {
    const Reader r = g.object("torquer", {"scale_factor", "max_torque"});
    const std::array<double, 2> sf = r.numbers<2>("scale_factor", {1, 1});
    c.torquer.scale_factor = Eigen::Vector2d(sf[0], sf[1]);
    c.torquer.max_torque = r.number("max_torque", 0);
  }
  c.seed = g.has("seed") ? g.count("seed") : 1u;
  parse_faults(g, run, s);
}

void parse_component(const Reader& r, const RunSpec& run, GyroComponentConfig<double>& c) {
  c.tick_s = run.tick_s;
  c.pitch_inertia = r.number("pitch_inertia");
  c.yaw_inertia = r.number("yaw_inertia");
  c.spin_inertia = r.number("spin_inertia");
  c.friction = r.number("friction");
  c.nominal_spin_hz = r.number("nominal_spin_hz");
  c.min_spin_hz = r.number("min_spin_hz");
  c.use_spin_readback = r.boolean("use_spin_readback", true);
  c.max_pitch_rate_rad_s = r.number("max_pitch_rate_rad_s");
  c.max_yaw_rate_rad_s = r.number("max_yaw_rate_rad_s");
  c.max_torque = r.number("max_torque");
  c.friction_compensation = r.boolean("friction_compensation", true);
  c.cage_gain_1_s = r.number("cage_gain_1_s");
  c.gimbal_cone_limit_rad = r.number("gimbal_cone_limit_rad");
  c.gimbal_stop_margin_rad = r.number("gimbal_stop_margin_rad");
  c.small_angle_limit_rad = r.number("small_angle_limit_rad", 0.01);
  c.pickoff_range_rad = r.number("pickoff_range_rad");
  c.max_pickoff_step_rad = r.number("max_pickoff_step_rad");
  c.estimator_gain = r.number("estimator_gain");
  c.residual_limit_rad = r.number("residual_limit_rad");
  c.residual_persistence_ticks = r.count32("residual_persistence_ticks");
  c.invalid_persistence_ticks = r.count32("invalid_persistence_ticks");
  c.spin_low_persistence_ticks = r.count32("spin_low_persistence_ticks");
  c.torquer_fail_persistence_ticks = r.count32("torquer_fail_persistence_ticks");
  c.uncage_settle_ticks = r.count32("uncage_settle_ticks");
  const GyroComponentConfig<double> defaults;
  c.max_tick_gap = r.has("max_tick_gap") ? r.count32("max_tick_gap") : defaults.max_tick_gap;
  c.input_persistence_ticks =
      r.has("input_persistence_ticks") ? r.count32("input_persistence_ticks") : defaults.input_persistence_ticks;
  c.max_body_rate_rad_s = r.number("max_body_rate_rad_s", defaults.max_body_rate_rad_s);
}

BodyProfile parse_body(const Reader& r, Scenario& s) {
  BodyProfile b;
  b.attitude_rad = r.numbers<3>("attitude_rad", {0, 0, 0});
  const json& rate = r.required("rate_rad_s");
  if (rate.is_array() && rate.size() == 2) {  // (q, r): no roll
    const std::array<double, 2> qr = r.numbers<2>("rate_rad_s");
    b.rate_rad_s = {0, qr[0], qr[1]};
    s.body_rate_pitch_yaw_only = true;
  } else if (rate.is_array() && rate.size() == 3) {
    b.rate_rad_s = r.numbers<3>("rate_rad_s");
  } else {
    r.fail("rate_rad_s", "expected an array of 3 numbers (p, q, r) or 2 (q, r), got " + Reader::describe(rate));
  }
  const std::string comp = r.text("composition", "rotation_vector");
  if (comp == "rotation_vector") {
    b.composition = RotationComposition::kRotationVector;
  } else if (comp == "pitch_then_yaw") {
    b.composition = RotationComposition::kPitchThenYaw;
  } else {
    r.fail("composition", "expected \"rotation_vector\" or \"pitch_then_yaw\", got \"" + comp + "\"");
  }
  if (r.has("weave")) {
    const Reader w = r.object("weave", {"pitch_amplitude_rad_s", "yaw_amplitude_rad_s", "frequency_hz", "yaw_phase_rad"});
    b.weave.pitch_amplitude_rad_s = w.number("pitch_amplitude_rad_s", 0);
    b.weave.yaw_amplitude_rad_s = w.number("yaw_amplitude_rad_s", 0);
    b.weave.frequency_hz = w.positive("frequency_hz");
    b.weave.yaw_phase_rad = w.number("yaw_phase_rad", 0);
  }
  if (r.has("accel") && r.has("specific_force")) {
    r.fail("accel", "give either \"accel\" (lateral y, normal z) or \"specific_force\" (x, y, z), not both");
  }
  if (r.has("accel")) {
    const std::array<double, 2> a = r.numbers<2>("accel");
    b.specific_force = {0, a[0], a[1]};
    s.body_accel_lateral_normal = true;
  } else {
    b.specific_force = r.numbers<3>("specific_force", {0, 0, 0});
  }
  if (b.composition == RotationComposition::kPitchThenYaw && b.rate_rad_s[0] != 0) {
    r.fail("rate_rad_s", "the pitch_then_yaw composition (the report's driver) has no roll: p must be 0");
  }
  return b;
}

std::vector<GuidanceEvent> parse_guidance(const Reader& r, const RunSpec& run, const std::string& file) {
  std::vector<GuidanceEvent> out;
  const json& list = r.array("schedule");
  const std::string base = r.path_of("schedule");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Reader e(file, list[i], at_index(base, i), {"t_s", "request", "slew_rate_rad_s", "nav_valid"});
    GuidanceEvent ev;
    ev.t_s = e.number("t_s");
    if (ev.t_s < 0) e.fail("t_s", "must be >= 0, got " + Reader::format(ev.t_s));
    if (!out.empty() && ev.t_s < out.back().t_s) {
      e.fail("t_s", "the schedule must be in time order (" + Reader::format(ev.t_s) + " s is before the previous " +
                        Reader::format(out.back().t_s) + " s)");
    }
    ev.tick = ticks_at(e, "t_s", ev.t_s, run.tick_s);
    const std::string req = e.text("request", "none");
    if (req == "none") {
      ev.request = ModeRequest::kNone;
    } else if (req == "cage") {
      ev.request = ModeRequest::kCage;
    } else if (req == "uncage") {
      ev.request = ModeRequest::kUncage;
    } else {
      e.fail("request", "expected \"none\", \"cage\" or \"uncage\", got \"" + req + "\"");
    }
    if (e.has("slew_rate_rad_s")) {
      const std::array<double, 2> w = e.numbers<2>("slew_rate_rad_s");
      ev.slew_rate_rad_s = Eigen::Vector2d(w[0], w[1]);
    }
    if (e.has("nav_valid")) ev.nav_valid = e.boolean("nav_valid");
    out.push_back(ev);
  }
  return out;
}

// Refuses, while the document is parsed, what nlohmann's DOM would hide or what no scenario
// needs: a key repeated in one object (the DOM keeps the last silently) and nesting deeper
// than kMaxJsonDepth. Follows the JSON path of every container to name the field.
class ParseChecker {
 public:
  explicit ParseChecker(const std::string& file) : file_(file) {}

  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: open(false); break;
      case json::parse_event_t::array_start: open(true); break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();
        const std::string& k = parsed.get_ref<const std::string&>();
        if (!f.keys.insert(k).second) {
          throw ScenarioError(file_, join(f.path, k), "duplicate key (a key may appear only once in an object)");
        }
        f.key = k;
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
      case json::parse_event_t::value: element_done(); break;
    }
    return true;
  }

 private:
  struct Frame {
    std::string path;
    bool array{false};
    std::size_t index{0};   // of the next element (arrays)
    std::string key;        // the last key (objects)
    std::set<std::string> keys;
  };
  void open(bool array) {
    std::string path;
    if (!frames_.empty()) {
      const Frame& parent = frames_.back();
      path = parent.array ? at_index(parent.path, parent.index) : join(parent.path, parent.key);
    }
    if (frames_.size() >= kMaxJsonDepth) {
      throw ScenarioError(file_, path, "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    }
    frames_.push_back(Frame{std::move(path), array, 0, {}, {}});
  }
  void element_done() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }

  std::string file_;
  std::vector<Frame> frames_;
};

void record_values(const json& j, const std::string& path, std::map<std::string, std::string>& out) {
  if (j.is_object()) {
    for (const auto& item : j.items()) record_values(item.value(), join(path, item.key()), out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) record_values(j[i], at_index(path, i), out);
  } else {
    out[path] = j.dump();
  }
}

}  // namespace

ScenarioError::ScenarioError(std::string file, std::string field, std::string reason)
    : std::runtime_error(printable(file) + ": " + printable(field) + ": " + printable(reason)),
      file_(std::move(file)),
      field_(std::move(field)),
      reason_(std::move(reason)) {}

std::optional<Precision> parse_precision(std::string_view name) noexcept {
  if (name == "double") return Precision::kDouble;
  if (name == "float") return Precision::kFloat;
  return std::nullopt;
}

std::optional<FaultKind> parse_fault_kind(std::string_view name) noexcept {
  for (const FaultName& n : kFaultNames) {
    if (name == n.name) return n.kind;
  }
  return std::nullopt;
}

const char* request_name(ModeRequest r) noexcept {
  switch (r) {
    case ModeRequest::kNone: return "none";
    case ModeRequest::kCage: return "cage";
    case ModeRequest::kUncage: return "uncage";
  }
  return "unknown";
}

Scenario parse_scenario(std::string_view json_text, const std::string& file) {
  json doc;
  try {
    doc = json::parse(json_text.begin(), json_text.end(), ParseChecker(file), true, false);
  } catch (const json::exception& e) {
    std::string what = e.what();
    if (!what.empty() && what.front() == '[') {
      const std::size_t close = what.find("] ");
      if (close != std::string::npos) what.erase(0, close + 2);
    }
    throw ScenarioError(file, "(document)", "not valid JSON: " + what);
  }

  Scenario s;
  s.file = file;
  const Reader top(s.file, doc, "", {"description", "run", "gyro", "component", "body", "guidance"});
  s.description = top.text("description", "");
  s.run = parse_run(top.object("run", {"tick_s", "rate_hz", "ticks", "duration_s", "precision"}));
  parse_gyro(top.object("gyro", {"plant", "rotor", "limits", "gravity", "errors", "gimbal", "pickoff", "torquer",
                                 "seed", "faults"}),
             s.run, s);
  parse_component(top.object("component",
                             {"pitch_inertia", "yaw_inertia", "spin_inertia", "friction", "nominal_spin_hz",
                              "min_spin_hz", "use_spin_readback", "max_pitch_rate_rad_s", "max_yaw_rate_rad_s",
                              "max_torque", "friction_compensation", "cage_gain_1_s", "gimbal_cone_limit_rad",
                              "gimbal_stop_margin_rad", "small_angle_limit_rad", "pickoff_range_rad",
                              "max_pickoff_step_rad", "estimator_gain", "residual_limit_rad",
                              "residual_persistence_ticks", "invalid_persistence_ticks",
                              "spin_low_persistence_ticks", "torquer_fail_persistence_ticks",
                              "uncage_settle_ticks", "max_tick_gap", "input_persistence_ticks",
                              "max_body_rate_rad_s"}),
                  s.run, s.component);
  s.body = parse_body(
      top.object("body", {"attitude_rad", "rate_rad_s", "composition", "weave", "accel", "specific_force"}), s);
  s.guidance = parse_guidance(top.object("guidance", {"schedule"}), s.run, s.file);
  record_values(doc, "", s.values);
  return s;
}

namespace {

struct Descriptor {
  int fd;
  ~Descriptor() { ::close(fd); }
};

// At most kMaxScenarioBytes of the file: its size is checked before reading when it has one,
// and reading stops one byte past the limit otherwise (/dev/zero, a pipe).
std::string read_bounded(const std::string& name) {
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    throw ScenarioError(name, "(file)", std::string("cannot open the file for reading: ") + std::strerror(errno));
  }
  const Descriptor closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw ScenarioError(name, "(file)", std::string("cannot stat the file: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw ScenarioError(name, "(file)", "is a directory, not a scenario file");
  const std::string limit = "the limit of " + std::to_string(kMaxScenarioBytes) + " bytes for a scenario";
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > kMaxScenarioBytes) {
    throw ScenarioError(name, "(file)", "the file has " + std::to_string(st.st_size) + " bytes, more than " + limit);
  }
  std::string text;
  std::array<char, 65536> buf{};
  while (true) {
    const ::ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw ScenarioError(name, "(file)", std::string("read error: ") + std::strerror(errno));
    if (n == 0) break;
    text.append(buf.data(), static_cast<std::size_t>(n));
    if (text.size() > kMaxScenarioBytes) throw ScenarioError(name, "(file)", "gave more than " + limit + " (stopped reading)");
  }
  return text;
}

}  // namespace

Scenario read_scenario(const std::filesystem::path& path) {
  const std::string name = path.string();
  return parse_scenario(read_bounded(name), name);
}

std::string body_rate_field(const Scenario& s, int axis) {
  if (s.body_rate_pitch_yaw_only) return axis == 0 ? "body.rate_rad_s" : "body.rate_rad_s[" + std::to_string(axis - 1) + "]";
  return "body.rate_rad_s[" + std::to_string(axis) + "]";
}

std::string body_force_field(const Scenario& s, int axis) {
  if (s.body_accel_lateral_normal) return axis == 0 ? "body.accel" : "body.accel[" + std::to_string(axis - 1) + "]";
  return "body.specific_force[" + std::to_string(axis) + "]";
}

std::string component_field_path(const Scenario& s, std::string_view field) {
  if (field == "tick_s") return s.run.tick_field;
  return join("component", field);
}

std::string gyro_field_path(const Scenario& s, std::string_view field) {
  struct Section {
    std::string_view field;
    std::string_view section;
  };
  static constexpr std::array<Section, 13> kSections = {{
      {"pitch_inertia", "rotor"},          {"yaw_inertia", "rotor"},
      {"spin_inertia", "rotor"},           {"friction", "rotor"},
      {"spin_hz", "rotor"},                {"spin_down_time_constant_s", "rotor"},
      {"gimbal_cone_limit_rad", "limits"}, {"pitch_gimbal_limit_rad", "limits"},
      {"yaw_gimbal_limit_rad", "limits"},  {"gimbal_stop_rad", "limits"},
      {"max_pitch_rate_rad_s", "limits"},  {"max_yaw_rate_rad_s", "limits"},
      {"small_angle_limit_rad", "limits"},
  }};
  if (field == "tick_s") return s.run.tick_field;
  if (s.gyro.plant == PlantKind::kGimbal) {
    // The gimbal plant's fields: three come from rotor and limits, the rest from gimbal.
    if (field == "spin_inertia") return "gyro.rotor.spin_inertia";
    if (field == "max_spin_hz") return "gyro.rotor.spin_hz";
    if (field == "stop_cone_rad") return "gyro.limits.gimbal_stop_rad";
    for (std::string_view k : kGimbalKeys) {
      if (k == field) return join("gyro.gimbal", field);
    }
  }
  for (const Section& sec : kSections) {
    if (sec.field == field) return join(join("gyro", sec.section), field);
  }
  std::string f(field);  // a path below gyro ("pickoff.lsb_rad", "faults[1].axis"): appended as is
  const std::string ticks = ".duration_ticks";
  if (f.rfind("faults[", 0) == 0 && f.size() > ticks.size() &&
      f.compare(f.size() - ticks.size(), ticks.size(), ticks) == 0) {
    f.replace(f.size() - ticks.size(), ticks.size(), ".duration_s");
  }
  return "gyro." + f;
}

}  // namespace gyro::sil
