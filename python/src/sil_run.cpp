// A SIL run (apps/sil_runner.hpp, gyro_sil's loop) from Python: the scenario parsed and
// checked as gyro_sil does, the run observed tick by tick, and the CSV's columns returned as
// NumPy arrays (the values the CSV formats, from sil::row_cells) with the component's
// telemetry (flags seen, counters, final mode) from the run's summary.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "interrupt.hpp"
#include "errors.hpp"
#include <nlohmann/json.hpp>

#include "scenario.hpp"
#include "scenario_source.hpp"
#include "sil_columns.hpp"
#include "sil_runner.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

// The most ticks run_sil takes (the output bound refuses far fewer at its default).
constexpr std::uint64_t kMaxTicks = std::uint64_t{1} << 53;

// Every standard column (sil::ColumnRecorder), as NumPy arrays. The run goes on with the GIL
// released; every kSignalCheckPeriod of wall time a tick takes the GIL back to run Python's
// signal handlers (PyErr_CheckSignals), so Ctrl-C stops the run within that period plus one
// tick: the handler's exception (KeyboardInterrupt) is left set and Interrupted thrown out of
// the loop.
class ColumnRecorder final : public sil::ColumnRecorder {
 public:
  void on_tick(const sil::TickRecord& r) override {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_check_ >= kSignalCheckPeriod) {
      last_check_ = now;
      if (python_signal_raised()) throw Interrupted{};
    }
    sil::ColumnRecorder::on_tick(r);
  }
  // name -> array (float64, uint64, or str).
  [[nodiscard]] py::dict arrays() const {
    const py::module_ np = py::module_::import("numpy");
    py::dict d;
    for (const sil::SilColumn& c : columns()) {
      const py::str key(std::string(c.name));
      switch (c.kind) {
        case sil::SilColumn::Kind::kIntegers:
          d[key] = py::array_t<std::uint64_t>(static_cast<py::ssize_t>(c.integers.size()), c.integers.data());
          break;
        case sil::SilColumn::Kind::kNames: d[key] = np.attr("array")(py::cast(c.names)); break;
        case sil::SilColumn::Kind::kNumbers:
          d[key] = py::array_t<double>(static_cast<py::ssize_t>(c.numbers.size()), c.numbers.data());
          break;
      }
    }
    return d;
  }

 private:
  std::chrono::steady_clock::time_point last_check_{std::chrono::steady_clock::now()};
};

py::dict telemetry(const sil::RunSummary& s) {
  py::dict t;
  t["precision"] = sil::to_string(s.precision);
  t["ticks"] = s.ticks;
  t["rows"] = s.rows;
  t["final_mode"] = enum_name(s.final_mode);
  t["flags_seen"] = s.flags_seen;
  py::list seen;
  py::dict counters;
  for (int b = 0; b < kComponentFlagCount; ++b) {
    if ((s.flags_seen & (1u << static_cast<unsigned>(b))) != 0u) seen.append(flag_name(b));
    counters[flag_name(b)] = s.counters[static_cast<std::size_t>(b)];
  }
  t["flags_seen_names"] = seen;
  t["counters"] = counters;
  t["refused_steps"] = s.refused_steps;
  t["nonfinite_values"] = s.nonfinite_values;
  t["gimbal_stop_hits"] = s.gimbal_stop_hits;
  t["max_abs_gimbal_rad"] = s.max_abs_gimbal_rad;
  t["wall_s"] = s.wall_s;
  return t;
}

// The body's trajectory handed in as columns: a mapping of column name (docs/scenarios.md,
// body.trajectory) to a 1-D sequence of numbers, copied as float64.
std::optional<sil::TrajectoryTable> trajectory_table(const py::object& trajectory) {
  if (trajectory.is_none()) return std::nullopt;
  if (!py::isinstance<py::dict>(trajectory)) {
    throw py::type_error("trajectory must be a dict of column name to a 1-D array of numbers");
  }
  sil::TrajectoryTable t;
  t.source = "<trajectory arrays>";
  t.from_file = false;
  const py::module_ np = py::module_::import("numpy");
  for (const auto& item : trajectory.cast<py::dict>()) {
    if (!py::isinstance<py::str>(item.first)) throw py::type_error("trajectory: column names must be str");
    const std::string name = item.first.cast<std::string>();
    const py::array_t<double, py::array::c_style | py::array::forcecast> a =
        np.attr("asarray")(item.second, "float64");
    if (a.ndim() != 1) {
      throw py::value_error("trajectory[" + py::repr(item.first).cast<std::string>() + "]: expected a 1-D array, got " +
                            std::to_string(a.ndim()) + " dimensions");
    }
    if (static_cast<std::size_t>(a.size()) > sil::kMaxTrajectoryRows) {
      throw py::value_error("trajectory[" + py::repr(item.first).cast<std::string>() + "]: " +
                            std::to_string(a.size()) + " rows, more than the limit of " +
                            std::to_string(sil::kMaxTrajectoryRows));
    }
    t.names.push_back(name);
    t.columns.emplace_back(a.data(), a.data() + a.size());
  }
  return t;
}

py::tuple run_sil(const py::object& scenario, const std::optional<std::string>& precision,
                  const py::object& ticks_arg, const py::object& max_output_bytes_arg, const py::object& trajectory) {
  std::optional<sil::Precision> p;
  if (precision) {
    p = sil::parse_precision(*precision);
    if (!p) {
      throw py::value_error("precision: expected 'float' or 'double', got " +
                            py::repr(py::str(*precision)).cast<std::string>());
    }
  }
  std::optional<std::uint64_t> ticks;
  if (!ticks_arg.is_none()) ticks = whole_number(ticks_arg, "ticks", 1, kMaxTicks);
  const std::uint64_t max_output_bytes =
      whole_number(max_output_bytes_arg, "max_output_bytes", 1, std::numeric_limits<std::uint64_t>::max());
  const DocumentSource src = document_source(scenario, "scenario");
  const std::optional<sil::TrajectoryTable> table = trajectory_table(trajectory);
  ColumnRecorder recorder;
  sil::RunSummary sum;
  try {
    const sil::Scenario s = sil::prepare_scenario(src.path, src.text, src.name, p, ticks, table ? &*table : nullptr);
    const std::string too_large = sil::output_bound_refusal(s, max_output_bytes, "max_output_bytes");
    if (!too_large.empty()) throw py::value_error(too_large);
    sil::RunOptions options;
    options.progress = false;
    py::gil_scoped_release release;
    sum = sil::run_scenario(s, recorder, options);
  } catch (const Interrupted&) {
    throw py::error_already_set();  // the KeyboardInterrupt (or whatever the handler raised)
  } catch (const sil::ScenarioError& e) {
    raise_python("ScenarioError", py::make_tuple(std::string(e.what()), e.field(), e.file()));
  } catch (const sil::RunError& e) {
    raise_python("RunError", py::make_tuple(std::string(e.what())));
  }
  return py::make_tuple(recorder.arrays(), telemetry(sum));
}

// The scenario as it is flown: its example or base expanded (apps/scenario_base.hpp), as a dict.
py::object read_scenario(const py::object& scenario) {
  const DocumentSource src = document_source(scenario, "scenario");
  std::string text;
  try {
    const sil::Scenario s = src.path ? sil::read_scenario(*src.path) : sil::parse_scenario(src.text, src.name);
    text = s.document->dump();
  } catch (const sil::ScenarioError& e) {
    raise_python("ScenarioError", py::make_tuple(std::string(e.what()), e.field(), e.file()));
  }
  return py::module_::import("json").attr("loads")(text);
}

}  // namespace

void bind_sil_run(py::module_& m) {
  m.def("read_scenario", &read_scenario, py::arg("scenario"),
        "The scenario (a file path or a dict) as it is flown, its example or base expanded, as a dict: "
        "its \"gyro\" and \"component\" sections are SimulatedGyro's and GyroComponent's keywords.");
  m.def("_run_sil", &run_sil, py::arg("scenario"), py::arg("precision") = py::none(), py::arg("ticks") = py::none(),
        py::arg("max_output_bytes") = sil::kDefaultMaxOutputBytes, py::arg("trajectory") = py::none(),
        "(columns, telemetry) of a SIL run; gyro.run_sil wraps it in a SilRun.");
  m.attr("DEFAULT_MAX_OUTPUT_BYTES") = sil::kDefaultMaxOutputBytes;
  m.def(
      "sil_columns",
      [](bool tracking) {
        std::vector<std::string> n;
        for (const auto c : sil::csv_columns(tracking)) n.emplace_back(c);
        return n;
      },
      py::arg("tracking") = false,
      "The names of gyro_sil's CSV columns, in order (tracking: of a run with guidance.track, "
      "which has pointing_error_true and los_rate_error last).");
  m.def(
      "component_flag_names",
      [] {
        std::vector<std::string> n;
        for (int b = 0; b < kComponentFlagCount; ++b) n.emplace_back(flag_name(b));
        return n;
      },
      "The component's flag names, bit 0 first.");
}

}  // namespace gyro::python
