// gyro_campaign: Monte Carlo campaigns of SIL runs, from one core to a cluster.
//
//   gyro_campaign run CAMPAIGN.json -o DIR [-j N] [--runs N] [--shard I/N] [--no-plots] [--quiet]
//   gyro_campaign run CAMPAIGN.json --run K -o DIR [--no-plots]
//   gyro_campaign merge DIR... -o DIR [--no-plots] [--quiet]
//   mpirun -np N gyro_campaign run CAMPAIGN.json -o DIR [-j M]
//
// Exit status: 0 done (whatever the runs' verdicts: see summary.md); 1 a failure at run time
// (an output not writable, a worker failed); 2 bad command line, bad campaign file, shards
// that do not make one campaign, or an output that would overwrite an input; 3 the outputs
// were written but a plot failed (gnuplot missing or failing).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "campaign_error.hpp"
#include "campaign_file.hpp"
#include "campaign_plots.hpp"
#include "campaign_run.hpp"
#include "cluster.hpp"
#include "csv_writer.hpp"
#include "option_values.hpp"
#include "output_dir.hpp"
#include "plot.hpp"
#include "printable.hpp"
#include "progress_line.hpp"
#include "run_plot.hpp"
#include "run_pool.hpp"
#include "run_table.hpp"
#include "run_timeline.hpp"
#include "signal_cleanup.hpp"
#include "sil_runner.hpp"
#include "summary.hpp"

namespace {

namespace fs = std::filesystem;
using namespace gyro::campaign;
using json = nlohmann::json;

constexpr int kExitRunFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitPlotFailed = 3;

// A batch of rows goes from a rank to rank 0 when it is this large or this old.
constexpr std::size_t kBatchBytes = 64 * 1024;
constexpr std::chrono::milliseconds kBatchAge{250};

// The largest manifest.json merge reads (the ones written are about 160 bytes).
constexpr std::uint64_t kMaxManifestBytes = 64 * 1024;

struct Options {
  std::string campaign;
  std::vector<std::string> dirs;  // merge
  std::string out;
  std::string threads_text{"1"};
  unsigned threads{1};
  std::string shard;
  std::string run_text;
  std::optional<std::uint64_t> run;
  std::string runs_text;
  std::optional<std::uint64_t> runs;  // the first N runs only
  bool no_plots{false};
  bool quiet{false};
};

// A message on standard error, its user-given text (paths, JSON keys and values) escaped:
// a control character would be interpreted by the terminal (printable.hpp).
void say(const std::string& message) {
  std::fprintf(stderr, "gyro_campaign: %s\n", gyro::sil::printable(message).c_str());
}

struct Shard {
  std::uint64_t index{0}, count{1};  // 0-based index of `count`
  std::uint64_t first{0}, end{0};    // its runs [first, end)
  [[nodiscard]] bool complete() const { return count == 1; }
  [[nodiscard]] std::string text() const { return std::to_string(index + 1) + "/" + std::to_string(count); }
};

// The share [first, end) of `part` out of `parts` of [0, n): contiguous, sizes differ by at most one.
std::pair<std::uint64_t, std::uint64_t> share(std::uint64_t n, std::uint64_t part, std::uint64_t parts) {
  return {n * part / parts, n * (part + 1) / parts};
}

std::optional<Shard> parse_shard(const std::string& text, std::uint64_t runs, std::string& why) {
  Shard s;
  if (text.empty()) {
    s.end = runs;
    return s;
  }
  const std::size_t slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used_i = 0, used_n = 0;
    const unsigned long long i = std::stoull(text.substr(0, slash), &used_i);
    const unsigned long long n = std::stoull(text.substr(slash + 1), &used_n);
    if (used_i != slash || used_n != text.size() - slash - 1 || text[0] == '-' || text[slash + 1] == '-') {
      throw std::invalid_argument("trailing text");
    }
    if (n < 1 || i < 1 || i > n) {
      why = "--shard " + text + ": expected I/N with 1 <= I <= N";
      return std::nullopt;
    }
    if (n > runs) {
      why = "--shard " + text + ": more shards than the campaign's " + std::to_string(runs) + " runs";
      return std::nullopt;
    }
    s.index = i - 1;
    s.count = n;
  } catch (const std::exception&) {
    why = "--shard " + text + ": expected I/N, e.g. 2/8 (shard 2 of 8)";
    return std::nullopt;
  }
  std::tie(s.first, s.end) = share(runs, s.index, s.count);
  return s;
}

std::string manifest(const Campaign& c, const Shard& s) {
  const json m = {{"format", "gyro_campaign 1"}, {"campaign", c.fingerprint}, {"runs", c.runs},
                  {"seed", c.seed},              {"shard", s.text()},         {"first_run", s.first},
                  {"end_run", s.end}};
  return m.dump(2) + "\n";
}

std::vector<std::string> split_rows(const std::string& batch) {
  std::vector<std::string> rows;
  for (std::size_t at = 0; at < batch.size();) {
    const std::size_t nl = batch.find('\n', at);
    rows.push_back(batch.substr(at, nl - at + 1));
    at = nl + 1;
  }
  return rows;
}

// The summary, its plots' data and the plots: a complete campaign's outputs after runs.csv.
int write_summary(const Campaign& c, const OutputDir& out, const RunTable& t, const Options& o) {
  const std::vector<PlotJob> jobs = o.no_plots ? std::vector<PlotJob>{} : campaign_plots(c, t);
  std::vector<std::string> pngs;
  for (const PlotJob& j : jobs) {
    out.write(j.data, j.data_text);
    pngs.push_back(j.png);
  }
  out.write("summary.md", make_summary(c, t, pngs));
  int status = 0;
  for (const PlotJob& j : jobs) {
    gyro::sil::TempFile tmp = out.temporary_for(j.png);
    tmp.close();  // gnuplot writes it
    try {
      gyro::sil::run_gnuplot(plot_script(j, (out.path() / j.data).string(), tmp.path().string()), tmp.path());
      out.publish(tmp, j.png);
    } catch (const gyro::sil::PlotError& e) {
      say("plot " + j.png + " failed: " + e.what());  // the temporary is removed with `tmp`
      status = kExitPlotFailed;
    }
  }
  if (!o.quiet) {
    std::uint64_t passed = 0, refused = 0, errors = 0;
    const std::size_t pass = *t.column("pass"), st = *t.column("status");
    for (std::size_t i = 0; i < t.size(); ++i) {
      passed += t.cell(i, pass) == "true" ? 1u : 0u;
      refused += t.cell(i, st) == "refused" ? 1u : 0u;
      errors += t.cell(i, st) == "error" ? 1u : 0u;
    }
    say(std::to_string(t.size()) + " runs: " + std::to_string(passed) + " passed, " +
        std::to_string(t.size() - passed - refused - errors) + " failed, " + std::to_string(refused) + " refused, " +
        std::to_string(errors) + " in error; wrote " + (out.path() / "summary.md").string());
  }
  return status;
}

// runs.csv, campaign.json, manifest.json; and for a complete campaign the summary and plots.
// `rows`: the shard's rows in run order, each a line of CSV with its newline.
int write_outputs(const Campaign& c, const OutputDir& out, const Shard& s, std::vector<std::string> rows,
                  const Options& o) {
  out.write("runs.csv", [&](std::ostream& f) {
    f << csv_line(table_header(c)) << '\n';
    for (const std::string& r : rows) f << r;
  });
  out.write("campaign.json", c.resolved_text);
  out.write("manifest.json", manifest(c, s));
  if (!s.complete()) {
    if (!o.quiet) {
      say("shard " + s.text() + " (runs " + std::to_string(s.first) + " to " + std::to_string(s.end - 1) +
          ") written to " + out.path().string() + "; join the shards with gyro_campaign merge");
    }
    return 0;
  }
  return write_summary(c, out, RunTable(c, std::move(rows), "runs.csv"), o);
}

const std::vector<std::string> kOutputs = {"runs.csv", "campaign.json", "manifest.json", "summary.md",
                                           "plots/latency_cdf.png", "plots/latency_cdf.dat",
                                           "plots/histograms.png", "plots/histograms.dat",
                                           "plots/scatter.png",    "plots/scatter.dat"};

std::vector<fs::path> inputs_of(const std::string& campaign_path, const Campaign& c) {
  std::vector<fs::path> in = {campaign_path};
  if (c.base_path) in.push_back(*c.base_path);
  return in;
}

// The campaign file, with --runs N applied.
Campaign read_options_campaign(const Options& o) {
  Campaign c = read_campaign(o.campaign);
  if (o.runs) keep_first_runs(c, *o.runs);
  return c;
}

// Rank 0: gathers every row of the shard (its own and the other ranks').
std::vector<std::string> gather(gyro::campaign::Cluster& cluster, RunPool& pool, const Shard& s, const Options& o) {
  std::vector<std::string> rows(s.end - s.first);
  ProgressLine progress(s.end - s.first, !o.quiet);
  const auto place = [&](std::string row) {
    const std::optional<std::uint64_t> k = row_run_index(row);
    if (!k || *k < s.first || *k >= s.end || !rows[*k - s.first].empty()) {
      throw std::logic_error("a row arrived twice or out of range: " + row.substr(0, 40));
    }
    rows[*k - s.first] = std::move(row);
    progress.advance(1);
  };
  int ranks_left = cluster.size() - 1;
  while (!pool.done() || ranks_left > 0) {
    for (std::string& r : pool.take(std::chrono::milliseconds(100))) place(std::move(r));
    std::string batch;
    bool last = false;
    bool received = false;
    while (cluster.receive_rows(batch, last)) {
      for (std::string& r : split_rows(batch)) place(std::move(r));
      ranks_left -= last ? 1 : 0;
      received = true;
    }
    if (pool.done() && !received) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  progress.finish();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].empty()) throw std::logic_error("run " + std::to_string(s.first + i) + " never arrived");
  }
  return rows;
}

// Other ranks: stream the rows to rank 0 in batches.
void stream_rows(gyro::campaign::Cluster& cluster, RunPool& pool) {
  std::string batch;
  auto sent = std::chrono::steady_clock::now();
  while (!pool.done()) {
    for (const std::string& r : pool.take(std::chrono::milliseconds(100))) batch += r;
    const auto now = std::chrono::steady_clock::now();
    if (!batch.empty() && (batch.size() >= kBatchBytes || now - sent >= kBatchAge)) {
      cluster.send_rows(std::move(batch), false);
      batch.clear();
      sent = now;
    }
  }
  cluster.send_rows(std::move(batch), true);
  cluster.flush();
}

int run_campaign(gyro::campaign::Cluster& cluster, const Options& o) {
  int status = 0;
  std::string text;
  Campaign c;
  std::optional<OutputDir> out;
  std::string why;
  if (cluster.root()) {
    try {
      c = read_options_campaign(o);
      if (!parse_shard(o.shard, c.runs, why)) throw std::invalid_argument(why);
      out.emplace(o.out, inputs_of(o.campaign, c));
      out->claim(kOutputs);
      text = c.resolved_text;
    } catch (const CampaignError& e) {
      say(std::string("bad campaign: ") + e.what());
      status = kExitBadInput;
    } catch (const OutputError& e) {
      say(e.what());
      status = kExitBadInput;
    } catch (const std::invalid_argument& e) {
      say(e.what());
      status = kExitBadInput;
    }
  }
  cluster.broadcast(text, status);
  if (status != 0) return status;
  if (!cluster.root()) {
    try {
      c = parse_campaign(text, o.campaign, fs::path(o.campaign).parent_path());
    } catch (const std::exception& e) {
      say("rank " + std::to_string(cluster.rank()) + ": " + e.what());
      cluster.abort(kExitRunFailed);
    }
  }
  const std::optional<Shard> shard = parse_shard(o.shard, c.runs, why);  // valid: rank 0 checked it
  const auto [first, end] = share(shard->end - shard->first, static_cast<std::uint64_t>(cluster.rank()),
                                  static_cast<std::uint64_t>(cluster.size()));
  try {
    RunPool pool(c, shard->first + first, shard->first + end, o.threads);
    if (cluster.root()) {
      std::vector<std::string> rows = gather(cluster, pool, *shard, o);
      status = write_outputs(c, *out, *shard, std::move(rows), o);
    } else {
      stream_rows(cluster, pool);
    }
  } catch (const OutputError& e) {
    say(e.what());
    status = kExitRunFailed;
  } catch (const std::exception& e) {
    say("rank " + std::to_string(cluster.rank()) + " failed: " + e.what());
    if (cluster.size() > 1) cluster.abort(kExitRunFailed);
    return kExitRunFailed;
  }
  std::string none;
  cluster.broadcast(none, status);
  return status;
}

// The title of run K's plot: the campaign's run, its seed and its fault.
std::string run_title(std::uint64_t k, const RunResult& r) {
  std::string title = "campaign run " + std::to_string(k) + " (seed " + std::to_string(r.plan.seed) + ")";
  if (r.plan.fault && r.plan.fault->kind) {
    title += "\n" + std::string(gyro::fault_kind_name(*r.plan.fault->kind)) + " at " +
             format_significant(r.plan.fault->start_s, 4) + " s, axis " + std::to_string(r.plan.fault->axis);
  }
  return title;
}

// --run K: one run alone, with its scenario, time history, plot and table row.
int rerun(gyro::campaign::Cluster& cluster, const Options& o) {
  if (cluster.size() > 1) {
    if (cluster.root()) say("--run takes one process: run it without mpirun");
    return kExitBadInput;
  }
  const std::uint64_t k = *o.run;
  const std::string stem = "run-" + std::to_string(k);
  Campaign c;
  std::optional<OutputDir> out;
  try {
    c = read_options_campaign(o);
    if (k >= c.runs) {
      say("--run " + std::to_string(k) + ": the campaign has runs 0 to " + std::to_string(c.runs - 1));
      return kExitBadInput;
    }
    out.emplace(o.out, inputs_of(o.campaign, c));
    out->claim({stem + ".json", stem + ".csv", stem + "-metrics.csv", stem + ".png"});
  } catch (const CampaignError& e) {
    say(std::string("bad campaign: ") + e.what());
    return kExitBadInput;
  } catch (const OutputError& e) {
    say(e.what());
    return kExitBadInput;
  }
  int status = 0;
  try {
    const RunPlan plan = plan_run(c, k);
    out->write(stem + ".json", plan.scenario.dump(2) + "\n");
    // The scenario's limits and tick for the plot (a scenario refused here is refused by the run too).
    std::optional<gyro::sil::Scenario> scenario;
    try {
      scenario = gyro::sil::parse_scenario_document(plan.scenario, stem + ".json");
    } catch (const gyro::sil::ScenarioError&) {
    }
    gyro::sil::TempFile tmp = out->temporary_for(stem + ".csv");
    gyro::sil::CsvWriter csv(tmp.stream());
    gyro::sil::CsvObserver history(csv);
    gyro::sil::TimelineObserver timeline(scenario ? scenario->run.tick_s : 1.0,
                                         scenario ? gyro::sil::timeline_resolution_s(*scenario) : 1.0);
    gyro::sil::FanOutObserver observers({&history, &timeline});
    const RunResult r = execute_run(c, k, &observers);
    bool written = csv.ok();
    try {
      tmp.close();
    } catch (const gyro::sil::OutputError&) {
      written = false;
    }
    const bool has_history = r.status != RunStatus::kRefused && written;
    if (has_history) out->publish(tmp, stem + ".csv");  // else removed with `tmp`
    out->write(stem + "-metrics.csv", csv_line(table_header(c)) + "\n" + format_row(c, r));
    if (has_history && !o.no_plots && scenario) {
      gyro::sil::TempFile png_tmp = out->temporary_for(stem + ".png");
      png_tmp.close();  // gnuplot writes it
      try {
        gyro::sil::plot_csv(gyro::sil::run_plot(out->path() / (stem + ".csv"), png_tmp.path(), run_title(k, r), *scenario,
                                                timeline.timeline()));
        out->publish(png_tmp, stem + ".png");
      } catch (const gyro::sil::PlotError& e) {
        say(std::string("plot failed: ") + e.what());  // the temporary is removed with `png_tmp`
        status = kExitPlotFailed;
      }
    }
    if (!o.quiet) {
      say("run " + std::to_string(k) + " (seed " + std::to_string(r.plan.seed) + "): " + to_string(r.status) +
          (r.reason.empty() ? "" : ": ") + r.reason + "; wrote " + out->path().string() + "/" + stem + ".*");
    }
    if (!written) throw OutputError("writing the time history failed");
  } catch (const OutputError& e) {
    say(e.what());
    return kExitRunFailed;
  }
  return status;
}

int merge(const Options& o) {
  try {
    std::string text;
    std::vector<fs::path> inputs, dirs;
    for (const std::string& d : o.dirs) {
      const fs::path dir(d);
      dirs.push_back(dir);
      for (const char* f : {"campaign.json", "manifest.json", "runs.csv"}) inputs.push_back(dir / f);
      const std::string t = read_file(dir / "campaign.json", kMaxCampaignBytes, "a campaign file");
      if (text.empty()) {
        text = t;
      } else if (t != text) {
        throw CampaignError((dir / "campaign.json").string(), "(document)",
                            "not the campaign of " + (dirs.front() / "campaign.json").string());
      }
    }
    const Campaign c = parse_campaign(text, (dirs.front() / "campaign.json").string(), dirs.front());
    std::vector<std::string> rows(c.runs);
    std::vector<std::size_t> from(c.runs);  // which directory each run came from
    for (std::size_t d = 0; d < dirs.size(); ++d) {
      const fs::path& dir = dirs[d];
      const fs::path manifest_path = dir / "manifest.json";
      const json m = parse_campaign_json(read_file(manifest_path, kMaxManifestBytes, "a manifest"), manifest_path.string());
      if (!m.is_object() || !m.contains("campaign") || m["campaign"] != c.fingerprint) {
        throw CampaignError(manifest_path.string(), "campaign", "not " + c.fingerprint);
      }
      const fs::path csv_path = dir / "runs.csv";
      const RunTable t = parse_run_table(read_file(csv_path, kMaxRunTableBytes, "a run table"), c, csv_path.string());
      for (std::size_t i = 0; i < t.size(); ++i) {
        const std::uint64_t k = *row_run_index(t.line(i));  // < runs: parse_run_table checked
        if (!rows[k].empty()) {
          throw CampaignError(csv_path.string(), "run " + std::to_string(k),
                              "also in " + (dirs[from[k]] / "runs.csv").string() + ": the shards overlap");
        }
        rows[k] = t.line(i) + "\n";
        from[k] = d;
      }
    }
    for (std::uint64_t k = 0; k < c.runs; ++k) {
      if (rows[k].empty()) {
        std::uint64_t end = k;
        while (end < c.runs && rows[end].empty()) ++end;
        throw CampaignError(o.out, "(merge)", "runs " + std::to_string(k) + " to " + std::to_string(end - 1) +
                                                  " are in none of the directories (a shard missing?)");
      }
    }
    const OutputDir out(o.out, inputs, dirs);
    out.claim(kOutputs);
    Shard whole;
    whole.end = c.runs;
    return write_outputs(c, out, whole, std::move(rows), o);
  } catch (const CampaignError& e) {
    say(std::string("cannot merge: ") + e.what());
    return kExitBadInput;
  } catch (const OutputError& e) {
    say(e.what());
    return kExitBadInput;
  }
}

// Every option value checked before anything is read: none is empty, none is read as "no
// limit" or as its default. Sets the thread count and --run's K.
bool check_values(const CLI::App& run, Options& o, std::string& why) {
  const std::optional<std::uint64_t> threads = parse_count("-j", o.threads_text, kMaxThreads, why);
  if (!threads) return false;
  o.threads = static_cast<unsigned>(*threads);
  if (o.threads == 0) o.threads = std::clamp(std::thread::hardware_concurrency(), 1u, kMaxThreads);
  if (o.out.empty()) {
    why = "-o is empty: name the output directory";
    return false;
  }
  if (std::find(o.dirs.begin(), o.dirs.end(), std::string()) != o.dirs.end()) {
    why = "merge: a directory is named by an empty string";
    return false;
  }
  if (run.count("--shard") > 0 && o.shard.empty()) {
    why = "--shard is empty: expected I/N, e.g. 2/8 (shard 2 of 8)";
    return false;
  }
  if (run.count("--run") > 0) {
    o.run = parse_count("--run", o.run_text, kMaxRuns - 1, why);
    if (!o.run) return false;
  }
  if (run.count("--runs") > 0) {
    o.runs = parse_count("--runs", o.runs_text, kMaxRuns, why);
    if (!o.runs) return false;
    if (*o.runs == 0) {
      why = "--runs 0: run at least one";
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (Cluster::launched_without_mpi()) {
    say("started by an MPI launcher, but built without MPI: every process would run the whole campaign. Rebuild "
        "with MPI (Debian: libopenmpi-dev), or use --shard I/N.");
    return kExitBadInput;
  }
  gyro::campaign::Cluster cluster(argc, argv);
  CLI::App app{"gyro_campaign: Monte Carlo campaigns of software-in-the-loop runs (docs/campaigns.md)"};
  app.require_subcommand(1);
  Options o;
  CLI::App* run = app.add_subcommand("run", "run a campaign (or one run of it with --run)");
  run->add_option("campaign", o.campaign, "campaign file (JSON, see docs/campaigns.md)")->required();
  run->add_option("-o,--output", o.out, "output directory (created if missing)")->required();
  run->add_option("-j,--jobs", o.threads_text,
                  "worker threads per process, at most " + std::to_string(kMaxThreads) + " (0: one per core)")
      ->capture_default_str();
  run->add_option("--shard", o.shard, "run only shard I of N (1 <= I <= N) and write it for gyro_campaign merge");
  run->add_option("--run", o.run_text, "rerun run K alone: its scenario, time history (gyro_sil CSV), plot and row");
  run->add_option("--runs", o.runs_text,
                  "run only the first N of the file's runs (each the same as in the whole campaign)");
  run->add_flag("--no-plots", o.no_plots, "no gnuplot plots");
  run->add_flag("-q,--quiet", o.quiet, "no progress or summary line on standard error");
  CLI::App* merge_cmd = app.add_subcommand("merge", "merge the output directories of a campaign's shards");
  merge_cmd->add_option("dirs", o.dirs, "the shards' output directories")->required();
  merge_cmd->add_option("-o,--output", o.out, "output directory (created if missing)")->required();
  merge_cmd->add_flag("--no-plots", o.no_plots, "no gnuplot plots");
  merge_cmd->add_flag("-q,--quiet", o.quiet, "no summary line on standard error");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (!cluster.root()) return e.get_exit_code() == 0 ? 0 : kExitBadInput;
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    say(std::string(e.what()) + " (run with --help for more information)");
    return kExitBadInput;
  }
  std::string why;
  if (!check_values(*run, o, why)) {
    if (cluster.root()) say(why);
    return kExitBadInput;
  }
  gyro::sil::signal_cleanup::install();

  if (merge_cmd->parsed()) {
    if (cluster.size() > 1) {
      if (cluster.root()) say("merge takes one process: run it without mpirun");
      return kExitBadInput;
    }
    return merge(o);
  }
  if (o.run) {
    if (!o.shard.empty()) {
      say("--run and --shard do not go together");
      return kExitBadInput;
    }
    return rerun(cluster, o);
  }
  return run_campaign(cluster, o);
}
