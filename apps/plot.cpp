#include "plot.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>
#include <system_error>
#include <thread>

#include "output_files.hpp"
#include "printable.hpp"
#include "signal_cleanup.hpp"

extern char** environ;

namespace gyro::sil {

namespace {

// A gnuplot single-quoted string: no escapes inside except '' for a quote.
std::string gp_quote(std::string_view s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += '\'';
    if (c == '\n' || c == '\r') c = ' ';  // gp_lines() splits lines first
    out += c;
  }
  out += '\'';
  return out;
}

// A title of several lines ('\n' in `s`) as a gnuplot string expression.
std::string gp_lines(std::string_view s) {
  std::string out;
  std::size_t start = 0;
  while (true) {
    const std::size_t nl = s.find('\n', start);
    out += gp_quote(s.substr(start, nl == std::string_view::npos ? std::string_view::npos : nl - start));
    if (nl == std::string_view::npos) break;
    out += " . \"\\n\" . ";
    start = nl + 1;
  }
  return out;
}

bool is_executable(const std::filesystem::path& p) {
  struct stat st {};
  return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
}

// Starts gnuplot on the script: no shell, its own process group (so that it and anything it
// starts can be killed together), standard input /dev/null, standard output to standard
// error. The signals gyro_sil cleans up on are blocked from before the spawn until the child
// is registered for the handler to kill, and restored in the child.
pid_t spawn_gnuplot(const std::filesystem::path& gnuplot, const std::filesystem::path& script) {
  sigset_t cleanup_signals, old_mask;
  sigemptyset(&cleanup_signals);
  for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&cleanup_signals, sig);
  ::pthread_sigmask(SIG_BLOCK, &cleanup_signals, &old_mask);

  posix_spawnattr_t attr;
  posix_spawn_file_actions_t actions;
  ::posix_spawnattr_init(&attr);
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  ::posix_spawnattr_setpgroup(&attr, 0);
  ::posix_spawnattr_setsigmask(&attr, &old_mask);
  ::posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  ::posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);

  const std::string prog = gnuplot.string();
  std::string arg = script.string();
  std::string argv0 = "gnuplot";
  char* argv[] = {argv0.data(), arg.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, prog.c_str(), &actions, &attr, argv, environ);
  if (rc == 0) signal_cleanup::set_child(pid);
  ::posix_spawn_file_actions_destroy(&actions);
  ::posix_spawnattr_destroy(&attr);
  ::pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  if (rc != 0) throw PlotError("cannot run " + printable(prog) + ": " + std::strerror(rc));
  return pid;
}

// Waits for the child, polling; past the time limit kills its process group. Its status.
int wait_for(pid_t pid, double timeout_s, const std::string& prog) {
  const auto start = std::chrono::steady_clock::now();
  const auto limit = std::chrono::duration<double>(timeout_s);
  auto pause = std::chrono::milliseconds(1);
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      signal_cleanup::set_child(0);
      throw PlotError("waiting for gnuplot failed: " + std::string(std::strerror(errno)));
    }
    if (std::chrono::steady_clock::now() - start > limit) {
      ::kill(-pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      signal_cleanup::set_child(0);
      std::ostringstream t;
      t.imbue(std::locale::classic());
      t << timeout_s;
      throw PlotError(printable(prog) + " did not finish within " + t.str() + " s (--plot-timeout): stopped");
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  signal_cleanup::set_child(0);  // reaped: its process group is gone
  return status;
}

}  // namespace

std::optional<std::filesystem::path> find_gnuplot() {
  if (const char* env = std::getenv("GNUPLOT"); env != nullptr && *env != '\0') {
    const std::filesystem::path p(env);
    if (p.has_parent_path()) return is_executable(p) ? std::optional(p) : std::nullopt;
    // A bare name: look it up on PATH like the default.
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string dir; std::getline(dirs, dir, ':');) {
      const std::filesystem::path cand = std::filesystem::path(dir.empty() ? "." : dir) / p;
      if (is_executable(cand)) return cand;
    }
    return std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path cand = std::filesystem::path(dir.empty() ? "." : dir) / "gnuplot";
    if (is_executable(cand)) return cand;
  }
  return std::nullopt;
}

namespace {

// Layout in pixels: the title above the panels, the time axis's label below them; the
// plotting areas share their left and right edges (the row names left, the keys right).
constexpr int kWidthPx = 1200;
constexpr int kTitlePx = 80;
constexpr int kTagLinePx = 15;  // a line of names above the top panel
constexpr double kCharPx = 6.5;  // the font's average character width
constexpr double kCharHeightPx = 15.0;  // gnuplot's character unit, vertically
constexpr int kBottomPx = 40;
constexpr int kPanelTopPadPx = 8;
constexpr int kPanelTicsPx = 24;  // each panel's time tick labels
constexpr double kLeftEdge = 0.14;
constexpr double kRightEdge = 0.80;
// A bar's label is written inside it when the bar is at least this share of the time axis.
constexpr double kLabelShare = 0.04;
// A bar is drawn at least this share of the time axis wide (3 pixels).
constexpr double kMinBarShare = 0.004;

// "#rrggbb" -> the integer gnuplot's "lc rgb variable" reads; black if malformed.
unsigned long rgb_value(std::string_view color) {
  if (color.size() != 7 || color[0] != '#') return 0;
  unsigned long v = 0;
  for (char c : color.substr(1)) {
    const int d = (c >= '0' && c <= '9') ? c - '0' : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : -1;
    if (d < 0) return 0;
    v = v * 16 + static_cast<unsigned long>(d);
  }
  return v;
}

// A label of a datablock: double-quoted, with no quote or line break inside.
std::string data_label(std::string_view s) {
  std::string out = "\"";
  for (char c : s) out += (c == '"' || c == '\n' || c == '\r' || c == '\\') ? ' ' : c;
  return out + "\"";
}

void raster_data(std::ostream& s, const PlotPanel& p, std::size_t index, double axis_s) {
  const double n = static_cast<double>(p.rows.size());
  s << "$raster" << index << " << EOD\n";
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const double y = n - static_cast<double>(i);  // the first row on top
    for (PlotBar b : p.rows[i].bars) {
      b.to_s = std::max(b.to_s, b.from_s + kMinBarShare * axis_s);  // a one-tick flag stays visible
      // Commas: the script's datafile separator holds for datablocks too.
      s << 0.5 * (b.from_s + b.to_s) << ',' << y << ',' << b.from_s << ',' << b.to_s << ',' << y - 0.38 << ','
        << y + 0.38 << ',' << rgb_value(b.color) << '\n';
    }
  }
  s << "EOD\n$rasterlabels" << index << " << EOD\n";
  bool any = false;
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    for (const PlotBar& b : p.rows[i].bars) {
      if (b.label.empty() || (axis_s > 0 && b.to_s - b.from_s < kLabelShare * axis_s)) continue;
      s << 0.5 * (b.from_s + b.to_s) << ',' << n - static_cast<double>(i) << ',' << data_label(b.label) << '\n';
      any = true;
    }
  }
  if (!any) s << "NaN,NaN,\"\"\n";
  s << "EOD\n";
}

bool has_bars(const PlotPanel& p) {
  return std::any_of(p.rows.begin(), p.rows.end(), [](const PlotRow& r) { return !r.bars.empty(); });
}

void series_plot(std::ostream& s, const PlotRequest& r, const PlotPanel& p, bool& first) {
  for (const PlotSeries& ser : p.series) {
    if (!first) s << ", \\\n     ";
    s << gp_quote(r.csv.string()) << " skip 1";
    if (r.every > 1) s << " every " << r.every;
    s << " using " << r.time_column << ":";
    if (ser.magnitude) {
      s << "(abs($" << ser.column << "))";
    } else {
      s << ser.column;
    }
    if (ser.points) {
      s << " with points pt 7 ps 0.35";
    } else {
      s << " with lines";
      if (ser.style.empty()) s << " lw 1.2";
    }
    if (!ser.style.empty()) s << " " << ser.style;
    s << " title " << gp_quote(ser.title);
    first = false;
  }
  for (const PlotLimit& l : p.limits) {
    for (int sign : {1, -1}) {
      if (sign < 0 && !l.mirrored) continue;
      if (!first) s << ", \\\n     ";
      s << sign * l.value << " with lines " << (l.style.empty() ? "dt 2 lw 1.5" : l.style) << " "
        << (sign > 0 ? "title " + gp_quote(l.title) : std::string("notitle"));
      first = false;
    }
  }
}

// A name of a marker or window, written above the top panel at its time.
struct Tag {
  double t_s{0};
  std::string text;
  std::string color;
  int line{0};  // 0: just above the panel, 1: above that, ...
};

// The names above the top panel, each on the lowest line where it overlaps no other (its
// width estimated from its length); none when the time axis is not known.
std::vector<Tag> tags_of(const PlotRequest& r) {
  std::vector<Tag> tags;
  if (!r.end_s || !(*r.end_s > 0)) return tags;
  for (const PlotWindow& w : r.windows) {
    if (!w.label.empty()) tags.push_back({w.from_s, w.label, w.label_color.empty() ? w.color : w.label_color, 0});
  }
  for (const PlotMarker& m : r.markers) tags.push_back({m.t_s, m.label, m.color, 0});
  std::stable_sort(tags.begin(), tags.end(), [](const Tag& a, const Tag& b) { return a.t_s < b.t_s; });
  const double plot_px = (kRightEdge - kLeftEdge) * kWidthPx;
  const double s_per_char = kCharPx / plot_px * *r.end_s;
  std::vector<double> line_end;  // where each line's last name ends (s)
  for (Tag& t : tags) {
    std::size_t line = 0;
    while (line < line_end.size() && line_end[line] > t.t_s) ++line;
    if (line == line_end.size()) line_end.push_back(0);
    line_end[line] = t.t_s + (static_cast<double>(t.text.size()) + 2) * s_per_char;
    t.line = static_cast<int>(line);
  }
  return tags;
}

int tag_lines(const std::vector<Tag>& tags) {
  int n = 0;
  for (const Tag& t : tags) n = std::max(n, t.line + 1);
  return n;
}

// The markers and windows of a panel; in the top one, their names above it.
void overlays(std::ostream& s, const PlotRequest& r, const std::vector<Tag>& tags, bool top) {
  s << "unset arrow\nunset label\nunset object\n";
  for (const PlotWindow& w : r.windows) {
    s << "set object rect from first " << w.from_s << ", graph 0 to first " << w.to_s
      << ", graph 1 behind fillcolor rgb " << gp_quote(w.color) << " fillstyle solid 0.22 noborder\n";
  }
  for (const PlotMarker& m : r.markers) {
    s << "set arrow from first " << m.t_s << ", graph 0 to first " << m.t_s << ", graph 1 nohead dashtype 2 lw 1.5 "
      << "linecolor rgb " << gp_quote(m.color) << " front\n";
  }
  if (!top) return;
  for (const Tag& t : tags) {
    s << "set label " << gp_quote(t.text) << " at first " << t.t_s << ", graph 1 offset 0,"
      << 0.7 + kTagLinePx / kCharHeightPx * t.line << " left textcolor rgb " << gp_quote(t.color) << " front\n";
  }
}

}  // namespace

std::string gnuplot_script(const PlotRequest& r) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(10);
  int panels_px = 0;
  for (const PlotPanel& p : r.panels) panels_px += p.height_px;
  const std::vector<Tag> tags = tags_of(r);
  const int title_px = kTitlePx + kTagLinePx * std::max(0, tag_lines(tags) - 1);
  const int height = title_px + panels_px + kBottomPx;
  const double axis_s = r.end_s.value_or(0.0);
  s << "# gyro_sil plot: panels on one time axis\n"
    << "set datafile separator comma\n"
    << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
    << "  set terminal pngcairo noenhanced size " << kWidthPx << "," << height << " font 'sans,10'\n"
    << "} else {\n"
    << "  set terminal png noenhanced size " << kWidthPx << "," << height << "\n"
    << "}\n"
    << "set output " << gp_quote(r.png.string()) << "\n";
  for (std::size_t i = 0; i < r.panels.size(); ++i) {
    if (!r.panels[i].rows.empty()) raster_data(s, r.panels[i], i, axis_s);
  }
  s << "set grid\n"
    << "set style textbox opaque noborder\n"
    << "set key outside right top\n"
    << "set lmargin at screen " << kLeftEdge << "\nset rmargin at screen " << kRightEdge << "\n";
  if (r.end_s) s << "set xrange [0:" << *r.end_s << "]\n";
  s << "set multiplot title " << gp_lines(r.title) << "\n";
  int top_px = title_px;
  for (std::size_t i = 0; i < r.panels.size(); ++i) {
    const PlotPanel& p = r.panels[i];
    const bool last = i + 1 == r.panels.size();
    const double y_top = 1.0 - static_cast<double>(top_px + kPanelTopPadPx) / height;
    top_px += p.height_px;
    const double y_bottom = 1.0 - static_cast<double>(top_px - kPanelTicsPx) / height;
    s << "set tmargin at screen " << y_top << "\nset bmargin at screen " << y_bottom << "\n";
    overlays(s, r, tags, i == 0);
    s << (last ? "set xlabel 't (s)'\n" : "unset xlabel\n");
    s << "set ylabel " << gp_quote(p.ylabel) << "\n";
    s << (p.log_y ? "set logscale y\nset format y '%.0e'\n" : "unset logscale y\nset format y '% h'\n");
    bool first = true;
    if (!p.rows.empty()) {
      const std::size_t n = p.rows.size();
      s << "set yrange [0.5:" << static_cast<double>(n) + 0.5 << "]\nset ytics (";
      for (std::size_t k = 0; k < n; ++k) s << (k ? ", " : "") << gp_quote(p.rows[k].name) << " " << n - k;
      s << ")\nset grid noytics\nset offsets 0, 0, 0, 0\n";
      s << "plot ";
      if (has_bars(p)) {
        s << "$raster" << i << " using 1:2:3:4:5:6:7 with boxxyerror fillstyle solid 0.85 noborder "
          << "linecolor rgb variable notitle, \\\n     $rasterlabels" << i
          << " using 1:2:3 with labels textcolor rgb '#ffffff' notitle";
      } else {
        s << "NaN notitle";
      }
      first = false;
    } else {
      // A limit at the edge of the autoscaled range stays off the border.
      s << "set autoscale y\nset ytics autofreq\nset grid ytics\nset offsets 0, 0, graph 0.06, graph 0.06\n";
      s << "plot ";
    }
    series_plot(s, r, p, first);
    if (first) s << "NaN notitle";
    s << "\n";
  }
  s << "unset multiplot\n";
  return s.str();
}

void plot_csv(const PlotRequest& r) { run_gnuplot(gnuplot_script(r), r.png, r.timeout_s); }

void run_gnuplot(const std::string& script_text, const std::filesystem::path& png, double timeout_s) {
  const std::optional<std::filesystem::path> gnuplot = find_gnuplot();
  if (!gnuplot) {
    throw PlotError("gnuplot not found (looked for " +
                    std::string(std::getenv("GNUPLOT") ? "$GNUPLOT" : "\"gnuplot\" on PATH") +
                    "); install it (Debian: apt-get install gnuplot-nox) or set GNUPLOT to its path");
  }
  if (!(timeout_s > 0)) throw PlotError("the gnuplot time limit must be > 0 s");

  // The script goes to a private temporary file (removed on return, or by a signal).
  TempFile script = [] {
    try {
      return TempFile::private_file("gyro_sil_plot");
    } catch (const OutputError& e) {
      throw PlotError(std::string("cannot create the gnuplot script: ") + e.what());
    }
  }();
  const bool written =
      std::fwrite(script_text.data(), 1, script_text.size(), script.stream()) == script_text.size();
  try {
    script.close();
  } catch (const OutputError& e) {
    throw PlotError(e.what());
  }
  if (!written) throw PlotError("cannot write the gnuplot script " + printable(script.path().string()));

  const pid_t pid = spawn_gnuplot(*gnuplot, script.path());
  const int status = wait_for(pid, timeout_s, gnuplot->string());
  const std::string prog = printable(gnuplot->string());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw PlotError(prog + " failed (" +
                    (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                       : std::string("killed by signal ") + std::to_string(WTERMSIG(status))) +
                    ")");
  }
  std::error_code ec;
  if (std::filesystem::file_size(png, ec) == 0 || ec) throw PlotError(prog + " wrote no image");
}

}  // namespace gyro::sil
