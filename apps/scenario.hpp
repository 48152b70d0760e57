// A gyro_sil scenario: what runs (component and stub configurations), the body's motion,
// the guidance schedule and the run's tick and length; read from JSON and checked field by
// field. The schema is documented in docs/scenarios.md.
//
// Every refusal is a ScenarioError naming the file, the field as a JSON path
// ("gyro.rotor.pitch_inertia", "guidance.schedule[2].t_s"; a key that is not a plain name is
// written as a JSON string in brackets: body["rate\u0001"]) and the reason. A refusal that is
// not about one field names a pseudo-field: "(file)" (cannot be read), "(document)" (not
// JSON), "(root)" (the document itself).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "body_motion.hpp"
#include "los_tracking.hpp"
#include "gyro/component_types.hpp"
#include "gyro/simulated_gyro.hpp"

namespace gyro::sil {

// The largest scenario file read (1 MiB; the shipped ones are about 2 KB). Larger files, and
// devices or pipes that keep giving bytes, are refused after reading at most this much.
inline constexpr std::uint64_t kMaxScenarioBytes = 1u << 20;

// Deepest nesting of arrays and objects accepted (the schema needs 4).
inline constexpr std::size_t kMaxJsonDepth = 16;

enum class Precision : std::uint8_t { kDouble, kFloat };

[[nodiscard]] constexpr const char* to_string(Precision p) noexcept {
  return p == Precision::kFloat ? "float" : "double";
}
// "float" or "double"; nullopt otherwise.
[[nodiscard]] std::optional<Precision> parse_precision(std::string_view name) noexcept;

// The fault kind named as in scenario files (gyro::fault_kind_name), FaultKind::kNone excluded.
[[nodiscard]] std::optional<FaultKind> parse_fault_kind(std::string_view name) noexcept;

[[nodiscard]] const char* request_name(ModeRequest r) noexcept;

// Levenshtein distance (the "did you mean" of unknown keys).
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

// what() is "file: field: reason" with control characters escaped (printable()); file(),
// field() and reason() are as given.
class ScenarioError : public std::runtime_error {
 public:
  ScenarioError(std::string file, std::string field, std::string reason);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

 private:
  std::string file_, field_, reason_;
};

// One entry of the guidance schedule, applied at the first tick at or after t_s.
struct GuidanceEvent {
  double t_s{0};
  std::uint64_t tick{0};                      // round(t_s / tick_s)
  ModeRequest request{ModeRequest::kNone};    // issued once, in that tick
  std::optional<Eigen::Vector2d> slew_rate_rad_s;  // held from then on when given
  std::optional<bool> nav_valid;                   // held from then on when given
};

struct RunSpec {
  double tick_s{0};
  std::string tick_field{"run.tick_s"};   // the key the tick came from (tick_s or rate_hz)
  std::uint64_t ticks{0};                 // number of ticks after tick 0 (rows = ticks + 1)
  std::string length_field{"run.ticks"};  // the key the length came from (ticks or duration_s)
  Precision precision{Precision::kDouble};
};

struct Scenario {
  std::string file;          // where it was read from (for messages)
  std::string description;
  RunSpec run{};
  GyroComponentConfig<double> component{};  // tick_s = run.tick_s
  SimulatedGyroConfig<double> gyro{};       // tick_s = run.tick_s; faults in file order
  std::size_t fault_count{0};
  BodyProfile body{};
  bool body_rate_pitch_yaw_only{false};  // body.rate_rad_s written as (q, r)
  bool body_accel_lateral_normal{false};  // body.accel written (lateral y, normal z)
  std::vector<GuidanceEvent> guidance;      // sorted by time
  std::optional<TrackSpec> track;           // guidance.track: LOS tracking from track.start_s on
  // The file as written (for messages about a value the component or the stub refused, and
  // the float run's range check; written_values() lists it by JSON path, when asked).
  std::shared_ptr<const nlohmann::json> document;
};

// Every number, string and boolean of the scenario's file as written, by JSON path.
[[nodiscard]] std::map<std::string, std::string> written_values(const Scenario& s);

// Parses and checks the schema and the values the component and stub do not check
// themselves (times, names, counts). Throws ScenarioError; `file` names the source.
[[nodiscard]] Scenario parse_scenario(std::string_view json_text, const std::string& file);
// The same from a parsed document (gyro_campaign's dispersed scenarios).
[[nodiscard]] Scenario parse_scenario_document(const nlohmann::json& doc, const std::string& file);

// A scenario's "gyro" section alone, at the tick tick_s, with the keys, defaults and refusals
// of docs/scenarios.md: a Scenario whose gyro (and fault_count, run.tick_s) is set, for
// gyro_field_path(). Refusals name the field below `path` ("rotor.pitch_inertia" for path "").
// The Python module's SimulatedGyro takes its keywords this way. Throws ScenarioError.
[[nodiscard]] Scenario parse_gyro_section(const nlohmann::json& gyro, double tick_s, const std::string& file,
                                          const std::string& path);
// The same for the "component" section (the Scenario's component).
[[nodiscard]] Scenario parse_component_section(const nlohmann::json& component, double tick_s,
                                               const std::string& file, const std::string& path);

// The sections a scenario writes for these configurations: what parse_gyro_section and
// parse_component_section read back as them (every field written, the gyro's first
// `fault_count` faults). The example gyros' scenario form (gyro.examples in Python).
[[nodiscard]] nlohmann::json gyro_section(const SimulatedGyroConfig<double>& c, std::size_t fault_count);
[[nodiscard]] nlohmann::json component_section(const GyroComponentConfig<double>& c);

// A body.trajectory without a file takes its table from `table` (the Python module's arrays),
// checked as a file's. Throws ScenarioError (also when the scenario has no body.trajectory, or
// one with a file).
void attach_trajectory(Scenario& s, const TrajectoryTable& table);

// Reads the file and parses it. A file that cannot be opened or read, a directory, or more
// than kMaxScenarioBytes is a ScenarioError with field "(file)"; reading is bounded even for
// /dev/zero or a pipe.
[[nodiscard]] Scenario read_scenario(const std::filesystem::path& path);

// The JSON path of the body rate about body axis 0 (p), 1 (q) or 2 (r), and of the specific
// force's component on axis 0 (x), 1 (y) or 2 (z), as the scenario wrote them.
[[nodiscard]] std::string body_rate_field(const Scenario& s, int axis);
[[nodiscard]] std::string body_force_field(const Scenario& s, int axis);

// The JSON path of a field the component's configure() named ("max_torque" ->
// "component.max_torque"), and of one the stub's configure() named ("pickoff.lsb_rad" ->
// "gyro.pickoff.lsb_rad", "faults[1].axis" -> "gyro.faults[1].axis").
[[nodiscard]] std::string component_field_path(const Scenario& s, std::string_view field);
[[nodiscard]] std::string gyro_field_path(const Scenario& s, std::string_view field);

}  // namespace gyro::sil
