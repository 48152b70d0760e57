#include "summary.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

#include "scenario.hpp"
#include "statistics.hpp"

namespace gyro::campaign {

namespace {

// At most this many failed runs are listed (all are in runs.csv).
constexpr std::size_t kListedFailures = 50;
constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

std::string pct(double share) {
  std::array<char, 32> buf{};
  const std::to_chars_result r =
      std::to_chars(buf.data(), buf.data() + buf.size(), 100.0 * share, std::chars_format::fixed, 2);
  return std::string(buf.data(), r.ptr) + " %";
}

std::string rate_cells(std::uint64_t k, std::uint64_t n) {
  if (n == 0) return "– | –";
  const Bounds b = wilson_interval(k, n);
  return pct(static_cast<double>(k) / static_cast<double>(n)) + " | " + pct(b.lo) + " – " + pct(b.hi);
}

std::string num(double v) { return std::isnan(v) ? "–" : format_significant(v, 4); }

// The values of a numeric column over the rows selected, sorted.
template <typename Pred>
std::vector<double> values(const RunTable& t, std::size_t col, Pred&& keep) {
  std::vector<double> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (!keep(row)) continue;
    if (const std::optional<double> v = cell_number(row[col])) out.push_back(*v);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Columns by name (present in every table of this campaign).
struct Cols {
  std::size_t run, seed, status, pass, failed, reason;
  std::optional<std::size_t> fault_kind, fault_start, safe_mode, cause, detected, latency, stop_contact, final_mode;
  std::optional<std::size_t> stop_protect;  // count_gimbal_stop_protect, when recorded
};

Cols columns_of(const RunTable& t) {
  Cols c{*t.column("run"),          *t.column("seed"),           *t.column("status"),
         *t.column("pass"),         *t.column("failed"),         *t.column("reason"),
         t.column("fault_kind"),    t.column("fault_start_s"),   t.column("safe_mode_s"),
         t.column("safe_mode_cause"), t.column("detected"),      t.column("latency_s"),
         t.column("stop_contact_s"), t.column("final_mode"), t.column("count_gimbal_stop_protect")};
  return c;
}

// A cell of an optional column; "" when the table has no such column.
std::string_view cell_of(const RunTable::Row& row, const std::optional<std::size_t>& col) {
  return col ? row[*col] : std::string_view();
}

std::string_view kind_of(const RunTable::Row& row, const Cols& k) {
  return k.fault_kind ? row[*k.fault_kind] : std::string_view("none");
}

// The fault kinds in the order the campaign lists them (each once; "none" included).
std::vector<std::string> kinds_of(const Campaign& c) {
  std::vector<std::string> out;
  if (!c.faults) return out;
  for (const FaultOption& o : c.faults->options) {
    const std::string k = o.kind ? gyro::fault_kind_name(*o.kind) : "none";
    if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
  }
  return out;
}

void header_section(const Campaign& c, const RunTable& t, std::string& md) {
  md += "# Campaign summary";
  if (!c.description.empty()) md += ": " + c.description;
  md += "\n\n";
  md += "| | |\n|---|---|\n";
  md += "| campaign | `campaign.json` (" + c.fingerprint + ") |\n";
  const auto d = c.base.find("description");
  md += "| base scenario | " + (d != c.base.end() && d->is_string() ? d->get<std::string>() : std::string("(no description)")) +
        " |\n";
  md += "| runs | " + std::to_string(t.size()) + " (seed " + std::to_string(c.seed) + ") |\n";
  md += "| dispersed fields | " + std::to_string(c.dispersions.size()) + " |\n";
  if (c.faults) {
    md += "| fault injection | " + std::string(c.faults->cycle ? "in turn over " : "at random among ") +
          std::to_string(c.faults->options.size()) + " options |\n";
  }
  md += "\nEvery run's seed, dispersed values, metrics and verdict are in `runs.csv`. Rerun the campaign with\n"
        "`gyro_campaign run campaign.json -o DIR`, or one run with its time history and plot with\n"
        "`gyro_campaign run campaign.json --run K -o DIR`. Rates are given with 95 % Wilson score intervals.\n\n";
}

// The outcome of the runs `keep` selects: passed, failed a criterion, refused, error.
struct Outcome {
  std::uint64_t runs{0}, passed{0}, refused{0}, errors{0};
  [[nodiscard]] std::uint64_t failed() const { return runs - passed - refused - errors; }
};

template <typename Pred>
Outcome outcome_of(const RunTable& t, const Cols& k, Pred&& keep) {
  Outcome o;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (!keep(row)) continue;
    ++o.runs;
    if (row[k.pass] == "true") ++o.passed;
    if (row[k.status] == "refused") ++o.refused;
    if (row[k.status] == "error") ++o.errors;
  }
  return o;
}

void outcome_section(const Campaign& c, const RunTable& t, const Cols& k, std::string& md) {
  md += "## Outcome\n\n";
  const Outcome all = outcome_of(t, k, [](const RunTable::Row&) { return true; });
  const std::uint64_t n = all.runs;
  md += "| outcome | runs | rate | 95 % interval |\n|---|--:|--:|---|\n";
  md += "| passed | " + std::to_string(all.passed) + " | " + rate_cells(all.passed, n) + " |\n";
  md += "| failed a criterion | " + std::to_string(all.failed()) + " | " + rate_cells(all.failed(), n) + " |\n";
  md += "| refused: the dispersed scenario is invalid | " + std::to_string(all.refused) + " | " +
        rate_cells(all.refused, n) + " |\n";
  md += "| error: the loop failed | " + std::to_string(all.errors) + " | " + rate_cells(all.errors, n) + " |\n\n";
  if (k.fault_kind) {
    md += "By the fault injected:\n\n| fault | runs | passed | failed a criterion | refused | error | pass rate | "
          "95 % interval |\n|---|--:|--:|--:|--:|--:|--:|---|\n";
    for (const std::string& kind : kinds_of(c)) {
      const Outcome o = outcome_of(t, k, [&](const RunTable::Row& row) { return kind_of(row, k) == kind; });
      md += "| " + (kind == "none" ? std::string("none (fault-free)") : kind) + " | " + std::to_string(o.runs) + " | " +
            std::to_string(o.passed) + " | " + std::to_string(o.failed()) + " | " + std::to_string(o.refused) + " | " +
            std::to_string(o.errors) + " | " + rate_cells(o.passed, o.runs) + " |\n";
    }
    md += "\n";
  }
  if (c.criteria.empty()) md += "The campaign sets no criteria: a run passes when it runs.\n\n";
}

void criteria_section(const Campaign& c, const RunTable& t, const Cols& k, std::string& md) {
  if (c.criteria.empty()) return;
  md += "## Criteria\n\n| # | criterion | runs judged | failed | failure rate | 95 % interval |\n"
        "|--:|---|--:|--:|--:|---|\n";
  for (std::size_t n = 0; n < c.criteria.size(); ++n) {
    const Criterion& cr = c.criteria[n];
    const std::string id = std::to_string(n + 1);
    std::uint64_t judged = 0, failed = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const RunTable::Row row = t.row(i);
      if (row[k.status] != "ok") continue;
      const std::string_view kind = kind_of(row, k);
      bool in = true;
      switch (cr.scope) {
        case RunScope::kAll: break;
        case RunScope::kFaultFree: in = kind == "none"; break;
        case RunScope::kFaulted: in = kind != "none"; break;
        case RunScope::kKinds: in = std::find(cr.kinds.begin(), cr.kinds.end(), kind) != cr.kinds.end(); break;
      }
      if (!in) continue;
      ++judged;
      // The verdict itself is the table's: the `failed` cell lists the criteria a run failed.
      const std::string_view f = row[k.failed];
      for (std::size_t at = 0; at <= f.size();) {
        const std::size_t end = std::min(f.find(';', at), f.size());
        if (f.substr(at, end - at) == id) ++failed;
        at = end + 1;
      }
    }
    md += "| " + id + " | " + cr.label + " | " + std::to_string(judged) + " | " + std::to_string(failed) + " | " +
          rate_cells(failed, judged) + " |\n";
  }
  md += "\nRuns refused or in error are not judged (they count as failed in the outcome).\n\n";
}

// "residual 140, pickoff 10": how often each cause latched safe mode among the rows.
template <typename Pred>
std::string cause_counts(const RunTable& t, const Cols& k, Pred&& keep) {
  if (!k.cause) return "–";
  std::map<std::string, std::uint64_t> counts;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (keep(row) && !row[*k.cause].empty()) ++counts[std::string(row[*k.cause])];
  }
  std::vector<std::pair<std::string, std::uint64_t>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string out;
  for (const auto& [cause, n] : sorted) out += (out.empty() ? "" : ", ") + cause + " " + std::to_string(n);
  return out.empty() ? "–" : out;
}

void detection_section(const Campaign& c, const RunTable& t, const Cols& k, std::string& md) {
  if (!c.faults || !c.metrics.safe_mode || !k.fault_kind) return;
  const std::size_t detected = *t.column("detected"), false_alarm = *t.column("false_alarm"),
                    after_stop = *t.column("safe_mode_after_stop"), latency = *t.column("latency_s");
  md += "## Fault detection\n\nDetection: safe mode reached at or after the fault's start; latency from the fault's\n"
        "start to safe mode. Safe mode before the fault's start (or in a run without a fault) is a false alarm,\n"
        "unless the gimbal had met its stop by then: that is counted on its own (\"after stop contact\"), as the\n"
        "body's motion, not the monitors, is what went wrong. \"Latched by\": the monitors whose flags were raised\n"
        "on the first tick in safe mode, over the kind's runs that reached it.\n\n";
  md += "| fault | runs | detected | detection rate | 95 % interval | false alarms | false-alarm rate | 95 % interval | "
        "after stop contact | latency p50 (ms) | p95 | p99 | max | latched by |\n"
        "|---|--:|--:|--:|---|--:|--:|---|--:|--:|--:|--:|--:|---|\n";
  for (const std::string& kind : kinds_of(c)) {
    const auto of_kind = [&](const RunTable::Row& row) { return kind_of(row, k) == kind && row[k.status] == "ok"; };
    std::uint64_t n = 0, det = 0, fa = 0, stop = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const RunTable::Row row = t.row(i);
      if (!of_kind(row)) continue;
      ++n;
      det += row[detected] == "true" ? 1u : 0u;
      fa += row[false_alarm] == "true" ? 1u : 0u;
      stop += row[after_stop] == "true" ? 1u : 0u;
    }
    std::vector<double> lat = values(t, latency, of_kind);
    for (double& v : lat) v *= 1e3;
    const bool faulted = kind != "none";
    md += "| " + kind + " | " + std::to_string(n) + " | " + (faulted ? std::to_string(det) : "–") + " | " +
          (faulted ? rate_cells(det, n) : "– | –") + " | " + std::to_string(fa) + " | " + rate_cells(fa, n) + " | " +
          std::to_string(stop) + " | " +
          (faulted ? num(percentile(lat, 0.5)) + " | " + num(percentile(lat, 0.95)) + " | " + num(percentile(lat, 0.99)) +
                         " | " + num(lat.empty() ? kNoValue : lat.back())
                   : "– | – | – | –") +
          " | " + cause_counts(t, k, of_kind) + " |\n";
  }
  md += "\n";
}

// One row of the metrics table: the metric over the runs `keep` selects.
template <typename Pred>
std::string metric_row(const RunTable& t, const MetricColumn& m, const std::string& label, Pred&& keep) {
  const std::size_t col = *t.column(m.name);
  if (m.type == ColumnType::kNumber) {
    const std::vector<double> v = values(t, col, keep);
    return "| " + label + " | " + std::to_string(v.size()) + " | " + num(v.empty() ? kNoValue : v.front()) + " | " +
           num(percentile(v, 0.05)) + " | " + num(percentile(v, 0.5)) + " | " + num(percentile(v, 0.95)) + " | " +
           num(percentile(v, 0.99)) + " | " + num(v.empty() ? kNoValue : v.back()) + " |\n";
  }
  std::map<std::string, std::uint64_t> counts;
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (!keep(row) || row[col].empty()) continue;
    ++counts[std::string(row[col])];
    ++n;
  }
  std::string text;
  for (const auto& [value, count] : counts) text += (text.empty() ? "" : ", ") + value + ": " + std::to_string(count);
  return "| " + label + " | " + std::to_string(n) + " | " + text + " | | | | | |\n";
}

void metrics_section(const Campaign& c, const RunTable& t, const Cols& k, std::string& md) {
  const std::vector<MetricColumn> cols = metric_columns(c.metrics);
  if (cols.empty()) return;
  const bool split = k.fault_kind.has_value();
  md += std::string("## Metrics\n\nOver the runs that ran (status ok) and have a value") +
        (split ? ", the runs without a fault and those with one apart" : "") +
        ".\n\n| metric | runs with a value | min | p5 | p50 | p95 | p99 | max |\n|---|--:|--:|--:|--:|--:|--:|--:|\n";
  const auto ran = [&](const RunTable::Row& row) { return row[k.status] == "ok"; };
  for (const MetricColumn& m : cols) {
    if (!split) {
      md += metric_row(t, m, m.name, ran);
      continue;
    }
    md += metric_row(t, m, m.name + " (fault-free)", [&](const RunTable::Row& row) { return ran(row) && kind_of(row, k) == "none"; });
    md += metric_row(t, m, m.name + " (faulted)", [&](const RunTable::Row& row) { return ran(row) && kind_of(row, k) != "none"; });
  }
  md += "\n";
}

void dispersion_section(const Campaign& c, const RunTable& t, std::string& md) {
  if (c.dispersions.empty()) return;
  md += "## Dispersed fields\n\n| field | distribution | applied | parameters | drawn min | drawn max |\n"
        "|---|---|---|---|--:|--:|\n";
  const auto all = [](const RunTable::Row&) { return true; };
  for (const Dispersion& d : c.dispersions) {
    std::string params;
    switch (d.distribution) {
      case Distribution::kUniform: params = "[" + num(d.min) + ", " + num(d.max) + "]"; break;
      case Distribution::kNormal: params = "mean " + num(d.mean) + ", sd " + num(d.sd); break;
      case Distribution::kTruncatedNormal:
        params = "mean " + num(d.mean) + ", sd " + num(d.sd) + " in [" + num(d.min) + ", " + num(d.max) + "]";
        break;
      case Distribution::kUniformInteger:
        params = "[" + std::to_string(d.int_min) + ", " + std::to_string(d.int_max) + "]";
        break;
      case Distribution::kChoice: params = std::to_string(d.values.size()) + " values"; break;
    }
    const std::vector<double> v = values(t, *t.column(d.path), all);
    md += "| `" + d.path + "` | " + to_string(d.distribution) + " | " + to_string(d.apply) + " | " + params + " | " +
          num(v.empty() ? kNoValue : v.front()) + " | " + num(v.empty() ? kNoValue : v.back()) + " |\n";
  }
  md += "\n";
}

// The likeliest cause of a run's failure, read off its row: a refusal or an error as its
// reason; else what happened in time order: the gimbal on its stop, safe mode and the monitors
// that latched it, a fault not detected or detected late, the final mode.
struct Cause {
  std::string category;  // "stop contact", "residual", "pickoff", "spin", "input", ...
  std::string text;
};

Cause likely_cause(const RunTable& t, std::size_t i, const Cols& k) {
  const RunTable::Row row = t.row(i);
  if (row[k.status] != "ok") return {std::string(row[k.status]), t.text(i, k.reason)};
  const std::optional<double> stop = cell_number(cell_of(row, k.stop_contact));
  const std::optional<double> safe = cell_number(cell_of(row, k.safe_mode));
  const std::optional<double> fault = cell_number(cell_of(row, k.fault_start));
  const std::string cause(cell_of(row, k.cause));
  Cause out;
  const auto add = [&out](const std::string& part) { out.text += (out.text.empty() ? "" : "; ") + part; };
  // The stop is the cause when the gimbal met it before safe mode and before any fault did.
  if (stop && (!safe || *stop <= *safe)) {
    if (!fault || *stop < *fault) out.category = "stop contact";
    add("stop contact at " + num(*stop) + " s");
  }
  if (safe) {
    const bool before = !fault || *safe < *fault;
    if (out.category.empty()) out.category = before ? cause : "late detection";
    add(std::string(before ? "safe mode" : "detected") + " at " + num(*safe) + " s by " + cause +
        (before && fault ? ", before the fault (" + num(*fault) + " s)" : ""));
    if (!before) add("latency " + num(1e3 * (*safe - *fault)) + " ms");
  } else if (fault) {
    if (out.category.empty()) out.category = "not detected";
    add("fault at " + num(*fault) + " s not detected");
  }
  // Neither stop nor safe mode nor fault: the stop protection holding the gimbal off its stop
  // (a slew or a track pulled back) is the likeliest, when the campaign counts it.
  const std::optional<double> protect = cell_number(cell_of(row, k.stop_protect));
  if (out.category.empty() && protect && *protect > 0) {
    out.category = "stop protection";
    add("stop protection for " + num(*protect) + " ticks");
  }
  if (out.category.empty()) out.category = "other";
  if (k.final_mode && !safe) add("ended " + std::string(row[*k.final_mode]));
  if (out.text.empty()) out.text = t.text(i, k.reason);
  return out;
}

void failures_section(const RunTable& t, const Cols& k, std::string& md) {
  std::vector<std::size_t> failed;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (row[k.pass] != "true") failed.push_back(i);
  }
  md += "## Failed runs\n\n";
  if (failed.empty()) {
    md += "None.\n\n";
    return;
  }
  std::map<std::string, std::uint64_t> by_cause;
  for (std::size_t i : failed) ++by_cause[likely_cause(t, i, k).category];
  md += std::to_string(failed.size()) + " runs did not pass. By likely cause: ";
  std::string list;
  for (const auto& [cause, n] : by_cause) list += (list.empty() ? "" : ", ") + cause + " " + std::to_string(n);
  md += list + ".";
  if (failed.size() > kListedFailures) md += " The first " + std::to_string(kListedFailures) + " below; all in runs.csv.";
  md += "\n\n| run | seed | fault | status | likely cause | what happened | criteria failed |\n"
        "|--:|--:|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < failed.size() && i < kListedFailures; ++i) {
    const RunTable::Row row = t.row(failed[i]);
    const Cause cause = likely_cause(t, failed[i], k);
    std::string what = cause.text;
    std::string criteria = t.text(failed[i], k.reason);
    std::replace(what.begin(), what.end(), '|', '/');
    std::replace(criteria.begin(), criteria.end(), '|', '/');
    md += "| " + std::string(row[k.run]) + " | " + std::string(row[k.seed]) + " | " +
          std::string(k.fault_kind ? row[*k.fault_kind] : "–") + " | " + std::string(row[k.status]) + " | " +
          cause.category + " | " + what + " | " + (row[k.status] == "ok" ? criteria : "–") + " |\n";
  }
  md += "\n";
}

}  // namespace

std::string format_significant(double v, int digits) {
  std::array<char, 48> buf{};
  const std::to_chars_result r =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, digits);
  return std::string(buf.data(), r.ptr);
}

std::string make_summary(const Campaign& c, const RunTable& t, const std::vector<std::string>& plots) {
  const Cols k = columns_of(t);
  std::string md;
  header_section(c, t, md);
  outcome_section(c, t, k, md);
  criteria_section(c, t, k, md);
  detection_section(c, t, k, md);
  metrics_section(c, t, k, md);
  dispersion_section(c, t, md);
  failures_section(t, k, md);
  if (!plots.empty()) {
    md += "## Plots\n\n";
    for (const std::string& p : plots) md += "![" + p + "](" + p + ")\n\n";
  }
  return md;
}

}  // namespace gyro::campaign
