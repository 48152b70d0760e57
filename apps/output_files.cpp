#include "output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <random>
#include <system_error>
#include <utility>

#include "printable.hpp"
#include "signal_cleanup.hpp"

namespace gyro::sil {

namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& s) { return "\"" + printable(s) + "\""; }
std::string quoted(const fs::path& p) { return quoted(p.string()); }

std::string errno_text(int e) { return std::strerror(e); }

// Device and inode of an existing file (symbolic links followed); nullopt if there is none.
std::optional<std::pair<dev_t, ino_t>> identity(const fs::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) != 0) return std::nullopt;
  return std::pair<dev_t, ino_t>(st.st_dev, st.st_ino);
}

std::optional<std::pair<dev_t, ino_t>> stdout_identity() {
  struct stat st {};
  if (::fstat(STDOUT_FILENO, &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return std::pair<dev_t, ino_t>(st.st_dev, st.st_ino);
}

OutputTarget target(const std::string& given, const std::string& option, bool stream_allowed) {
  const std::string name = option + " " + quoted(given);
  if (given.empty()) throw OutputRefused(option + " is empty");
  const fs::path p(given);
  if (given.back() == '/' || p.filename() == "." || p.filename() == "..") {
    throw OutputRefused(name + " names a directory, not a file");
  }
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(p, ec);
  const fs::file_status st = fs::status(p, ec);
  if (ec && st.type() != fs::file_type::not_found) {
    throw OutputError("cannot inspect " + name + ": " + ec.message());
  }
  OutputTarget t{given, p, OutputTarget::Kind::kFile};
  switch (st.type()) {
    case fs::file_type::not_found:
      if (fs::is_symlink(link)) throw OutputRefused(name + " is a symbolic link to a missing file");
      return t;
    case fs::file_type::regular:
      t.final_path = fs::canonical(p, ec);  // through symbolic links: the target is replaced
      if (ec) throw OutputError("cannot resolve " + name + ": " + ec.message());
      return t;
    case fs::file_type::directory: throw OutputRefused(name + " is a directory");
    case fs::file_type::character:
    case fs::file_type::fifo:
      if (!stream_allowed) throw OutputRefused(name + " is not a regular file (gnuplot writes a file)");
      t.kind = OutputTarget::Kind::kStream;
      return t;
    default: throw OutputRefused(name + " is not a regular file");
  }
}

// The same file: by identity when both exist, else by their spelling with every existing
// directory on the way resolved (symbolic links and ../ included).
bool same_file(const fs::path& a, const fs::path& b) {
  const auto ia = identity(a), ib = identity(b);
  if (ia && ib) return *ia == *ib;
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

std::string random_suffix() {
  static std::random_device device;
  static std::mt19937_64 gen((static_cast<std::uint64_t>(device()) << 32) ^ device() ^
                             static_cast<std::uint64_t>(::getpid()));
  constexpr std::string_view kChars = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::string s(10, 'x');
  for (char& c : s) c = kChars[gen() % kChars.size()];
  return s;
}

}  // namespace

OutputPlan plan_outputs(const fs::path& scenario, const std::string& csv, const std::string& png) {
  OutputPlan plan;
  const auto input = identity(scenario);
  const auto out = stdout_identity();
  if (csv == "-") {
    plan.csv = OutputTarget{csv, {}, OutputTarget::Kind::kStream};
    if (input && out && *input == *out) throw OutputRefused("standard output is the scenario file");
  } else {
    plan.csv = target(csv, "-o", true);
    if (same_file(csv, scenario)) throw OutputRefused("-o " + quoted(csv) + " is the scenario file");
  }
  if (!png.empty()) {
    plan.png = target(png, "--plot", false);
    if (same_file(png, scenario)) throw OutputRefused("--plot " + quoted(png) + " is the scenario file");
    if (csv == "-") {
      if (out && identity(png) == out) throw OutputRefused("--plot " + quoted(png) + " is standard output's file");
    } else if (same_file(csv, png)) {
      throw OutputRefused("--plot " + quoted(png) + " is the same file as -o " + quoted(csv));
    }
  }
  return plan;
}

// ---------------------------------------------------------------------------------------

TempFile::TempFile(TempFile&& o) noexcept
    : path_(std::move(o.path_)),
      final_path_(std::move(o.final_path_)),
      stream_(std::exchange(o.stream_, nullptr)),
      slot_(std::exchange(o.slot_, -1)),
      created_dirs_(std::move(o.created_dirs_)),
      done_(std::exchange(o.done_, true)) {}

TempFile::~TempFile() { remove_all(); }

void TempFile::remove_all() noexcept {
  if (stream_ != nullptr) std::fclose(stream_);
  stream_ = nullptr;
  if (!done_) {
    ::unlink(path_.c_str());
    signal_cleanup::forget(slot_);
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
      ::rmdir(it->first.c_str());  // only if empty: another output may have put its file there
      signal_cleanup::forget(it->second);
    }
  }
  done_ = true;
}

TempFile TempFile::beside(const fs::path& final_path) {
  TempFile t;
  t.final_path_ = final_path;
  fs::path dir = final_path.parent_path();
  if (dir.empty()) dir = ".";

  // Missing directories, outermost first.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path d = dir; !d.empty() && !fs::exists(d, ec) && !ec; d = d.parent_path()) {
    missing.insert(missing.begin(), d);
    if (d == d.parent_path()) break;
  }
  for (const fs::path& d : missing) {
    const signal_cleanup::Deferred created_then_registered;
    if (::mkdir(d.c_str(), 0777) != 0) {
      const int e = errno;
      if (e == EEXIST && fs::is_directory(d, ec)) continue;
      throw OutputError("cannot create the directory " + quoted(d) + ": " + errno_text(e));
    }
    const int slot = signal_cleanup::add_directory(d.string());
    t.created_dirs_.emplace_back(d, slot);
  }

  // The permissions of the file it replaces, or the default of a new file.
  struct stat existing {};
  const bool replaces = ::stat(final_path.c_str(), &existing) == 0 && S_ISREG(existing.st_mode);
  const std::string stem = "." + final_path.filename().string() + ".";
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate = dir / (stem + random_suffix() + ".tmp");
    const signal_cleanup::Deferred created_then_registered;
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) {
      const int e = errno;
      if (e == EEXIST) continue;
      throw OutputError("cannot create a temporary file in " + quoted(dir) + " for " + quoted(final_path) + ": " +
                        errno_text(e));
    }
    t.path_ = candidate;
    t.slot_ = signal_cleanup::add_file(candidate.string());
    if (replaces) ::fchmod(fd, existing.st_mode & 07777);
    t.stream_ = ::fdopen(fd, "wb");
    if (t.stream_ == nullptr) {
      ::close(fd);
      throw OutputError("cannot open " + quoted(candidate) + ": " + errno_text(errno));
    }
    return t;
  }
  throw OutputError("cannot create a temporary file in " + quoted(dir) + ": every name tried exists");
}

TempFile TempFile::private_file(const std::string& stem) {
  TempFile t;
  const char* tmpdir = std::getenv("TMPDIR");
  const fs::path dir = (tmpdir != nullptr && *tmpdir != '\0') ? fs::path(tmpdir) : fs::path("/tmp");
  std::string tmpl = (dir / (stem + "_XXXXXX")).string();
  const signal_cleanup::Deferred created_then_registered;
  const int fd = ::mkostemp(tmpl.data(), O_CLOEXEC);  // O_CREAT | O_EXCL, mode 0600
  if (fd < 0) throw OutputError("cannot create a temporary file in " + quoted(dir) + ": " + errno_text(errno));
  t.path_ = tmpl;
  t.slot_ = signal_cleanup::add_file(tmpl);
  t.stream_ = ::fdopen(fd, "wb");
  if (t.stream_ == nullptr) {
    ::close(fd);
    throw OutputError("cannot open " + quoted(t.path_) + ": " + errno_text(errno));
  }
  return t;
}

void TempFile::close() {
  if (stream_ == nullptr) return;
  std::FILE* f = std::exchange(stream_, nullptr);
  bool ok = std::fflush(f) == 0;
  int e = ok ? 0 : errno;
  if (ok && !final_path_.empty() && ::fsync(::fileno(f)) != 0) {
    ok = false;
    e = errno;
  }
  if (std::fclose(f) != 0 && ok) {
    ok = false;
    e = errno;
  }
  if (!ok) throw OutputError("writing " + quoted(final_path_.empty() ? path_ : final_path_) + " failed: " + errno_text(e));
}

void TempFile::commit() {
  if (final_path_.empty()) throw OutputError("a private temporary file is never committed");
  close();
  if (::rename(path_.c_str(), final_path_.c_str()) != 0) {
    throw OutputError("cannot rename " + quoted(path_) + " to " + quoted(final_path_) + ": " + errno_text(errno));
  }
  signal_cleanup::forget(slot_);
  for (const auto& d : created_dirs_) signal_cleanup::forget(d.second);
  done_ = true;
}

void copy_to_stream(const fs::path& from, std::FILE* to, const std::string& to_name) {
  std::FILE* in = std::fopen(from.c_str(), "rb");
  if (in == nullptr) throw OutputError("cannot read " + quoted(from) + ": " + errno_text(errno));
  std::array<char, 65536> buf{};
  bool ok = true;
  std::size_t n = 0;
  while (ok && (n = std::fread(buf.data(), 1, buf.size(), in)) > 0) ok = std::fwrite(buf.data(), 1, n, to) == n;
  ok = ok && std::ferror(in) == 0;
  std::fclose(in);
  if (!ok || std::fflush(to) != 0) throw OutputError("writing " + to_name + " failed");
}

std::FILE* open_stream(const OutputTarget& t) {
  if (t.given == "-") return stdout;
  const int fd = ::open(t.final_path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw OutputError("cannot open " + quoted(t.given) + " for writing: " + errno_text(errno));
  std::FILE* f = ::fdopen(fd, "wb");
  if (f == nullptr) {
    ::close(fd);
    throw OutputError("cannot open " + quoted(t.given) + " for writing: " + errno_text(errno));
  }
  return f;
}

}  // namespace gyro::sil
