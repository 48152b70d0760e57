#include "output_dir.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <streambuf>
#include <system_error>

#include "bounded_read.hpp"
#include "printable.hpp"

namespace gyro::campaign {

namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& p) { return "\"" + sil::printable(p.string()) + "\""; }

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// An ostream's buffer writing to a C stream (the temporary file's).
class StreamToFile : public std::streambuf {
 public:
  explicit StreamToFile(std::FILE* f) : f_(f) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    return std::fputc(traits_type::to_char_type(c), f_) == EOF ? traits_type::eof() : c;
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    return static_cast<std::streamsize>(std::fwrite(s, 1, static_cast<std::size_t>(n), f_));
  }

 private:
  std::FILE* f_;
};

}  // namespace

OutputDir::OutputDir(fs::path dir, std::vector<fs::path> inputs, const std::vector<fs::path>& input_dirs)
    : dir_(std::move(dir)), inputs_(std::move(inputs)) {
  if (dir_.empty()) throw OutputError("-o is empty: name the output directory");
  for (const fs::path& d : input_dirs) {
    if (same_file(dir_, d)) throw OutputError("the output directory " + quoted(dir_) + " is one of the inputs");
  }
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (!fs::is_directory(dir_, ec)) {
    throw OutputError("cannot create the output directory " + quoted(dir_) + (ec ? ": " + ec.message() : ""));
  }
  std::string why;
  lock_ = DirectoryLock::take(dir_, why);
  if (!lock_) throw OutputError(why);
}

void OutputDir::check(const std::string& relative) const {
  const fs::path target = dir_ / relative;
  for (const fs::path& in : inputs_) {
    if (same_file(target, in)) {
      throw OutputError("the output " + quoted(target) + " would overwrite the input " + quoted(in));
    }
  }
  // Below the directory the user named, nothing is followed.
  fs::path at = dir_;
  const fs::path rel(relative);
  for (auto it = rel.begin(); it != rel.end(); ++it) {
    at /= *it;
    const bool last = std::next(it) == rel.end();
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) {
      if (errno == ENOENT) return;  // made fresh when written
      throw OutputError("cannot inspect " + quoted(at) + ": " + std::strerror(errno));
    }
    if (S_ISLNK(st.st_mode)) {
      throw OutputError(quoted(at) + " is a symbolic link: refused, not followed (gyro_campaign writes only " +
                        (last ? "its own files" : "into directories it made") + " below " + quoted(dir_) + ")");
    }
    if (!last && !S_ISDIR(st.st_mode)) throw OutputError(quoted(at) + " is not a directory");
    if (last && !S_ISREG(st.st_mode)) throw OutputError(quoted(at) + " is not a regular file: not replaced");
    if (last && ((st.st_mode & S_IWUSR) == 0 || ::access(at.c_str(), W_OK) != 0)) {
      throw OutputError(quoted(at) + " is read-only: not replaced (make it writable, or choose another directory)");
    }
  }
}

void OutputDir::claim(const std::vector<std::string>& names) const {
  for (const std::string& n : names) check(n);
  std::error_code ec;
  if (fs::exists(dir_ / kOutputMarker, ec)) return;
  for (const std::string& n : names) {
    if (fs::exists(dir_ / n, ec)) {
      throw OutputError(sil::printable((dir_ / n).string()) + " exists, in a directory gyro_campaign did not write (no " +
                        kOutputMarker + "): choose a new or empty directory");
    }
  }
  write(kOutputMarker, "This directory holds gyro_campaign's outputs: it replaces its own files here.\n");
}

sil::TempFile OutputDir::temporary_for(const std::string& relative) const {
  check(relative);
  try {
    return sil::TempFile::beside(dir_ / relative);
  } catch (const sil::OutputError& e) {
    throw OutputError(e.what());
  }
}

void OutputDir::publish(sil::TempFile& temporary, const std::string& relative) const {
  check(relative);
  try {
    temporary.commit();
  } catch (const sil::OutputError& e) {
    throw OutputError(e.what());
  }
}

void OutputDir::write(const std::string& relative, std::string_view content) const {
  write(relative, [&](std::ostream& out) { out.write(content.data(), static_cast<std::streamsize>(content.size())); });
}

void OutputDir::write(const std::string& relative, const std::function<void(std::ostream&)>& fill) const {
  sil::TempFile tmp = temporary_for(relative);
  StreamToFile buf(tmp.stream());
  std::ostream out(&buf);
  fill(out);
  out.flush();
  if (!out || std::ferror(tmp.stream()) != 0) {
    throw OutputError("writing " + quoted(dir_ / relative) + " failed: " + std::strerror(errno));
  }
  publish(tmp, relative);
}

std::string read_file(const fs::path& p, std::uint64_t max_bytes, const std::string& what) {
  std::string why;
  std::optional<std::string> text = sil::read_bounded(p.string(), max_bytes, what, why);
  if (!text) throw OutputError(sil::printable(p.string()) + ": " + why);
  return std::move(*text);
}

}  // namespace gyro::campaign
