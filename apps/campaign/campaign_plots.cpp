#include "campaign_plots.hpp"

#include <algorithm>
#include <cmath>

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

std::optional<PlotJob> latency_cdf(const Campaign& c, const RunTable& t) {
  if (!c.faults || !c.metrics.safe_mode) return std::nullopt;
  const std::size_t status = *t.column("status"), latency = *t.column("latency_s"), kind_col = *t.column("fault_kind");
  PlotJob job{"plots/latency_cdf.png", "plots/latency_cdf.dat", "", ""};
  std::vector<std::string> titles;
  for (const FaultOption& o : c.faults->options) {
    if (!o.kind) continue;
    const std::string kind = gyro::fault_kind_name(*o.kind);
    if (std::find(titles.begin(), titles.end(), kind) != titles.end()) continue;
    std::uint64_t runs = 0;
    for (std::size_t i = 0; i < t.size(); ++i) runs += t.cell(i, kind_col) == kind && t.cell(i, status) == "ok" ? 1u : 0u;
    const std::vector<double> v = column_values(t, latency, status, kind, kind_col);
    if (runs == 0 || v.empty()) continue;
    titles.push_back(kind);
    job.data_text += "# " + kind + ": latency (ms), share of its " + std::to_string(runs) + " runs detected by then\n";
    for (std::size_t i = 0; i < v.size(); ++i) {
      job.data_text += g(v[i] * 1e3) + " " + g(static_cast<double>(i + 1) / static_cast<double>(runs)) + "\n";
    }
    job.data_text += "\n\n";
  }
  if (titles.empty()) return std::nullopt;
  std::string names;
  for (const std::string& k : titles) names += (names.empty() ? "" : " ") + k;
  job.script = "# gyro_campaign: CDF of the detection latency per fault kind\n" + terminal(1100, 650) +
               "set grid\nset key outside right top\nset xlabel 'latency from the fault to safe mode (ms)'\n"
               "set ylabel 'share of the runs detected'\nset yrange [0:1.02]\nset logscale x\n"
               "set title 'Detection latency per fault kind'\nkinds = " + gp_string(names) + "\n"
               "plot for [i=0:" + std::to_string(titles.size() - 1) +
               "] '@DATA@' index i using 1:2 with steps lw 2 title word(kinds, i + 1)\n";
  return job;
}

std::optional<PlotJob> histograms(const Campaign& c, const RunTable& t) {
  const std::size_t status = *t.column("status");
  PlotJob job{"plots/histograms.png", "plots/histograms.dat", "", ""};
  std::vector<std::string> titles;
  for (const MetricColumn& m : metric_columns(c.metrics)) {
    if (m.type != ColumnType::kNumber || m.name.rfind("count_", 0) == 0) continue;  // counters: mostly 0
    const std::vector<double> v = column_values(t, *t.column(m.name), status);
    if (v.empty() || v.front() == v.back()) continue;  // nothing to bin
    const double lo = v.front(), width = (v.back() - lo) / kBins;
    std::vector<std::uint64_t> counts(kBins, 0);
    for (double x : v) ++counts[std::min<std::size_t>(static_cast<std::size_t>((x - lo) / width), kBins - 1)];
    job.data_text += "# " + m.name + ": bin centre, runs (" + std::to_string(v.size()) + " with a value)\n";
    for (int b = 0; b < kBins; ++b) {
      job.data_text += g(lo + (b + 0.5) * width) + " " + std::to_string(counts[static_cast<std::size_t>(b)]) + "\n";
    }
    job.data_text += "\n\n";
    titles.push_back(m.name);
  }
  if (titles.empty()) return std::nullopt;
  const std::size_t rows = (titles.size() + 1) / 2;
  job.script = "# gyro_campaign: histograms of the metrics\n" + terminal(1200, static_cast<int>(60 + 300 * rows)) +
               "set grid\nset style fill solid 0.6 border -1\nset ylabel 'runs'\nunset key\n"
               "set multiplot layout " + std::to_string(rows) + ",2 title 'Metrics over the runs'\n";
  for (std::size_t i = 0; i < titles.size(); ++i) {
    job.script += "set title " + gp_string(titles[i]) + "\nplot '@DATA@' index " + std::to_string(i) +
                  " using 1:2 with boxes lc rgb '#1f4e9c'\n";
  }
  job.script += "unset multiplot\n";
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
