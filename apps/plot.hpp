// Plots of a gyro_sil CSV with gnuplot: panels stacked on one time axis (their plotting areas
// aligned), each with series from the CSV, limit lines, or a raster of bars (modes, flags);
// markers and shaded windows run through every panel. run_plot.hpp says what a run's plot
// shows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace gyro::sil {

// How long gnuplot may take by default: a run's plot (run_plot.hpp: 17 curves, one row in 11)
// of the 200,001 rows of a 103 MB CSV took about 4.7 s on the 2-core development machine, so
// the largest CSV of the default output limit (1 GiB, about 2 million rows) takes about a
// minute.
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
  bool magnitude{false};  // plot |value|
};

// A horizontal line across a panel: a limit (and its mirror at -value when `mirrored`).
struct PlotLimit {
  double value{0};
  std::string title;
  std::string style;  // e.g. "dt 2 lw 1.5 lc rgb '#d62728'"
  bool mirrored{false};
};

// A bar of a raster row, from_s to to_s, in a colour ("#rrggbb"); `label` is written inside
// it when it is wide enough.
struct PlotBar {
  double from_s{0}, to_s{0};
  std::string color;
  std::string label;
};

struct PlotRow {
  std::string name;  // the row's tick label
  std::vector<PlotBar> bars;
};

struct PlotPanel {
  std::string ylabel;
  std::vector<PlotSeries> series;  // from the CSV
  std::vector<PlotLimit> limits;
  std::vector<PlotRow> rows;       // a raster, top row first (instead of or beside series)
  bool log_y{false};
  int height_px{330};
};

// An instant marked by a vertical line through every panel, named at the top.
struct PlotMarker {
  double t_s{0};
  std::string label;
  std::string color;
};

// A stretch of time shaded in every panel, named at the top (unless the name is empty).
struct PlotWindow {
  double from_s{0}, to_s{0};
  std::string label;
  std::string color;        // the shade
  std::string label_color;  // the name's (a pale shade's colour is hard to read as text)
};

struct PlotRequest {
  std::filesystem::path csv;
  std::filesystem::path png;  // written by gnuplot (gyro_sil gives it a temporary file)
  std::string title;  // '\n' starts a new line
  int time_column{1};
  std::vector<PlotPanel> panels;  // stacked top to bottom on one time axis
  std::vector<PlotMarker> markers;
  std::vector<PlotWindow> windows;
  std::optional<double> end_s;  // the time axis runs from 0 to here (default: the data's range)
  std::uint64_t every{1};       // plot every Nth row of the CSV (a long run's plot needs no more)
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
