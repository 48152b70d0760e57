#include "plot.hpp"

#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

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

// Removes the file when it goes out of scope.
struct TempFile {
  std::filesystem::path path;
  ~TempFile() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove(path, ec);
  }
};

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

void plot_csv(const PlotRequest& r) { run_gnuplot(gnuplot_script(r), r.png); }

void run_gnuplot(const std::string& script_text, const std::filesystem::path& png) {
  const std::optional<std::filesystem::path> gnuplot = find_gnuplot();
  if (!gnuplot) {
    throw PlotError("gnuplot not found (looked for " +
                    std::string(std::getenv("GNUPLOT") ? "$GNUPLOT" : "\"gnuplot\" on PATH") +
                    "); install it (Debian: apt-get install gnuplot-nox) or set GNUPLOT to its path");
  }

  // The script goes to a private temporary file.
  std::string tmpl = (std::filesystem::temp_directory_path() / "gyro_sil_plot_XXXXXX.gp").string();
  const int fd = ::mkstemps(tmpl.data(), 3);
  if (fd < 0) throw PlotError("cannot create a temporary gnuplot script: " + std::string(std::strerror(errno)));
  ::close(fd);
  TempFile script{tmpl};
  {
    std::ofstream out(script.path, std::ios::binary | std::ios::trunc);
    out << script_text;
    if (!out) throw PlotError("cannot write the gnuplot script " + script.path.string());
  }

  std::error_code ec;
  std::filesystem::remove(png, ec);  // so a stale image is never taken for a new one

  const std::string prog = gnuplot->string();
  std::string arg = script.path.string();
  std::string argv0 = "gnuplot";
  char* argv[] = {argv0.data(), arg.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawn(&pid, prog.c_str(), nullptr, nullptr, argv, environ);
  if (rc != 0) throw PlotError("cannot run " + prog + ": " + std::strerror(rc));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw PlotError("waiting for gnuplot failed: " + std::string(std::strerror(errno)));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw PlotError(prog + " failed (" +
                    (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                       : std::string("killed by a signal")) +
                    ") drawing " + png.string());
  }
  if (!std::filesystem::exists(png, ec) || std::filesystem::file_size(png, ec) == 0) {
    throw PlotError("gnuplot wrote no image to " + png.string());
  }
}

}  // namespace gyro::sil
