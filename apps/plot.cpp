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

std::string gnuplot_script(const PlotRequest& r) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  const int rows = static_cast<int>(r.panels.size());
  const int height = 120 + 330 * rows;
  s << "# gyro_sil plot: gimbal angles against time\n"
    << "set datafile separator comma\n"
    << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
    << "  set terminal pngcairo noenhanced size 1200," << height << " font 'sans,10'\n"
    << "} else {\n"
    << "  set terminal png noenhanced size 1200," << height << "\n"
    << "}\n"
    << "set output " << gp_quote(r.png.string()) << "\n"
    << "set grid\n"
    << "set key outside right top\n"
    << "set xlabel 't (s)'\n"
    << "set multiplot layout " << rows << ",1 title " << gp_lines(r.title) << "\n";
  for (const PlotPanel& p : r.panels) {
    s << "set ylabel " << gp_quote(p.ylabel) << "\n";
    s << "plot ";
    bool first = true;
    for (const PlotSeries& ser : p.series) {
      if (!first) s << ", \\\n     ";
      s << (first ? gp_quote(r.csv.string()) : std::string("''")) << " skip 1 using " << r.time_column << ":"
        << ser.column;
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
