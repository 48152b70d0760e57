// The summary's plots, drawn by gnuplot from data files computed here (so the data are the
// same bytes whatever made the table): histograms of every numeric metric, and the CDF of
// the detection latency per fault kind (over all runs of the kind: undetected runs keep the
// curve below 1).
#pragma once

#include <string>
#include <vector>

#include "campaign_file.hpp"
#include "run_table.hpp"

namespace gyro::campaign {

struct PlotJob {
  std::string png;     // relative to the output directory ("plots/latency_cdf.png")
  std::string data;    // the data file's relative path
  std::string data_text;
  // The gnuplot script, with @DATA@ and @PNG@ where the paths go.
  std::string script;
};

[[nodiscard]] std::vector<PlotJob> campaign_plots(const Campaign& c, const RunTable& t);

// The script with its placeholders replaced.
[[nodiscard]] std::string plot_script(const PlotJob& job, const std::string& data_path, const std::string& png_path);

}  // namespace gyro::campaign
