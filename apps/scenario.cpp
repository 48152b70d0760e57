// Scenario JSON -> Scenario, with every refusal naming file, JSON path and reason.
#include "scenario.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <span>
#include <type_traits>
#include <sstream>
#include <utility>

#include "bounded_read.hpp"
#include "printable.hpp"
#include "scenario_base.hpp"
#include "scenario_defaults.hpp"
#include "strict_json.hpp"

namespace gyro::sil {

namespace {

using json = nlohmann::json;

// Longest run accepted: a sanity bound (the CSV has one row per tick).
constexpr std::uint64_t kMaxTicks = 100'000'000;

}  // namespace

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

namespace {

// Reads one JSON object of a scenario (gyro/strict_json.hpp), with the scenario's own getters.
class Reader : public StrictObject<ScenarioError> {
 public:
  Reader(const std::string& file, const json& j, std::string path, std::initializer_list<std::string_view> keys)
      : Reader(file, j, std::move(path), std::span<const std::string_view>(keys.begin(), keys.size())) {}
  Reader(const std::string& file, const json& j, std::string path, std::span<const std::string_view> keys)
      : StrictObject(file, j, std::move(path), keys, KeyJoin::kQuoted) {}

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
    fail(key, std::string("expected a non-negative integer, got ") + describe_json(v));
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
    if (!v.is_number_integer()) fail(key, std::string("expected an integer, got ") + describe_json(v));
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

  template <std::size_t N>
  [[nodiscard]] std::array<double, N> numbers(std::string_view key) const {
    const json& v = required(key);
    const std::string p = path_of(key);
    if (!v.is_array() || v.size() != N) {
      fail(key, "expected an array of " + std::to_string(N) + " numbers, got " + describe_json(v));
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = number_at(v[i], at_index(p, i));
    return out;
  }
  template <std::size_t N>
  [[nodiscard]] std::array<double, N> numbers(std::string_view key, const std::array<double, N>& fallback) const {
    return has(key) ? numbers<N>(key) : fallback;
  }

  [[nodiscard]] Reader object(std::string_view key, std::initializer_list<std::string_view> keys) const {
    return Reader(file(), required(key), path_of(key), keys);
  }
  [[nodiscard]] Reader object(std::string_view key, std::span<const std::string_view> keys) const {
    return Reader(file(), required(key), path_of(key), keys);
  }

  [[nodiscard]] static std::string format(double v) {
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os.precision(10);
    os << v;
    return os.str();
  }

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

bool same_section(const char* a, const char* b) {
  return a == b || (a != nullptr && b != nullptr && std::string_view(a) == b);
}

// A field's key in its object: the last part of its name ("pickoff.lsb_rad" -> "lsb_rad").
std::string_view field_key(const Field& f) {
  const std::string_view n = f.name;
  const std::size_t dot = n.rfind('.');
  return dot == std::string_view::npos ? n : n.substr(dot + 1);
}

// The keys a scenario may give for the fields of `c` in `section` (nullptr: those directly in
// the struct's own object), from the struct's field table.
template <class Config>
std::vector<std::string_view> field_keys(const Config& c, const char* section) {
  std::vector<std::string_view> keys;
  visit_fields(
      [&](const Field& f, const auto&) {
        if (f.presence != Presence::kImplied && same_section(f.section, section)) keys.push_back(field_key(f));
      },
      c);
  return keys;
}

// An enumerator by the name enum_names(E) gives it ("motor", "free").
template <class E>
E read_enum(const Reader& r, std::string_view key) {
  const std::string text = r.text(key, "");
  E value{};
  if (enum_from_name(text, value)) return value;
  constexpr auto names = enum_names(E{});
  std::string expected;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) expected += i + 1 == names.size() ? " or " : ", ";
    expected += '"' + std::string(names[i]) + '"';
  }
  r.fail(key, "expected " + expected + ", got \"" + text + "\"");
}

// Reads the fields of `c` in `section` as its field table names them: a required one must be
// there, an optional one left out keeps the value `c` has.
template <class Config>
void read_fields(const Reader& r, Config& c, const char* section) {
  visit_fields(
      [&](const Field& f, auto& value) {
        if (f.presence == Presence::kImplied || !same_section(f.section, section)) return;
        const std::string_view key = field_key(f);
        if (f.presence == Presence::kOptional && !r.has(key)) return;
        using M = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<M, double>) {
          value = r.number(key);
        } else if constexpr (std::is_same_v<M, bool>) {
          value = r.boolean(key);
        } else if constexpr (std::is_same_v<M, std::uint32_t>) {
          value = r.count32(key);
        } else if constexpr (std::is_same_v<M, std::uint64_t>) {
          value = r.count(key);
        } else if constexpr (kHasEnumNames<M>) {
          (void)r.required(key);
          value = read_enum<M>(r, key);
        } else if constexpr (kHasFieldTable<M>) {
          read_fields(r.object(key, field_keys(value, nullptr)), value, nullptr);
        } else if constexpr (std::is_base_of_v<Eigen::EigenBase<M>, M>) {
          const auto a = r.numbers<static_cast<std::size_t>(M::RowsAtCompileTime)>(key);
          for (std::size_t i = 0; i < a.size(); ++i) value(static_cast<Eigen::Index>(i)) = a[i];
        } else {  // only implied fields are of other types (the faults, the plant's kind)
          r.fail(key, "no reader for this field's type");
        }
      },
      c);
}

// The fields of `c` in `section` as a scenario writes them, into the object `out`: what
// read_fields reads back as `c` (every field, optional ones included).
template <class Config>
void write_fields(json& out, const Config& c, const char* section) {
  visit_fields(
      [&](const Field& f, const auto& value) {
        if (f.presence == Presence::kImplied || !same_section(f.section, section)) return;
        const std::string key(field_key(f));
        using M = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<M, double> || std::is_same_v<M, bool> || std::is_same_v<M, std::uint32_t> ||
                      std::is_same_v<M, std::uint64_t>) {
          out[key] = value;
        } else if constexpr (kHasEnumNames<M>) {
          out[key] = enum_name(value);
        } else if constexpr (kHasFieldTable<M>) {
          json inner = json::object();
          write_fields(inner, value, nullptr);
          out[key] = inner;
        } else if constexpr (std::is_base_of_v<Eigen::EigenBase<M>, M>) {
          json a = json::array();
          for (Eigen::Index i = 0; i < value.size(); ++i) a.push_back(value(i));
          out[key] = a;
        }
      },
      c);
}

// The names of the fault kinds a scenario can schedule, in enum order.
std::string fault_kind_list() {
  std::string names;
  for (int k = 1; k < kFaultKindCount; ++k) {
    names += (names.empty() ? "" : ", ") + std::string(fault_kind_name(static_cast<FaultKind>(k)));
  }
  return names;
}

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
      f.fail("kind", "unknown fault kind \"" + kind.get<std::string>() + "\" (one of: " + fault_kind_list() + ")");
    }
    ev.kind = *k;
    const double start = f.number("start_s");
    if (start < 0) f.fail("start_s", "must be >= 0, got " + Reader::format(start));
    ev.start_tick = ticks_at(f, "start_s", start, run.tick_s);
    const double duration = f.non_negative("duration_s", 0);
    ev.duration_ticks = duration > 0 ? std::max<std::uint64_t>(1, ticks_at(f, "duration_s", duration, run.tick_s)) : 0;
    ev.axis = static_cast<int>(f.integer("axis", -1, -1, 1, "0 (pitch), 1 (yaw) or -1 (both)"));
    if (fault_needs_magnitude(ev.kind) && !f.has("magnitude")) {
      f.fail("magnitude", std::string("missing required field (needed by kind \"") + fault_kind_name(ev.kind) + "\")");
    }
    ev.magnitude = f.number("magnitude", 0);
  }
  s.fault_count = list.size();
}

// The gimbal plant: the rotor's spin inertia, spin and friction from gyro.rotor, its stop
// from gyro.limits.gimbal_stop_rad, the rest from gyro.gimbal (docs/scenarios.md).
void parse_gimbal(const Reader& r, SimulatedGyroConfig<double>& c) {
  GimbalPlantConfig<double>& g = c.gimbal;
  g.spin_inertia = c.gyro.spin_inertia;
  g.max_spin_hz = c.spin_hz;
  g.stop_cone_rad = c.gimbal_stop_rad;
  // The scenario's defaults: the bearings' friction the rotor's, a wide envelope.
  g.inner_friction = c.gyro.friction;
  g.outer_friction = c.gyro.friction;
  set_scenario_envelope(g);
  read_fields(r, g, nullptr);
  // Optional in the table (a free rotor has no motor), required by the default drive.
  if (g.spin_drive == SpinDrive::kMotor && !r.has("motor_torque_limit")) {
    r.fail("motor_torque_limit", "missing required field (needed by spin_drive \"motor\", the default)");
  }
}

void parse_gyro(const Reader& g, const RunSpec& run, Scenario& s) {
  SimulatedGyroConfig<double>& c = s.gyro;
  c.tick_s = run.tick_s;
  c.seed = kScenarioSeed;
  for (const char* section : {"rotor", "limits"}) {
    std::vector<std::string_view> keys = field_keys(c.gyro, section);
    for (std::string_view k : field_keys(c, section)) keys.push_back(k);
    const Reader r = g.object(section, keys);
    read_fields(r, c.gyro, section);
    read_fields(r, c, section);
  }
  read_fields(g, c.gyro, nullptr);  // gravity, errors
  const std::string plant = g.text("plant", "gimbal");
  if (plant == "gimbal") {
    c.plant = PlantKind::kGimbal;
    if (!g.has("gimbal")) {
      g.fail("gimbal", "missing required field for plant \"gimbal\" (the default): the device's inertias and "
                       "bearings; or set gyro.plant to \"report\" for the report's linear model");
    }
    parse_gimbal(g.object("gimbal", field_keys(c.gimbal, nullptr)), c);
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
  read_fields(g, c, nullptr);  // pickoff, torquer, seed
  parse_faults(g, run, s);
}

void parse_component(const Reader& r, const RunSpec& run, GyroComponentConfig<double>& c) {
  c.tick_s = run.tick_s;
  read_fields(r, c, nullptr);
}

// body.trajectory: the table named by `file` (relative to the scenario's directory), or the
// columns handed in later (attach_trajectory) when there is no file.
BodyProfile parse_body_trajectory(const Reader& body, const Scenario& s) {
  for (const char* key : {"attitude_rad", "rate_rad_s", "composition", "weave", "accel", "specific_force"}) {
    if (body.has(key)) body.fail(key, "give either \"trajectory\" or the constant-rate profile, not both");
  }
  const Reader r = body.object("trajectory", {"file", "attitude", "tolerance_rad"});
  BodyProfile b;
  TrajectorySpec spec;
  spec.attitude = r.has("attitude") ? read_enum<TrajectoryAttitude>(r, "attitude") : TrajectoryAttitude::kQuaternion;
  if (r.has("tolerance_rad")) {
    spec.tolerance_rad = r.positive("tolerance_rad");
    if (!(spec.tolerance_rad <= 0.1)) r.fail("tolerance_rad", "must be <= 0.1, got " + Reader::format(spec.tolerance_rad));
  }
  spec.file_field = r.path_of("file");
  if (r.has("file")) {
    const std::filesystem::path f = r.text("file", "");
    const std::filesystem::path resolved = f.is_absolute() ? f : std::filesystem::path(s.file).parent_path() / f;
    spec.file = resolved.string();
    try {
      b.trajectory = std::make_shared<const BodyTrajectory>(
          build_trajectory(read_trajectory_csv(spec.file, spec.attitude), spec));
    } catch (const ScenarioError& e) {
      // Named as the scenario's field, the file's row and column in the reason.
      const std::string where = e.field() == "(file)" ? "" : e.field() + ": ";
      r.fail("file", e.file() + ": " + where + e.reason());
    }
  }
  b.trajectory_spec = spec;
  return b;
}

BodyProfile parse_body(const Reader& r, Scenario& s) {
  if (r.has("trajectory")) return parse_body_trajectory(r, s);
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
    r.fail("rate_rad_s", "expected an array of 3 numbers (p, q, r) or 2 (q, r), got " + describe_json(rate));
  }
  b.composition =
      r.has("composition") ? read_enum<RotationComposition>(r, "composition") : RotationComposition::kRotationVector;
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
    if (e.has("request")) ev.request = read_enum<ModeRequest>(e, "request");
    if (e.has("slew_rate_rad_s")) {
      const std::array<double, 2> w = e.numbers<2>("slew_rate_rad_s");
      ev.slew_rate_rad_s = Eigen::Vector2d(w[0], w[1]);
    }
    if (e.has("nav_valid")) ev.nav_valid = e.boolean("nav_valid");
    out.push_back(ev);
  }
  return out;
}

Eigen::Vector3d vector3(const Reader& r, std::string_view key) {
  const std::array<double, 3> v = r.numbers<3>(key);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

// guidance.track (docs/scenarios.md): the LOS, the gain and the start; the schedule's slew
// commands from the start on would be overridden, so they are refused.
TrackSpec parse_track(const Reader& guidance, const RunSpec& run, const std::vector<GuidanceEvent>& schedule) {
  const Reader r = guidance.object("track", {"start_s", "gain_1_s", "line_of_sight", "target", "own"});
  TrackSpec t;
  t.start_s = r.non_negative("start_s", 0);
  t.start_tick = ticks_at(r, "start_s", t.start_s, run.tick_s);
  t.gain_1_s = r.non_negative("gain_1_s", 0);
  const double max_gain = kMaxTrackGainTicks / run.tick_s;
  if (t.gain_1_s > max_gain) {
    r.fail("gain_1_s", "must be <= " + Reader::format(max_gain) + " (" + Reader::format(kMaxTrackGainTicks) +
                           " / " + run.tick_field + ": the loop sees a one-tick-old estimate), got " +
                           Reader::format(t.gain_1_s));
  }
  const bool inertial = r.has("line_of_sight"), geometry = r.has("target");
  if (inertial == geometry) {
    r.fail(inertial ? "target" : "line_of_sight",
           "give either \"line_of_sight\" (an inertial direction and rate) or \"target\" (and \"own\") positions "
           "and velocities, exactly one");
  }
  LineOfSightSpec& los = t.los;
  if (inertial) {
    if (r.has("own")) r.fail("own", "only with \"target\": the own position makes a LOS with the target's");
    const Reader l = r.object("line_of_sight", {"direction", "rate_rad_s"});
    los.source = LineOfSightSpec::Source::kInertial;
    const Eigen::Vector3d d = vector3(l, "direction");
    if (!(d.norm() > 0) || !std::isfinite(d.norm())) {
      l.fail("direction", "must be a non-zero finite vector, got length " + Reader::format(d.norm()));
    }
    los.direction = d.normalized();
    los.rate_rad_s = l.has("rate_rad_s") ? vector3(l, "rate_rad_s") : Eigen::Vector3d::Zero();
    if (!(los.rate_rad_s.norm() <= kMaxLosRateRadS)) {
      l.fail("rate_rad_s", "its magnitude must be <= " + Reader::format(kMaxLosRateRadS) + " rad/s, got " +
                               Reader::format(los.rate_rad_s.norm()));
    }
  } else {
    los.source = LineOfSightSpec::Source::kTargetGeometry;
    const Reader target = r.object("target", {"position_m", "velocity_m_s"});
    los.target_position_m = vector3(target, "position_m");
    los.target_velocity_m_s = target.has("velocity_m_s") ? vector3(target, "velocity_m_s") : Eigen::Vector3d::Zero();
    if (r.has("own")) {
      const Reader own = r.object("own", {"position_m", "velocity_m_s"});
      los.own_position_m = own.has("position_m") ? vector3(own, "position_m") : Eigen::Vector3d::Zero();
      los.own_velocity_m_s = own.has("velocity_m_s") ? vector3(own, "velocity_m_s") : Eigen::Vector3d::Zero();
    }
    const double duration = static_cast<double>(run.ticks) * run.tick_s;
    const double closest = closest_range_m(los, duration);
    if (!(closest >= kMinTrackRangeM) || !std::isfinite(closest)) {
      r.fail("target", "the target comes within " + Reader::format(closest) + " m of the own position during the run; " +
                           "the range must stay >= " + Reader::format(kMinTrackRangeM) + " m");
    }
  }
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    if (schedule[i].slew_rate_rad_s && schedule[i].tick >= t.start_tick) {
      guidance.fail_at(join_key(at_index(guidance.path_of("schedule"), i), "slew_rate_rad_s"),
                    "the tracker commands the slew from guidance.track.start_s = " + Reader::format(t.start_s) +
                        " s on; a slew command at " + Reader::format(schedule[i].t_s) + " s would be overridden");
    }
  }
  return t;
}

void record_values(const json& j, const std::string& path, std::map<std::string, std::string>& out) {
  if (j.is_object()) {
    for (const auto& item : j.items()) record_values(item.value(), join_key(path, item.key()), out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) record_values(j[i], at_index(path, i), out);
  } else {
    out[path] = j.dump();
  }
}

}  // namespace

std::map<std::string, std::string> written_values(const Scenario& s) {
  std::map<std::string, std::string> out;
  if (s.document) record_values(*s.document, "", out);
  return out;
}

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
  for (int k = 1; k < kFaultKindCount; ++k) {
    if (name == fault_kind_name(static_cast<FaultKind>(k))) return static_cast<FaultKind>(k);
  }
  return std::nullopt;
}

const char* request_name(ModeRequest r) noexcept {
  const char* name = enum_name(r);
  return name != nullptr ? name : "unknown";
}

Scenario parse_scenario(std::string_view json_text, const std::string& file) {
  json doc;
  try {
    doc = parse_strict_json(json_text, kMaxJsonDepth, KeyJoin::kQuoted);
  } catch (const JsonRefusal& r) {
    throw ScenarioError(file, r.field(), r.reason());
  }
  return parse_scenario_document(resolve_scenario_base(doc, std::filesystem::path(file).parent_path(), file), file);
}

namespace {

constexpr std::string_view kGyroKeys[] = {"plant",  "rotor",   "limits",  "gravity", "errors",
                                          "gimbal", "pickoff", "torquer", "seed",    "faults"};

// A section's run: the tick alone (its field named "tick_s").
RunSpec section_run(double tick_s, const std::string& file) {
  RunSpec run;
  run.tick_field = "tick_s";
  if (!(tick_s > 0) || !std::isfinite(tick_s)) {
    throw ScenarioError(file, "tick_s", "must be > 0, got " + Reader::format(tick_s));
  }
  run.tick_s = tick_s;
  return run;
}

}  // namespace

nlohmann::json gyro_section(const SimulatedGyroConfig<double>& c, std::size_t fault_count) {
  json g = json::object();
  g["plant"] = c.plant == PlantKind::kGimbal ? "gimbal" : "report";
  for (const char* section : {"rotor", "limits"}) {
    json part = json::object();
    write_fields(part, c.gyro, section);
    write_fields(part, c, section);
    g[section] = part;
  }
  write_fields(g, c.gyro, nullptr);  // gravity, errors
  if (c.plant == PlantKind::kGimbal) {
    g.erase("errors");  // the report plant's alone
    json gimbal = json::object();
    write_fields(gimbal, c.gimbal, nullptr);
    g["gimbal"] = gimbal;
    g["rotor"].erase("spin_down_time_constant_s");
  }
  write_fields(g, c, nullptr);  // pickoff, torquer, seed
  if (fault_count > 0) {
    json faults = json::array();
    for (std::size_t i = 0; i < fault_count; ++i) {
      const FaultEvent<double>& f = c.faults[i];
      json e = {{"kind", fault_kind_name(f.kind)},
                {"start_s", static_cast<double>(f.start_tick) * c.tick_s},
                {"axis", f.axis}};
      if (f.duration_ticks > 0) e["duration_s"] = static_cast<double>(f.duration_ticks) * c.tick_s;
      if (fault_needs_magnitude(f.kind)) e["magnitude"] = f.magnitude;
      faults.push_back(e);
    }
    g["faults"] = faults;
  }
  return g;
}

nlohmann::json component_section(const GyroComponentConfig<double>& c) {
  json out = json::object();
  write_fields(out, c, nullptr);
  return out;
}

Scenario parse_gyro_section(const nlohmann::json& gyro, double tick_s, const std::string& file, const std::string& path) {
  Scenario s;
  s.file = file;
  s.run = section_run(tick_s, file);
  parse_gyro(Reader(s.file, gyro, path, kGyroKeys), s.run, s);
  return s;
}

Scenario parse_component_section(const nlohmann::json& component, double tick_s, const std::string& file,
                                 const std::string& path) {
  Scenario s;
  s.file = file;
  s.run = section_run(tick_s, file);
  parse_component(Reader(s.file, component, path, field_keys(s.component, nullptr)), s.run, s.component);
  return s;
}

Scenario parse_scenario_document(const nlohmann::json& doc, const std::string& file) {
  Scenario s;
  s.file = file;
  const Reader top(s.file, doc, "", {"description", "run", "gyro", "component", "body", "guidance"});
  s.description = top.text("description", "");
  s.run = parse_run(top.object("run", {"tick_s", "rate_hz", "ticks", "duration_s", "precision"}));
  parse_gyro(top.object("gyro", kGyroKeys), s.run, s);
  parse_component(top.object("component", field_keys(s.component, nullptr)), s.run, s.component);
  s.body = parse_body(
      top.object("body",
                 {"attitude_rad", "rate_rad_s", "composition", "weave", "accel", "specific_force", "trajectory"}),
      s);
  const Reader guidance = top.object("guidance", {"schedule", "track"});
  s.guidance = parse_guidance(guidance, s.run, s.file);
  if (guidance.has("track")) s.track = parse_track(guidance, s.run, s.guidance);
  s.document = std::make_shared<const json>(doc);
  return s;
}

namespace {

// At most kMaxScenarioBytes of the file (bounded_read.hpp).
std::string read_scenario_text(const std::string& name) {
  std::string why;
  std::optional<std::string> text = read_bounded(name, kMaxScenarioBytes, "a scenario", why);
  if (!text) throw ScenarioError(name, "(file)", why);
  return std::move(*text);
}

}  // namespace

Scenario read_scenario(const std::filesystem::path& path) {
  const std::string name = path.string();
  return parse_scenario(read_scenario_text(name), name);
}

void attach_trajectory(Scenario& s, const TrajectoryTable& table) {
  if (!s.body.trajectory_spec) {
    throw ScenarioError(s.file, "body.trajectory", "a trajectory's columns were given, but the scenario's body has "
                                                   "no \"trajectory\" section");
  }
  if (s.body.trajectory) {
    throw ScenarioError(s.file, s.body.trajectory_spec->file_field,
                        "give either a trajectory file or the trajectory's columns, not both");
  }
  s.body.trajectory = std::make_shared<const BodyTrajectory>(build_trajectory(table, *s.body.trajectory_spec));
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
  return join_key("component", field);
}

std::string gyro_field_path(const Scenario& s, std::string_view field) {
  if (field == "tick_s") return s.run.tick_field;
  if (s.gyro.plant == PlantKind::kGimbal) {
    // The gimbal plant's fields: three come from rotor and limits, the rest from gimbal.
    if (field == "spin_inertia") return "gyro.rotor.spin_inertia";
    if (field == "max_spin_hz") return "gyro.rotor.spin_hz";
    if (field == "stop_cone_rad") return "gyro.limits.gimbal_stop_rad";
    for (std::string_view k : field_keys(s.gyro.gimbal, nullptr)) {
      if (k == field) return join_key("gyro.gimbal", field);
    }
  }
  // The fields a scenario gives in gyro.rotor and gyro.limits.
  std::string in_section;
  const auto find = [&](const Field& f, const auto&) {
    if (in_section.empty() && f.section != nullptr && field_key(f) == field) {
      in_section = join_key(join_key("gyro", f.section), field);
    }
  };
  visit_fields(find, s.gyro.gyro);
  visit_fields(find, s.gyro);
  if (!in_section.empty()) return in_section;
  std::string f(field);  // a path below gyro ("pickoff.lsb_rad", "faults[1].axis"): appended as is
  const std::string ticks = ".duration_ticks";
  if (f.rfind("faults[", 0) == 0 && f.size() > ticks.size() &&
      f.compare(f.size() - ticks.size(), ticks.size(), ticks) == 0) {
    f.replace(f.size() - ticks.size(), ticks.size(), ".duration_s");
  }
  return "gyro." + f;
}

}  // namespace gyro::sil
