// gyro_sil: runs the flight gyro component against the simulated gyro, as a scenario file
// describes, and writes the time history as CSV (and a plot that explains the run: run_plot.hpp).
//
//   gyro_sil SCENARIO.json [-o out.csv] [--plot out.png] [--precision float|double] [--ticks N]
//            [--quiet] [--max-output-bytes N] [--plot-timeout S]
//            [--pil SOCKET [--pil-firmware IMAGE.elf] [--pil-machine M] [--pil-tick-clocks N]
//             [--pil-fault KIND@TICK[+TICKS]]... [--pil-timeout S]]
//
// --pil runs the component on an emulated target over a serial line (docs/pil.md) instead of
// in process: the same loop, CSV (plus pil_* columns) and plot.
//
// Exit status (docs/scenarios.md): 0 done; 1 the run failed (the software refused a call, a
// non-finite value, an output not writable); 2 refused before anything ran (command line,
// scenario, output paths, resource limits); 3 the CSV was written but the plot failed. A
// signal (SIGINT, SIGTERM, SIGHUP, SIGPIPE) removes the temporary files and ends gyro_sil
// with that signal. Every failure prints one line on standard error, --quiet or not.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "csv_writer.hpp"
#include "sil_option_values.hpp"
#include "output_files.hpp"
#include "plot.hpp"
#include "run_plot.hpp"
#include "run_timeline.hpp"
#include "printable.hpp"
#include "scenario.hpp"
#include "scenario_limits.hpp"
#include "signal_cleanup.hpp"
#include "sil_columns.hpp"  // kDefaultMaxOutputBytes
#include "sil_runner.hpp"

namespace {

namespace fs = std::filesystem;
using namespace gyro::sil;

constexpr int kExitRunFailed = 1;
constexpr int kExitRefused = 2;
constexpr int kExitPlotFailed = 3;


int fail(int status, const std::string& message) {
  std::fprintf(stderr, "gyro_sil: %s\n", message.c_str());
  return status;
}

// Where the CSV goes while the run writes it: a temporary file beside the final one, a
// private temporary (a stream output that gnuplot must also read), or the stream itself.
struct CsvSink {
  std::optional<TempFile> file;
  std::FILE* stream{nullptr};  // the stream output (standard output, a device, a FIFO)
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> owned{nullptr, &std::fclose};  // the stream, unless stdout
  std::string name;            // for messages

  [[nodiscard]] std::FILE* out() const { return file ? file->stream() : stream; }

  // The CSV is complete: closed, ready for gnuplot to read.
  void finish() {
    if (file) {
      file->close();
    } else if (std::fflush(stream) != 0) {
      throw OutputError("writing " + name + " failed");
    }
  }
  // Puts it where it belongs: renamed into place, or copied to the stream.
  void commit() {
    if (!file) return;
    if (stream == nullptr) {
      file->commit();
    } else {
      copy_to_stream(file->path(), stream, name);
    }
  }
};

CsvSink open_csv(const OutputTarget& t, bool plotting) {
  CsvSink sink;
  sink.name = t.given == "-" ? "standard output" : "\"" + printable(t.given) + "\"";
  if (t.kind == OutputTarget::Kind::kFile) {
    sink.file.emplace(TempFile::beside(t.final_path));
    return sink;
  }
  sink.stream = open_stream(t);
  if (sink.stream != stdout) sink.owned.reset(sink.stream);
  if (plotting) sink.file.emplace(TempFile::private_file("gyro_sil_csv"));
  return sink;
}

void print_pil_summary(const PilSummary& p) {
  const double ipc = p.instructions_per_clock();
  const double cycles = p.cycles == 0 ? 1.0 : static_cast<double>(p.cycles);
  const gyro::pil::TickOut& r = p.last_report;
  std::fprintf(stderr,
               "gyro_sil: pil: target in %s, timer %u clocks per tick; %llu ticks run, %llu skipped, %u overruns; "
               "%.0f exchanges/s\n",
               p.target_real_bytes == 8 ? "double" : "float", p.tick_clocks, static_cast<unsigned long long>(p.cycles),
               static_cast<unsigned long long>(p.skipped), p.overruns,
               p.exchange_wall_s > 0 ? static_cast<double>(p.cycles) / p.exchange_wall_s : 0.0);
  std::fprintf(stderr,
               "gyro_sil: pil: step %.0f instructions mean, %.0f worst at tick %llu (clocks x %.0f under -icount "
               "shift=0)\n",
               static_cast<double>(p.step_clocks_total) / cycles * ipc, static_cast<double>(p.step_clocks_worst) * ipc,
               static_cast<unsigned long long>(p.worst_tick), ipc);
  std::fprintf(stderr,
               "gyro_sil: pil: gyro link at the target: %u readings, %u timeouts, %u bus errors, %u duplicates, %u "
               "lost, %u CRC errors, %u header errors, %u bytes skipped; %llu torque commands applied\n",
               r.port.readings, r.port.timeouts, r.port.bus_errors, r.port.duplicates, r.port.frames_lost, r.crc_errors,
               r.header_errors, r.bytes_skipped, static_cast<unsigned long long>(p.torque_commands));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gyro_sil: runs the gyro flight component against the simulated gyro hardware from a "
               "scenario file and writes the time history as CSV"};
  std::string scenario_path;
  std::string csv_path = "-";
  std::string plot_path;
  std::string precision_name;
  std::string max_output_bytes_text;  // parsed after CLI11 (sil_option_values.hpp): no silent wrap
  std::string plot_timeout_text;
  std::string pil_timeout_text;
  bool quiet = false;
  bool resolved = false;
  std::uint64_t ticks = 0;
  PilOptions pil;
  std::vector<std::string> pil_faults;
  std::uint32_t pil_tick_clocks = 0;
  app.add_option("scenario", scenario_path, "scenario file (JSON, see docs/scenarios.md)")->required();
  app.add_option("-o,--output", csv_path, "CSV time history to write ('-' = standard output)")
      ->capture_default_str();
  app.add_option("--plot", plot_path, "also plot the run to this PNG: gimbal, rates, torque, residual against their limits, modes and flags (needs gnuplot)");
  app.add_option("--precision", precision_name, "run the component and the stub in float or double "
                                                "(default: the scenario's run.precision)")
      ->check(CLI::IsMember({"float", "double"}));
  CLI::Option* max_output_opt =
      app.add_option("--max-output-bytes", max_output_bytes_text,
                     "refuse a run whose CSV could exceed this size: bytes, or with a unit (kB = 1000 B, KiB, MB, "
                     "MiB, GB, GiB, ...; default 1GiB; at least 1 B, no value turns the bound off)");
  CLI::Option* plot_timeout_opt = app.add_option(
      "--plot-timeout", plot_timeout_text, "seconds gnuplot may take before it is stopped (default 300, at most 86400)");
  app.add_option("--ticks", ticks, "run this many ticks after tick 0 instead of the scenario's duration")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 40));
  app.add_flag("--resolved", resolved,
               "write the scenario as it is flown (its example or base expanded, docs/scenarios.md) as JSON to "
               "--output instead of running it");
  app.add_flag("-q,--quiet", quiet, "no progress or summary on standard error (failures are still reported)");
  CLI::Option* pil_opt = app.add_option("--pil", pil.socket,
                                        "processor in the loop: run the component on the target behind this UNIX "
                                        "socket (QEMU's serial chardev server); see docs/pil.md");
  app.add_option("--pil-firmware", pil.firmware, "start QEMU with this PIL image (gyro_fw_pil.elf) on the socket "
                                                 "(without it: attach to a QEMU already listening there)")
      ->needs(pil_opt);
  app.add_option("--pil-machine", pil.machine, "QEMU machine of the started target (mps2-an386: Cortex-M4F, "
                                               "mps2-an500: Cortex-M7)")
      ->capture_default_str()
      ->needs(pil_opt);
  app.add_option("--pil-tick-clocks", pil_tick_clocks, "the target's timer period in its clocks (default: the "
                                                       "scenario's tick); shorter than a step to provoke overruns")
      ->check(CLI::Range(2u, 1u << 24))
      ->needs(pil_opt);
  app.add_option("--pil-fault", pil_faults, "inject a fault on the gyro link: KIND@TICK[+TICKS], KIND one of crc, "
                                            "drop, duplicate, stall, noise (repeatable)")
      ->needs(pil_opt);
  CLI::Option* pil_timeout_opt =
      app.add_option("--pil-timeout", pil_timeout_text,
                     "seconds of silence from the target before giving up (default 30, at most 3600)")
          ->needs(pil_opt);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return fail(kExitRefused, "bad command line: " + printable(e.what()) + " (see --help)");
  }
  // Every value CLI11 took as text, checked whole before anything else (sil_option_values.hpp).
  std::string refusal;
  const auto refused = [&refusal] { return fail(kExitRefused, "bad command line: " + refusal + " (see --help)"); };
  struct StringOption {
    const char* name;
    const std::string* value;
    const char* what;  // what to give instead of nothing
  };
  const StringOption strings[] = {
      {"scenario", &scenario_path, "a scenario file"},
      {"--output", &csv_path, "a file name, or - for standard output"},
      {"--plot", &plot_path, "a PNG file name"},
      {"--precision", &precision_name, "float or double"},
      {"--pil", &pil.socket, "the path of the target's serial socket"},
      {"--pil-firmware", &pil.firmware, "a PIL image (gyro_fw_pil.elf)"},
      {"--pil-machine", &pil.machine, "a QEMU machine (mps2-an386, mps2-an500)"}};
  for (const StringOption& o : strings) {
    const CLI::Option* opt = app.get_option_no_throw(o.name);
    const bool given = std::string_view(o.name) == "scenario" || (opt != nullptr && opt->count() != 0);
    if (given && !check_not_empty(o.name, *o.value, o.what, refusal)) return refused();
  }
  for (const std::string& text : pil_faults) {
    if (!check_not_empty("--pil-fault", text, "KIND@TICK[+TICKS]", refusal)) return refused();
  }
  std::uint64_t max_output_bytes = kDefaultMaxOutputBytes;
  if (max_output_opt->count() != 0) {
    const std::optional<std::uint64_t> v = parse_byte_size("--max-output-bytes", max_output_bytes_text, refusal);
    if (!v) return refused();
    max_output_bytes = *v;
  }
  double plot_timeout_s = kDefaultPlotTimeoutS;
  if (plot_timeout_opt->count() != 0) {
    const std::optional<double> v = parse_seconds("--plot-timeout", plot_timeout_text, kMaxPlotTimeoutS, refusal);
    if (!v) return refused();
    plot_timeout_s = *v;
  }
  if (pil_timeout_opt->count() != 0) {
    const std::optional<double> v = parse_seconds("--pil-timeout", pil_timeout_text, kMaxPilTimeoutS, refusal);
    if (!v) return refused();
    pil.timeout_s = *v;
  }
  signal_cleanup::install();
  const std::string shown = printable(scenario_path);

  const std::optional<Precision> precision =
      precision_name.empty() ? std::nullopt : parse_precision(precision_name);
  for (const std::string& text : pil_faults) {
    std::string error;
    const std::optional<WireFault> f = parse_wire_fault(text, error);
    if (!f) return fail(kExitRefused, "bad command line: --pil-fault " + quoted_value(text) + ": " + error);
    pil.faults.push_back(*f);
  }
  if (pil_tick_clocks != 0) pil.tick_clocks = pil_tick_clocks;
  pil.target_console = !quiet;

  // Everything that can be refused is refused before any output exists.
  Scenario scenario;
  OutputPlan plan;
  try {
    scenario = load_scenario(scenario_path, precision);
    plan = plan_outputs(scenario_path, csv_path, plot_path);
  } catch (const ScenarioError& e) {
    return fail(kExitRefused, std::string("bad scenario: ") + e.what());
  } catch (const OutputRefused& e) {
    return fail(kExitRefused, std::string("refused: ") + e.what());
  } catch (const OutputError& e) {
    return fail(kExitRunFailed, e.what());
  }
  if (resolved) {
    try {
      CsvSink out = open_csv(plan.csv, false);
      const std::string text = scenario.document->dump(2) + "\n";
      if (std::fwrite(text.data(), 1, text.size(), out.out()) != text.size()) {
        return fail(kExitRunFailed, "writing " + out.name + " failed");
      }
      out.finish();
      out.commit();
    } catch (const OutputError& e) {
      return fail(kExitRunFailed, e.what());
    }
    return 0;
  }
  if (ticks != 0) scenario.run.ticks = ticks;
  try {
    check_trajectory_covers_run(scenario);
  } catch (const ScenarioError& e) {
    return fail(kExitRefused, std::string("bad scenario: ") + e.what());
  }
  const std::uint64_t csv_bound = csv_size_bound(scenario);
  if (csv_bound > max_output_bytes) {
    return fail(kExitRefused, std::string("refused: ") + ScenarioError(scenario.file, scenario.run.length_field,
                                                          "the CSV could take up to " + std::to_string(csv_bound) +
                                                              " bytes (" + std::to_string(scenario.run.ticks + 1) +
                                                              " rows), more than the limit of " +
                                                              std::to_string(max_output_bytes) +
                                                              " (raise it with --max-output-bytes)")
                                                  .what());
  }

  const bool plotting = plan.png.has_value();
  try {
    CsvSink csv_out = open_csv(plan.csv, plotting);
    std::optional<TempFile> png_out;
    if (plotting) {
      png_out.emplace(TempFile::beside(plan.png->final_path));
      png_out->close();  // gnuplot writes it
    }

    RunOptions options;
    options.progress = !quiet;
    options.label = "gyro_sil: " + printable(fs::path(scenario_path).filename().string());
    options.max_csv_bytes = max_output_bytes;
    if (!pil.socket.empty()) options.pil = pil;
    CsvWriter csv(csv_out.out());
    CsvObserver rows(csv, max_output_bytes);
    TimelineObserver timeline(scenario.run.tick_s, timeline_resolution_s(scenario));
    FanOutObserver observers({&rows, &timeline});
    RunSummary sum;
    try {
      sum = run_scenario(scenario, observers, options);
    } catch (const ScenarioError& e) {
      return fail(kExitRefused, std::string("bad scenario: ") + e.what());
    } catch (const RunError& e) {
      return fail(kExitRunFailed, shown + ": run failed: " + printable(e.what()));
    }
    if (!csv.ok()) return fail(kExitRunFailed, "writing " + csv_out.name + " failed");
    if (sum.nonfinite_values != 0) {
      return fail(kExitRunFailed, shown + ": run failed: " + std::to_string(sum.nonfinite_values) +
                                      " non-finite values in the CSV (not written)");
    }
    csv_out.finish();

    std::string plot_failure;
    if (plotting) {
      try {
        PlotRequest request =
            run_plot(csv_out.file->path(), png_out->path(), scenario_title(scenario), scenario, timeline.timeline());
        request.timeout_s = plot_timeout_s;
        plot_csv(request);
      } catch (const PlotError& e) {
        plot_failure = e.what();
      }
    }
    csv_out.commit();
    if (plotting && plot_failure.empty()) png_out->commit();

    if (!quiet) {
      const std::string flags = flag_names(sum.flags_seen);
      const bool to_file = plan.csv.kind == OutputTarget::Kind::kFile;
      std::fprintf(stderr,
                   "gyro_sil: %s: %llu ticks (%.6g s simulated, %s) in %.3f s; final mode %s; flags raised: %s%s%s\n",
                   shown.c_str(), static_cast<unsigned long long>(sum.ticks),
                   static_cast<double>(sum.ticks) * scenario.run.tick_s, to_string(sum.precision), sum.wall_s,
                   gyro::enum_name_or(sum.final_mode, "?"), flags.empty() ? "none" : flags.c_str(),
                   to_file ? "; wrote " : "", to_file ? printable(plan.csv.given).c_str() : "");
      if (sum.pil) print_pil_summary(*sum.pil);
      if (plotting && plot_failure.empty()) std::fprintf(stderr, "gyro_sil: plot: %s\n", printable(plot_path).c_str());
    }
    if (!plot_failure.empty()) return fail(kExitPlotFailed, "plot failed: " + plot_failure);
  } catch (const OutputError& e) {
    return fail(kExitRunFailed, e.what());
  }
  return 0;
}
