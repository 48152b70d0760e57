#include "run_table.hpp"

#include <algorithm>
#include <array>
#include <charconv>

#include "campaign_error.hpp"
#include "scenario.hpp"

namespace gyro::campaign {

namespace {

using json = nlohmann::json;

std::string integer_cell(std::int64_t v) { return std::to_string(v); }

std::string json_cell(const json& v) {
  if (v.is_number_unsigned()) return std::to_string(v.get<std::uint64_t>());
  if (v.is_number_integer()) return integer_cell(v.get<std::int64_t>());
  if (v.is_number()) return number_cell(v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

std::string optional_cell(const std::optional<double>& v) { return v ? number_cell(*v) : std::string(); }
std::string bool_cell(bool b) { return b ? "true" : "false"; }

// The metric cells of a run, in metric_columns() order (all empty when it did not run).
std::vector<std::string> metric_cells(const Campaign& c, const RunResult& r) {
  const MetricSet& ms = c.metrics;
  std::vector<std::string> out;
  const RunMetrics* m = r.metrics ? &*r.metrics : nullptr;
  if (ms.healthy_residual) out.push_back(m ? optional_cell(m->max_residual_healthy_rad) : "");
  if (ms.residual_persistence) out.push_back(m ? optional_cell(m->half_limit_persistence_ticks) : "");
  if (ms.envelope) {
    out.push_back(m ? number_cell(m->max_cone_rad) : "");
    out.push_back(m ? optional_cell(m->max_gimbal_step_rad) : "");
  }
  if (ms.safe_mode) {
    out.push_back(m ? optional_cell(m->safe_mode_s) : "");
    out.push_back(m ? m->safe_mode_cause : "");
    out.push_back(m && m->detected ? bool_cell(*m->detected) : "");
    out.push_back(m ? bool_cell(m->false_alarm) : "");
    out.push_back(m ? bool_cell(m->safe_mode_after_stop) : "");
    out.push_back(m ? optional_cell(m->latency_s) : "");
  }
  if (ms.slew_rate_error) out.push_back(m ? optional_cell(m->slew_rate_error_rad_s) : "");
  if (ms.pointing_error) out.push_back(m ? optional_cell(m->max_pointing_error_rad) : "");
  if (ms.tracking) {
    out.push_back(m ? optional_cell(m->max_track_pointing_error_rad) : "");
    out.push_back(m ? optional_cell(m->max_los_rate_error_rad_s) : "");
  }
  if (ms.final_mode) out.push_back(m ? gyro::enum_name_or(m->final_mode, "?") : "");
  for (int bit : ms.flag_counters) {
    out.push_back(m ? std::to_string(m->counters[static_cast<std::size_t>(bit)]) : "");
  }
  if (ms.gimbal_stop) {
    out.push_back(m ? optional_cell(m->stop_contact_s) : "");
    out.push_back(m ? number_cell(m->time_at_stop_s) : "");
  }
  return out;
}

// Scopes other than "all" exist only with a fault injection: they go by the injected kind.
bool in_scope(const Criterion& k, const RunResult& r) {
  const std::string kind = r.plan.fault && r.plan.fault->kind ? gyro::fault_kind_name(*r.plan.fault->kind) : "none";
  switch (k.scope) {
    case RunScope::kAll: return true;
    case RunScope::kFaultFree: return kind == "none";
    case RunScope::kFaulted: return kind != "none";
    case RunScope::kKinds: return std::find(k.kinds.begin(), k.kinds.end(), kind) != k.kinds.end();
  }
  return true;
}

bool holds(const Criterion& k, const std::string& cell) {
  if (cell.empty()) return false;  // no value: not shown to hold
  if (k.op == Criterion::Op::kEquals && !k.text.empty()) return cell == k.text;
  const std::optional<double> v = cell_number(cell);
  if (!v) return false;
  switch (k.op) {
    case Criterion::Op::kMax: return *v <= k.number;
    case Criterion::Op::kMin: return *v >= k.number;
    case Criterion::Op::kEquals: return *v == k.number;
  }
  return false;
}

}  // namespace

std::string number_cell(double v) {
  std::array<char, 32> buf{};
  const std::to_chars_result r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::optional<double> cell_number(std::string_view cell) {
  double v = 0;
  const std::from_chars_result r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (cell.empty() || r.ec != std::errc{} || r.ptr != cell.data() + cell.size()) return std::nullopt;
  return v;
}

std::vector<std::string> table_header(const Campaign& c) {
  std::vector<std::string> h = {"run", "seed", "status", "pass"};
  if (c.faults) {
    for (const char* f : {"fault_kind", "fault_start_s", "fault_duration_s", "fault_axis", "fault_magnitude"}) {
      h.emplace_back(f);
    }
  }
  for (const Dispersion& d : c.dispersions) h.push_back(d.path);
  for (const MetricColumn& m : metric_columns(c.metrics)) h.push_back(m.name);
  h.emplace_back("failed");
  h.emplace_back("reason");
  return h;
}

std::string format_row(const Campaign& c, const RunResult& r) {
  std::vector<std::string> cells = {std::to_string(r.plan.index), std::to_string(r.plan.seed), to_string(r.status)};
  const std::size_t pass_at = cells.size();
  cells.emplace_back();
  if (c.faults) {
    const FaultDraw& f = *r.plan.fault;
    if (f.kind) {
      cells.emplace_back(gyro::fault_kind_name(*f.kind));
      cells.push_back(number_cell(f.start_s));
      cells.push_back(number_cell(f.duration_s));
      cells.push_back(std::to_string(f.axis));
      cells.push_back(f.magnitude ? number_cell(*f.magnitude) : "");
    } else {
      cells.insert(cells.end(), {"none", "", "", "", ""});
    }
  }
  for (const json& v : r.plan.values) cells.push_back(json_cell(v));
  const std::size_t metrics_at = cells.size();
  for (std::string& m : metric_cells(c, r)) cells.push_back(std::move(m));

  std::string failed;
  std::string reason = r.reason;
  bool pass = r.status == RunStatus::kOk;
  if (pass) {
    const std::vector<MetricColumn> columns = metric_columns(c.metrics);
    for (std::size_t i = 0; i < c.criteria.size(); ++i) {
      const Criterion& k = c.criteria[i];
      if (!in_scope(k, r)) continue;
      const auto col = std::find_if(columns.begin(), columns.end(), [&](const MetricColumn& m) { return m.name == k.metric; });
      const std::string& cell = cells[metrics_at + static_cast<std::size_t>(col - columns.begin())];
      if (holds(k, cell)) continue;
      pass = false;
      failed += (failed.empty() ? "" : ";") + std::to_string(i + 1);
      reason += (reason.empty() ? "" : "; ") + k.label + ": " + (cell.empty() ? std::string("no value") : cell);
    }
  }
  cells[pass_at] = pass ? "true" : "false";
  cells.push_back(failed);
  std::replace(reason.begin(), reason.end(), '\n', ' ');
  std::replace(reason.begin(), reason.end(), '\r', ' ');
  cells.push_back(reason);
  return csv_line(cells) + "\n";
}

std::string csv_line(const std::vector<std::string>& cells) {
  std::string out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i != 0) out += ',';
    const std::string& c = cells[i];
    if (c.find_first_of(",\"\n\r") == std::string::npos) {
      out += c;
      continue;
    }
    out += '"';
    for (char ch : c) {
      if (ch == '"') out += '"';
      out += ch;
    }
    out += '"';
  }
  return out;
}

std::optional<std::vector<std::string>> split_csv_line(std::string_view line) {
  std::vector<std::string> cells(1);
  std::size_t i = 0;
  while (i < line.size()) {
    const char ch = line[i];
    if (ch == ',') {
      cells.emplace_back();
      ++i;
    } else if (ch == '"' && cells.back().empty()) {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            cells.back() += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        cells.back() += line[i++];
      }
      if (!closed || (i < line.size() && line[i] != ',')) return std::nullopt;
    } else {
      cells.back() += ch;
      ++i;
    }
  }
  return cells;
}


std::optional<std::uint64_t> row_run_index(std::string_view row) {
  const std::size_t comma = row.find(',');
  const std::string_view cell = row.substr(0, comma);
  std::uint64_t v = 0;
  const std::from_chars_result r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (cell.empty() || r.ec != std::errc{} || r.ptr != cell.data() + cell.size()) return std::nullopt;
  return v;
}

namespace {

// The start of each cell of a CSV line (quotes respected), then the line's length; nullopt if
// a quote is not closed or a closing quote is not followed by a comma.
std::optional<std::vector<std::uint32_t>> cell_starts(std::string_view line) {
  std::vector<std::uint32_t> starts = {0};
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch != '"') continue;
      if (i + 1 < line.size() && line[i + 1] == '"') {
        ++i;
        continue;
      }
      quoted = false;
      if (i + 1 < line.size() && line[i + 1] != ',') return std::nullopt;
    } else if (ch == '"' && i == starts.back()) {
      quoted = true;
    } else if (ch == ',') {
      starts.push_back(static_cast<std::uint32_t>(i + 1));
    }
  }
  if (quoted) return std::nullopt;
  starts.push_back(static_cast<std::uint32_t>(line.size() + 1));  // as if a comma followed
  return starts;
}

}  // namespace

RunTable::RunTable(const Campaign& c, std::vector<std::string> rows, const std::string& file, std::size_t first_line)
    : header_(table_header(c)), lines_(std::move(rows)) {
  const std::size_t width = header_.size();
  starts_.reserve(lines_.size() * (width + 1));
  for (std::size_t r = 0; r < lines_.size(); ++r) {
    std::string& line = lines_[r];
    if (!line.empty() && line.back() == '\n') line.pop_back();
    const std::string where = "line " + std::to_string(first_line + r);
    if (line.size() >= UINT32_MAX) throw CampaignError(file, where, "a line longer than 4 GB");
    const std::optional<std::vector<std::uint32_t>> st = cell_starts(line);
    if (!st) throw CampaignError(file, where, "broken quoting");
    if (st->size() != width + 1) {
      throw CampaignError(file, where, std::to_string(st->size() - 1) + " cells, expected " + std::to_string(width));
    }
    const std::optional<std::uint64_t> run = row_run_index(line);
    if (!run || *run >= c.runs) {
      throw CampaignError(file, where, "not a run of this campaign: \"" + line.substr(0, line.find(',')) + "\"");
    }
    starts_.insert(starts_.end(), st->begin(), st->end());
  }
}

std::optional<std::size_t> RunTable::column(std::string_view name) const {
  const auto it = std::find(header_.begin(), header_.end(), name);
  if (it == header_.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header_.begin());
}

std::string_view RunTable::cell(std::size_t row, std::size_t col) const {
  const std::uint32_t* st = &starts_[row * (header_.size() + 1)];
  return std::string_view(lines_[row]).substr(st[col], st[col + 1] - st[col] - 1);
}

std::string RunTable::text(std::size_t row, std::size_t col) const {
  const std::string_view raw = cell(row, col);
  if (raw.empty() || raw.front() != '"') return std::string(raw);
  return split_csv_line(raw)->front();
}

RunTable parse_run_table(std::string_view text, const Campaign& c, const std::string& file) {
  const std::size_t nl = text.find('\n');
  if (text.empty()) throw CampaignError(file, "line 1", "empty file");
  if (nl == std::string_view::npos || text.back() != '\n') {
    throw CampaignError(file, "line " + std::to_string(std::count(text.begin(), text.end(), '\n') + 1),
                        "no newline at the end");
  }
  const std::vector<std::string> expected = table_header(c);
  const std::optional<std::vector<std::string>> header = split_csv_line(text.substr(0, nl));
  if (!header || *header != expected) {
    throw CampaignError(file, "line 1", "the header is not this campaign's (" + csv_line(expected) + ")");
  }
  std::vector<std::string> rows;
  for (std::size_t pos = nl + 1; pos < text.size();) {
    const std::size_t end = text.find('\n', pos);
    rows.emplace_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  return RunTable(c, std::move(rows), file);
}

}  // namespace gyro::campaign
