// gyro_sil: runs the flight gyro component against the simulated gyro, as a scenario file
// describes, and writes the time history as CSV (and a plot of the gimbal angles).
//
//   gyro_sil SCENARIO.json [-o out.csv] [--plot out.png] [--precision float|double] [--quiet]
//
// Exit status: 0 done; 1 the run failed (software refused a call, output not writable);
// 2 bad command line or bad scenario (the message names file, field and reason);
// 3 the CSV was written but the plot failed (gnuplot missing or failing).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>

#include "csv_writer.hpp"
#include "plot.hpp"
#include "scenario.hpp"
#include "sil_runner.hpp"

namespace {

namespace fs = std::filesystem;
using namespace gyro::sil;

constexpr int kExitRunFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitPlotFailed = 3;

void make_parent_dirs(const fs::path& p) {
  const fs::path parent = p.parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);  // a failure shows up when the file is opened
}

PlotRequest gimbal_plot(const fs::path& csv, const fs::path& png, const Scenario& s) {
  PlotRequest r;
  r.csv = csv;
  r.png = png;
  r.title = fs::path(s.file).filename().string() + " (" + to_string(s.run.precision) + ")";
  // The description, wrapped at word boundaries.
  std::string line;
  std::istringstream words(s.description);
  for (std::string w; words >> w;) {
    if (!line.empty() && line.size() + 1 + w.size() > 110) {
      r.title += "\n" + line;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) r.title += "\n" + line;
  r.time_column = csv_column("t");
  const char* true_style = "lw 3 lc rgb '#9a9a9a'";
  const char* meas_style = "lc rgb '#d62728'";
  const char* pred_style = "lw 1 dt 2 lc rgb '#1f4e9c'";
  for (const char* axis : {"pitch", "yaw"}) {
    const std::string a(axis);
    r.panels.push_back({"gimbal " + a + " (rad)",
                        {{csv_column("gimbal_" + a), "true", false, true_style},
                         {csv_column("gimbal_" + a + "_meas"), "measured (accepted)", true, meas_style},
                         {csv_column("gimbal_" + a + "_pred"), "predicted", false, pred_style}}});
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gyro_sil: runs the gyro flight component against the simulated gyro hardware from a "
               "scenario file and writes the time history as CSV"};
  std::string scenario_path;
  std::string csv_path = "-";
  std::string plot_path;
  std::string precision_name;
  bool quiet = false;
  app.add_option("scenario", scenario_path, "scenario file (JSON, see docs/scenarios.md)")->required();
  app.add_option("-o,--output", csv_path, "CSV time history to write ('-' = standard output)")
      ->capture_default_str();
  app.add_option("--plot", plot_path, "also plot the gimbal angles against time to this PNG (needs gnuplot)");
  app.add_option("--precision", precision_name, "run the component and the stub in float or double "
                                                "(default: the scenario's run.precision)")
      ->check(CLI::IsMember({"float", "double"}));
  app.add_flag("-q,--quiet", quiet, "no progress or summary on standard error");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }

  const std::optional<Precision> precision =
      precision_name.empty() ? std::nullopt : parse_precision(precision_name);

  Scenario scenario;
  try {
    scenario = load_scenario(scenario_path, precision);
  } catch (const ScenarioError& e) {
    std::fprintf(stderr, "gyro_sil: bad scenario: %s\n", e.what());
    return kExitBadInput;
  }

  // With the CSV on standard output a plot needs a file to read: a temporary copy.
  const bool to_stdout = csv_path == "-";
  fs::path csv_file = csv_path;
  if (to_stdout && !plot_path.empty()) {
    csv_file = fs::temp_directory_path() / ("gyro_sil_" + std::to_string(::getpid()) + ".csv");
  }
  std::FILE* out = stdout;
  if (!to_stdout || !plot_path.empty()) {
    make_parent_dirs(csv_file);
    out = std::fopen(csv_file.c_str(), "wb");
    if (out == nullptr) {
      std::fprintf(stderr, "gyro_sil: cannot write %s\n", csv_file.c_str());
      return kExitRunFailed;
    }
  }

  RunOptions options;
  options.progress = !quiet;
  options.label = "gyro_sil: " + fs::path(scenario_path).filename().string();
  CsvWriter csv(out);
  RunSummary sum;
  try {
    sum = run_scenario(scenario, csv, options);
  } catch (const ScenarioError& e) {
    if (out != stdout) std::fclose(out);
    std::fprintf(stderr, "gyro_sil: bad scenario: %s\n", e.what());
    return kExitBadInput;
  } catch (const RunError& e) {
    if (out != stdout) std::fclose(out);
    std::fprintf(stderr, "gyro_sil: %s: run failed: %s\n", scenario_path.c_str(), e.what());
    return kExitRunFailed;
  }
  const bool closed = (out == stdout) ? std::fflush(out) == 0 : std::fclose(out) == 0;
  if (!closed || !csv.ok()) {
    std::fprintf(stderr, "gyro_sil: writing %s failed\n", to_stdout ? "standard output" : csv_file.c_str());
    return kExitRunFailed;
  }

  if (!quiet) {
    const std::string flags = flag_names(sum.flags_seen);
    std::fprintf(stderr,
                 "gyro_sil: %s: %llu ticks (%.6g s simulated, %s) in %.3f s; final mode %s; flags raised: %s%s%s\n",
                 scenario_path.c_str(), static_cast<unsigned long long>(sum.ticks),
                 static_cast<double>(sum.ticks) * scenario.run.tick_s, to_string(sum.precision), sum.wall_s,
                 gyro::to_string(sum.final_mode), flags.empty() ? "none" : flags.c_str(),
                 to_stdout ? "" : "; wrote ", to_stdout ? "" : csv_file.c_str());
    if (sum.nonfinite_values != 0) {
      std::fprintf(stderr, "gyro_sil: warning: %llu non-finite values in the CSV\n",
                   static_cast<unsigned long long>(sum.nonfinite_values));
    }
  }

  int status = sum.nonfinite_values == 0 ? 0 : kExitRunFailed;
  if (!plot_path.empty()) {
    try {
      make_parent_dirs(plot_path);
      plot_csv(gimbal_plot(csv_file, plot_path, scenario));
      if (!quiet) std::fprintf(stderr, "gyro_sil: plot: %s\n", plot_path.c_str());
    } catch (const PlotError& e) {
      std::fprintf(stderr, "gyro_sil: plot failed: %s\n", e.what());
      status = status == 0 ? kExitPlotFailed : status;
    }
    if (to_stdout) {
      std::ifstream in(csv_file, std::ios::binary);
      std::cout << in.rdbuf();
      std::cout.flush();
      std::error_code ec;
      fs::remove(csv_file, ec);
    }
  }
  return status;
}
