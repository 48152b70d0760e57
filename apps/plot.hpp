// Plots of a gyro_sil CSV with gnuplot: the gimbal angles against time, one panel per axis,
// the true angles as lines and the component's measured (and predicted) angles on top, as the
// report's Figures show the nutation riding on the slow drift.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyro::sil {

// How long gnuplot may take by default: it drew the 200,001 rows of a 103 MB CSV in about
// 10.5 s on the 2-core development machine, so the largest CSV of the default output limit
// (1 GiB, about 2 million rows) takes about 2 minutes.
inline constexpr double kDefaultPlotTimeoutS = 300.0;

class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PlotSeries {
  int column{0};  // 1-based CSV column
  std::string title;
  bool points{false};  // small points instead of a line
  std::string style;   // extra gnuplot style, e.g. "lw 3 lc rgb '#a0a0a0'"
};

struct PlotPanel {
  std::string ylabel;
  std::vector<PlotSeries> series;
};

struct PlotRequest {
  std::filesystem::path csv;
  std::filesystem::path png;  // written by gnuplot (gyro_sil gives it a temporary file)
  std::string title;  // '\n' starts a new line
  int time_column{1};
  std::vector<PlotPanel> panels;  // stacked top to bottom
  double timeout_s{kDefaultPlotTimeoutS};  // gnuplot is killed after this long
};

// The gnuplot program: $GNUPLOT if set, else "gnuplot" on PATH; nullopt if there is none.
[[nodiscard]] std::optional<std::filesystem::path> find_gnuplot();

// The gnuplot script that draws `r` (exposed for tests).
[[nodiscard]] std::string gnuplot_script(const PlotRequest& r);

// Writes r.png with gnuplot: run directly (no shell) in its own process group, with standard
// input from /dev/null and its standard output sent to standard error (which keeps a CSV on
// standard output clean), killed (the whole group) after r.timeout_s. Throws PlotError when
// gnuplot is missing, fails, times out, or leaves no image.
void plot_csv(const PlotRequest& r);

// Runs gnuplot on `script`, which must draw `png`, as plot_csv does (killed after timeout_s).
void run_gnuplot(const std::string& script, const std::filesystem::path& png,
                 double timeout_s = kDefaultPlotTimeoutS);

}  // namespace gyro::sil
