#include "output_dir.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

namespace gyro::campaign {

namespace {

namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

}  // namespace

OutputDir::OutputDir(fs::path dir, std::vector<fs::path> inputs, const std::vector<fs::path>& input_dirs)
    : dir_(std::move(dir)), inputs_(std::move(inputs)) {
  for (const fs::path& d : input_dirs) {
    if (same_file(dir_, d)) throw OutputError("the output directory " + dir_.string() + " is one of the inputs");
  }
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_, ec)) {
    throw OutputError("cannot create the output directory " + dir_.string() + (ec ? ": " + ec.message() : ""));
  }
}

void OutputDir::check(const std::string& relative) const {
  const fs::path target = dir_ / relative;
  for (const fs::path& in : inputs_) {
    if (same_file(target, in)) {
      throw OutputError("the output " + target.string() + " would overwrite the input " + in.string());
    }
  }
}

void OutputDir::claim(const std::vector<std::string>& names) const {
  for (const std::string& n : names) check(n);
  std::error_code ec;
  if (fs::exists(dir_ / kOutputMarker, ec)) return;
  for (const std::string& n : names) {
    if (fs::exists(dir_ / n, ec)) {
      throw OutputError((dir_ / n).string() + " exists, in a directory gyro_campaign did not write (no " +
                        kOutputMarker + "): choose a new or empty directory");
    }
  }
  write(kOutputMarker, "This directory holds gyro_campaign's outputs: it replaces its own files here.\n");
}

fs::path OutputDir::temporary_for(const std::string& relative) const {
  check(relative);
  const fs::path target = dir_ / relative;
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  std::string tmpl = (target.parent_path() / ("." + target.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw OutputError("cannot create a temporary file beside " + target.string() + ": " + std::strerror(errno));
  ::close(fd);
  return tmpl;
}

void OutputDir::publish(const fs::path& temporary, const std::string& relative) const {
  const fs::path target = dir_ / relative;
  // mkstemp makes the file 0600; outputs get the usual permissions (umask applies).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(temporary.c_str(), 0666 & ~mask);
  if (std::rename(temporary.c_str(), target.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::error_code ec;
    fs::remove(temporary, ec);
    throw OutputError("cannot rename " + temporary.string() + " to " + target.string() + ": " + why);
  }
}

void OutputDir::write(const std::string& relative, std::string_view content) const {
  write(relative, [&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
}

void OutputDir::write(const std::string& relative, const std::function<void(std::ostream&)>& fill) const {
  const fs::path tmp = temporary_for(relative);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    fill(out);
    out.close();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw OutputError("writing " + (dir_ / relative).string() + " failed");
    }
  }
  publish(tmp, relative);
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw OutputError("cannot open " + p.string() + " for reading");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw OutputError("read error on " + p.string());
  return s.str();
}

}  // namespace gyro::campaign
