// A SIL run kept in memory as gyro_sil's CSV columns (sil::csv_columns(), the values
// sil::row_cells gives, before formatting): what the Python module and the C API return.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sil_runner.hpp"

namespace gyro::sil {

// gyro_sil's --max-output-bytes default, and the bound of an in-memory run's CSV up front.
inline constexpr std::uint64_t kDefaultMaxOutputBytes = std::uint64_t{1} << 30;  // 1 GiB

// One column: numbers, whole numbers (tick, flag words, statuses) or names (mode, request),
// as the first row's cell of the column is.
struct SilColumn {
  enum class Kind : std::uint8_t { kNumbers, kIntegers, kNames };
  std::string_view name;
  Kind kind{Kind::kNumbers};
  std::vector<double> numbers;
  std::vector<std::uint64_t> integers;
  std::vector<const char*> names;  // static strings
};

// Keeps every standard column of every tick (the tracking ones too, when the run tracks).
class ColumnRecorder : public TickObserver {
 public:
  ColumnRecorder();
  void on_start(const Scenario& s) override;
  void on_tick(const TickRecord& r) override;
  [[nodiscard]] const std::vector<SilColumn>& columns() const noexcept { return columns_; }
  [[nodiscard]] std::uint64_t rows() const noexcept { return rows_; }

 private:
  void set_columns(bool tracking);
  std::vector<CellValue> row_;
  std::vector<SilColumn> columns_;
  std::uint64_t rows_{0};
};

// The scenario as gyro_sil takes it (read from `path`, or parsed from `json_text` named `name`,
// and checked), with the precision and the length overridden when given, and the body's
// trajectory from `trajectory` when given (attach_trajectory). Throws ScenarioError.
[[nodiscard]] Scenario prepare_scenario(const std::optional<std::string>& path, std::string_view json_text,
                                        const std::string& name, std::optional<Precision> precision,
                                        std::optional<std::uint64_t> ticks,
                                        const TrajectoryTable* trajectory = nullptr);

// Why a run of `s` is refused when its CSV could pass `max_bytes` bytes (gyro_sil's bound, checked
// before the run; the columns in memory take less: 8 bytes a number against 16 or more
// characters), "" when it fits. `option` names the bound ("max_output_bytes").
[[nodiscard]] std::string output_bound_refusal(const Scenario& s, std::uint64_t max_bytes, std::string_view option);

}  // namespace gyro::sil
