// A campaign run (apps/campaign, gyro_campaign's library) from Python: the campaign parsed
// as gyro_campaign does, its runs executed on worker threads (RunPool), and the per-run table
// (runs.csv) returned column by column: run and seed as uint64 (a seed is 64 bits, which
// float64 would round), the verdicts (pass and the boolean metrics) as lists of bool (None
// where a run has none, e.g. refused), other numbers as float64 (NaN for an empty cell),
// anything else as a list of str.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "interrupt.hpp"
#include "campaign_error.hpp"
#include "campaign_file.hpp"
#include "errors.hpp"
#include "run_pool.hpp"
#include "run_table.hpp"
#include "scenario.hpp"
#include "scenario_source.hpp"

namespace py = pybind11;

namespace gyro::python {

namespace {

using campaign::Campaign;

// The table's rows in run order, as runs.csv holds them. Called without the GIL; between
// collections (every kSignalCheckPeriod) it takes the GIL to run Python's signal handlers, and
// when one raises it stops the pool: no new run starts, the runs under way finish (a run's
// work at most, on each worker) and Interrupted is thrown once they are joined.
campaign::RunTable run_all(const Campaign& c, unsigned threads) {
  std::vector<std::pair<std::uint64_t, std::string>> rows;
  campaign::RunPool pool(c, 0, c.runs, threads);
  while (!pool.done()) {
    if (python_signal_raised()) throw Interrupted{};  // ~RunPool stops and joins the workers
    for (std::string& r : pool.take(kSignalCheckPeriod)) {
      const std::uint64_t k = campaign::row_run_index(r).value_or(std::numeric_limits<std::uint64_t>::max());
      rows.emplace_back(k, std::move(r));
    }
  }
  std::sort(rows.begin(), rows.end());
  std::string text = campaign::csv_line(campaign::table_header(c)) + "\n";
  for (const auto& [k, r] : rows) text += r;
  return campaign::parse_run_table(text, c, c.file);
}

// The columns whose cells are whole numbers of 64 bits, and those that hold a verdict.
bool is_index_column(const std::string& name) { return name == "run" || name == "seed"; }

std::vector<std::string> boolean_columns(const Campaign& c) {
  std::vector<std::string> names = {"pass"};
  for (const campaign::MetricColumn& m : campaign::metric_columns(c.metrics)) {
    if (m.type == campaign::ColumnType::kBoolean) names.push_back(m.name);
  }
  return names;
}

py::array_t<std::uint64_t> index_column(const campaign::RunTable& t, std::size_t col) {
  py::array_t<std::uint64_t> out(static_cast<py::ssize_t>(t.size()));
  auto v = out.mutable_unchecked<1>();
  for (std::size_t r = 0; r < t.size(); ++r) {
    const std::string cell = t.text(r, col);
    std::uint64_t x = 0;
    const std::from_chars_result p = std::from_chars(cell.data(), cell.data() + cell.size(), x);
    if (cell.empty() || p.ec != std::errc{} || p.ptr != cell.data() + cell.size()) {
      throw py::value_error("runs.csv: " + t.header()[col] + " of row " + std::to_string(r) + " is not a whole number: " +
                            cell);
    }
    v(static_cast<py::ssize_t>(r)) = x;
  }
  return out;
}

py::list boolean_column(const campaign::RunTable& t, std::size_t col) {
  py::list out;
  for (std::size_t r = 0; r < t.size(); ++r) {
    const std::string cell = t.text(r, col);
    if (cell == "true") {
      out.append(py::bool_(true));
    } else if (cell == "false") {
      out.append(py::bool_(false));
    } else {
      out.append(py::none());
    }
  }
  return out;
}

py::dict table_columns(const campaign::RunTable& t, const Campaign& c) {
  py::dict d;
  const std::vector<std::string> verdicts = boolean_columns(c);
  for (std::size_t col = 0; col < t.header().size(); ++col) {
    const std::string& name = t.header()[col];
    if (is_index_column(name)) {
      d[py::str(name)] = index_column(t, col);
      continue;
    }
    if (std::find(verdicts.begin(), verdicts.end(), name) != verdicts.end()) {
      d[py::str(name)] = boolean_column(t, col);
      continue;
    }
    std::vector<double> numbers;
    bool numeric = true;
    for (std::size_t r = 0; r < t.size() && numeric; ++r) {
      const std::string cell = t.text(r, col);
      const std::optional<double> v = campaign::cell_number(cell);
      if (cell.empty()) {
        numbers.push_back(std::numeric_limits<double>::quiet_NaN());
      } else if (v) {
        numbers.push_back(*v);
      } else {
        numeric = false;
      }
    }
    const py::str key(t.header()[col]);
    if (numeric) {
      d[key] = py::array_t<double>(static_cast<py::ssize_t>(numbers.size()), numbers.data());
    } else {
      py::list texts;
      for (std::size_t r = 0; r < t.size(); ++r) texts.append(t.text(r, col));
      d[key] = texts;
    }
  }
  return d;
}

py::tuple run_campaign(const py::object& source, const py::object& runs_arg, const py::object& threads_arg,
                       const std::optional<std::string>& base_dir) {
  // gyro_campaign -j's bound (one constant, campaign::kMaxThreads), checked before any work.
  const auto threads = static_cast<unsigned>(whole_number(threads_arg, "threads", 1, campaign::kMaxThreads));
  std::optional<std::uint64_t> runs;
  if (!runs_arg.is_none()) runs = whole_number(runs_arg, "runs", 1, campaign::kMaxRuns);
  const DocumentSource src = document_source(source, "campaign");
  py::dict columns;
  std::vector<std::string> header;
  try {
    Campaign c = src.path ? campaign::read_campaign(*src.path)
                          : campaign::parse_campaign(src.text, src.name,
                                                     base_dir ? std::filesystem::path(*base_dir)
                                                              : std::filesystem::current_path());
    if (runs) {
      if (*runs > c.runs) {
        throw py::value_error("runs: expected a whole number from 1 to the campaign's run count " +
                              std::to_string(c.runs) + ", got " + std::to_string(*runs));
      }
      campaign::keep_first_runs(c, *runs);  // each run's row depends only on (campaign, index)
    }
    std::optional<campaign::RunTable> table;
    {
      py::gil_scoped_release release;
      table.emplace(run_all(c, threads));
    }
    header = table->header();
    columns = table_columns(*table, c);
  } catch (const Interrupted&) {
    throw py::error_already_set();  // the KeyboardInterrupt (or whatever the handler raised)
  } catch (const campaign::CampaignError& e) {
    raise_python("ScenarioError", py::make_tuple(std::string(e.what()), e.field(), e.file()));
  } catch (const sil::ScenarioError& e) {
    raise_python("ScenarioError", py::make_tuple(std::string(e.what()), e.field(), e.file()));
  }
  return py::make_tuple(header, columns);
}

}  // namespace

void bind_campaign_run(py::module_& m) {
  m.attr("MAX_THREADS") = campaign::kMaxThreads;
  m.def("_run_campaign", &run_campaign, py::arg("campaign"), py::arg("runs") = py::none(), py::arg("threads") = 1,
        py::arg("base_dir") = py::none(),
        "(header, columns) of a campaign's per-run table; gyro.run_campaign wraps it in a CampaignRun.");
}

}  // namespace gyro::python
