// A Monte Carlo campaign of SIL runs, as its JSON file describes it: a base scenario (a path
// or inline), fields set on it, dispersions of scenario fields by JSON path, injected faults,
// the run count and seed, the metrics recorded per run and the pass/fail criteria. The
// schema is documented in docs/campaigns.md.
//
// Every refusal is a CampaignError naming the file, the field as a JSON path
// ("dispersions[2].min") and the reason. A dispersion whose path is not in the base scenario
// is refused, never ignored.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gyro/simulated_gyro.hpp"
#include "json_path.hpp"

namespace gyro::campaign {

enum class Distribution : std::uint8_t { kUniform, kNormal, kTruncatedNormal, kUniformInteger, kChoice };
enum class Apply : std::uint8_t { kSet, kScale, kOffset };

[[nodiscard]] const char* to_string(Distribution d) noexcept;
[[nodiscard]] const char* to_string(Apply a) noexcept;

struct Dispersion {
  std::string path;                 // canonical ("guidance.schedule[2].slew_rate_rad_s[0]")
  std::vector<PathStep> steps;
  Distribution distribution{Distribution::kUniform};
  Apply apply{Apply::kSet};
  double min{0}, max{0};            // uniform, truncated normal
  double mean{0}, sd{0};            // normal, truncated normal
  std::int64_t int_min{0}, int_max{0};  // uniform_integer (inclusive)
  std::vector<nlohmann::json> values;   // choice
  std::vector<double> cumulative_weights;  // choice: running sums, the last is the total
  std::uint64_t stream{0};          // noise stream id: a hash of the path
};

// A closed interval [lo, hi]; lo == hi is a fixed value.
struct Interval {
  double lo{0}, hi{0};
};

// One alternative of the fault injection: a kind (or none) and the ranges drawn per run.
struct FaultOption {
  std::optional<FaultKind> kind;    // nullopt: the run gets no fault
  std::uint64_t weight{1};
  Interval start_s{};
  Interval duration_s{};            // 0 = permanent
  std::vector<int> axes{-1};        // drawn uniformly
  std::optional<Interval> magnitude;
  bool either_sign{false};          // magnitude's sign drawn too
};

struct FaultInjection {
  bool cycle{true};                 // run k takes option pattern[k mod pattern size]; else random
  std::vector<FaultOption> options;
  std::vector<std::size_t> pattern; // cycle: option indices, each repeated `weight` times
  std::vector<double> cumulative_weights;  // random
};

// A window of the run over which a metric takes its largest value.
struct Window {
  double from_s{0}, to_s{0};
};

struct MetricSet {
  bool healthy_residual{false};     // max_residual_healthy_rad
  bool residual_persistence{false}; // half_limit_persistence_ticks
  bool envelope{false};             // max_cone_rad, max_gimbal_step_rad
  bool safe_mode{false};            // safe_mode_s, detected, false_alarm, latency_s
  std::optional<Window> slew_rate_error;  // slew_rate_error_rad_s
  std::optional<Window> pointing_error;   // max_pointing_error_rad
  std::optional<Window> tracking;         // max_track_pointing_error_rad, max_los_rate_error_rad_s
  bool final_mode{false};           // final_mode
  std::vector<int> flag_counters;   // count_<flag>: component flag bit numbers
  bool gimbal_stop{false};          // time_at_stop_s
};

// Which runs a criterion judges.
enum class RunScope : std::uint8_t { kAll, kFaultFree, kFaulted, kKinds };

struct Criterion {
  std::string metric;               // a per-run column
  enum class Op : std::uint8_t { kMax, kMin, kEquals } op{Op::kMax};
  double number{0};                 // max, min, or equals on a number
  std::string text;                 // equals on a name or a boolean ("free", "true")
  RunScope scope{RunScope::kAll};
  std::vector<std::string> kinds;   // kKinds: fault kind names
  std::string label;                // "latency_s <= 0.3 (faulted runs)"
};

// A scatter plot of the summary: one per-run column against another.
struct Scatter {
  std::string x, y;
};

struct Campaign {
  std::string file;                 // where it was read from (for messages)
  std::string description;
  std::string base_source;          // the base scenario's path as written, or "inline"
  std::optional<std::filesystem::path> base_path;  // that file, when it is one
  nlohmann::json base;              // the base scenario with `set` applied
  std::uint64_t runs{0};
  std::uint64_t seed{0};
  std::vector<Dispersion> dispersions;
  std::optional<FaultInjection> faults;
  MetricSet metrics;
  std::vector<Criterion> criteria;
  std::vector<Scatter> scatter;
  double tick_s{0};                 // of the base scenario
  std::uint64_t ticks{0};
  // The campaign with its base scenario inline (keys sorted, two-space indent): what
  // campaign.json holds in every output directory, and the text MPI ranks receive.
  std::string resolved_text;
  std::string fingerprint;          // "fnv1a64:<16 hex digits>" of resolved_text
};

// Largest run count accepted, checked before anything is allocated for the runs: the per-run
// table is held in memory, about 2 kB a run (223 MB for 100,000 runs, docs/campaigns.md), so
// 10^6 runs need about 2 GB. Larger campaigns are several campaigns with other seeds.
inline constexpr std::uint64_t kMaxRuns = 1'000'000;

// Largest campaign file read (4 MiB, checked before reading; the shipped ones are about
// 6 KB). It bounds campaign.json in an output directory too: a campaign whose resolved text
// (its base scenario inline) is longer is refused, so that every campaign.json written can
// be read back by merge and run.
inline constexpr std::uint64_t kMaxCampaignBytes = 4u << 20;

// Deepest nesting of arrays and objects accepted: a base scenario inline (the scenario's own
// bound is 16 levels) inside the campaign, with room to spare.
inline constexpr std::size_t kMaxCampaignDepth = 32;

// Largest total of the fault injection's weights (the "cycle" pattern holds one entry per
// unit of weight).
inline constexpr std::uint64_t kMaxWeightTotal = 1'000'000;

// Campaign or manifest text -> document by the strict reader (strict_json.hpp), nested at
// most kMaxCampaignDepth levels. Throws CampaignError.
[[nodiscard]] nlohmann::json parse_campaign_json(std::string_view text, const std::string& file);

// Parses and checks the campaign; a base scenario given as a path is read relative to
// `base_dir`. Throws CampaignError.
[[nodiscard]] Campaign parse_campaign(std::string_view json_text, const std::string& file,
                                      const std::filesystem::path& base_dir);

// Reads the file (at most kMaxCampaignBytes; a base scenario file at most
// sil::kMaxScenarioBytes, both checked before reading) and parses it (the base path relative
// to the file's directory).
[[nodiscard]] Campaign read_campaign(const std::filesystem::path& path);

// The campaign of the first `n` of c's runs (1 <= n <= c.runs): each run is the same as in
// the whole campaign (a run depends only on the campaign's seed and its index), and
// campaign.json, its fingerprint and the manifest say `n` runs. Throws CampaignError
// (field "runs") otherwise.
void keep_first_runs(Campaign& c, std::uint64_t n);

// The per-run metric columns the metric set records, in order, with their kind of value.
enum class ColumnType : std::uint8_t { kNumber, kBoolean, kMode, kCause };
struct MetricColumn {
  std::string name;
  ColumnType type{ColumnType::kNumber};
};
[[nodiscard]] std::vector<MetricColumn> metric_columns(const MetricSet& m);

// The names of the component's flags, bit by bit ("gimbal_limit", ...).
[[nodiscard]] const std::vector<std::string>& component_flag_names();

// FNV-1a, 64 bits.
[[nodiscard]] std::uint64_t fnv1a64(std::string_view text) noexcept;

}  // namespace gyro::campaign
