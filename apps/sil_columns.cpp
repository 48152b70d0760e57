#include "sil_columns.hpp"

#include <type_traits>
#include <variant>

#include "scenario_limits.hpp"

namespace gyro::sil {

ColumnRecorder::ColumnRecorder() { set_columns(false); }

void ColumnRecorder::set_columns(bool tracking) {
  const std::span<const std::string_view> names = csv_columns(tracking);
  row_.assign(names.size(), CellValue{});
  columns_.assign(names.size(), SilColumn{});
  for (std::size_t i = 0; i < columns_.size(); ++i) columns_[i].name = names[i];
  rows_ = 0;
}

void ColumnRecorder::on_start(const Scenario& s) { set_columns(s.track.has_value()); }

void ColumnRecorder::on_tick(const TickRecord& r) {
  row_cells(r, row_);
  for (std::size_t i = 0; i < row_.size(); ++i) {
    SilColumn& c = columns_[i];
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, double>) {
            c.kind = SilColumn::Kind::kNumbers;
            c.numbers.push_back(v);
          } else if constexpr (std::is_same_v<V, std::uint64_t>) {
            c.kind = SilColumn::Kind::kIntegers;
            c.integers.push_back(v);
          } else {
            c.kind = SilColumn::Kind::kNames;
            c.names.push_back(v);
          }
        },
        row_[i]);
  }
  ++rows_;
}

Scenario prepare_scenario(const std::optional<std::string>& path, std::string_view json_text, const std::string& name,
                          std::optional<Precision> precision, std::optional<std::uint64_t> ticks,
                          const TrajectoryTable* trajectory) {
  Scenario s = path ? read_scenario(*path) : parse_scenario(json_text, name);
  if (precision) s.run.precision = *precision;
  if (trajectory != nullptr) attach_trajectory(s, *trajectory);
  check_configs(s);
  if (ticks) s.run.ticks = *ticks;
  check_trajectory_covers_run(s);
  return s;
}

std::string output_bound_refusal(const Scenario& s, std::uint64_t max_bytes, std::string_view option) {
  const std::uint64_t bound = csv_size_bound(s);
  if (bound <= max_bytes) return "";
  const std::string o(option);
  return o + ": the run's output could take up to " + std::to_string(bound) + " bytes (" +
         std::to_string(s.run.ticks + 1) + " rows of " + std::to_string(csv_row_bytes_bound(s.run.ticks, s.track.has_value())) +
         " bytes), more than the limit of " + std::to_string(max_bytes) + " (raise it with " + o +
         "=..., or run fewer ticks)";
}

}  // namespace gyro::sil
