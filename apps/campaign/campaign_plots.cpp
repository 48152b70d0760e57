#include "campaign_plots.hpp"

#include <algorithm>
#include <cmath>

#include "json_path.hpp"
#include "scenario.hpp"
#include "summary.hpp"

namespace gyro::campaign {

namespace {

constexpr int kBins = 30;

// gnuplot single-quoted string.
std::string gp_string(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string terminal(int width, int height) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n  set terminal pngcairo noenhanced size " + size +
         " font 'sans,10'\n} else {\n  set terminal png noenhanced size " + size + "\n}\nset output '@PNG@'\n";
}

std::string g(double v) { return format_significant(v, 10); }

std::vector<double> column_values(const RunTable& t, std::size_t col, std::size_t status,
                                  const std::string& kind = "", std::optional<std::size_t> kind_col = {}) {
  std::vector<double> out;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const RunTable::Row row = t.row(i);
    if (row[status] != "ok") continue;
    if (kind_col && row[*kind_col] != kind) continue;
    if (const std::optional<double> v = cell_number(row[col])) out.push_back(*v);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A value a metric is judged against: a criterion's bound, or the base scenario's limit the
// metric is measured for.
struct Threshold {
  double value{0};
  std::string label;
};

// The base scenario's number at `path` ("component.residual_limit_rad"), if it has one.
std::optional<double> base_number(const Campaign& c, std::string_view path) {
  std::string why;
  const std::optional<std::vector<PathStep>> steps = parse_path(path, why);
  const nlohmann::json* v = steps ? find_path(c.base, *steps, why) : nullptr;
  if (v == nullptr || !v->is_number()) return std::nullopt;
  return v->get<double>();
}

std::vector<Threshold> thresholds_of(const Campaign& c, const std::string& metric, double scale = 1.0) {
  std::vector<Threshold> out;
  for (const Criterion& k : c.criteria) {
    if (k.metric == metric && k.op != Criterion::Op::kEquals) {
      out.push_back({k.number * scale, "criterion " + metric + (k.op == Criterion::Op::kMax ? " <= " : " >= ") +
                                           format_significant(k.number, 4)});
    }
  }
  // The limit each metric is measured for (docs/campaigns.md, "Metrics"), as the base sets it.
  struct Limit {
    const char* metric;
    const char* path;
  };
  constexpr Limit kLimits[] = {{"max_residual_healthy_rad", "component.residual_limit_rad"},
                               {"half_limit_persistence_ticks", "component.residual_persistence_ticks"},
                               {"max_cone_rad", "component.gimbal_cone_limit_rad"},
                               {"max_cone_rad", "gyro.limits.gimbal_stop_rad"},
                               {"max_gimbal_step_rad", "component.max_pickoff_step_rad"}};
  for (const Limit& l : kLimits) {
    if (metric != l.metric) continue;
    if (const std::optional<double> v = base_number(c, l.path)) {
      const std::string_view path(l.path);
      out.push_back({*v * scale, std::string(path.substr(path.rfind('.') + 1)) + " " + format_significant(*v, 4)});
    }
  }
  return out;
}

// The vertical lines of thresholds in the current panel, named at their top.
std::string threshold_lines(const std::vector<Threshold>& th) {
  std::string s = "unset arrow\nunset label\n";
  for (std::size_t i = 0; i < th.size(); ++i) {
    s += "set arrow from " + g(th[i].value) + ", graph 0 to " + g(th[i].value) +
         ", graph 1 nohead lw 2 dt 2 lc rgb '#d62728' front\n";
    s += "set label " + gp_string(th[i].label) + " at " + g(th[i].value) +
         ", graph 0.97 rotate by 90 right offset -0.8,0 textcolor rgb '#d62728' front\n";
  }
  return s;
}

std::optional<PlotJob> latency_cdf(const Campaign& c, const RunTable& t) {
  if (!c.faults || !c.metrics.safe_mode) return std::nullopt;
  const std::size_t status = *t.column("status"), latency = *t.column("latency_s"), kind_col = *t.column("fault_kind");
  PlotJob job{"plots/latency_cdf.png", "plots/latency_cdf.dat", "", ""};
  // One curve per fault kind; kinds whose curves are identical share one (named after all of
  // them), so that no curve lies hidden under another.
  struct Curve {
    std::vector<std::string> kinds;
    std::uint64_t runs{0};
    std::vector<double> latency_s;
  };
  std::vector<Curve> curves;
  std::vector<std::string> seen;
  for (const FaultOption& o : c.faults->options) {
    if (!o.kind) continue;
    const std::string kind = gyro::fault_kind_name(*o.kind);
    if (std::find(seen.begin(), seen.end(), kind) != seen.end()) continue;
    seen.push_back(kind);
    std::uint64_t runs = 0;
    for (std::size_t i = 0; i < t.size(); ++i) runs += t.cell(i, kind_col) == kind && t.cell(i, status) == "ok" ? 1u : 0u;
    std::vector<double> v = column_values(t, latency, status, kind, kind_col);
    if (runs == 0 || v.empty()) continue;
    const auto same = std::find_if(curves.begin(), curves.end(),
                                   [&](const Curve& k) { return k.runs == runs && k.latency_s == v; });
    if (same != curves.end()) {
      same->kinds.push_back(kind);
    } else {
      curves.push_back({{kind}, runs, std::move(v)});
    }
  }
  if (curves.empty()) return std::nullopt;
  std::string plots;
  for (std::size_t n = 0; n < curves.size(); ++n) {
    const Curve& k = curves[n];
    std::string name;
    for (const std::string& kind : k.kinds) name += (name.empty() ? "" : ", ") + kind;
    if (k.latency_s.front() == k.latency_s.back()) name += " (all " + format_significant(k.latency_s.front() * 1e3, 4) + " ms)";
    job.data_text += "# " + name + ": latency (ms), share of its " + std::to_string(k.runs) + " runs detected by then\n" +
                     g(k.latency_s.front() * 1e3) + " 0\n";  // the step up from none
    for (std::size_t i = 0; i < k.latency_s.size(); ++i) {
      job.data_text += g(k.latency_s[i] * 1e3) + " " + g(static_cast<double>(i + 1) / static_cast<double>(k.runs)) + "\n";
    }
    job.data_text += "\n\n";
    plots += std::string(n == 0 ? "plot " : ", \\\n     ") + "'@DATA@' index " + std::to_string(n) +
             " using 1:2 with steps lw 2 dt " + std::to_string(n % 4 + 1) + " title " + gp_string(name);
  }
  job.script = "# gyro_campaign: CDF of the detection latency per fault kind\n" + terminal(1100, 650) +
               "set grid\nset key outside right top\nset xlabel 'latency from the fault to safe mode (ms)'\n"
               "set ylabel 'share of the runs detected'\nset yrange [0:1.05]\nset logscale x\n"
               "set title 'Detection latency per fault kind'\n" + threshold_lines(thresholds_of(c, "latency_s", 1e3)) +
               plots + "\n";
  return job;
}

// The step of the grid the values lie on (their smallest gap, when every value is a whole
// number of it from the smallest to 1e-9 of it), or 0.
double grid_step(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.size() < 2) return 0;
  double step = v[1] - v[0];
  for (std::size_t i = 2; i < v.size(); ++i) step = std::min(step, v[i] - v[i - 1]);
  for (double x : v) {
    const double n = (x - v.front()) / step;
    if (std::abs(n - std::round(n)) > 1e-9 * std::max(1.0, n)) return 0;
  }
  return step;
}

// A histogram's panel is drawn with a log count axis when one bin holds more than this share
// of the runs: the rest would be a row of slivers.
constexpr double kLogCountShare = 0.8;

std::optional<PlotJob> histograms(const Campaign& c, const RunTable& t) {
  const std::size_t status = *t.column("status");
  const std::optional<std::size_t> kind_col = t.column("fault_kind");
  PlotJob job{"plots/histograms.png", "plots/histograms.dat", "", ""};
  std::string panels;
  std::size_t count = 0;
  for (const MetricColumn& m : metric_columns(c.metrics)) {
    if (m.type != ColumnType::kNumber || m.name.rfind("count_", 0) == 0) continue;  // counters: mostly 0
    const std::size_t col = *t.column(m.name);
    std::vector<double> free, faulted;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const RunTable::Row row = t.row(i);
      if (row[status] != "ok") continue;
      const std::optional<double> v = cell_number(row[col]);
      if (!v) continue;
      (kind_col && row[*kind_col] != "none" ? faulted : free).push_back(*v);
    }
    std::vector<double> all = free;
    all.insert(all.end(), faulted.begin(), faulted.end());
    if (all.empty()) continue;
    const auto [lo_it, hi_it] = std::minmax_element(all.begin(), all.end());
    if (*lo_it == *hi_it) continue;  // one value: a table row says it, a plot would not
    // Values on a grid coarser than kBins bins of the range (counts, half-ticks) get a bin per
    // grid step, centred on the values; others kBins bins.
    const double step = grid_step(all);
    const bool on_grid = step > 0 && (*hi_it - *lo_it) / step < kBins;
    const double lo = on_grid ? *lo_it - 0.5 * step : *lo_it;
    const double width = on_grid ? step : (*hi_it - lo) / kBins;
    const int bins = on_grid ? static_cast<int>(std::lround((*hi_it - *lo_it) / step)) + 1 : kBins;
    std::vector<std::uint64_t> n_free(static_cast<std::size_t>(bins), 0), n_faulted(n_free);
    const auto bin = [&](double x) {
      return std::min<std::size_t>(static_cast<std::size_t>((x - lo) / width), static_cast<std::size_t>(bins) - 1);
    };
    for (double x : free) ++n_free[bin(x)];
    for (double x : faulted) ++n_faulted[bin(x)];
    std::uint64_t largest = 0;
    for (int b = 0; b < bins; ++b) {
      largest = std::max(largest, n_free[static_cast<std::size_t>(b)] + n_faulted[static_cast<std::size_t>(b)]);
    }
    const bool log_counts = static_cast<double>(largest) > kLogCountShare * static_cast<double>(all.size());
    job.data_text += "# " + m.name + ": bin centre, runs without a fault, runs with one (" + std::to_string(all.size()) +
                     " with a value)\n";
    for (int b = 0; b < bins; ++b) {
      const auto i = static_cast<std::size_t>(b);
      job.data_text += g(lo + (b + 0.5) * width) + " " + std::to_string(n_free[i]) + " " + std::to_string(n_faulted[i]) + "\n";
    }
    job.data_text += "\n\n";
    // The x range holds the data and every threshold.
    const std::vector<Threshold> th = thresholds_of(c, m.name);
    double x0 = lo, x1 = *hi_it;
    for (const Threshold& h : th) {
      x0 = std::min(x0, h.value);
      x1 = std::max(x1, h.value);
    }
    const double pad = 0.04 * (x1 - x0);
    const std::string idx = std::to_string(count);
    // Empty bins are not drawn (on a log axis they have no place); every box is one bin wide.
    panels += "set title " + gp_string(m.name + (log_counts ? " (runs: log scale)" : "")) + "\n" + threshold_lines(th) +
              "set xrange [" + g(x0 - pad) + ":" + g(x1 + pad) + "]\nset boxwidth " + g(width) + " absolute\n" +
              (log_counts ? "set logscale y\nset yrange [0.8:*]\n" : "unset logscale y\nset yrange [0:*]\n") + "plot ";
    bool first = true;
    if (!free.empty()) {
      panels += "'@DATA@' index " + idx + " using 1:($2 > 0 ? $2 : NaN) with boxes fillstyle solid 0.5 noborder " +
                "lc rgb '#1f4e9c' title " + gp_string(kind_col ? "fault-free (" + std::to_string(free.size()) + ")" : "runs");
      first = false;
    }
    if (!faulted.empty()) {
      panels += std::string(first ? "" : ", ") + "'@DATA@' index " + idx +
                " using 1:($3 > 0 ? $3 : NaN) with boxes lc rgb '#e6550d' lw 2 fillstyle empty title " +
                gp_string("faulted (" + std::to_string(faulted.size()) + ")");
    }
    panels += "\n";
    ++count;
  }
  if (count == 0) return std::nullopt;
  const std::size_t rows = (count + 1) / 2;
  job.script = "# gyro_campaign: histograms of the metrics\n" + terminal(1200, static_cast<int>(60 + 330 * rows)) +
               "set grid\nset ylabel 'runs'\nset key below horizontal\nset offsets 0, 0, graph 0.1, 0\nset format x '%.3g'\n"
               "set multiplot layout " + std::to_string(rows) + ",2 title 'Metrics over the runs: thresholds dashed red'\n" +
               panels + "unset multiplot\n";
  return job;
}

std::optional<PlotJob> scatter(const Campaign& c, const RunTable& t) {
  if (c.scatter.empty()) return std::nullopt;
  const std::size_t status = *t.column("status"), pass = *t.column("pass");
  PlotJob job{"plots/scatter.png", "plots/scatter.dat", "", ""};
  for (const Scatter& s : c.scatter) {
    const std::size_t x = *t.column(s.x), y = *t.column(s.y);
    job.data_text += "# " + s.x + ", " + s.y + ", passed (1) or not (0)\n";
    for (std::size_t i = 0; i < t.size(); ++i) {
      const RunTable::Row row = t.row(i);
      if (row[status] != "ok" || row[x].empty() || row[y].empty()) continue;
      job.data_text += std::string(row[x]) + " " + std::string(row[y]) + " " + (row[pass] == "true" ? "1" : "0") + "\n";
    }
    job.data_text += "\n\n";
  }
  const std::size_t rows = (c.scatter.size() + 1) / 2;
  job.script = "# gyro_campaign: scatter plots\n" + terminal(1200, static_cast<int>(60 + 380 * rows)) +
               "set grid\nset key top left\nset multiplot layout " + std::to_string(rows) +
               ",2 title 'Runs: passed in blue, failed in red'\n";
  for (std::size_t i = 0; i < c.scatter.size(); ++i) {
    const std::string idx = std::to_string(i);
    job.script += "set xlabel " + gp_string(c.scatter[i].x) + "\nset ylabel " + gp_string(c.scatter[i].y) + "\n" +
                  "plot '@DATA@' index " + idx + " using 1:($3 == 1 ? $2 : NaN) with points pt 7 ps 0.4 " +
                  "lc rgb '#1f4e9c' title 'passed', '' index " + idx +
                  " using 1:($3 == 0 ? $2 : NaN) with points pt 7 ps 0.4 lc rgb '#d62728' title 'failed'\n";
  }
  job.script += "unset multiplot\n";
  return job;
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
}

}  // namespace

std::vector<PlotJob> campaign_plots(const Campaign& c, const RunTable& t) {
  std::vector<PlotJob> out;
  if (std::optional<PlotJob> j = latency_cdf(c, t)) out.push_back(std::move(*j));
  if (std::optional<PlotJob> j = histograms(c, t)) out.push_back(std::move(*j));
  if (std::optional<PlotJob> j = scatter(c, t)) out.push_back(std::move(*j));
  return out;
}

std::string plot_script(const PlotJob& job, const std::string& data_path, const std::string& png_path) {
  std::string s = job.script;
  std::string d = data_path, p = png_path;
  replace_all(d, "'", "''");
  replace_all(p, "'", "''");
  replace_all(s, "@DATA@", d);
  replace_all(s, "@PNG@", p);
  return s;
}

}  // namespace gyro::campaign
